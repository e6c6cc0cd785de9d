// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where the slice planes go: their normal, spacing, count and back-to-front order. The vertex
// shader cuts each plane with the box; this part is plain CPU math so it can be tested.

#include <glm/vec3.hpp>

#include "core/view_params.h"
#include "core/volume.h"

namespace lic3d {

// The volume's box in world units: centred at the origin, longest side 1, physical proportions.
glm::vec3 boxHalfExtent(Dims dims, const GridGeometry& geometry);

struct SlicePlan {
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // unit, pointing towards the viewer
  float firstOffset = 0.0f;            // plane of slice 0 (farthest): dot(normal, x) = offset
  float spacing = 0.0f;                // offset of slice k = firstOffset + k * spacing
  int count = 0;
  int axis = -1;           // the grid axis for axis-aligned slicing, -1 otherwise
  float voxelSize = 0.0f;  // smallest voxel side in world units (opacity reference)
};

// `toViewer` is the unit direction from the volume towards the camera. `requested` slices, or
// one per voxel along the slicing direction when requested <= 0.
SlicePlan planSlices(Slicing slicing, Dims dims, glm::vec3 halfExtent, glm::vec3 toViewer,
                     int requested);

}  // namespace lic3d
