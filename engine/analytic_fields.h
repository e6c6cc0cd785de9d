#pragma once
// Analytic vector fields sampled on a grid: the fields of the thesis plus standard test flows.

#include <optional>
#include <span>
#include <string_view>

#include "volume.h"

namespace lic3d {

enum class AnalyticField {
  Tornado,     // R. Crawfis' procedural tornado (gen_tornado, The Ohio State University), [0,1]^3
  Corner,      // flow around a corner, thesis section 4.5, sampled on [0,1]^3
  Solenoidal,  // thesis section 6.2: (yz(y^2+z^2), xz(x^2+z^2), xy(x^2+y^2)) on [-1,1]^3
  Vortex,      // (-y, x, 0.2) on [-1,1]^3: helices around the z axis
  Abc,         // Arnold-Beltrami-Childress flow, A = sqrt 3, B = sqrt 2, C = 1, on [0,2pi]^3
};

std::span<const std::string_view> analyticFieldNames();
std::optional<AnalyticField> parseAnalyticField(std::string_view name);
std::string_view toString(AnalyticField field);

// Samples the field at voxel centres. Voxels are cubes: the longest grid axis spans the field's
// domain and shorter axes span a centred part of it, so streamlines keep the field's shape on
// non-cubic grids. `time` is the tornado's time parameter (ignored by the other fields).
VectorField makeAnalyticField(AnalyticField field, Dims dims, double time = 0.0);

}  // namespace lic3d
