// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A reduced copy of a LIC volume too large to draw (docs/SCALE.md, "Rendering"): every factor-th
// voxel along each axis, gathered from the bricks as they are made. Every factor-th voxel rather
// than an average: the streaks are about a voxel wide, and an average of a few would grey them.

#include <cstdint>
#include <utility>

#include "core/error.h"
#include "core/volume.h"
#include "core/voxel_target.h"
#include "jobs/bricks.h"

namespace lic3d {

// ceil(dims / factor) on each axis.
Dims reducedDims(Dims dims, int factor);

// The grid of every factor-th voxel of `geometry`'s: the same origin, factor times the spacing.
GridGeometry reducedGeometry(const GridGeometry& geometry, int factor);

// Voxels (factor i, factor j, factor k) of `field`, on reducedGeometry.
VectorField reduceField(const VectorField& field, int factor);

// The smallest factor >= 2 for which `fits` accepts the reduced grid; nothing past `largest`.
std::optional<int> chooseReduction(Dims dims, int largest, const std::function<bool(Dims)>& fits);

class ReducedVolume {
 public:
  ReducedVolume(Dims whole, const GridGeometry& geometry, int factor);

  // Where a LIC of the whole grid is read back to (LicVolumeOptions::target): the runs' voxels
  // that fall on the reduced grid, from any thread; a NaN (a voxel sparsity hides) is kept as not
  // drawn when `sparse`. The volume must outlive the target.
  VoxelTarget target(bool sparse);

  int factor() const { return factor_; }
  const ScalarVolume& volume() const { return volume_; }
  // The volume moved out once every brick is in, so that the host never holds two copies.
  ScalarVolume takeVolume() { return std::move(volume_); }

 private:
  int factor_;
  Dims whole_;
  ScalarVolume volume_;
};

}  // namespace lic3d
