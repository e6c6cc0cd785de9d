#include "core/view_params.h"

#include <algorithm>
#include <string>

namespace lic3d {
namespace {

bool inUnit(float v) { return v >= 0.0f && v <= 1.0f; }

}  // namespace

glm::vec2 greyTransfer(const ViewParams& view, const TransferFacts& facts) {
  float scale = 1.0f, offset = 0.0f;  // grey before gain and brightness
  if (view.manualWindow) {
    const float width = std::max(view.windowHigh - view.windowLow, 1e-6f);
    scale = 1.0f / width;
    offset = -view.windowLow / width;
  } else if (view.contrast) {
    // Histogram stretch: the drawn voxels' mean goes to 0.5, their deviation to the target.
    scale = kContrastTargetDeviation / std::max(facts.intensityDeviation, 1e-4f);
    offset = 0.5f - scale * facts.intensityMean;
  }
  // grey = 0.5 + gain * (grey0 - 0.5) + brightness
  return {view.gain * scale, 0.5f + view.gain * (offset - 0.5f) + view.brightness};
}

ColorRange colorRange(const ViewParams& view, const TransferFacts& facts) {
  return view.autoColorRange ? ColorRange{facts.minMagnitude, facts.maxMagnitude}
                             : ColorRange{view.colorLow, view.colorHigh};
}

glm::vec2 magnitudeTransfer(const ColorRange& range) {
  return {range.low, 1.0f / std::max(range.high - range.low, 1e-30f)};
}

Result<void> validate(const ViewParams& view) {
  if (view.width < 1 || view.height < 1 || view.width > 16384 || view.height > 16384)
    return inputError("image size must be 1..16384 pixels per side, got " +
                      std::to_string(view.width) + "x" + std::to_string(view.height));
  if (!inUnit(view.alpha)) return inputError("--alpha must be in [0,1]");
  if (view.manualWindow && !(view.windowLow < view.windowHigh))
    return inputError("--window: need LO < HI");
  if (!view.autoColorRange && !(view.colorLow < view.colorHigh))
    return inputError("--color-range: need MIN < MAX");
  if (view.magnitudeOpacity < 0.0f || !inUnit(view.magnitudeThreshold))
    return inputError("--magnitude-opacity must be >= 0 and --magnitude-threshold in [0,1]");
  for (int a = 0; a < 3; ++a)
    if (!inUnit(view.clipMin[a]) || !inUnit(view.clipMax[a]) ||
        !(view.clipMin[a] < view.clipMax[a]))
      return inputError("--clip: each axis needs 0 <= min < max <= 1");
  if (view.roi != RoiShape::None && !(view.roiSize > 0.0f))
    return inputError("--roi-size must be positive");
  if (view.fog && !(view.fogStart < view.fogEnd)) return inputError("--fog: need START < END");
  if (view.stereo != StereoMode::None && view.camera.orthographic)
    return inputError("--stereo needs a perspective camera (drop --ortho)");
  if (view.eyeSeparation < 0.0f || view.zeroParallax < 0.0f)
    return inputError("--eye-separation and --zero-parallax must not be negative");
  if (view.stereo == StereoMode::SideBySide && view.width > 8192)
    return inputError("side-by-side stereo doubles the width: --width must be at most 8192");
  return {};
}

}  // namespace lic3d
