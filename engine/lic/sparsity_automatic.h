// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to the sparsity mask and the Poisson sampler (not an API): what the automatic sparsity
// parameters (points = 0, radius = 0; see kDefaultBlackFraction) resolve to on a grid.

#include <cmath>
#include <cstddef>

#include "core/lic_params.h"
#include "core/volume.h"
#include "lic/point_sets.h"

namespace lic3d::points {

// The smallest radius in [kMinSparsityRadius, largest] for which fits(radius) holds (fits grows
// with the radius), rounded up to 0.01 voxel.
template <class Fits>
float smallestRadiusThatFits(Fits fits, float largest) {
  if (fits(kMinSparsityRadius)) return kMinSparsityRadius;
  float lo = kMinSparsityRadius, hi = largest;
  for (int i = 0; i < 40; ++i) {
    const float mid = 0.5f * (lo + hi);
    (fits(mid) ? hi : lo) = mid;
  }
  return std::ceil(hi * 100.0f) / 100.0f;
}

// Whether the memory limits hold: Bridson's grid at most kMaxPoissonGridCells cells, at most
// kMaxSparsityPoints jitter cells.
bool poissonFits(Dims dims, float radius);
bool jitterFits(Dims dims, float radius);

// The longest axis in voxels: the largest radius allowed.
float largestAxis(Dims dims);

// What makeSparsityMask runs: the automatic values resolved (see kDefaultBlackFraction). On
// grids so large that an automatic value would break a memory limit, the value is moved to the
// limit (fewer points, a larger radius) rather than failing.
struct ResolvedParams {
  std::size_t points = 0;  // poisson: how many of the maximal set to keep, 0 = all
  float radius = 0.0f;
  bool radiusFromPoints = false;  // poisson: radius derived from --sparsity-points
};

ResolvedParams resolve(const SparsityParams& params, Dims dims);

}  // namespace lic3d::points
