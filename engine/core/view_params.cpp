// SPDX-License-Identifier: BSD-3-Clause
#include "core/view_params.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

#include "core/parameter_ranges.h"
#include "core/text.h"

namespace lic3d {
glm::vec2 greyTransfer(const ViewParams& view, const TransferFacts& facts) {
  float scale = 1.0f, offset = 0.0f;  // grey before gain and brightness
  auto window = [&](float low, float high) {
    const float width = std::max(high - low, 1e-6f);
    scale = 1.0f / width;
    offset = -low / width;
  };
  if (view.manualWindow) {
    window(view.windowLow, view.windowHigh);
  } else if (view.percentileWindow && facts.intensities && facts.intensities->total() > 0) {
    window(static_cast<float>(facts.intensities->percentile(view.windowPercentiles.x)),
           static_cast<float>(facts.intensities->percentile(view.windowPercentiles.y)));
  } else if (view.contrast && facts.intensityMean < kSparseIntensityMean && facts.intensities &&
             facts.intensities->total() > 0) {
    window(static_cast<float>(facts.intensities->percentile(kSparseWindowPercentiles.x)),
           static_cast<float>(facts.intensities->percentile(kSparseWindowPercentiles.y)));
  } else if (view.contrast) {
    // Histogram stretch: the drawn voxels' mean goes to 0.5, their deviation to the target.
    scale = kContrastTargetDeviation / std::max(facts.intensityDeviation, 1e-4f);
    offset = 0.5f - scale * facts.intensityMean;
  }
  // grey = 0.5 + gain * (grey0 - 0.5) + brightness
  return {view.gain * scale, 0.5f + view.gain * (offset - 0.5f) + view.brightness};
}

namespace {

bool straddlesZero(double min, double max) { return min < 0.0 && max > 0.0; }

// [-m, m], m the larger magnitude of the range's ends.
ColorRange symmetric(ColorRange range) {
  const float m = std::max(std::abs(range.low), std::abs(range.high));
  return {-m, m};
}

ColorRange automaticRange(const ViewParams& view, const ValueHistogram* values, float min,
                          float max) {
  if (view.rangeTail > 0.0f && values && values->total() > 0) {
    const auto low = static_cast<float>(values->percentile(view.rangeTail));
    const auto high = static_cast<float>(values->percentile(1.0 - view.rangeTail));
    if (high > low) return {low, high};
  }
  return {min, max};
}

}  // namespace

namespace {

ColorRange automaticColorRange(const ViewParams& view, const TransferFacts& facts) {
  return automaticRange(view, facts.colorValues.get(), facts.minMagnitude, facts.maxMagnitude);
}

ColorRange automaticOpacityRange(const ViewParams& view, const ValueHistogram& values) {
  return automaticRange(view, &values, static_cast<float>(values.min),
                        static_cast<float>(values.max));
}

}  // namespace

bool divergingColor(const ViewParams& view, const TransferFacts& facts) {
  if (!view.divergingWhenSigned || !view.autoColorRange || !view.transfer.colors.empty())
    return false;
  const ColorRange range = automaticColorRange(view, facts);
  return straddlesZero(range.low, range.high);
}

bool signedOpacity(const ViewParams& view, const TransferFacts& facts) {
  if (view.opacityBy == view.colorBy || !facts.opacityValues) return divergingColor(view, facts);
  if (!view.divergingWhenSigned) return false;
  const ColorRange range = automaticOpacityRange(view, *facts.opacityValues);
  return straddlesZero(range.low, range.high);
}

ColorRange colorRange(const ViewParams& view, const TransferFacts& facts) {
  if (!view.autoColorRange) return {view.colorLow, view.colorHigh};
  const ColorRange range = automaticColorRange(view, facts);
  return divergingColor(view, facts) ? symmetric(range) : range;
}

ColorRange opacityRange(const ViewParams& view, const TransferFacts& facts) {
  if (view.opacityBy == view.colorBy || !facts.opacityValues) return colorRange(view, facts);
  const ColorRange range = automaticOpacityRange(view, *facts.opacityValues);
  return signedOpacity(view, facts) ? symmetric(range) : range;
}

ViewParams shownView(const ViewParams& view, const TransferFacts& facts) {
  ViewParams shown = view;
  if (divergingColor(view, facts)) shown.colormap = Colormap::CoolWarm;
  const bool ramp = view.magnitudeOpacity > 0.0f || view.magnitudeThreshold > 0.0f;
  if (ramp && view.transfer.opacities.empty() && signedOpacity(view, facts)) {
    // The ramp of the size s = |2t - 1| (t = 0.5 is zero), at 33 sizes and at the threshold's
    // step, mirrored about t = 0.5.
    std::vector<double> sizes;
    for (int k = 0; k <= 32; ++k) sizes.push_back(k / 32.0);
    const double threshold = view.magnitudeThreshold;
    if (threshold > 0.0) {
      std::erase_if(sizes, [&](double s) { return s < threshold; });
      sizes.insert(sizes.begin(), {0.0, std::max(threshold - 1e-4, 0.0), threshold});
    }
    std::vector<OpacityPoint>& points = shown.transfer.opacities;
    for (const double s : sizes) {
      const double alpha = s < threshold ? 0.0 : std::pow(s, view.magnitudeOpacity);
      points.push_back({0.5 + 0.5 * s, alpha});
      if (s > 0.0) points.push_back({0.5 - 0.5 * s, alpha});
    }
    std::sort(points.begin(), points.end(),
              [](const OpacityPoint& a, const OpacityPoint& b) { return a.x < b.x; });
  }
  return shown;
}

glm::vec3 viewColor(const ViewParams& view, float t) {
  return view.transfer.colors.empty() ? sampleColormap(view.colormap, t) : view.transfer.color(t);
}

float opacityWeight(const ViewParams& view, float t) {
  if (!view.transfer.opacities.empty()) return static_cast<float>(view.transfer.opacity(t));
  if (view.magnitudeOpacity > 0.0f || view.magnitudeThreshold > 0.0f)
    return t < view.magnitudeThreshold
               ? 0.0f
               : std::max(std::pow(t, view.magnitudeOpacity), view.opacityFloor);
  return 1.0f;
}

float resolvedAlpha(const ViewParams& view, const TransferFacts& facts, Dims dims) {
  if (!(view.opticalDepth > 0.0f)) return view.alpha;
  // Cauchy's mean chord of a convex body, 4 V / S: the mean length of a ray through the box.
  const double a = dims.x, b = dims.y, c = dims.z;
  const double chord = 2.0 * a * b * c / std::max(a * b + b * c + c * a, 1.0);
  double grey = 1.0;
  if (view.opacityMode == OpacityMode::Intensity && facts.intensities &&
      facts.intensities->total() > 0) {
    const glm::vec2 transfer = greyTransfer(view, facts);
    grey = facts.intensities->mean(
        [&](double i) { return std::clamp(transfer.x * i + transfer.y, 0.0, 1.0); });
  } else if (view.opacityMode == OpacityMode::Intensity) {
    grey = 0.5;
  }
  double weight = 1.0;
  const ValueHistogram* values =
      view.opacityBy == view.colorBy ? facts.colorValues.get() : facts.opacityValues.get();
  if (values && values->total() > 0) {
    const glm::vec2 t = magnitudeTransfer(opacityRange(view, facts));
    weight = values->mean([&](double v) {
      return opacityWeight(view, std::clamp(static_cast<float>((v - t.x) * t.y), 0.0f, 1.0f));
    });
  }
  const double perVoxel = chord * facts.drawnFraction * grey * weight;
  if (!(perVoxel > 0.0)) return 1.0f;
  return static_cast<float>(std::clamp(view.opticalDepth / perVoxel, 0.005, 1.0));
}

glm::vec2 magnitudeTransfer(const ColorRange& range) {
  return {range.low, 1.0f / std::max(range.high - range.low, 1e-30f)};
}

ViewParams scaledView(const ViewParams& view, float scale) {
  ViewParams scaled = view;
  const auto times = [scale](int pixels) {
    return std::max(1, static_cast<int>(std::lround(static_cast<float>(pixels) * scale)));
  };
  scaled.width = times(view.width);
  scaled.height = times(view.height);
  scaled.fontSize = view.fontSize * scale;  // 0, the automatic size, follows the height
  return scaled;
}

Result<void> validate(const ViewParams& view) {
  namespace r = ranges;
  LIC3D_TRY(checkRange(r::kImageWidth, view.width));
  LIC3D_TRY(checkRange(r::kImageHeight, view.height));
  LIC3D_TRY(checkRange(r::kSlices, view.slices));
  LIC3D_TRY(checkRange(r::kAzimuth, view.camera.azimuth));
  LIC3D_TRY(checkRange(r::kElevation, view.camera.elevation));
  LIC3D_TRY(checkRange(r::kDistance, view.camera.distance));
  LIC3D_TRY(checkRange(r::kFov, view.camera.fovY));
  LIC3D_TRY(checkRange(r::kFontSize, view.fontSize));
  for (int c = 0; c < 3; ++c) {
    LIC3D_TRY(checkRange(r::kBackground, view.background[c]));
    LIC3D_TRY(checkRange(r::kFogColor, view.fogColor[c]));
  }
  LIC3D_TRY(checkRange(r::kAlpha, view.alpha));
  LIC3D_TRY(checkRange(r::kOpticalDepth, view.opticalDepth));
  LIC3D_TRY(checkRange(r::kRangeTail, view.rangeTail));
  LIC3D_TRY(checkRange(r::kWindowPercentiles, view.windowPercentiles.x));
  LIC3D_TRY(checkRange(r::kWindowPercentiles, view.windowPercentiles.y));
  if (view.percentileWindow && !(view.windowPercentiles.x < view.windowPercentiles.y))
    return parameterError(r::kWindowPercentiles.key, "needs LOW < HIGH");
  if (view.colorBy.empty()) return parameterError("view.color_by", "must name a scalar");
  if (view.opacityBy.empty()) return parameterError("view.opacity_by", "must name a scalar");
  if (Result<void> tf = validate(view.transfer, "view.transfer_function"); !tf) {
    Error e = std::move(tf).error();
    e.parameter = "view.transfer_function";
    return e;
  }
  if (view.manualWindow) {
    LIC3D_TRY(checkRange(r::kWindow, view.windowLow));
    LIC3D_TRY(checkRange(r::kWindow, view.windowHigh));
    if (!(view.windowLow < view.windowHigh)) return parameterError(r::kWindow.key, "needs LO < HI");
  }
  LIC3D_TRY(checkRange(r::kGain, view.gain));
  LIC3D_TRY(checkRange(r::kBrightness, view.brightness));
  if (!view.autoColorRange) {
    LIC3D_TRY(checkRange(r::kColorRange, view.colorLow));
    LIC3D_TRY(checkRange(r::kColorRange, view.colorHigh));
    if (!(view.colorLow < view.colorHigh))
      return parameterError(r::kColorRange.key, "needs MIN < MAX");
  }
  LIC3D_TRY(checkRange(r::kMagnitudeOpacity, view.magnitudeOpacity));
  LIC3D_TRY(checkRange(r::kMagnitudeThreshold, view.magnitudeThreshold));
  for (int a = 0; a < 3; ++a) {
    LIC3D_TRY(checkRange(r::kClipMin, view.clipMin[a]));
    LIC3D_TRY(checkRange(r::kClipMax, view.clipMax[a]));
    if (!(view.clipMin[a] < view.clipMax[a]))
      return parameterError(r::kClipMin.key, "needs min < max on each axis");
    LIC3D_TRY(checkRange(r::kRoiCenter, view.roiCenter[a]));
    LIC3D_TRY(checkRange(r::kClipPlanePoint, view.clipPlanePoint[a]));
    LIC3D_TRY(checkRange(r::kClipPlaneNormal, view.clipPlaneNormal[a]));
    LIC3D_TRY(checkRange(r::kRoiRotation, view.roiRotation[a]));
  }
  if (view.clipPlane && !(glm::length(view.clipPlaneNormal) > 1e-6f))
    return parameterError(r::kClipPlaneNormal.key,
                          "must not be zero: the normal given is (" +
                              tripleText(glm::dvec3(view.clipPlaneNormal), ", ") +
                              "), its length must exceed 1e-6");
  LIC3D_TRY(checkRange(r::kRoiSize, view.roiSize));
  LIC3D_TRY(checkRange(r::kFogRange, view.fogStart));
  LIC3D_TRY(checkRange(r::kFogRange, view.fogEnd));
  if (view.fog && !(view.fogStart < view.fogEnd))
    return parameterError(r::kFogRange.key, "needs START < END");
  if (view.stereo != StereoMode::None && view.camera.orthographic)
    return parameterError("view.stereo",
                          "needs a perspective camera, not view.camera.orthographic");
  LIC3D_TRY(checkRange(r::kEyeSeparation, view.eyeSeparation));
  LIC3D_TRY(checkRange(r::kZeroParallax, view.zeroParallax));
  if (view.stereo == StereoMode::SideBySide && 2 * view.width > kMaxImageSize)
    return parameterError(r::kImageWidth.key, "must be at most " +
                                                  std::to_string(kMaxImageSize / 2) +
                                                  " with side-by-side stereo, which doubles it");
  LIC3D_TRY(checkRange(r::kAmbient, view.light.ambient));
  LIC3D_TRY(checkRange(r::kDiffuse, view.light.diffuse));
  LIC3D_TRY(checkRange(r::kSpecular, view.light.specular));
  LIC3D_TRY(checkRange(r::kOpacityFloor, view.opacityFloor));
  LIC3D_TRY(checkRange(r::kHalo, view.halo));
  LIC3D_TRY(checkRange(r::kHaloRadius, view.haloRadius));
  LIC3D_TRY(checkRange(r::kOcclusion, view.occlusion));
  return checkRange(r::kShininess, view.light.shininess);
}

}  // namespace lic3d
