// SPDX-License-Identifier: BSD-3-Clause
#include "core/slice_geometry.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

namespace lic3d {

glm::vec3 boxHalfExtent(Dims dims, const GridGeometry& geometry) {
  // The box covers whole voxels (texel extents), as the 3D texture does.
  const glm::dvec3 size = glm::dvec3(dims) * geometry.spacing;
  const double longest = std::max({size.x, size.y, size.z});
  return glm::vec3(0.5 * size / longest);
}

SlicePlan planSlices(Slicing slicing, Dims dims, glm::vec3 halfExtent, glm::vec3 toViewer,
                     int requested) {
  SlicePlan plan;
  const glm::vec3 voxel = 2.0f * halfExtent / glm::vec3(dims);
  plan.voxelSize = std::min({voxel.x, voxel.y, voxel.z});
  float reach = 0.0f;  // half the box's extent along the normal
  if (slicing == Slicing::AxisAligned) {
    const glm::vec3 a = glm::abs(toViewer);
    plan.axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
    plan.normal = glm::vec3(0.0f);
    plan.normal[plan.axis] = toViewer[plan.axis] >= 0.0f ? 1.0f : -1.0f;
    reach = halfExtent[plan.axis];
    plan.count = requested > 0 ? requested : dims[plan.axis];
  } else {
    plan.normal = glm::normalize(toViewer);
    reach = glm::dot(glm::abs(plan.normal), halfExtent);
    plan.count = requested > 0
                     ? requested
                     : std::max(1, static_cast<int>(std::ceil(2.0f * reach / plan.voxelSize)));
  }
  plan.spacing = 2.0f * reach / static_cast<float>(plan.count);
  plan.firstOffset = -reach + 0.5f * plan.spacing;
  return plan;
}

}  // namespace lic3d
