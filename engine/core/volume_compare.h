#pragma once
// How alike two LIC volumes are, beyond per-voxel differences: used to decide whether a faster
// kernel may replace the exact one (docs/LIC_SEMANTICS.md) and reported by `lic3d bench --kernels`.

#include <cstddef>
#include <functional>

#include "core/volume.h"

namespace lic3d {

// Pearson correlation of two volumes on the same grid, over the voxels `keep` accepts (all of
// them when it is empty). 1 when either volume is constant there.
double correlation(const ScalarVolume& a, const ScalarVolume& b,
                   const std::function<bool(std::size_t)>& keep = {});

}  // namespace lic3d
