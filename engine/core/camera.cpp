// SPDX-License-Identifier: BSD-3-Clause
#include "core/camera.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace lic3d {

CameraMatrices computeCamera(const CameraParams& params, glm::vec3 halfExtent, float aspect,
                             float eyeOffset, float zeroParallax) {
  const float azimuth = glm::radians(params.azimuth);
  const float elevation = glm::radians(std::clamp(params.elevation, -89.9f, 89.9f));
  const float fovY = glm::radians(std::clamp(params.fovY, 1.0f, 170.0f));
  const float radius = glm::length(halfExtent);
  // The narrower of the two fields of view decides whether the bounding sphere fits.
  const float halfFov = std::min(fovY, 2.0f * std::atan(std::tan(0.5f * fovY) * aspect)) * 0.5f;
  const float margin = 1.04f;

  CameraMatrices m;
  m.toViewer = glm::vec3(std::cos(elevation) * std::cos(azimuth),
                         std::cos(elevation) * std::sin(azimuth), std::sin(elevation));
  m.distance = params.distance > 0.0f ? params.distance : margin * radius / std::sin(halfFov);
  const glm::vec3 worldUp(0.0f, 0.0f, 1.0f);
  m.right = glm::normalize(glm::cross(-m.toViewer, worldUp));
  m.up = glm::cross(m.right, -m.toViewer);
  // Both eyes look parallel to the central view direction (no toe-in: no vertical parallax).
  const glm::vec3 shift = eyeOffset * m.right;
  m.eye = params.target + m.distance * m.toViewer + shift;
  m.view = glm::lookAt(m.eye, params.target + shift, worldUp);

  if (params.orthographic) {
    // The visible height matches what the perspective view shows at the target's distance.
    const float halfHeight = m.distance * std::tan(0.5f * fovY);
    const float halfWidth = halfHeight * aspect;
    const float depth = m.distance + 2.0f * radius + glm::length(params.target);
    m.projection = glm::ortho(-halfWidth, halfWidth, -halfHeight, halfHeight, 0.0f, 2.0f * depth);
  } else {
    const float nearPlane =
        std::max(1e-3f * m.distance, m.distance - 2.0f * radius - glm::length(params.target));
    const float farPlane = m.distance + 2.0f * radius + glm::length(params.target);
    const float top = nearPlane * std::tan(0.5f * fovY);
    const float halfWidth = top * aspect;
    const float parallaxDistance = zeroParallax > 0.0f ? zeroParallax : m.distance;
    const float frustumShift = eyeOffset * nearPlane / parallaxDistance;
    m.projection = glm::frustum(-halfWidth - frustumShift, halfWidth - frustumShift, -top, top,
                                nearPlane, farPlane);
  }
  m.projection[1][1] *= -1.0f;  // Vulkan's clip space has y pointing down
  m.viewProjection = m.projection * m.view;
  return m;
}

}  // namespace lic3d
