// SPDX-License-Identifier: BSD-3-Clause
#include "lic/derived_fields.h"

#include <glm/geometric.hpp>

#include "core/parallel.h"

namespace lic3d {
namespace {

// d v / d x_axis at voxel (i,j,k): central differences inside, one-sided on the faces.
glm::vec3 derivative(const VectorField& field, glm::ivec3 at, int axis) {
  const int n = field.dims[axis];
  if (n < 2) return glm::vec3(0.0f);
  glm::ivec3 lo = at, hi = at;
  lo[axis] = std::max(at[axis] - 1, 0);
  hi[axis] = std::min(at[axis] + 1, n - 1);
  const double distance = static_cast<double>(hi[axis] - lo[axis]) * field.geometry.spacing[axis];
  return (field.at(hi.x, hi.y, hi.z) - field.at(lo.x, lo.y, lo.z)) / static_cast<float>(distance);
}

glm::vec3 curlAt(const VectorField& field, glm::ivec3 at) {
  const glm::vec3 dx = derivative(field, at, 0);
  const glm::vec3 dy = derivative(field, at, 1);
  const glm::vec3 dz = derivative(field, at, 2);
  return {dy.z - dz.y, dz.x - dx.z, dx.y - dy.x};
}

}  // namespace

std::optional<DerivedQuantity> derivedQuantity(std::string_view name) {
  return parseEnum<DerivedQuantity>(name);
}

PointScalars derivedScalars(const VectorField& field, DerivedQuantity quantity,
                            const std::string& unit, unsigned threads) {
  PointScalars out;
  out.dims = field.dims;
  out.geometry = field.geometry;
  out.name = std::string(enumName(quantity));
  if (quantity == DerivedQuantity::Speed) out.unit = unit;
  out.values.resize(field.vectors.size());
  const Dims d = field.dims;
  parallelFor(static_cast<std::size_t>(d.z), threads, [&](std::size_t layer) {
    const int k = static_cast<int>(layer);
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const glm::vec3& v = field.at(i, j, k);
        float value = 0.0f;
        switch (quantity) {
          case DerivedQuantity::Speed: value = glm::length(v); break;
          case DerivedQuantity::Vorticity: value = glm::length(curlAt(field, {i, j, k})); break;
          case DerivedQuantity::Helicity: value = glm::dot(v, curlAt(field, {i, j, k})); break;
        }
        out.values[voxelIndex(d, i, j, k)] = value;
      }
  });
  return out;
}

}  // namespace lic3d
