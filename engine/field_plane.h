#pragma once
// 2D fields for 2D LIC (thesis chapter 3): a VectorField one voxel thick, NX x NY x 1, whose
// vectors lie in the x-y plane (z components 0). A plane of a 3D field, or a file whose grid is
// flat along one axis, becomes such a field here, so the 2D passes read x and y only.

#include <glm/vec2.hpp>

#include "error.h"
#include "volume.h"

namespace lic3d {

// The axes that span a plane across `axis`, in picture order (right, up): across z, x and y;
// across y, x and z; across x, y and z.
glm::ivec2 planeAxes(int axis);

// Whether `field` is a 2D field: one voxel thick along z.
inline bool isPlanar(const VectorField& field) { return field.dims.z == 1; }

// Voxel layer `index` across `axis` of a 3D field (index in 0..N-1 along that axis, else
// InvalidInput naming the grid). In-plane components are kept; the component along `axis` is
// dropped: 2D LIC follows the vectors' projection onto the plane.
Result<VectorField> extractPlane(const VectorField& field, int axis, int index);

// A field read from a 2D file: its one flat axis (one voxel) is the plane's normal. An
// InvalidInput error naming `what` when no axis or more than one is flat.
Result<VectorField> planarField(const VectorField& field, const std::string& what);

}  // namespace lic3d
