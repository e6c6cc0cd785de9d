// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// 2D fields for 2D LIC (thesis chapter 3): a VectorField one voxel thick, NX x NY x 1, whose
// vectors lie in the x-y plane (z components 0). A plane of a 3D field, or a file whose grid is
// flat along one axis, becomes such a field here, so the 2D passes read x and y only.

#include <cstdint>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <vector>

#include "core/error.h"
#include "core/volume.h"

namespace lic3d {

// The axes that span a plane across `axis`, in picture order (right, up): across z, x and y;
// across y, x and z; across x, y and z.
glm::ivec2 planeAxes(int axis);

// Voxel layer `index` across `axis` of a grid of `dims` and `geometry`, as a 2D field: its grid
// is the layer's (the plane's normal becomes z, one voxel at the layer's position), its vectors
// the in-plane components of vectorAt(voxel) for each voxel of the layer (a glm::dvec3).
template <class VectorAt>
VectorField makePlane(Dims dims, const GridGeometry& geometry, int axis, int index,
                      const VectorAt& vectorAt) {
  const glm::ivec2 in = planeAxes(axis);
  VectorField plane;
  plane.dims = Dims(dims[in.x], dims[in.y], 1);
  const GridGeometry& g = geometry;
  plane.geometry.spacing = glm::dvec3(g.spacing[in.x], g.spacing[in.y], g.spacing[axis]);
  plane.geometry.origin =
      glm::dvec3(g.origin[in.x], g.origin[in.y], g.origin[axis] + index * g.spacing[axis]);
  plane.vectors.resize(voxelCount(plane.dims));
  for (int j = 0; j < plane.dims.y; ++j)
    for (int i = 0; i < plane.dims.x; ++i) {
      glm::ivec3 voxel(index);
      voxel[in.x] = i;
      voxel[in.y] = j;
      const glm::dvec3 v = vectorAt(voxel);
      plane.vectors[voxelIndex(plane.dims, i, j, 0)] =
          glm::vec3(static_cast<float>(v[in.x]), static_cast<float>(v[in.y]), 0.0f);
    }
  return plane;
}

// Whether `field` is a 2D field: one voxel thick along z.
inline bool isPlanar(const VectorField& field) { return field.dims.z == 1; }

// Voxel layer `index` across `axis` of a 3D field (index in 0..N-1 along that axis, else
// InvalidInput naming the grid). In-plane components are kept; the component along `axis` is
// dropped: 2D LIC follows the vectors' projection onto the plane.
Result<VectorField> extractPlane(const VectorField& field, int axis, int index);

// The picture axes of a plane whose unit normal (physical space) is `normal`: up is the z axis
// projected onto the plane, plus near z (|n.z| > cos 30 degrees) the y axis projected, weighted
// from 0 at 30 degrees to 1 at the z axis; right = up x n, so n = right x up points at the
// viewer. Continuous in the normal but at one normal near each of +z and -z (about 23 degrees
// from z towards +y, and towards -y from -z), where the picture turns: a field of directions on
// a sphere has such a point. (1,0,0) gives the --slice x picture (right y, up z), (0,-1,0)
// --slice y (right x, up z), (0,0,1) --slice z (right x, up y).
struct PlaneAxes {
  glm::dvec3 right, up;
};
PlaneAxes planePictureAxes(glm::dvec3 normal);

// A plane of a grid with different spacings along its two axes, resampled bilinearly onto the
// finer spacing over the same extent, so that a pixel of its picture is square in physical space
// (a plane whose spacings agree to 1e-6 is returned as it is).
VectorField isotropicPlane(const VectorField& plane);

// A plane at any orientation through a 3D field: through `point` (fractions of the box) with
// `normal` (in box axes, so that (0,0,1) is the z layers' normal on any box). Its picture axes are
// planePictureAxes of the normal in physical space. The plane's grid has the field's smallest
// spacing over the rectangle that bounds the plane's cut through the box; each point gets the
// field's trilinear interpolation projected onto u and v. Points outside the box get zero vectors
// and are marked in `outside` (1 per voxel of the plane's grid), which the picture paints as
// background. InvalidInput when the plane misses the box or the normal is zero.
struct ObliquePlane {
  VectorField field;
  std::vector<std::uint8_t> outside;
};
Result<ObliquePlane> obliquePlane(const VectorField& field, glm::dvec3 point, glm::dvec3 normal);

// A field read from a 2D file: its one flat axis (one voxel) is the plane's normal. An
// InvalidInput error naming `what` when no axis or more than one is flat.
Result<VectorField> planarField(const VectorField& field, const std::string& what);

}  // namespace lic3d
