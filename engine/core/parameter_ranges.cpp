// SPDX-License-Identifier: BSD-3-Clause
#include "core/parameter_ranges.h"

#include "core/text.h"

namespace lic3d {

std::string ParameterRange::text() const {
  return (minExclusive ? "(" : "[") + formatNumber(min) + ", " + formatNumber(max) +
         (maxExclusive ? ")" : "]");
}

Result<void> checkRange(const ParameterRange& range, double value) {
  if (range.contains(value)) return {};
  return parameterError(range.key, "must be in " + range.text() + ", got " + formatNumber(value));
}

const ParameterRange* findParameterRange(std::string_view key) {
  static constexpr const ParameterRange* kAll[] = {
      &ranges::kLength,
      &ranges::kStep,
      &ranges::kSparsityPoints,
      &ranges::kSparsityRadius,
      &ranges::kSparsityRatio,
      &ranges::kSeedSpots,
      &ranges::kSeedFraction,
      &ranges::kSparsityAmount,
      &ranges::kGrid,
      &ranges::kResolution,
      &ranges::kTime,
      &ranges::kTimeSteps,
      &ranges::kPlaneIndex,
      &ranges::kPlaneWidth,
      &ranges::kPlaneHeight,
      &ranges::kPlanePoint,
      &ranges::kPlaneNormal,
      &ranges::kImageWidth,
      &ranges::kImageHeight,
      &ranges::kSlices,
      &ranges::kAzimuth,
      &ranges::kElevation,
      &ranges::kDistance,
      &ranges::kFov,
      &ranges::kAlpha,
      &ranges::kOpticalDepth,
      &ranges::kRangeTail,
      &ranges::kWindowPercentiles,
      &ranges::kWindow,
      &ranges::kGain,
      &ranges::kBrightness,
      &ranges::kColorRange,
      &ranges::kMagnitudeOpacity,
      &ranges::kMagnitudeThreshold,
      &ranges::kClipMin,
      &ranges::kClipMax,
      &ranges::kRoiCenter,
      &ranges::kClipPlanePoint,
      &ranges::kClipPlaneNormal,
      &ranges::kRoiSize,
      &ranges::kRoiRotation,
      &ranges::kFogRange,
      &ranges::kBackground,
      &ranges::kFogColor,
      &ranges::kEyeSeparation,
      &ranges::kZeroParallax,
      &ranges::kAmbient,
      &ranges::kDiffuse,
      &ranges::kSpecular,
      &ranges::kOpacityFloor,
      &ranges::kHalo,
      &ranges::kHaloRadius,
      &ranges::kOcclusion,
      &ranges::kFontSize,
      &ranges::kScale,
      &ranges::kShininess,
  };
  for (const ParameterRange* range : kAll)
    if (range->key == key) return range;
  return nullptr;
}

}  // namespace lic3d
