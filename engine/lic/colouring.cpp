// SPDX-License-Identifier: BSD-3-Clause
#include "lic/colouring.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/colormap.h"
#include "lic/annotation.h"
#include "lic/legend.h"
#include "lic/lic_reference.h"

namespace lic3d {
namespace {

std::uint8_t toByte(float value) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

RgbaImage colourLic2D(const ScalarVolume& lic, const VectorField& field, const ViewParams& view,
                      const std::vector<std::uint8_t>& outside) {
  // The plane's point nearest to pixel (i, j) (the 2D LIC's mapping, lic_reference.h), for the
  // outside mask.
  const auto isOutside = [&](int i, int j) {
    if (outside.empty()) return false;
    const auto at = [](int p, int pixels, int points) {
      const double x = (p + 0.5) * points / pixels - 0.5;
      return std::clamp(static_cast<int>(std::lround(x)), 0, points - 1);
    };
    return outside[voxelIndex(field.dims, at(i, lic.dims.x, field.dims.x),
                              at(j, lic.dims.y, field.dims.y), 0)] != 0;
  };
  // The image's own statistics feed the contrast stretch, as the histogram pass does in 3D.
  double sum = 0.0, squares = 0.0, n = 0.0;
  std::vector<float> drawn;  // the percentile window's values
  drawn.reserve(lic.values.size());
  for (int j = 0; j < lic.dims.y; ++j)
    for (int i = 0; i < lic.dims.x; ++i) {
      if (isOutside(i, j)) continue;
      const double v = lic.at(i, j, 0);
      drawn.push_back(static_cast<float>(v));
      sum += v;
      squares += v * v;
      n += 1.0;
    }
  n = std::max(n, 1.0);
  TransferFacts facts;
  facts.minMagnitude = static_cast<float>(minMagnitude(field));
  facts.maxMagnitude = static_cast<float>(maxMagnitude(field));
  facts.intensityMean = static_cast<float>(sum / n);
  facts.intensityDeviation =
      static_cast<float>(std::sqrt(std::max(0.0, squares / n - (sum / n) * (sum / n))));
  // The percentile window's values; the sparse rule of the contrast stretch stays 3D's alone.
  if (view.percentileWindow)
    facts.intensities = std::make_shared<const ValueHistogram>(histogramOf(drawn));
  // The slices' own numbers for this view: grey = transfer.x * I + transfer.y,
  // t = (|v| - magnitude.x) * magnitude.y.
  const glm::vec2 transfer = greyTransfer(view, facts);
  const ColorRange range = colorRange(view, facts);
  const glm::vec2 magnitude = magnitudeTransfer(range);
  const bool byMagnitude = view.color == ColorMode::Magnitude;
  // A field of one speed (the wave) has no range to spread: rounding alone would pick the ends.
  const float low = range.low, high = range.high;
  const bool oneSpeed = high - low <= 1e-6f * std::max(std::abs(high), 1e-30f);
  const FieldSampler sampler(field, lic.dims);
  const glm::dvec3 unit = sampler.unitScale();

  RgbaImage image;
  image.width = lic.dims.x;
  image.height = lic.dims.y;
  image.pixels.resize(static_cast<std::size_t>(image.width) * image.height * 4);
  for (int j = 0; j < lic.dims.y; ++j)
    for (int i = 0; i < lic.dims.x; ++i) {
      const float grey = std::clamp(transfer.x * lic.at(i, j, 0) + transfer.y, 0.0f, 1.0f);
      glm::vec3 rgb(grey);
      if (byMagnitude) {
        const glm::dvec3 v = sampler.at(glm::dvec3(i, j, 0)) / unit;  // physical
        const float t =
            oneSpeed ? 0.5f
                     : std::clamp((static_cast<float>(glm::length(v)) - magnitude.x) * magnitude.y,
                                  0.0f, 1.0f);
        rgb = viewColor(view, t) * grey;
      }
      if (isOutside(i, j)) rgb = view.background;
      const std::size_t p = 4 * (static_cast<std::size_t>(image.height - 1 - j) * image.width + i);
      image.pixels[p + 0] = toByte(rgb.r);
      image.pixels[p + 1] = toByte(rgb.g);
      image.pixels[p + 2] = toByte(rgb.b);
      image.pixels[p + 3] = 255;
    }
  if (view.legend && byMagnitude) {
    const LegendSpec legend{[&view](float t) { return viewColor(view, t); }, low, high,
                            viewLegendTitle(view, "speed", field.unit)};
    return annotatedPicture(image, &legend, view.title, view.background, view.fontSize);
  }
  return annotatedPicture(image, nullptr, view.title, view.background, view.fontSize);
}

RgbaVolume colourLicVolume(const ScalarVolume& lic, const VectorField& field,
                           const ViewParams& given, const TransferFacts& facts,
                           const VolumeScalars& scalars) {
  const ViewParams view = shownView(given, facts);
  const glm::vec2 transfer = greyTransfer(view, facts);
  const glm::vec2 colorT = magnitudeTransfer(colorRange(view, facts));
  const glm::vec2 opacityT = magnitudeTransfer(opacityRange(view, facts));
  const bool byColor = view.color == ColorMode::Magnitude;
  const bool weighted = view.magnitudeOpacity > 0.0f || view.magnitudeThreshold > 0.0f ||
                        !view.transfer.opacities.empty();
  const float alphaPerVoxel = resolvedAlpha(view, facts, lic.dims);

  RgbaVolume out;
  out.dims = lic.dims;
  out.geometry = field.geometry;
  out.rgba.resize(4 * lic.values.size());
  for (std::size_t i = 0; i < lic.values.size(); ++i) {
    const float grey = std::clamp(transfer.x * lic.values[i] + transfer.y, 0.0f, 1.0f);
    float alpha = view.opacityMode == OpacityMode::Intensity ? alphaPerVoxel * grey : alphaPerVoxel;
    if (!lic.drawn.empty() && !lic.drawn[i]) alpha = 0.0f;
    glm::vec3 rgb(grey);
    if (byColor || weighted) {
      // In double: the square of a float speed of 1e25 (or 1e-20) leaves the float range.
      const auto speed = static_cast<float>(glm::length(glm::dvec3(field.vectors[i])));
      const float colorValue = scalars.color ? scalars.color->values[i] : speed;
      const float opacityValue = scalars.opacity ? scalars.opacity->values[i] : speed;
      if (byColor)
        rgb = viewColor(view, std::clamp((colorValue - colorT.x) * colorT.y, 0.0f, 1.0f)) * grey;
      if (weighted)
        alpha *=
            opacityWeight(view, std::clamp((opacityValue - opacityT.x) * opacityT.y, 0.0f, 1.0f));
      if (std::isnan(colorValue) || std::isnan(opacityValue)) alpha = 0.0f;
    }
    out.rgba[4 * i + 0] = toByte(rgb.r);
    out.rgba[4 * i + 1] = toByte(rgb.g);
    out.rgba[4 * i + 2] = toByte(rgb.b);
    out.rgba[4 * i + 3] = toByte(alpha);
  }
  return out;
}

}  // namespace lic3d
