// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How alike two LIC volumes are, beyond per-voxel differences: used to decide whether a faster
// kernel may replace the exact one (docs/LIC_SEMANTICS.md) and reported by `lic3d bench --kernels`.

#include <cstddef>
#include <functional>
#include <span>

#include "core/volume.h"

namespace lic3d {

// Pearson correlation of two volumes on the same grid, over the voxels `keep` accepts (all of
// them when it is empty). 1 when either volume is constant there.
double correlation(const ScalarVolume& a, const ScalarVolume& b,
                   const std::function<bool(std::size_t)>& keep = {});
// The same for two series of values of equal length (a sample of voxels).
double correlation(std::span<const double> a, std::span<const double> b);

}  // namespace lic3d
