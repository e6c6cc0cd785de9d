// SPDX-License-Identifier: BSD-3-Clause
// The distributions laid on a grid: the thesis' jittering (one point per cell, thinned to the
// radius) and the regular checkerboard of diagonal planes that it compares the others with.

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include "lic/fixed_point.h"
#include "lic/point_sets.h"

namespace lic3d {
using namespace points;
namespace {

// Number of voxels on each diagonal plane i + j + k = s of the grid.
std::vector<std::uint64_t> diagonalPlaneCounts(Dims dims) {
  const std::size_t planes = static_cast<std::size_t>(dims.x + dims.y + dims.z - 2);
  // Voxels of the xy-plane with i + j = t, then summed over k by a running window.
  std::vector<std::uint64_t> xy(planes, 0);
  for (int t = 0; t <= dims.x + dims.y - 2; ++t)
    xy[static_cast<std::size_t>(t)] =
        static_cast<std::uint64_t>(std::min(dims.x - 1, t) - std::max(0, t - dims.y + 1) + 1);
  std::vector<std::uint64_t> counts(planes, 0);
  std::uint64_t window = 0;
  for (std::size_t s = 0; s < planes; ++s) {
    window += xy[s];
    if (s >= static_cast<std::size_t>(dims.z)) window -= xy[s - static_cast<std::size_t>(dims.z)];
    counts[s] = window;
  }
  return counts;
}

}  // namespace

std::vector<glm::vec3> jitteredPoints(Dims dims, float radius, std::uint64_t seed) {
  std::vector<glm::vec3> result;
  if (!validDims(dims)) return result;
  const FixedExtent extent = fixedExtent(dims);
  const std::int64_t r = fixedRadius(radius);
  const std::int64_t r2 = r * r;
  const std::size_t nx = cellsAlong(extent.x, r), ny = cellsAlong(extent.y, r),
                    nz = cellsAlong(extent.z, r);
  // Cells have side r, so a kept point closer than r sits in one of the 26 neighbouring cells;
  // of those, the 13 before this one in scan order can hold kept points. Two z-layers suffice.
  struct Slot {
    FixedPoint p;
    bool kept = false;
  };
  std::vector<Slot> layers(2 * nx * ny);
  const auto slot = [&](std::size_t cx, std::size_t cy, std::size_t cz) -> Slot& {
    return layers[cx + nx * (cy + ny * (cz & 1))];
  };
  // Counter-based: cell c's point depends only on (seed, c).
  const std::uint64_t key = noiseHash(seed, kJitterStream);
  for (std::size_t cz = 0; cz < nz; ++cz)
    for (std::size_t cy = 0; cy < ny; ++cy)
      for (std::size_t cx = 0; cx < nx; ++cx) {
        const std::uint64_t bits = noiseHash(key, cx + nx * (cy + ny * cz));
        // Uniform in the cell, clipped to the volume at the far faces.
        const auto jitter = [&](std::size_t c, std::int64_t axisExtent, int bitSlot) {
          const std::int64_t lo = static_cast<std::int64_t>(c) * r;
          return static_cast<std::int32_t>(lo +
                                           scaled21(bits, bitSlot, std::min(r, axisExtent - lo)));
        };
        Slot& here = slot(cx, cy, cz);
        here.p = {jitter(cx, extent.x, 0), jitter(cy, extent.y, 1), jitter(cz, extent.z, 2)};
        here.kept = true;
        for (int dz = -1; dz <= 0 && here.kept; ++dz)
          for (int dy = -1; dy <= 1 && here.kept; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              if (dz == 0 && (dy > 0 || (dy == 0 && dx >= 0))) break;  // not yet visited
              if ((dz < 0 && cz == 0) || (dy < 0 && cy == 0) || (dx < 0 && cx == 0) ||
                  (dx > 0 && cx + 1 == nx) || (dy > 0 && cy + 1 == ny))
                continue;
              const Slot& other =
                  slot(cx + static_cast<std::size_t>(dx), cy + static_cast<std::size_t>(dy),
                       cz + static_cast<std::size_t>(dz));
              if (other.kept && distanceSquared(other.p, here.p) < r2) {
                here.kept = false;
                break;
              }
            }
        if (here.kept) result.push_back(toVoxels(here.p));
      }
  return result;
}

CheckerboardPattern checkerboardPattern(float ratio, Dims dims) {
  const double target = std::clamp(static_cast<double>(ratio), 0.0, 1.0);
  if (!validDims(dims)) return {};
  const std::vector<std::uint64_t> counts = diagonalPlaneCounts(dims);
  const auto voxels = static_cast<double>(voxelCount(dims));
  struct Choice {
    CheckerboardPattern pattern;
    double error;
  };
  std::vector<Choice> choices;
  std::vector<std::uint64_t> perResidue;
  for (int period = 2; period <= kMaxCheckerboardPeriod; ++period) {
    perResidue.assign(static_cast<std::size_t>(period), 0);
    for (std::size_t s = 0; s < counts.size(); ++s)
      perResidue[s % static_cast<std::size_t>(period)] += counts[s];
    for (int black = 1; black < period; ++black) {
      if (std::gcd(black, period) != 1) continue;  // same fraction as a shorter period
      const CheckerboardPattern pattern{black, period};
      std::uint64_t blackVoxels = 0;
      for (std::size_t residue = 0; residue < perResidue.size(); ++residue)
        if (pattern.isBlack(residue)) blackVoxels += perResidue[residue];
      choices.push_back({pattern, std::abs(static_cast<double>(blackVoxels) / voxels - target)});
    }
  }
  double closest = std::numeric_limits<double>::max();
  for (const Choice& c : choices) closest = std::min(closest, c.error);
  // Periods are visited shortest first: the first choice near enough wins.
  const double enough = std::max(closest, 0.01 * std::min(target, 1.0 - target));
  for (const Choice& c : choices)
    if (c.error <= enough) return c.pattern;
  return {};
}

}  // namespace lic3d
