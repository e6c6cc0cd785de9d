#include "lic/field_plane.h"

#include <string>

namespace lic3d {
glm::ivec2 planeAxes(int axis) {
  switch (axis) {
    case 0: return {1, 2};
    case 1: return {0, 2};
    default: return {0, 1};
  }
}

Result<VectorField> extractPlane(const VectorField& field, int axis, int index) {
  if (axis < 0 || axis > 2) return inputError("a plane is across x, y or z");
  const Dims d = field.dims;
  if (index < 0 || index >= d[axis])
    return inputError("the grid " + gridText(d) + " has " + std::to_string(d[axis]) +
                      " layers across " + std::string(1, static_cast<char>('x' + axis)) + " (0.." +
                      std::to_string(d[axis] - 1) + "), not " + std::to_string(index));
  return makePlane(d, field.geometry, axis, index, [&](glm::ivec3 voxel) {
    return glm::dvec3(field.at(voxel.x, voxel.y, voxel.z));
  });
}

Result<VectorField> planarField(const VectorField& field, const std::string& what) {
  int flat = -1, flatAxes = 0;
  for (int a = 0; a < 3; ++a)
    if (field.dims[a] == 1) {
      flat = a;
      ++flatAxes;
    }
  if (flatAxes == 0)
    return parameterError("plane.axis", "must name a plane of " + what + ": its grid " +
                                            gridText(field.dims) + " is 3D");
  if (flatAxes > 1)
    return inputError(what + ": the grid " + gridText(field.dims) +
                      " is flat along more than one axis; 2D LIC needs a plane");
  return extractPlane(field, flat, 0);
}

}  // namespace lic3d
