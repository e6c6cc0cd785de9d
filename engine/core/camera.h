// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An orbit camera around the centre of the volume's box, z up.

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

namespace lic3d {

struct CameraParams {
  float azimuth = 35.0f;    // degrees around +z, 0 looks from +x
  float elevation = 25.0f;  // degrees above the xy plane
  float distance = 0.0f;    // from the box centre in world units (longest box side = 1); 0: fit
  float fovY = 30.0f;       // vertical field of view in degrees (perspective)
  bool orthographic = false;
  glm::vec3 target{0.0f};  // the point orbited, in world units (pan moves it)

  bool operator==(const CameraParams&) const = default;
};

struct CameraMatrices {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};  // Vulkan clip space: y down, depth in [0,1]
  glm::mat4 viewProjection{1.0f};
  glm::vec3 eye{0.0f};       // camera position (of this eye, for stereo)
  glm::vec3 toViewer{0.0f};  // unit vector from the target towards the (central) eye
  glm::vec3 right{0.0f};     // unit screen-right direction in world space
  glm::vec3 up{0.0f};        // unit screen-up direction in world space
  float distance = 0.0f;     // from the target to the central eye
};

// `halfExtent` is half the box size in world units; the whole box fits the view when
// distance = 0 (its bounding sphere touches neither image edge).
//
// Stereo (thesis 5.3.2): `eyeOffset` moves the eye along screen-right (-E/2 left, +E/2 right)
// and shifts the frustum off-axis so that points at `zeroParallax` from the eye (0: the target's
// distance) project to the same pixel for both eyes. Perspective only.
CameraMatrices computeCamera(const CameraParams& params, glm::vec3 halfExtent, float aspect,
                             float eyeOffset = 0.0f, float zeroParallax = 0.0f);

}  // namespace lic3d
