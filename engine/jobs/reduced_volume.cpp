// SPDX-License-Identifier: BSD-3-Clause
#include "jobs/reduced_volume.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace lic3d {

Dims reducedDims(Dims dims, int factor) { return (dims + Dims(factor - 1)) / factor; }

GridGeometry reducedGeometry(const GridGeometry& geometry, int factor) {
  GridGeometry reduced = geometry;
  reduced.spacing *= static_cast<double>(factor);
  return reduced;
}

VectorField reduceField(const VectorField& field, int factor) {
  VectorField reduced;
  reduced.dims = reducedDims(field.dims, factor);
  reduced.geometry = reducedGeometry(field.geometry, factor);
  reduced.unit = field.unit;
  reduced.vectors.reserve(voxelCount(reduced.dims));
  for (int k = 0; k < reduced.dims.z; ++k)
    for (int j = 0; j < reduced.dims.y; ++j)
      for (int i = 0; i < reduced.dims.x; ++i)
        reduced.vectors.push_back(field.at(i * factor, j * factor, k * factor));
  return reduced;
}

std::optional<int> chooseReduction(Dims dims, int largest, const std::function<bool(Dims)>& fits) {
  for (int factor = 2; factor <= largest; ++factor)
    if (fits(reducedDims(dims, factor))) return factor;
  return std::nullopt;
}

ReducedVolume::ReducedVolume(Dims whole, const GridGeometry& geometry, int factor)
    : factor_(factor), whole_(whole) {
  volume_.dims = reducedDims(whole, factor);
  volume_.geometry = reducedGeometry(geometry, factor);
  resizeLarge(volume_.values, voxelCount(volume_.dims));  // zeros, faulted in on all threads
}

VoxelTarget ReducedVolume::target(bool sparse) {
  if (sparse) volume_.drawn.assign(volume_.values.size(), 1);
  VoxelTarget target;
  target.dims = whole_;
  target.write = [this](std::uint64_t first, const float* values,
                        std::size_t count) -> Result<void> {
    const std::uint64_t row = static_cast<std::uint64_t>(whole_.x);
    const std::uint64_t layer = row * static_cast<std::uint64_t>(whole_.y);
    // Row by row: only rows at multiples of the factor in y and z hold reduced voxels.
    for (std::uint64_t v = first, end = first + count; v < end;) {
      const std::uint64_t rowEnd = std::min(end, (v / row + 1) * row);
      const int y = static_cast<int>((v / row) % whole_.y);
      const int z = static_cast<int>(v / layer);
      if (y % factor_ == 0 && z % factor_ == 0) {
        const int x0 = static_cast<int>(v % row);
        for (int x = (x0 + factor_ - 1) / factor_ * factor_;
             static_cast<std::uint64_t>(x) < rowEnd - v + static_cast<std::uint64_t>(x0);
             x += factor_) {
          const float value = values[v - first + static_cast<std::uint64_t>(x - x0)];
          const std::size_t to = voxelIndex(volume_.dims, x / factor_, y / factor_, z / factor_);
          const bool hidden = std::isnan(value);
          volume_.values[to] = hidden ? 0.0f : value;
          if (!volume_.drawn.empty()) volume_.drawn[to] = hidden ? 0 : 1;
        }
      }
      v = rowEnd;
    }
    return {};
  };
  return target;
}

}  // namespace lic3d
