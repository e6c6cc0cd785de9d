// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The accepted range of every numeric parameter, in one table: validate() (core/lic_params.h,
// core/view_params.h, core/session.h), the CLI's option checks and the desktop app's sliders all
// read it. Each range names its parameter by its session key, which error messages name too (a
// front end may show its own flag or widget in its place, see Error::parameter).

#include <limits>
#include <string>
#include <string_view>

#include "core/error.h"

namespace lic3d {

struct ParameterRange {
  std::string_view key;  // the session key: "lic.length", "view.camera.fov"
  double min = 0.0;
  double max = 0.0;
  // Where the app's slider runs, inside [min, max]; a value outside it is typed in.
  double sliderMin = 0.0;
  double sliderMax = 0.0;
  bool minExclusive = false;  // (min, ... instead of [min, ...
  bool maxExclusive = false;

  // False for NaN.
  bool contains(double value) const {
    return (minExclusive ? value > min : value >= min) &&
           (maxExclusive ? value < max : value <= max);
  }
  // "[0, 4096]", "(0, 1)": the interval as messages and help texts print it.
  std::string text() const;
  // The range from a larger minimum (a front end that takes a default for the smaller values).
  constexpr ParameterRange atLeast(double newMin) const {
    ParameterRange copy = *this;
    copy.min = newMin;
    copy.sliderMin = newMin > sliderMin ? newMin : sliderMin;
    return copy;
  }
  // The same range for another parameter (the two ends of a pair, the components of a vector).
  constexpr ParameterRange named(std::string_view otherKey) const {
    ParameterRange copy = *this;
    copy.key = otherKey;
    return copy;
  }
};

// InvalidInput naming the key unless `range` contains `value`: "lic.length must be in [0, 4096],
// got 5000".
Result<void> checkRange(const ParameterRange& range, double value);

// The longest LIC length: streamlines of 2 * 4096 samples are far beyond any useful picture.
inline constexpr int kMaxLicLength = 4096;
inline constexpr int kMaxGridSize = 2048;    // per axis of an analytic field's grid
inline constexpr int kMaxImageSize = 16384;  // per side of a picture

namespace ranges {

// ---- LicParams and the noise
// ---------------------------------------------------------------------
inline constexpr ParameterRange kLength{"lic.length", 0, kMaxLicLength, 0, 100};
inline constexpr ParameterRange kStep{"lic.step", 1e-3, 8, 0.1, 2};
inline constexpr ParameterRange kSparsityPoints{"lic.sparsity.points", 0, 1 << 30, 0, 1 << 20};
inline constexpr ParameterRange kSparsityRadius{"lic.sparsity.radius", 0, 4096, 0, 8};
inline constexpr ParameterRange kSparsityRatio{"lic.sparsity.ratio", 0, 1, 0.01, 0.99, true, true};
inline constexpr ParameterRange kSeedSpots{"noise.seed_spots", 0, 1 << 30, 0, 1 << 20};
inline constexpr ParameterRange kSeedFraction{"noise.seed_fraction", 0, 0.5, 0, 0.02};
inline constexpr ParameterRange kSparsityAmount{"lic.sparsity.amount", 0, 0.99, 0, 0.95};

// ---- The session -------------------------------------------------------------------------------
inline constexpr ParameterRange kGrid{"field.grid", 1, kMaxGridSize, 1, 512};
inline constexpr ParameterRange kResolution{"field.resolution", 2, kMaxGridSize, 2, 512};
inline constexpr ParameterRange kTime{"time", -1e12, 1e12, 0, 1};
// 0 (sampled exactly) or 2.. steps; 1 is refused separately.
inline constexpr ParameterRange kTimeSteps{"time_steps", 0, 100000, 0, 1024};
inline constexpr ParameterRange kPlaneIndex{"plane.index", -1, kMaxGridSize * 8, -1, 2048};
inline constexpr ParameterRange kPlaneWidth{"plane.width", 0, kMaxImageSize, 0, 4096};
inline constexpr ParameterRange kPlaneHeight = kPlaneWidth.named("plane.height");
inline constexpr ParameterRange kPlanePoint{"plane.point", -10, 10, 0, 1};
inline constexpr ParameterRange kPlaneNormal{"plane.normal", -1, 1, -1, 1};

// ---- ViewParams --------------------------------------------------------------------------------
inline constexpr ParameterRange kImageWidth{"view.width", 1, kMaxImageSize, 1, 4096};
inline constexpr ParameterRange kImageHeight = kImageWidth.named("view.height");
inline constexpr ParameterRange kSlices{"view.slices", 0, kMaxImageSize, 0, 1024};
inline constexpr ParameterRange kAzimuth{"view.camera.azimuth", -1e6, 1e6, -180, 180};
inline constexpr ParameterRange kElevation{"view.camera.elevation", -90, 90, -89, 89};
inline constexpr ParameterRange kDistance{"view.camera.distance", 0, 1000, 0, 10};
inline constexpr ParameterRange kFov{"view.camera.fov", 1, 170, 5, 120};
inline constexpr ParameterRange kAlpha{"view.alpha", 0, 1, 0, 1};
inline constexpr ParameterRange kOpticalDepth{"view.optical_depth", 0, 20, 0, 4};
inline constexpr ParameterRange kRangeTail{"view.range_tail", 0, 0.25, 0, 0.05};
inline constexpr ParameterRange kWindowPercentiles{"view.window_percentiles", 0, 1, 0, 1};
inline constexpr ParameterRange kWindow{"view.window", 0, 1, 0, 1};
inline constexpr ParameterRange kGain{"view.gain", 0, 100, 0, 4};
inline constexpr ParameterRange kBrightness{"view.brightness", -1, 1, -1, 1};
inline constexpr ParameterRange kColorRange{"view.color_range", -1e30, 1e30, 0, 1};
inline constexpr ParameterRange kMagnitudeOpacity{"view.magnitude_opacity", 0, 100, 0, 4};
inline constexpr ParameterRange kMagnitudeThreshold{"view.magnitude_threshold", 0, 1, 0, 1};
inline constexpr ParameterRange kClipMin{"view.clip_min", 0, 1, 0, 1};
inline constexpr ParameterRange kClipMax = kClipMin.named("view.clip_max");
inline constexpr ParameterRange kRoiCenter{"view.roi_center", -10, 10, 0, 1};
inline constexpr ParameterRange kClipPlanePoint = kRoiCenter.named("view.clip_plane_point");
inline constexpr ParameterRange kClipPlaneNormal{"view.clip_plane_normal", -1, 1, -1, 1};
inline constexpr ParameterRange kRoiSize{"view.roi_size", 1e-3, 10, 0.01, 1.5};
inline constexpr ParameterRange kRoiRotation{"view.roi_rotation", -3600, 3600, -180, 180};
inline constexpr ParameterRange kFogRange{"view.fog_range", -10, 10, -0.5, 1.5};
inline constexpr ParameterRange kBackground{"view.background", 0, 1, 0, 1};
inline constexpr ParameterRange kFogColor = kBackground.named("view.fog_color");
inline constexpr ParameterRange kEyeSeparation{"view.eye_separation", 0, 100, 0, 0.3};
inline constexpr ParameterRange kZeroParallax{"view.zero_parallax", 0, 1000, 0, 10};
inline constexpr ParameterRange kAmbient{"view.light.ambient", 0, 10, 0, 1};
inline constexpr ParameterRange kDiffuse{"view.light.diffuse", 0, 10, 0, 1.5};
inline constexpr ParameterRange kSpecular{"view.light.specular", 0, 10, 0, 1.5};
inline constexpr ParameterRange kOpacityFloor{"view.opacity_floor", 0, 1, 0, 1};
inline constexpr ParameterRange kHalo{"view.halo", 0, 4, 0, 2};
inline constexpr ParameterRange kHaloRadius{"view.halo_radius", 0.25, 8, 0.5, 4};
inline constexpr ParameterRange kOcclusion{"view.occlusion", 0, 1, 0, 1};
inline constexpr ParameterRange kFontSize{"view.font_size", 0, 1024, 0, 64};
// --scale (scaledView): not a key of its own, the session keeps the sizes it gives.
inline constexpr ParameterRange kScale{"scale", 0.05, 64, 0.25, 8};
inline constexpr ParameterRange kShininess{"view.light.shininess", 1, 1000, 1, 128};

}  // namespace ranges

// The range of the parameter with session key `key` among those above, or null.
const ParameterRange* findParameterRange(std::string_view key);

}  // namespace lic3d
