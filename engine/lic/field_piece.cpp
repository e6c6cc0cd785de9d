// SPDX-License-Identifier: BSD-3-Clause
#include "lic/field_piece.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/parallel.h"
#include "lic/lic_reference.h"

namespace lic3d {
namespace {

Result<void> checkBox(Dims whole, Dims offset, Dims dims) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || offset[a] < 0 || offset[a] + dims[a] > whole[a])
      return inputError("the box of " + std::to_string(dims.x) + "x" + std::to_string(dims.y) +
                        "x" + std::to_string(dims.z) + " voxels at " + std::to_string(offset.x) +
                        "," + std::to_string(offset.y) + "," + std::to_string(offset.z) +
                        " does not lie inside the grid");
  return {};
}

// The grid of the box at `offset` of a grid with `whole`'s geometry.
GridGeometry boxGeometry(const GridGeometry& whole, Dims offset) {
  GridGeometry box;
  box.spacing = whole.spacing;
  box.origin = whole.origin + glm::dvec3(offset) * whole.spacing;
  return box;
}

}  // namespace

int licGhostLayers(const LicParams& params) {
  const int steps = std::max(params.length - params.bias, params.length + params.bias);
  return static_cast<int>(std::ceil(steps * static_cast<double>(params.step))) + 1;
}

Result<VectorField> cutFieldPiece(const VectorField& whole, Dims offset, Dims dims) {
  return cutFieldPiece(whole, offset, dims, maxVoxelSpeedOverVoxels(whole));
}

Result<VectorField> cutFieldPiece(const VectorField& whole, Dims offset, Dims dims,
                                  double wholeMaxVoxelSpeed) {
  LIC3D_TRY(checkBox(whole.dims, offset, dims));
  VectorField piece;
  piece.dims = dims;
  piece.geometry = boxGeometry(whole.geometry, offset);
  piece.vectors.resize(voxelCount(dims));
  // Row by row, the layers on the available threads (a brick of a large grid is gigabytes).
  parallelFor(static_cast<std::size_t>(dims.z), 0, [&](std::size_t layer) {
    const int k = static_cast<int>(layer);
    for (int j = 0; j < dims.y; ++j)
      std::copy_n(&whole.at(offset.x, offset.y + j, offset.z + k), dims.x,
                  &piece.vectors[voxelIndex(dims, 0, j, k)]);
  });
  piece.piece = FieldPiece{whole.dims, offset, wholeMaxVoxelSpeed};
  return piece;
}

Result<ScalarVolume> cutVolume(const ScalarVolume& volume, Dims offset, Dims dims) {
  LIC3D_TRY(checkBox(volume.dims, offset, dims));
  ScalarVolume out;
  out.dims = dims;
  out.geometry = boxGeometry(volume.geometry, offset);
  out.values.resize(voxelCount(dims));
  if (!volume.drawn.empty()) out.drawn.resize(voxelCount(dims));
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const std::size_t from = voxelIndex(volume.dims, offset.x + i, offset.y + j, offset.z + k);
        const std::size_t to = voxelIndex(dims, i, j, k);
        out.values[to] = volume.values[from];
        if (!out.drawn.empty()) out.drawn[to] = volume.drawn[from];
      }
  return out;
}

}  // namespace lic3d
