#pragma once
// Colour maps for magnitude: the thesis' blue-yellow-red ramp (5.1.2) and two perceptual maps.

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/enum_names.h"

namespace lic3d {

enum class Colormap : std::uint32_t {
  Thesis = 0,    // blue -> yellow -> red, linear between the three
  Viridis = 1,   // matplotlib's viridis (van der Walt & Smith): perceptually uniform, CC0 data
  CoolWarm = 2,  // K. Moreland's diverging cool-warm map (2009)
};
inline constexpr int kColormapCount = 3;
LIC3D_ENUM_NAMES(Colormap, {Colormap::Thesis, "thesis"}, {Colormap::Viridis, "viridis"},
                 {Colormap::CoolWarm, "coolwarm"})

// The colour at t in [0,1] (clamped), as display RGB in [0,1].
glm::vec3 sampleColormap(Colormap map, float t);

// Every map as rows of `width` RGBA8 texels: row i is Colormap(i). The GPU samples this table
// (kColormapWidth x kColormapCount) so GPU colours and the legend come from the same numbers.
inline constexpr int kColormapWidth = 256;
std::vector<std::uint8_t> colormapTable();

}  // namespace lic3d
