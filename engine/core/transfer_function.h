// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Transfer functions: colour and opacity as piecewise-linear functions of a scalar, as ParaView
// stores them in its colour-map presets ("RGBPoints": x r g b ..., "Points": x opacity midpoint
// sharpness ...). Control points are kept relative: x in [0, 1] spans the view's colour (or
// opacity) range, the way ParaView rescales a preset to the data. Colour maps given by name are
// the built-in ones (core/colormap.h); a transfer function's colours replace them.

#include <cstddef>
#include <glm/vec3.hpp>
#include <string>
#include <vector>

#include "core/error.h"

namespace lic3d {

struct ColorPoint {
  double x = 0.0;  // in [0, 1]
  glm::vec3 rgb{0.0f};
  bool operator==(const ColorPoint&) const = default;
};

struct OpacityPoint {
  double x = 0.0;  // in [0, 1]
  double alpha = 0.0;
  bool operator==(const OpacityPoint&) const = default;
};

struct TransferFunction {
  std::string name;
  std::vector<ColorPoint> colors;       // empty: the view's colour map
  std::vector<OpacityPoint> opacities;  // empty: the view's magnitude opacity
  bool operator==(const TransferFunction&) const = default;

  bool empty() const { return colors.empty() && opacities.empty(); }
  // Linear between control points, constant beyond the first and the last; t clamped to [0,1].
  glm::vec3 color(double t) const;
  double opacity(double t) const;
};

// Control points sorted by x, x within [0, 1], colours and opacities within [0, 1], at least
// one point in each non-empty list; InvalidInput naming `what` otherwise.
Result<void> validate(const TransferFunction& tf, const std::string& what);

// The most bytes of a preset file lic3d reads, and so the most control points a preset holds: each
// takes four numbers and their commas, "0,0,0,0," at the least.
inline constexpr std::size_t kMaxPresetBytes = std::size_t{16} << 20;
inline constexpr std::size_t kMaxPresetPoints = kMaxPresetBytes / 8;

// A ParaView colour-map preset: one object, or an array of them (the first is taken). Its x
// values are rescaled to [0, 1] over the colour points' span (the opacity points' own span when
// there are no colour points). InvalidInput naming `source` for anything else.
Result<TransferFunction> transferFunctionFromJson(const std::string& text,
                                                  const std::string& source);
// The same as a ParaView preset array of one, which ParaView's "Import Presets" reads.
std::string transferFunctionToJson(const TransferFunction& tf);

}  // namespace lic3d
