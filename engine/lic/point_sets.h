// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Point distributions for sparsity masks (lic/sparsity.h) and seed noise: points that should be
// even but not regular (thesis 5.1.4.2): Poisson disk (exact, and the thesis' best-candidate
// approximation), jittering, and the Halton and Hammersley low-discrepancy sequences; plus the
// thesis' regular checkerboard for comparison.
//
// Every distribution is a pure function of its parameters and seed, identical on every machine
// and compiler: the random numbers are SplitMix64 (integer only), and the random geometry runs in
// fixed point (1/1024 voxel), so no floating-point rounding or contraction decides which points
// are kept. Returned points are exact floats of those fixed-point values.

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <utility>
#include <vector>

#include "core/volume.h"

namespace lic3d {

// Points per cubic radius that Bridson's sampling (k = kPoissonAttempts) leaves when it runs
// until maximal, measured inside 128^3 and 256^3 volumes (a boundary adds a little).
inline constexpr double kPoissonDensity = 0.52;
// Fraction of jitter cells (side = radius) whose point is kept, measured on 128^3 and 256^3.
inline constexpr double kJitterDensity = 0.39;

// k of Bridson 2007: candidates tried around an active sample before it is retired. Bridson
// used 30; 10 leaves 1.2 % of the volume farther than r from every sample (30: 0.3 %) and 13 %
// fewer points, in less than half the time (1M points in 256^3 on one thread of the 2-core build
// machine: 1.1-1.5 s, 2.4 s with k = 30). For a sparsity mask those small gaps do not show.
inline constexpr int kPoissonAttempts = 10;
// m of Mitchell's best-candidate algorithm as the thesis used it (5.1.4.2.1): m * n candidates
// for the (n+1)-th point, up to n = kBestCandidateHistory; from there on m * kBestCandidateHistory
// candidates per point, so the time grows with n instead of n^2 and the automatic point count
// (10 % of the voxels, 210,000 points on 128^3) is reached.
inline constexpr int kBestCandidateFactor = 10;
inline constexpr std::size_t kBestCandidateHistory = 32;

// Limits that keep memory and time bounded before anything is allocated (validate()).
inline constexpr float kMinSparsityRadius = 0.5f;
inline constexpr std::size_t kMaxSparsityPoints = std::size_t{1} << 25;
// Best candidate costs about m * kBestCandidateHistory candidate tests per point, most of them
// one distance; their memory accesses are random, so the time per point grows slowly with n: on
// one core of the build machine 0.16 s for 16,384 points in 128^3, 0.95 s for 65,536, 5.7 s for
// 209,715 (10 % of 128^3). The limit keeps it under a few minutes.
inline constexpr std::size_t kMaxBestCandidatePoints = std::size_t{1} << 21;
// The background grid of Bridson's algorithm has about 5.2 V / r^3 cells of 4 bytes.
inline constexpr std::size_t kMaxPoissonGridCells = std::size_t{1} << 26;
// Longest period of the checkerboard pattern (see checkerboardPattern).
inline constexpr int kMaxCheckerboardPeriod = 64;

// phi_b(i): i written in base b, mirrored about the radix point (thesis 5.1.4.2.2).
// phi_2(1) = 0.5, phi_3(1) = 1/3, phi_2(6) = 0.375. In [0, 1), correctly rounded for
// i < 2^53 / b; 0 for base < 2.
double radicalInverse(std::uint32_t base, std::uint64_t index);

// Points in continuous voxel coordinates [0,NX) x [0,NY) x [0,NZ). The generators trust their
// arguments (makeSparsityMask validates first); non-positive dims or counts give no points.

// i = 1..count: (phi_2(i), phi_3(i), phi_5(i)) * dims.
std::vector<glm::vec3> haltonPoints(Dims dims, std::size_t count);
// i = 1..count: (i / count, phi_2(i), phi_3(i)) * dims; the thesis' first point is
// (1/N, 0.5, 1/3). The last, i / count = 1, is kept inside, in the last voxel layer of x.
std::vector<glm::vec3> hammersleyPoints(Dims dims, std::size_t count);
// The voxels of haltonPoints (halton) or hammersleyPoints, exactly: floor(n * coordinate) of the
// exact rational coordinate, which the float points can round up into the next voxel where it lies
// within a float's precision below a voxel face. What sparsity masks blacken; the GPU's
// licScaledRadicalInverse (shaders/sparsity_mask.h) gives the same voxels.
std::vector<glm::ivec3> lowDiscrepancyVoxels(Dims dims, std::size_t count, bool halton);
// Exact Poisson disk sampling (Bridson 2007, "Fast Poisson disk sampling in arbitrary
// dimensions"), O(n): background grid of cell r / sqrt(3), k = kPoissonAttempts candidates in the
// annulus [r, 2r] around an active sample. Every pair is at least `radius` apart, and the set is
// maximal up to the k-attempt criterion, or stops at maxPoints. Volumes of many grid layers along
// z are cut into 2 or 4 slabs, sampled on up to `threads` threads at once (0: one per CPU
// the process may run on), and then the thin bands between them (poissonDiskBands) are sampled from
// the slabs' samples on either side (see the .cpp). The points depend on the arguments other than
// `threads` only: never on the machine, the thread count or the timing. The active sample is drawn
// from the first grid tile that has one, for cache locality (see the .cpp), so each slab grows
// along z, and the points are listed in z order (slab, band, slab, ...): a set stopped by maxPoints
// lacks the top of the volume. For n even points, take a radius whose maximal set is larger (about
// kPoissonDensity V / r^3 points) and a random subset. radius is raised to kMinSparsityRadius.
// Memory: grids of about 5.2 V / r^3 cells of 4 bytes in all, and 12 bytes per point.
std::vector<glm::vec3> poissonDiskPoints(Dims dims, float radius, std::uint64_t seed,
                                         std::size_t maxPoints, unsigned threads = 0);
// The z ranges [z0, z1) in voxels of the bands between the slabs that poissonDiskPoints cuts
// this volume into for this radius; none if it samples the volume whole. For tests and
// measurements: a band is about 1.2 r thick.
std::vector<std::pair<float, float>> poissonDiskBands(Dims dims, float radius);
// About `count` points of an exact Poisson disk set, evenly over the whole volume: the radius
// whose maximal set has a few more points than asked for, then a random subset of `count`.
// Stopping the sampling at the count instead would leave the end of the volume empty.
std::vector<glm::vec3> poissonDiskPointsByCount(Dims dims, std::size_t count, std::uint64_t seed);
// Mitchell's best candidate (1991), the thesis' approximation of Poisson disk: point n+1 is, of
// m * n uniform candidates (n >= 1), the one farthest from the points so far.
std::vector<glm::vec3> bestCandidatePoints(Dims dims, std::size_t count, int candidatesPerPoint,
                                           std::uint64_t seed);
// The thesis' jittering (5.1.4.2.1 (c)): one point uniform in each cell of a grid of side
// `radius`, kept only if no point kept before it (cells in z, y, x order) is within `radius`.
// radius is raised to kMinSparsityRadius.
std::vector<glm::vec3> jitteredPoints(Dims dims, float radius, std::uint64_t seed);

// The checkerboard (thesis 5.1.4.2.1 (a)): voxel (i,j,k) is black where
//   ((i + j + k) * black) mod period < black,
// so black / period of the diagonal planes i+j+k = s are black, spread as evenly as the period
// allows; black = 1, period = 2 is the classic 3D checkerboard. A regular pattern can only hit
// fractions black / period, so of the patterns with period <= kMaxCheckerboardPeriod (counted
// exactly on `dims`) this picks the shortest period whose black fraction is within 1 % of the
// ratio (relative to the rarer colour), or else the closest: 0.05 gives every 20th plane, not a
// lucky 3/59; 0.37 gives 7/19.
struct CheckerboardPattern {
  int black = 1;
  int period = 2;
  bool operator==(const CheckerboardPattern&) const = default;
  // Whether the diagonal plane i + j + k = s is black.
  bool isBlack(std::uint64_t s) const {
    return (s * static_cast<std::uint64_t>(black)) % static_cast<std::uint64_t>(period) <
           static_cast<std::uint64_t>(black);
  }
};
CheckerboardPattern checkerboardPattern(float ratio, Dims dims);

}  // namespace lic3d
