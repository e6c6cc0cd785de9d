#include "core/view_params.h"

#include <algorithm>
#include <string>

#include "core/parameter_ranges.h"

namespace lic3d {
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
  namespace r = ranges;
  LIC3D_TRY(checkRange(r::kImageWidth, view.width));
  LIC3D_TRY(checkRange(r::kImageHeight, view.height));
  LIC3D_TRY(checkRange(r::kSlices, view.slices));
  LIC3D_TRY(checkRange(r::kAzimuth, view.camera.azimuth));
  LIC3D_TRY(checkRange(r::kElevation, view.camera.elevation));
  LIC3D_TRY(checkRange(r::kDistance, view.camera.distance));
  LIC3D_TRY(checkRange(r::kFov, view.camera.fovY));
  for (int c = 0; c < 3; ++c) {
    LIC3D_TRY(checkRange(r::kBackground, view.background[c]));
    LIC3D_TRY(checkRange(r::kFogColor, view.fogColor[c]));
  }
  LIC3D_TRY(checkRange(r::kAlpha, view.alpha));
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
    LIC3D_TRY(checkRange(r::kRoiRotation, view.roiRotation[a]));
  }
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
  return checkRange(r::kShininess, view.light.shininess);
}

}  // namespace lic3d
