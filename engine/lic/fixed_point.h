// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to the point samplers and the sparsity mask (not an API): the fixed-point geometry and
// the integer random numbers that keep every distribution identical on every machine.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <utility>
#include <vector>

#include "core/volume.h"
#include "io/file_util.h"
#include "lic/point_sets.h"
#include "lic/random.h"

namespace lic3d::points {

// Random geometry runs on integers in units of 1/1024 voxel: coordinates below 16384 * 1024 =
// 2^24 convert to float exactly, and squared distances fit in int64 with room to spare.
inline constexpr int kFixedBits = 10;
inline constexpr std::int64_t kFixedOne = std::int64_t{1} << kFixedBits;
inline constexpr float kFixedToVoxels = 1.0f / static_cast<float>(kFixedOne);

// Streams of the seed, so distributions sharing a seed do not share random numbers.
inline constexpr std::uint64_t kPoissonStream = 0x506F6973736F6E31ull;
inline constexpr std::uint64_t kPoissonSlabStream = 0x506F69536C616230ull;  // plus the slab
inline constexpr std::uint64_t kPoissonBandStream = 0x506F6942616E6430ull;  // plus the band
inline constexpr std::uint64_t kBestCandidateStream = 0x4265737443616E64ull;
inline constexpr std::uint64_t kJitterStream = 0x4A69747465723031ull;
inline constexpr std::uint64_t kSubsetStream = 0x5375627365743031ull;

struct FixedPoint {
  std::int32_t x = 0, y = 0, z = 0;
};

inline std::int64_t distanceSquared(const FixedPoint& a, const FixedPoint& b) {
  const std::int64_t dx = a.x - b.x, dy = a.y - b.y, dz = a.z - b.z;
  return dx * dx + dy * dy + dz * dz;
}

inline glm::vec3 toVoxels(const FixedPoint& p) {
  return {static_cast<float>(p.x) * kFixedToVoxels, static_cast<float>(p.y) * kFixedToVoxels,
          static_cast<float>(p.z) * kFixedToVoxels};
}

// SplitMix64 (Steele, Lea, Flood 2014), started from the project's noiseHash of (seed, stream).
class Random {
 public:
  Random(std::uint64_t seed, std::uint64_t stream) : state_(noiseHash(seed, stream)) {}

  std::uint64_t next() {
    state_ += 0x9E3779B97F4A7C15ull;
    std::uint64_t z = state_;
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
  }

  // Uniform in [0, n), n < 2^32: Lemire's multiply-shift, bias below n / 2^32.
  std::uint32_t below(std::size_t n) {
    return static_cast<std::uint32_t>(((next() >> 32) * static_cast<std::uint64_t>(n)) >> 32);
  }

 private:
  std::uint64_t state_;
};

// Keeps `count` of the points, chosen uniformly at random (a partial Fisher-Yates shuffle).
inline void keepRandomSubset(std::vector<glm::vec3>& points, std::size_t count,
                             std::uint64_t seed) {
  if (count == 0 || points.size() <= count) return;
  Random random(seed, kSubsetStream);
  for (std::size_t i = 0; i < count; ++i)
    std::swap(points[i], points[i + random.below(points.size() - i)]);
  points.resize(count);
}

// One 64-bit random word gives three 21-bit fractions; each maps to [0, span) by multiply-shift.
// Spans above 2^21 units (grids over 2048 voxels) then land on a lattice of span / 2^21 units,
// finer than 1/128 voxel.
inline std::int64_t scaled21(std::uint64_t bits, int slot, std::int64_t span) {
  const std::int64_t fraction = static_cast<std::int64_t>((bits >> (21 * slot)) & 0x1FFFFF);
  return (fraction * span) >> 21;
}

inline std::int64_t isqrt(std::int64_t value) {
  if (value <= 0) return 0;
  auto root = static_cast<std::int64_t>(std::sqrt(static_cast<double>(value)));
  while (root * root > value) --root;
  while ((root + 1) * (root + 1) <= value) ++root;
  return root;
}

// floor(v / d) for 0 <= v < 2^27 by multiply and shift (Granlund, Montgomery 1994, "Division
// by invariant integers using multiplication"): the grid searches divide every candidate's
// coordinates by the cell size, and a 64-bit idiv costs 40-90 cycles.
class CellDivider {
 public:
  explicit CellDivider(std::int64_t divisor) {
    int log2Ceil = 0;
    while ((std::int64_t{1} << log2Ceil) < divisor) ++log2Ceil;
    shift_ = kValueBits + log2Ceil;
    multiplier_ = (std::int64_t{1} << shift_) / divisor + 1;
  }
  std::int64_t operator()(std::int64_t value) const { return (value * multiplier_) >> shift_; }

 private:
  static constexpr int kValueBits = 27;
  std::int64_t multiplier_ = 1;
  int shift_ = 0;
};

inline bool validDims(Dims dims) {
  return dims.x >= 1 && dims.y >= 1 && dims.z >= 1 && dims.x <= static_cast<int>(kMaxAxisSize) &&
         dims.y <= static_cast<int>(kMaxAxisSize) && dims.z <= static_cast<int>(kMaxAxisSize);
}

struct FixedExtent {
  std::int64_t x, y, z;
};
inline FixedExtent fixedExtent(Dims dims) {
  return {dims.x * kFixedOne, dims.y * kFixedOne, dims.z * kFixedOne};
}

// The radius in fixed point, rounded up so that integer distances >= it are >= the radius.
inline std::int64_t fixedRadius(float radius) {
  const double r = std::max(static_cast<double>(radius), static_cast<double>(kMinSparsityRadius));
  return static_cast<std::int64_t>(std::ceil(r * static_cast<double>(kFixedOne)));
}

inline std::size_t cellsAlong(std::int64_t extent, std::int64_t cell) {
  return static_cast<std::size_t>((extent + cell - 1) / cell);
}

// Bridson's background grid: the largest integer cell C with C * sqrt(3) <= R, so a cell (a cube
// of side C) holds at most one sample.
struct PoissonGridShape {
  std::int64_t cell = 1;
  int reach = 2;                       // a conflicting sample lies at most this many cells away
  std::size_t nx = 0, ny = 0, nz = 0;  // including `reach` empty cells of padding on each side
  std::size_t cells() const { return nx * ny * nz; }
};

inline PoissonGridShape poissonGridShape(Dims dims, std::int64_t fixedR) {
  PoissonGridShape shape;
  shape.cell = std::max<std::int64_t>(1, isqrt(fixedR * fixedR / 3));
  while (3 * shape.cell * shape.cell > fixedR * fixedR && shape.cell > 1) --shape.cell;
  shape.reach = static_cast<int>((fixedR + shape.cell - 1) / shape.cell);
  const FixedExtent e = fixedExtent(dims);
  const auto pad = static_cast<std::size_t>(2 * shape.reach);
  shape.nx = cellsAlong(e.x, shape.cell) + pad;
  shape.ny = cellsAlong(e.y, shape.cell) + pad;
  shape.nz = cellsAlong(e.z, shape.cell) + pad;
  return shape;
}

inline std::size_t jitterCells(Dims dims, std::int64_t fixedR) {
  const FixedExtent e = fixedExtent(dims);
  return cellsAlong(e.x, fixedR) * cellsAlong(e.y, fixedR) * cellsAlong(e.z, fixedR);
}

}  // namespace lic3d::points
