// SPDX-License-Identifier: BSD-3-Clause
#include "lic/sparsity_automatic.h"

#include <algorithm>
#include <cmath>

#include "lic/fixed_point.h"
#include "lic/sparsity.h"

namespace lic3d::points {
namespace {

// The radius r (a multiple of 1/1024 voxel, rounded up) with r^3 >= volumePerPoint: an integer
// cube root, since std::cbrt may round differently from one C library to another and the
// automatic radius must be the same everywhere.
float radiusForVolume(double volumePerPoint) {
  const double limit = std::ldexp(1.0, 60);  // (2^20 units)^3: a 1024-voxel radius
  const double scaled = std::ceil(volumePerPoint * std::ldexp(1.0, 3 * kFixedBits));
  const auto target = static_cast<std::uint64_t>(std::min(scaled, limit));
  std::uint64_t lo = 0, hi = std::uint64_t{1} << 20;  // lo^3 < target <= hi^3
  while (hi - lo > 1) {
    const std::uint64_t mid = (lo + hi) / 2;
    (mid * mid * mid >= target ? hi : lo) = mid;
  }
  return static_cast<float>(hi) * kFixedToVoxels;
}

std::size_t automaticPointCount(double blackFraction, Dims dims, std::size_t limit) {
  const double points = std::round(blackFraction * static_cast<double>(voxelCount(dims)));
  return std::clamp<std::size_t>(static_cast<std::size_t>(points), 1, limit);
}

// Poisson with a point count: a radius whose maximal set has about this many times more points,
// of which a random subset of exactly the count is kept. Stopping the sampling at the count
// instead would leave the last part of the volume (in the order it grows) empty.
constexpr double kPoissonSurplus = 1.1;

}  // namespace

bool poissonFits(Dims dims, float radius) {
  return poissonGridShape(dims, fixedRadius(radius)).cells() <= kMaxPoissonGridCells;
}
bool jitterFits(Dims dims, float radius) {
  return jitterCells(dims, fixedRadius(radius)) <= kMaxSparsityPoints;
}

float largestAxis(Dims dims) { return static_cast<float>(std::max({dims.x, dims.y, dims.z})); }

ResolvedParams resolve(const SparsityParams& params, Dims dims) {
  ResolvedParams resolved;
  const auto voxels = static_cast<double>(voxelCount(dims));
  const auto given = static_cast<std::size_t>(std::max(params.points, 0));
  const auto automatic = [&](std::size_t limit) {
    return automaticPointCount(params.blackFraction, dims, limit);
  };
  switch (params.distribution) {
    case SparsityDistribution::None:
    case SparsityDistribution::Checkerboard: break;
    case SparsityDistribution::Halton:
    case SparsityDistribution::Hammersley:
      resolved.points = given > 0 ? given : automatic(kMaxSparsityPoints);
      break;
    case SparsityDistribution::PoissonApprox:
      resolved.points = given > 0 ? given : automatic(kMaxBestCandidatePoints);
      break;
    case SparsityDistribution::Poisson:
      resolved.points = given;
      if (params.radius > 0.0f) {
        resolved.radius = params.radius;
        break;
      }
      if (given == 0) resolved.points = automatic(kMaxSparsityPoints);
      resolved.radius =
          std::max(radiusForVolume(kPoissonDensity * voxels /
                                   (kPoissonSurplus * static_cast<double>(resolved.points))),
                   kMinSparsityRadius);
      resolved.radiusFromPoints = given > 0;
      if (given == 0 && !poissonFits(dims, resolved.radius))
        resolved.radius = smallestRadiusThatFits([&](float r) { return poissonFits(dims, r); },
                                                 largestAxis(dims));
      break;
    case SparsityDistribution::Jitter:
      resolved.radius = params.radius;
      if (params.radius > 0.0f) break;
      resolved.radius = radiusForVolume(kJitterDensity / params.blackFraction);
      if (!jitterFits(dims, resolved.radius))
        resolved.radius =
            smallestRadiusThatFits([&](float r) { return jitterFits(dims, r); }, largestAxis(dims));
      break;
  }
  return resolved;
}

}  // namespace lic3d::points
