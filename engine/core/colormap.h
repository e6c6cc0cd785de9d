// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Colour maps for magnitude: the thesis' blue-yellow-red ramp (5.1.2) and two perceptual maps,
// each a table of 256 colours that the GPU samples and the legend and the CPU colouring read, so
// they cannot disagree. A transfer function (core/transfer_function.h) can replace them.

#include <array>
#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/enum_names.h"

namespace lic3d {

struct TransferFunction;

enum class Colormap : std::uint32_t {
  Thesis = 0,    // blue -> yellow -> red, linear between the three
  Viridis = 1,   // matplotlib's viridis (van der Walt & Smith): perceptually uniform, CC0 data
  CoolWarm = 2,  // K. Moreland's diverging cool-warm map (2009), interpolated in Msh space
};
inline constexpr int kColormapCount = 3;
LIC3D_ENUM_NAMES(Colormap, {Colormap::Thesis, "thesis"}, {Colormap::Viridis, "viridis"},
                 {Colormap::CoolWarm, "coolwarm"})

inline constexpr int kColormapWidth = 256;

// The map's 256 colours, entry i at t = i / 255, display RGB in [0,1].
std::span<const glm::vec3, kColormapWidth> colormapColors(Colormap map);

// The colour at t in [0,1] (clamped): linear between the table's entries, as the GPU samples it.
glm::vec3 sampleColormap(Colormap map, float t);

// The colour map table the slices sample, RGBA8, kColormapWidth texels per row: rows
// 0..kColormapCount-1 are the built-in maps (alpha 1); row kColormapCount (kCustomColormapRow)
// is `tf`'s colours (or the built-in `map` when it has none) with its opacity in alpha.
inline constexpr int kCustomColormapRow = kColormapCount;  // kSliceCustomColormapRow in GLSL
inline constexpr int kColormapRows = kColormapCount + 1;
std::vector<std::uint8_t> colormapTable(const TransferFunction& tf, Colormap map);

// Moreland's diverging interpolation in Msh space between two display colours, at w in [0,1].
glm::vec3 divergingColor(glm::vec3 low, glm::vec3 high, double w);

}  // namespace lic3d
