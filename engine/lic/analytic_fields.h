// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Analytic vector fields sampled on a grid: the fields of the thesis plus standard test flows.

#include <glm/vec2.hpp>
#include <optional>
#include <span>
#include <string_view>

#include "core/enum_names.h"
#include "core/volume.h"

namespace lic3d {

enum class AnalyticField {
  Tornado,     // R. Crawfis' procedural tornado (gen_tornado, The Ohio State University), [0,1]^3
  Corner,      // flow around a corner, thesis section 4.5, sampled on [0,1]^3
  Solenoidal,  // thesis section 6.2: (yz(y^2+z^2), xz(x^2+z^2), xy(x^2+y^2)) on [-1,1]^3
  Vortex,      // (-y, x, 0.2) on [-1,1]^3: helices around the z axis
  Abc,         // Arnold-Beltrami-Childress flow, A = sqrt 3, B = sqrt 2, C = 1, on [0,2pi]^3
};

LIC3D_ENUM_NAMES(AnalyticField, {AnalyticField::Tornado, "tornado"},
                 {AnalyticField::Corner, "corner"}, {AnalyticField::Solenoidal, "solenoidal"},
                 {AnalyticField::Vortex, "vortex"}, {AnalyticField::Abc, "abc"})

// Samples the field at voxel centres. Voxels are cubes: the longest grid axis spans the field's
// domain and shorter axes span a centred part of it, so streamlines keep the field's shape on
// non-cubic grids. `time` is the tornado's time parameter (ignored by the other fields).
VectorField makeAnalyticField(AnalyticField field, Dims dims, double time = 0.0);
// Where makeAnalyticField(field, dims) puts its voxels: the field's domain on the longest axis.
GridGeometry analyticGeometry(AnalyticField field, Dims dims);

// One plane of makeAnalyticField(field, dims, time): voxel layer `index` across `axis` (0, 1, 2
// for x, y, z), sampled alone, as a 2D field (field_plane.h).
VectorField makeAnalyticFieldPlane(AnalyticField field, Dims dims, int axis, int index,
                                   double time = 0.0);

// The time after which the field repeats, 0 if it does not change with time. The tornado's
// centre line turns with sin(0.04 t) and cos(0.03 t): it repeats after 200 pi.
double timePeriod(AnalyticField field);

// ---- 2D fields (thesis chapter 3) ---------------------------------------------------------------
// A 2D field is a VectorField one voxel thick (NX x NY x 1) with vectors in the x-y plane.
enum class AnalyticField2D {
  Circle,  // (-y, x) on [-1,1]^2: circles about the centre, the thesis' Figure 3.7
  Saddle,  // (x, -y) on [-1,1]^2: a saddle point at the centre
  Wave,    // thesis 3.5: (cos 2pi(x - t), sin 2pi(x - t)) on [0,1]^2, the time-varying field
};

LIC3D_ENUM_NAMES(AnalyticField2D, {AnalyticField2D::Circle, "circle"},
                 {AnalyticField2D::Saddle, "saddle"}, {AnalyticField2D::Wave, "wave"})

// Sampled at pixel centres with square pixels, as makeAnalyticField does in 3D.
VectorField makeAnalyticField2D(AnalyticField2D field, glm::ivec2 size, double time = 0.0);
// 1 for the wave (it repeats after one unit of time), 0 for the steady fields.
double timePeriod(AnalyticField2D field);

}  // namespace lic3d
