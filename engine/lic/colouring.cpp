#include "lic/colouring.h"

#include <algorithm>
#include <cmath>

#include "core/colormap.h"
#include "lic/legend.h"
#include "lic/lic_reference.h"

namespace lic3d {
namespace {

std::uint8_t toByte(float value) {
  return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0f, 1.0f) * 255.0f));
}

}  // namespace

RgbaImage colourLic2D(const ScalarVolume& lic, const VectorField& field, const ViewParams& view) {
  // The image's own statistics feed the contrast stretch, as the histogram pass does in 3D.
  double sum = 0.0, squares = 0.0;
  for (const float v : lic.values) {
    sum += v;
    squares += static_cast<double>(v) * v;
  }
  const double n = std::max<double>(1.0, static_cast<double>(lic.values.size()));
  TransferFacts facts;
  facts.minMagnitude = static_cast<float>(minMagnitude(field));
  facts.maxMagnitude = static_cast<float>(maxMagnitude(field));
  facts.intensityMean = static_cast<float>(sum / n);
  facts.intensityDeviation =
      static_cast<float>(std::sqrt(std::max(0.0, squares / n - (sum / n) * (sum / n))));
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
        rgb = sampleColormap(view.colormap, t) * grey;
      }
      const std::size_t p = 4 * (static_cast<std::size_t>(image.height - 1 - j) * image.width + i);
      image.pixels[p + 0] = toByte(rgb.r);
      image.pixels[p + 1] = toByte(rgb.g);
      image.pixels[p + 2] = toByte(rgb.b);
      image.pixels[p + 3] = 255;
    }
  if (view.legend && byMagnitude)
    drawLegend(image, view.colormap, low, high, "|v|", view.background);
  return image;
}

RgbaVolume colourLicVolume(const ScalarVolume& lic, const VectorField& field,
                           const ViewParams& view, const TransferFacts& facts) {
  const glm::vec2 transfer = greyTransfer(view, facts);
  const glm::vec2 magnitude = magnitudeTransfer(colorRange(view, facts));
  const bool byMagnitude = view.color == ColorMode::Magnitude;
  const bool magnitudeOpacity = view.magnitudeOpacity > 0.0f || view.magnitudeThreshold > 0.0f;

  RgbaVolume out;
  out.dims = lic.dims;
  out.geometry = field.geometry;
  out.rgba.resize(4 * lic.values.size());
  for (std::size_t i = 0; i < lic.values.size(); ++i) {
    const float grey = std::clamp(transfer.x * lic.values[i] + transfer.y, 0.0f, 1.0f);
    float alpha = view.opacityMode == OpacityMode::Intensity ? view.alpha * grey : view.alpha;
    if (!lic.drawn.empty() && !lic.drawn[i]) alpha = 0.0f;
    glm::vec3 rgb(grey);
    if (byMagnitude || magnitudeOpacity) {
      const float speed = glm::length(field.vectors[i]);
      const float t = std::clamp((speed - magnitude.x) * magnitude.y, 0.0f, 1.0f);
      if (byMagnitude) rgb = sampleColormap(view.colormap, t) * grey;
      if (magnitudeOpacity)
        alpha *= t < view.magnitudeThreshold ? 0.0f : std::pow(t, view.magnitudeOpacity);
    }
    out.rgba[4 * i + 0] = toByte(rgb.r);
    out.rgba[4 * i + 1] = toByte(rgb.g);
    out.rgba[4 * i + 2] = toByte(rgb.b);
    out.rgba[4 * i + 3] = toByte(alpha);
  }
  return out;
}

}  // namespace lic3d
