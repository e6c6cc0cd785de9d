// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where a LIC volume's voxels go as they are read back from the device: the memory of a volume of
// the whole grid on the host, or runs handed to a writer (a file written in place, a reduced
// copy). Voxel indices are of the whole grid (x fastest); runs arrive from several threads at
// once and never overlap (docs/SCALE.md, "Read-back").

#include <cstddef>
#include <cstdint>
#include <functional>

#include "core/error.h"
#include "core/volume.h"

namespace lic3d {

struct VoxelTarget {
  Dims dims{0};  // the whole grid the voxel indices are of
  // The memory of the whole grid's values, written straight by the conversion; null: `write`
  // takes the runs.
  float* values = nullptr;
  // With `values`: where the drawn flags go (a sparsity mask), or null to leave them. Without
  // `values`, hidden voxels are written as NaN ("no value" to ParaView and VisIt).
  std::uint8_t* drawn = nullptr;
  // The `count` values of the voxels [first, first + count), from any thread; runs are disjoint.
  std::function<Result<void>(std::uint64_t first, const float* values, std::size_t count)> write;
  // The stage (core/stage_times.h) the time in `write` is reported as, where it is its own
  // ("volume write" for a file); else it is part of the read-back's.
  const char* writeStage = nullptr;
};

// A target writing straight into `volume` (sized to its grid), its drawn flags included where it
// has them.
inline VoxelTarget memoryTarget(ScalarVolume& volume) {
  VoxelTarget target;
  target.dims = volume.dims;
  target.values = volume.values.data();
  target.drawn = volume.drawn.empty() ? nullptr : volume.drawn.data();
  return target;
}

}  // namespace lic3d
