// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How the LIC volume is drawn. Changing any of this redraws; it never recomputes the LIC volume.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <memory>
#include <string>

#include "core/camera.h"
#include "core/colormap.h"
#include "core/enum_names.h"
#include "core/error.h"
#include "core/transfer_function.h"
#include "core/value_histogram.h"
#include "core/volume.h"

namespace lic3d {

enum class Slicing {
  ViewAligned,  // planes perpendicular to the view direction (default)
  AxisAligned,  // planes perpendicular to the grid axis closest to the view direction
                // (thesis 4.1.2)
};

enum class OpacityMode {
  Constant,   // every voxel has the global alpha (thesis 5.1.1)
  Intensity,  // alpha times the grey value: dark gaps between streamlines turn clear
};

// How slices sample the LIC volume: thesis 6.4's nearest and linear; the cubic B-spline, smooth
// across voxel faces where linear sampling shows the voxels as facets; auto: cubic where a voxel
// covers more than kCubicFromPixels pixels on the screen, else linear. The B-spline smooths as
// it goes (a 1024^2 picture of a 128^3 grid, 5 pixels per voxel, turned soft) and its 8 fetches
// cost 2.7 times linear's on an H200 (docs/LOOKS.md): it is for close-ups.
enum class VolumeFilter { Nearest, Linear, Cubic, Auto };
inline constexpr float kCubicFromPixels = 6.0f;
enum class ColorMode { None, Magnitude };              // grey, or coloured by |v| (thesis 5.1.2)
enum class RoiShape { None, Sphere, Cube, Cylinder };  // thesis 5.2.2
enum class StereoMode { None, Anaglyph, SideBySide };  // thesis 5.3.2
// Thesis 5.3.3 (Phong with the streamline's principal normal), illuminated lines, and Phong with
// the normal of the streak: the LIC intensity's gradient across the flow.
enum class Lighting { None, Phong, Lines, Gradient };

LIC3D_ENUM_NAMES(Slicing, {Slicing::ViewAligned, "view"}, {Slicing::AxisAligned, "axis"})
LIC3D_ENUM_NAMES(OpacityMode, {OpacityMode::Constant, "constant"},
                 {OpacityMode::Intensity, "intensity"})
LIC3D_ENUM_NAMES(VolumeFilter, {VolumeFilter::Nearest, "nearest"}, {VolumeFilter::Linear, "linear"},
                 {VolumeFilter::Cubic, "cubic"}, {VolumeFilter::Auto, "auto"})
LIC3D_ENUM_NAMES(ColorMode, {ColorMode::None, "none"}, {ColorMode::Magnitude, "magnitude"})
LIC3D_ENUM_NAMES(RoiShape, {RoiShape::None, "none"}, {RoiShape::Sphere, "sphere"},
                 {RoiShape::Cube, "cube"}, {RoiShape::Cylinder, "cylinder"})
LIC3D_ENUM_NAMES(StereoMode, {StereoMode::None, "none"}, {StereoMode::Anaglyph, "anaglyph"},
                 {StereoMode::SideBySide, "side-by-side"})
LIC3D_ENUM_NAMES(Lighting, {Lighting::None, "none"}, {Lighting::Phong, "phong"},
                 {Lighting::Lines, "lines"}, {Lighting::Gradient, "gradient"})

struct LightTerms {
  float ambient = 0.35f;
  float diffuse = 0.75f;
  float specular = 0.35f;
  float shininess = 24.0f;

  bool operator==(const LightTerms&) const = default;
};

struct ViewParams {
  int width = 1024;  // per eye for side-by-side stereo
  int height = 1024;
  Slicing slicing = Slicing::ViewAligned;
  int slices = 0;  // 0: one slice per voxel along the view direction
  CameraParams camera;
  glm::vec3 background{0.0f, 0.0f, 0.0f};  // display RGB in [0,1]

  // Thesis 5.1.1: opacity per voxel of distance, corrected for the slice spacing.
  float alpha = 0.3f;
  // > 0: alpha is chosen from the data instead, so that a ray through the volume meets about this
  // optical depth (the volume's opacity weights, the drawn fraction and the grey measured on the
  // data; passes/slice_pass.h, resolvedAlpha). Looks set it; 0 keeps `alpha`.
  float opticalDepth = 0.0f;
  OpacityMode opacityMode = OpacityMode::Intensity;
  VolumeFilter filter = VolumeFilter::Auto;

  // Grey transfer of the LIC intensity I. With contrast (default), the drawn voxels' mean and
  // standard deviation are stretched to 0.5 and kContrastTargetDeviation (a histogram stretch);
  // without, grey = I. A manual window [low, high] maps to [0, 1] instead. Then
  // grey = 0.5 + gain * (grey - 0.5) + brightness.
  bool contrast = true;
  // The window from percentiles of the drawn voxels' LIC values instead (fractions low, high):
  // sparse volumes and seed noise, whose values a mean and deviation do not describe.
  bool percentileWindow = false;
  glm::vec2 windowPercentiles{0.01f, 0.99f};
  bool manualWindow = false;
  float windowLow = 0.0f;
  float windowHigh = 1.0f;
  float gain = 1.0f;
  float brightness = 0.0f;

  // Thesis 5.1.2: colour by a scalar through a colour map over [colorLow, colorHigh]
  // (automatic: the scalar's percentiles rangeTail and 1 - rangeTail, its min and max for 0); the
  // LIC grey modulates it. The legend is drawn beside the picture.
  ColorMode color = ColorMode::None;
  Colormap colormap = Colormap::Thesis;
  // A signed colour scalar (its automatic range has low < 0 < high: helicity) under the automatic
  // colour map and range is drawn with the diverging cool-warm map over a range symmetric about
  // zero, and a signed opacity scalar weighs by its size |value| (shownView). Choosing the map
  // (--colormap, --tf) or the range (--color-range) turns it off.
  bool divergingWhenSigned = true;
  // What colour and opacity follow: "speed" (|v|), "vorticity" (|curl v|), "helicity"
  // (v . curl v) or a point scalar of the field's file by name (loading/scalars.h).
  std::string colorBy = "speed";
  std::string opacityBy = "speed";
  float rangeTail = 0.0f;
  // Colours and opacities as functions of the scalar, replacing the colour map (its colours)
  // and the magnitude opacity (its opacities); empty by default.
  TransferFunction transfer;
  bool autoColorRange = true;
  float colorLow = 0.0f;
  float colorHigh = 1.0f;
  bool legend = false;
  // The box's edges with each axis labelled by its physical range (origin to the last voxel
  // centre, in the file's units), drawn over the picture.
  bool axes = false;
  std::string title;  // drawn above the picture when not empty
  // The legend's title ("|B| [T]"); empty: the colour quantity and its unit where the file
  // gives one ("speed [m/s]", "vorticity").
  std::string legendTitle;
  // The annotation's text size in pixels (the em; lines, ticks and gaps follow it, lic/legend.h);
  // 0: 1/50 of the picture's height (20 px at 1024), at least 10.
  float fontSize = 0.0f;

  // Thesis 5.1.3: alpha *= t^exponent, t = the opacity scalar normalised over its range (the
  // colour range when it is the colour scalar); 0 is off. Voxels with t below the threshold vanish.
  float magnitudeOpacity = 0.0f;
  float magnitudeThreshold = 0.0f;
  // The least weight t^exponent gives above the threshold: weak flow stays in the picture.
  float opacityFloor = 0.0f;

  // Thesis 5.2.1: the drawn part of the box, as fractions of it along x, y, z.
  glm::vec3 clipMin{0.0f};
  glm::vec3 clipMax{1.0f};

  // A clip plane at any orientation: the half of the box the normal points into is cut away.
  // The point is in fractions of the box, the normal in box axes.
  bool clipPlane = false;
  glm::vec3 clipPlanePoint{0.5f};
  glm::vec3 clipPlaneNormal{0.0f, 0.0f, 1.0f};

  // Thesis 5.2.2: a region of interest in fractions of the box (centre, size of the longest
  // side), rotated by Euler angles in degrees (x, then y, then z).
  RoiShape roi = RoiShape::None;
  glm::vec3 roiCenter{0.5f};
  float roiSize = 0.5f;
  glm::vec3 roiRotation{0.0f};
  bool roiOutside = false;

  // Thesis 5.3.1: linear fog between start and end, fractions of the depth from the volume's
  // nearest to its farthest point; the colour defaults to the background.
  bool fog = false;
  float fogStart = 0.0f;
  float fogEnd = 1.0f;
  bool fogColorFromBackground = true;
  glm::vec3 fogColor{0.0f};

  // Thesis 5.3.2: off-axis stereo. 0 picks defaults: separation = zero-parallax distance / 30,
  // zero parallax at the volume's centre.
  StereoMode stereo = StereoMode::None;
  float eyeSeparation = 0.0f;
  float zeroParallax = 0.0f;

  // Thesis 5.3.3.
  Lighting lighting = Lighting::None;
  LightTerms light;

  // Depth cues (docs/LOOKS.md). Halos: around a streak, up to `halo` times its opacity in the
  // background colour, `haloRadius` voxels out, so a near streak cuts the far ones it crosses
  // (0: off). Occlusion: each slice darkened by the opacity in front of it, spread over a 45
  // degree cone towards the viewer, by up to this fraction (0: off).
  float halo = 0.0f;
  float haloRadius = 1.5f;
  float occlusion = 0.0f;
  // Each pixel's samples offset along its ray by part of a slice spacing (against the slices'
  // wood-grain pattern); off gives the thesis' plain slicing.
  bool jitter = true;

  bool operator==(const ViewParams&) const = default;
};

// Grey deviation of the drawn voxels after the contrast stretch: +-2 deviations span [0,1].
inline constexpr float kContrastTargetDeviation = 0.25f;
// The stretch assumes white noise, whose LIC values centre on 0.5. Seed noise (sparse bright
// spots on black) leaves most voxels near 0: tornado 48^3 with 500 seeds has mean 0.004, median
// 0, 95th percentile 0.036, and the stretch made it an opaque block. Below this mean of the drawn
// voxels the stretch takes the window between the percentiles kSparseWindowPercentiles instead
// (the streamlines look's window), so the lit streamlines show and the rest is clear.
inline constexpr float kSparseIntensityMean = 0.25f;
inline constexpr glm::vec2 kSparseWindowPercentiles{0.85f, 0.95f};

// What a picture's colours come from besides the view: the drawn voxels' LIC mean and
// deviation (the contrast stretch) and the field's |v| over its voxels (the automatic colour
// range). The slices (GPU) and the CPU colouring (lic/colouring.h) take the same numbers.
struct TransferFacts {
  float intensityMean = 0.5f;
  float intensityDeviation = 0.1f;
  float minMagnitude = 0.0f;  // of the colour scalar over the voxels
  float maxMagnitude = 1.0f;
  // What percentile ranges, windows and the automatic alpha are measured on, where known: the
  // drawn voxels' LIC values, the colour scalar and the opacity scalar (null: the colour one).
  std::shared_ptr<const ValueHistogram> intensities;
  std::shared_ptr<const ValueHistogram> colorValues;
  std::shared_ptr<const ValueHistogram> opacityValues;
  float drawnFraction = 1.0f;  // of the voxels, the rest hidden by sparsity
};

// The grey transfer as a line, grey = x * I + y (clamped to [0,1] by its users): the window (or
// the percentile window), or the contrast stretch, then gain and brightness.
glm::vec2 greyTransfer(const ViewParams& view, const TransferFacts& facts);

// The |v| range that colour and magnitude opacity span: the view's, or the field's.
struct ColorRange {
  float low = 0.0f;
  float high = 1.0f;
};
ColorRange colorRange(const ViewParams& view, const TransferFacts& facts);
// The range the opacity scalar is normalised over: the colour range when it is the colour
// scalar, else its own automatic range.
ColorRange opacityRange(const ViewParams& view, const TransferFacts& facts);
// Whether the colour scalar is drawn diverging: its automatic range (min and max, or the
// percentiles of rangeTail) has low < 0 < high, under the view's automatic map and range
// (ViewParams::divergingWhenSigned).
bool divergingColor(const ViewParams& view, const TransferFacts& facts);
// Whether the opacity scalar weighs by its size: signed, with divergingWhenSigned, its range
// symmetric about zero (the colour range when it is the colour scalar: then diverging too).
bool signedOpacity(const ViewParams& view, const TransferFacts& facts);

// The view as drawn for these data: with divergingColor, the cool-warm map; with signedOpacity
// and the magnitude opacity, a transfer function of opacities |2t - 1|^E (0 below the threshold)
// in its place, so that both signs of the scalar show. The passes, the legend and the CPU
// colouring draw this view; sessions keep the one given.
ViewParams shownView(const ViewParams& view, const TransferFacts& facts);

// t = (|v| - x) * y maps the colour range to [0, 1].
glm::vec2 magnitudeTransfer(const ColorRange& range);

// The colour at t in [0, 1] of the colour range: the transfer function's colours, else the
// colour map (the table the slices sample, core/colormap.h).
glm::vec3 viewColor(const ViewParams& view, float t);

// The opacity weight of a voxel whose opacity scalar is at t in [0, 1] of its range: the
// transfer function's opacity, else the magnitude opacity t^E (0 below the threshold), else 1.
float opacityWeight(const ViewParams& view, float t);

// The alpha per voxel of depth the slices use: `alpha`, or with an optical depth the alpha at
// which a ray of the box's mean chord length (4 V / S, in voxels of `dims`) meets that depth,
// given the drawn fraction, the mean grey (intensity opacity) and the mean opacity weight
// measured on the data. In [0.005, 1].
float resolvedAlpha(const ViewParams& view, const TransferFacts& facts, Dims dims);

// The view `scale` times larger (--scale): width, height and a given font size, so that a
// poster-size picture keeps the layout of the smaller one.
ViewParams scaledView(const ViewParams& view, float scale);

// The ranges of core/parameter_ranges.h and their consistency; InvalidInput naming the
// parameter.
Result<void> validate(const ViewParams& view);

}  // namespace lic3d
