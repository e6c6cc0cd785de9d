#pragma once
// How the LIC volume is drawn. Changing any of this redraws; it never recomputes the LIC volume.

#include <glm/vec3.hpp>

#include "camera.h"

namespace lic3d {

enum class Slicing {
  ViewAligned,  // planes perpendicular to the view direction (default)
  AxisAligned,  // planes perpendicular to the grid axis closest to the view direction (thesis 4.1.2)
};

enum class OpacityMode {
  Constant,   // every voxel has the global alpha (thesis 5.1.1)
  Intensity,  // alpha times the grey value: dark gaps between streamlines turn clear
};

enum class VolumeFilter { Nearest, Linear };  // how slices sample the LIC volume (thesis 6.4)

struct ViewParams {
  int width = 1024;
  int height = 1024;
  Slicing slicing = Slicing::ViewAligned;
  int slices = 0;  // 0: one slice per voxel along the view direction
  CameraParams camera;
  float alpha = 0.3f;  // opacity per voxel of distance, corrected for the slice spacing
  OpacityMode opacityMode = OpacityMode::Intensity;
  VolumeFilter filter = VolumeFilter::Linear;
  glm::vec3 background{0.0f, 0.0f, 0.0f};  // linear RGB in [0,1]
  // Grey transfer: the intensity window [low, high] maps to [0,1] (auto: the LIC volume's
  // 3rd and 97th percentiles), then grey = 0.5 + contrast * (g - 0.5) + brightness.
  bool autoWindow = true;
  float windowLow = 0.0f;
  float windowHigh = 1.0f;
  float contrast = 1.0f;
  float brightness = 0.0f;

  bool operator==(const ViewParams&) const = default;
};

}  // namespace lic3d
