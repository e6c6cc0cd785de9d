#pragma once
// How the LIC volume is drawn. Changing any of this redraws; it never recomputes the LIC volume.

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/camera.h"
#include "core/colormap.h"
#include "core/enum_names.h"
#include "core/error.h"

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

enum class VolumeFilter { Nearest, Linear };  // how slices sample the LIC volume (thesis 6.4)
enum class ColorMode { None, Magnitude };     // grey, or coloured by |v| (thesis 5.1.2)
enum class RoiShape { None, Sphere, Cube, Cylinder };  // thesis 5.2.2
enum class StereoMode { None, Anaglyph, SideBySide };  // thesis 5.3.2
enum class Lighting { None, Phong, Lines };            // thesis 5.3.3, and illuminated lines

LIC3D_ENUM_NAMES(Slicing, {Slicing::ViewAligned, "view"}, {Slicing::AxisAligned, "axis"})
LIC3D_ENUM_NAMES(OpacityMode, {OpacityMode::Constant, "constant"},
                 {OpacityMode::Intensity, "intensity"})
LIC3D_ENUM_NAMES(VolumeFilter, {VolumeFilter::Nearest, "nearest"}, {VolumeFilter::Linear, "linear"})
LIC3D_ENUM_NAMES(ColorMode, {ColorMode::None, "none"}, {ColorMode::Magnitude, "magnitude"})
LIC3D_ENUM_NAMES(RoiShape, {RoiShape::None, "none"}, {RoiShape::Sphere, "sphere"},
                 {RoiShape::Cube, "cube"}, {RoiShape::Cylinder, "cylinder"})
LIC3D_ENUM_NAMES(StereoMode, {StereoMode::None, "none"}, {StereoMode::Anaglyph, "anaglyph"},
                 {StereoMode::SideBySide, "side-by-side"})
LIC3D_ENUM_NAMES(Lighting, {Lighting::None, "none"}, {Lighting::Phong, "phong"},
                 {Lighting::Lines, "lines"})

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
  OpacityMode opacityMode = OpacityMode::Intensity;
  VolumeFilter filter = VolumeFilter::Linear;

  // Grey transfer of the LIC intensity I. With contrast (default), the drawn voxels' mean and
  // standard deviation are stretched to 0.5 and kContrastTargetDeviation (a histogram stretch);
  // without, grey = I. A manual window [low, high] maps to [0, 1] instead. Then
  // grey = 0.5 + gain * (grey - 0.5) + brightness.
  bool contrast = true;
  bool manualWindow = false;
  float windowLow = 0.0f;
  float windowHigh = 1.0f;
  float gain = 1.0f;
  float brightness = 0.0f;

  // Thesis 5.1.2: colour by |v| through a colour map over [colorLow, colorHigh] (automatic: the
  // field's min and max |v|); the LIC grey modulates it. The legend is drawn into the image.
  ColorMode color = ColorMode::None;
  Colormap colormap = Colormap::Thesis;
  bool autoColorRange = true;
  float colorLow = 0.0f;
  float colorHigh = 1.0f;
  bool legend = false;
  // The box's edges with each axis labelled by its physical range (origin to the last voxel
  // centre, in the file's units), drawn over the picture.
  bool axes = false;

  // Thesis 5.1.3: alpha *= t^exponent, t = |v| normalised over the colour range; 0 is off.
  // Voxels with t below the threshold vanish.
  float magnitudeOpacity = 0.0f;
  float magnitudeThreshold = 0.0f;

  // Thesis 5.2.1: the drawn part of the box, as fractions of it along x, y, z.
  glm::vec3 clipMin{0.0f};
  glm::vec3 clipMax{1.0f};

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

  bool operator==(const ViewParams&) const = default;
};

// Grey deviation of the drawn voxels after the contrast stretch: +-2 deviations span [0,1].
inline constexpr float kContrastTargetDeviation = 0.25f;

// What a picture's colours come from besides the view: the drawn voxels' LIC mean and
// deviation (the contrast stretch) and the field's |v| over its voxels (the automatic colour
// range). The slices (GPU) and the CPU colouring (lic/colouring.h) take the same numbers.
struct TransferFacts {
  float intensityMean = 0.5f;
  float intensityDeviation = 0.1f;
  float minMagnitude = 0.0f;
  float maxMagnitude = 1.0f;
};

// The grey transfer as a line, grey = x * I + y (clamped to [0,1] by its users): the window, or
// the contrast stretch, then gain and brightness.
glm::vec2 greyTransfer(const ViewParams& view, const TransferFacts& facts);

// The |v| range that colour and magnitude opacity span: the view's, or the field's.
struct ColorRange {
  float low = 0.0f;
  float high = 1.0f;
};
ColorRange colorRange(const ViewParams& view, const TransferFacts& facts);
// t = (|v| - x) * y maps the colour range to [0, 1].
glm::vec2 magnitudeTransfer(const ColorRange& range);

// The ranges of core/parameter_ranges.h and their consistency; InvalidInput naming the
// parameter.
Result<void> validate(const ViewParams& view);

}  // namespace lic3d
