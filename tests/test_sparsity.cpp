// SPDX-License-Identifier: BSD-3-Clause
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>
#include <set>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "lic/noise.h"
#include "lic/sparsity.h"

namespace lic3d {
namespace {

// Non-cubic on purpose: a mixed-up axis puts points outside or in the wrong voxels.
constexpr Dims kOddDims{24, 32, 40};

bool inside(Dims dims, const glm::vec3& p) {
  return p.x >= 0.0f && p.y >= 0.0f && p.z >= 0.0f && p.x < static_cast<float>(dims.x) &&
         p.y < static_cast<float>(dims.y) && p.z < static_cast<float>(dims.z);
}

// Buckets points into cubes of side `cell`, so neighbour queries look at 27 buckets instead of
// every point (the Poisson sets below have thousands of points).
class PointGrid {
 public:
  PointGrid(Dims dims, float cell, const std::vector<glm::vec3>& points)
      : cell_(cell), points_(points) {
    size_ = glm::ivec3(glm::ceil(glm::vec3(dims) / cell));
    buckets_.resize(static_cast<std::size_t>(size_.x) * size_.y * size_.z);
    for (std::size_t i = 0; i < points.size(); ++i) buckets_[bucketOf(points[i])].push_back(i);
  }

  // Smallest distance from q to a point other than `skip`, looking only within one cell.
  double nearest(const glm::vec3& q,
                 std::size_t skip = std::numeric_limits<std::size_t>::max()) const {
    const glm::ivec3 c = cellOf(q);
    double best = std::numeric_limits<double>::infinity();
    for (int dz = -1; dz <= 1; ++dz)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const glm::ivec3 n = c + glm::ivec3(dx, dy, dz);
          if (glm::any(glm::lessThan(n, glm::ivec3(0))) ||
              glm::any(glm::greaterThanEqual(n, size_)))
            continue;
          for (std::size_t i : buckets_[index(n)]) {
            if (i == skip) continue;
            best = std::min(best, glm::length(glm::dvec3(points_[i]) - glm::dvec3(q)));
          }
        }
    return best;
  }

  // Smallest distance between two points, for sets whose spacing is at least `cell`.
  double minimumPairDistance() const {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < points_.size(); ++i) best = std::min(best, nearest(points_[i], i));
    return best;
  }

 private:
  glm::ivec3 cellOf(const glm::vec3& p) const {
    return glm::clamp(glm::ivec3(glm::floor(p / cell_)), glm::ivec3(0), size_ - 1);
  }
  std::size_t index(glm::ivec3 c) const {
    return static_cast<std::size_t>(c.x) +
           static_cast<std::size_t>(size_.x) *
               (static_cast<std::size_t>(c.y) + static_cast<std::size_t>(size_.y) * c.z);
  }
  std::size_t bucketOf(const glm::vec3& p) const { return index(cellOf(p)); }

  float cell_;
  const std::vector<glm::vec3>& points_;
  glm::ivec3 size_{0};
  std::vector<std::vector<std::size_t>> buckets_;
};

// Uniform test points from the project's own hash, independent of the code under test.
std::vector<glm::vec3> uniformPoints(Dims dims, std::size_t count, std::uint64_t seed) {
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i < count; ++i) {
    const auto unit = [&](std::uint64_t axis) {
      return static_cast<float>(static_cast<double>(noiseHash(seed, 3 * i + axis) >> 11) *
                                0x1.0p-53);
    };
    points.emplace_back(unit(0) * static_cast<float>(dims.x), unit(1) * static_cast<float>(dims.y),
                        unit(2) * static_cast<float>(dims.z));
  }
  return points;
}

// Uniform test points in the box [lo, hi), from the project's own hash.
std::vector<glm::vec3> uniformPointsIn(glm::vec3 lo, glm::vec3 hi, std::size_t count,
                                       std::uint64_t seed) {
  std::vector<glm::vec3> points;
  for (std::size_t i = 0; i < count; ++i) {
    glm::vec3 unit;
    for (int axis = 0; axis < 3; ++axis)
      unit[axis] = static_cast<float>(
          static_cast<double>(noiseHash(seed, 3 * i + static_cast<std::uint64_t>(axis)) >> 11) *
          0x1.0p-53);
    points.push_back(lo + unit * (hi - lo));
  }
  return points;
}

double meanNearestNeighbour(Dims dims, const std::vector<glm::vec3>& points, float cell) {
  const PointGrid grid(dims, cell, points);
  double sum = 0.0;
  for (std::size_t i = 0; i < points.size(); ++i) sum += grid.nearest(points[i], i);
  return sum / static_cast<double>(points.size());
}

double blackFraction(const SparsityMask& mask) {
  return static_cast<double>(mask.blackCount) / static_cast<double>(voxelCount(mask.dims));
}

SparsityParams paramsFor(SparsityDistribution distribution) {
  SparsityParams params;
  params.distribution = distribution;
  return params;
}

// The mask's grid limit (2^31 voxels) is the mask's only: a grid past it without sparsity is
// valid (1792^3 on a large device, or in bricks).
TEST(Sparsity, TheMasksVoxelLimitAppliesOnlyWithAMask) {
  SparsityParams none;
  EXPECT_TRUE(validate(none, Dims(1792)));
  SparsityParams jitter;
  jitter.distribution = SparsityDistribution::Jitter;
  EXPECT_FALSE(validate(jitter, Dims(1792)));
  EXPECT_TRUE(validate(jitter, Dims(1024)));
}

TEST(Sparsity, NamesRoundTrip) {
  std::vector<std::string_view> names;
  for (const auto& n : enumNames<SparsityDistribution>()) names.push_back(n.name);
  ASSERT_EQ(names.size(), 7u);
  EXPECT_EQ(names[3], "poisson-approx");
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto parsed = parseEnum<SparsityDistribution>(names[i]);
    ASSERT_TRUE(parsed.has_value()) << names[i];
    EXPECT_EQ(static_cast<std::size_t>(*parsed), i);
    EXPECT_EQ(enumName(*parsed), names[i]);
  }
  EXPECT_FALSE(parseEnum<SparsityDistribution>("Poisson").has_value());
  EXPECT_FALSE(parseEnum<SparsityDistribution>("").has_value());
}

TEST(Sparsity, RadicalInverseKnownValues) {
  EXPECT_EQ(radicalInverse(2, 1), 0.5);
  EXPECT_EQ(radicalInverse(3, 1), 1.0 / 3.0);
  EXPECT_EQ(radicalInverse(2, 6), 0.375);  // 110 -> 0.011
  EXPECT_EQ(radicalInverse(5, 3), 0.6);
  EXPECT_EQ(radicalInverse(2, 0), 0.0);
  EXPECT_EQ(radicalInverse(3, 5), 7.0 / 9.0);   // 12 -> 0.21
  EXPECT_EQ(radicalInverse(7, 8), 8.0 / 49.0);  // 11 -> 0.11, a base without a fast path
  EXPECT_EQ(radicalInverse(2, 1u << 20), 0x1.0p-21);
  EXPECT_LT(radicalInverse(2, std::numeric_limits<std::uint64_t>::max()), 1.0);
}

TEST(Sparsity, HaltonPointsAreRadicalInversesTimesDims) {
  const std::vector<glm::vec3> points = haltonPoints(kOddDims, 2000);
  ASSERT_EQ(points.size(), 2000u);
  // i = 1: (1/2, 1/3, 1/5); i = 2: (1/4, 2/3, 2/5).
  EXPECT_FLOAT_EQ(points[0].x, 12.0f);
  EXPECT_FLOAT_EQ(points[0].y, 32.0f / 3.0f);
  EXPECT_FLOAT_EQ(points[0].z, 8.0f);
  EXPECT_FLOAT_EQ(points[1].x, 6.0f);
  EXPECT_FLOAT_EQ(points[1].y, 64.0f / 3.0f);
  EXPECT_FLOAT_EQ(points[1].z, 16.0f);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::uint64_t n = i + 1;
    ASSERT_EQ(points[i].x, static_cast<float>(radicalInverse(2, n) * kOddDims.x)) << n;
    ASSERT_EQ(points[i].y, static_cast<float>(radicalInverse(3, n) * kOddDims.y)) << n;
    ASSERT_EQ(points[i].z, static_cast<float>(radicalInverse(5, n) * kOddDims.z)) << n;
  }
}

TEST(Sparsity, HammersleyPointsFollowTheThesis) {
  const std::size_t count = 250;
  const std::vector<glm::vec3> points = hammersleyPoints(kOddDims, count);
  ASSERT_EQ(points.size(), count);
  // The thesis' first point (1/N, phi_2(1), phi_3(1)) = (1/N, 0.5, 1/3), times the grid.
  EXPECT_FLOAT_EQ(points[0].x, 24.0f / 250.0f);
  EXPECT_FLOAT_EQ(points[0].y, 16.0f);
  EXPECT_FLOAT_EQ(points[0].z, 40.0f / 3.0f);
  for (std::size_t i = 0; i + 1 < count; ++i) {
    const std::uint64_t n = i + 1;
    ASSERT_FLOAT_EQ(points[i].x, static_cast<float>(n) * 24.0f / 250.0f) << n;
    ASSERT_EQ(points[i].y, static_cast<float>(radicalInverse(2, n) * kOddDims.y)) << n;
    ASSERT_EQ(points[i].z, static_cast<float>(radicalInverse(3, n) * kOddDims.z)) << n;
  }
  // i = N gives x = NX exactly; it is kept in the last layer.
  EXPECT_LT(points.back().x, 24.0f);
  EXPECT_GT(points.back().x, 23.999f);
}

TEST(Sparsity, PoissonKeepsTheRadiusAndLeavesNoRoom) {
  const float radius = 2.5f;
  const std::vector<glm::vec3> points =
      poissonDiskPoints({64, 64, 64}, radius, 7, std::numeric_limits<std::size_t>::max());
  ASSERT_GT(points.size(), 5000u);
  for (const glm::vec3& p : points) ASSERT_TRUE(inside({64, 64, 64}, p));
  const PointGrid grid({64, 64, 64}, radius, points);
  EXPECT_GE(grid.minimumPairDistance(), radius * (1.0 - 1e-6));

  // Near-maximal: a random point is never 2r from every sample, and rarely even r.
  const PointGrid coarse({64, 64, 64}, 2.0f * radius, points);
  const std::vector<glm::vec3> probes = uniformPoints({64, 64, 64}, 20000, 99);
  int farther = 0;
  for (const glm::vec3& q : probes) {
    const double d = coarse.nearest(q);
    ASSERT_LT(d, 2.0 * radius) << q.x << " " << q.y << " " << q.z;
    farther += d >= radius;
  }
  EXPECT_LT(farther, 600) << "more than 3 % of the volume could still take a sample";
  EXPECT_NEAR(static_cast<double>(points.size()) * radius * radius * radius / (64.0 * 64 * 64),
              kPoissonDensity, 0.05);
}

TEST(Sparsity, PoissonOnANonCubicGridAndStopsAtMaxPoints) {
  const std::vector<glm::vec3> all =
      poissonDiskPoints(kOddDims, 2.0f, 3, std::numeric_limits<std::size_t>::max());
  ASSERT_GT(all.size(), 1000u);
  glm::vec3 highest(0.0f);
  for (const glm::vec3& p : all) {
    ASSERT_TRUE(inside(kOddDims, p));
    highest = glm::max(highest, p);
  }
  // The samples reach the far corner of every axis, so no axis was taken for another.
  EXPECT_GT(highest.x, 22.0f);
  EXPECT_GT(highest.y, 30.0f);
  EXPECT_GT(highest.z, 38.0f);
  EXPECT_GE(PointGrid(kOddDims, 2.0f, all).minimumPairDistance(), 2.0 * (1.0 - 1e-6));

  const std::vector<glm::vec3> capped = poissonDiskPoints(kOddDims, 2.0f, 3, 100);
  EXPECT_EQ(capped.size(), 100u);
}

// 64 x 64 x 320 with r = 2 has 278 grid layers along z: four slabs and three bands.
constexpr Dims kSlabbedDims{64, 64, 320};

TEST(Sparsity, PoissonCutsOnlyLargeVolumesIntoSlabs) {
  EXPECT_TRUE(poissonDiskBands({32, 32, 32}, 2.5f).empty());
  EXPECT_TRUE(poissonDiskBands({64, 64, 64}, 1.72f).empty());
  EXPECT_EQ(poissonDiskBands({256, 256, 256}, 2.06f).size(), 1u);  // the 1M-point case
  EXPECT_EQ(poissonDiskBands({256, 256, 512}, 2.06f).size(), 3u);
  const auto bands = poissonDiskBands(kSlabbedDims, 2.0f);
  ASSERT_EQ(bands.size(), 3u);
  float previous = 0.0f;
  for (const auto& [z0, z1] : bands) {
    // At least r thick, so samples of two slabs are r apart; not much more, or it costs.
    EXPECT_GE(z1 - z0, 2.0f);
    EXPECT_LT(z1 - z0, 3.0f);
    EXPECT_GT(z0, previous + 40.0f) << "slabs of similar size";
    previous = z1;
  }
  EXPECT_LT(previous, 320.0f - 40.0f);
}

TEST(Sparsity, PoissonKeepsTheRadiusAcrossTheBands) {
  struct Case {
    Dims dims;
    float radius;
    std::uint64_t seed;
  };
  for (const auto& [dims, radius, seed] :
       {Case{kSlabbedDims, 2.0f, 3}, Case{{40, 24, 200}, 1.0f, 8}, Case{{20, 36, 700}, 2.7f, 5}}) {
    ASSERT_FALSE(poissonDiskBands(dims, radius).empty()) << dims.z;
    const std::vector<glm::vec3> points =
        poissonDiskPoints(dims, radius, seed, std::numeric_limits<std::size_t>::max());
    for (const glm::vec3& p : points) ASSERT_TRUE(inside(dims, p));
    EXPECT_GE(PointGrid(dims, radius, points).minimumPairDistance(), radius * (1.0 - 1e-6))
        << dims.z;
    EXPECT_NEAR(static_cast<double>(points.size()) * radius * radius * radius /
                    (static_cast<double>(dims.x) * dims.y * dims.z),
                kPoissonDensity, 0.05)
        << dims.z;
  }
}

TEST(Sparsity, PoissonBandsLeaveNoMoreRoomThanTheRestOfTheVolume) {
  const float r = 2.0f;
  const std::vector<glm::vec3> points =
      poissonDiskPoints(kSlabbedDims, r, 3, std::numeric_limits<std::size_t>::max());
  const auto bands = poissonDiskBands(kSlabbedDims, r);
  ASSERT_EQ(bands.size(), 3u);
  const PointGrid grid(kSlabbedDims, 2.0f * r, points);
  // The fraction of probes at least r from every sample: room for one more. Probes stay 2r from
  // the x and y faces, where every part of the volume has more room.
  const glm::vec2 lo(2.0f * r), hi(64.0f - 2.0f * r);
  const auto room = [&](float z0, float z1, std::size_t count, std::uint64_t seed) {
    std::size_t free = 0;
    for (const glm::vec3& q : uniformPointsIn(glm::vec3(lo, z0), glm::vec3(hi, z1), count, seed)) {
      const double d = grid.nearest(q);
      EXPECT_LT(d, 2.0 * r) << q.x << " " << q.y << " " << q.z;
      free += d >= r;
    }
    return static_cast<double>(free) / static_cast<double>(count);
  };
  // Inside the bands, next to them (2r either side: slab samples pressed against the band), and
  // in the middle of the slabs, with about 500 free probes in each.
  double inBands = 0.0, nextToBands = 0.0;
  for (std::size_t b = 0; b < bands.size(); ++b) {
    const auto [z0, z1] = bands[b];
    inBands += room(z0, z1, 20000, 10 + b) / 3.0;
    nextToBands +=
        (room(z0 - 2.0f * r, z0, 10000, 20 + b) + room(z1, z1 + 2.0f * r, 10000, 30 + b)) / 6.0;
  }
  const double inSlabs =
      room(20.0f, 60.0f, 30000, 40) / 2.0 + room(260.0f, 300.0f, 30000, 41) / 2.0;
  EXPECT_GT(inSlabs, 0.003);
  EXPECT_LT(inSlabs, 0.02);
  // Without the band sampling pressing in from both sides (see sampleRegion), the bands had twice
  // the room of the slabs.
  EXPECT_LT(inBands, 1.25 * inSlabs) << inBands << " against " << inSlabs;
  EXPECT_LT(nextToBands, 1.25 * inSlabs) << nextToBands << " against " << inSlabs;
}

TEST(Sparsity, PoissonIsTheSameOnAnyNumberOfThreads) {
  const Dims dims{16, 16, 400};  // four slabs, as in the golden values below
  const auto sample = [&](unsigned threads) {
    return poissonDiskPoints(dims, 2.0f, 9, std::numeric_limits<std::size_t>::max(), threads);
  };
  ASSERT_EQ(poissonDiskBands(dims, 2.0f).size(), 3u);
  const std::vector<glm::vec3> one = sample(1);
  ASSERT_GT(one.size(), 5000u);
  for (const unsigned threads : {0u, 2u, 3u, 4u, 16u}) EXPECT_EQ(sample(threads), one) << threads;
  // Several at once, so the threads of each run in another order and at other times.
  std::vector<std::vector<glm::vec3>> concurrent(3);
  std::vector<std::thread> callers;
  for (std::size_t i = 0; i < concurrent.size(); ++i)
    callers.emplace_back([&, i] { concurrent[i] = sample(static_cast<unsigned>(i + 2)); });
  for (std::thread& caller : callers) caller.join();
  for (const std::vector<glm::vec3>& points : concurrent) EXPECT_EQ(points, one);
}

TEST(Sparsity, PoissonStopsAtMaxPointsInZOrder) {
  const std::vector<glm::vec3> all =
      poissonDiskPoints(kSlabbedDims, 2.0f, 4, std::numeric_limits<std::size_t>::max());
  const float firstBand = poissonDiskBands(kSlabbedDims, 2.0f).front().first;
  // Fewer than the first slab holds: its first samples, all below the first band.
  const std::vector<glm::vec3> few = poissonDiskPoints(kSlabbedDims, 2.0f, 4, 1000);
  ASSERT_EQ(few.size(), 1000u);
  EXPECT_TRUE(std::equal(few.begin(), few.end(), all.begin()));
  for (const glm::vec3& p : few) ASSERT_LT(p.z, firstBand);
  // All but one: the same points, less the last.
  const std::vector<glm::vec3> most = poissonDiskPoints(kSlabbedDims, 2.0f, 4, all.size() - 1);
  ASSERT_EQ(most.size(), all.size() - 1);
  EXPECT_TRUE(std::equal(most.begin(), most.end(), all.begin()));
  // Half: still exact, and lacking the top of the volume.
  const std::vector<glm::vec3> half = poissonDiskPoints(kSlabbedDims, 2.0f, 4, all.size() / 2);
  ASSERT_EQ(half.size(), all.size() / 2);
  EXPECT_GE(PointGrid(kSlabbedDims, 2.0f, half).minimumPairDistance(), 2.0 * (1.0 - 1e-6));
  for (const glm::vec3& p : half) ASSERT_LT(p.z, 240.0f);
}

TEST(Sparsity, BestCandidateSpreadsPointsBetterThanUniform) {
  const Dims dims{48, 40, 32};
  const std::size_t count = 600;
  const std::vector<glm::vec3> best = bestCandidatePoints(dims, count, kBestCandidateFactor, 5);
  ASSERT_EQ(best.size(), count);
  for (const glm::vec3& p : best) ASSERT_TRUE(inside(dims, p));
  const std::vector<glm::vec3> uniform = uniformPoints(dims, count, 5);
  const float cell = 8.0f;  // above any nearest-neighbour distance here
  const double bestMean = meanNearestNeighbour(dims, best, cell);
  const double uniformMean = meanNearestNeighbour(dims, uniform, cell);
  // Uniform points in 3D: mean nearest distance 0.554 (V/n)^(1/3) = 3.9 here; best candidate
  // with m = 10 is near 0.8 (V/n)^(1/3).
  EXPECT_GT(bestMean, 1.3 * uniformMean) << bestMean << " vs " << uniformMean;
}

TEST(Sparsity, BestCandidateWithOneCandidateIsUniformRandom) {
  // m = 1 takes n candidates for point n+1; the first point is a single candidate.
  const std::vector<glm::vec3> points = bestCandidatePoints(kOddDims, 50, 1, 2);
  ASSERT_EQ(points.size(), 50u);
  std::set<std::tuple<float, float, float>> distinct;
  for (const glm::vec3& p : points) {
    ASSERT_TRUE(inside(kOddDims, p));
    distinct.insert({p.x, p.y, p.z});
  }
  EXPECT_EQ(distinct.size(), 50u);
}

TEST(Sparsity, JitterKeepsTheRadius) {
  for (const float radius : {0.5f, 1.0f, 2.5f, 4.0f}) {
    const std::vector<glm::vec3> points = jitteredPoints(kOddDims, radius, 11);
    ASSERT_FALSE(points.empty());
    for (const glm::vec3& p : points) ASSERT_TRUE(inside(kOddDims, p));
    EXPECT_GE(PointGrid(kOddDims, radius, points).minimumPairDistance(), radius * (1.0 - 1e-6))
        << radius;
    // At most one point per cell of side r, and most cells keep theirs.
    const double cells =
        std::ceil(24.0 / radius) * std::ceil(32.0 / radius) * std::ceil(40.0 / radius);
    EXPECT_LE(static_cast<double>(points.size()), cells);
    EXPECT_GT(static_cast<double>(points.size()), 0.25 * cells) << radius;
  }
}

TEST(Sparsity, SameSeedSamePointsOtherSeedOtherPoints) {
  const auto poisson = [](std::uint64_t seed) {
    return poissonDiskPoints(kOddDims, 2.0f, seed, std::numeric_limits<std::size_t>::max());
  };
  const auto best = [](std::uint64_t seed) {
    return bestCandidatePoints(kOddDims, 200, kBestCandidateFactor, seed);
  };
  const auto jitter = [](std::uint64_t seed) { return jitteredPoints(kOddDims, 2.0f, seed); };
  EXPECT_EQ(poisson(1), poisson(1));
  EXPECT_EQ(best(1), best(1));
  EXPECT_EQ(jitter(1), jitter(1));
  EXPECT_NE(poisson(1), poisson(2));
  EXPECT_NE(best(1), best(2));
  EXPECT_NE(jitter(1), jitter(2));

  SparsityParams params = paramsFor(SparsityDistribution::Poisson);
  params.seed = 9;
  const auto a = makeSparsityMask(params, kOddDims);
  const auto b = makeSparsityMask(params, kOddDims);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->black, b->black);
}

TEST(Sparsity, SameSeedSamePointsOnEveryMachine) {
  // Golden values: integer random numbers and fixed-point geometry make them the same for every
  // compiler and CPU. A change here changes every mask lic3d has made for a seed.
  const std::vector<glm::vec3> poisson =
      poissonDiskPoints({32, 32, 32}, 2.5f, 1, std::numeric_limits<std::size_t>::max());
  const std::vector<glm::vec3> best = bestCandidatePoints({32, 32, 32}, 20, 10, 1);
  const std::vector<glm::vec3> jitter = jitteredPoints({32, 32, 32}, 2.5f, 1);
  ASSERT_GE(poisson.size(), 2u);
  ASSERT_GE(jitter.size(), 2u);
  EXPECT_EQ(poisson.size(), 1156u);
  EXPECT_EQ(poisson[1], glm::vec3(22.146484375f, 6.529296875f, 25.357421875f));
  EXPECT_EQ(best[19], glm::vec3(2.33203125f, 0.4580078125f, 8.4833984375f));
  EXPECT_EQ(jitter.size(), 911u);
  EXPECT_EQ(jitter[1], glm::vec3(4.734375f, 2.3203125f, 0.2265625f));

  // Four slabs and three bands, whatever the number of threads.
  const std::vector<glm::vec3> slabbed =
      poissonDiskPoints({16, 16, 400}, 2.0f, 1, std::numeric_limits<std::size_t>::max());
  ASSERT_EQ(slabbed.size(), 7080u);
  EXPECT_EQ(slabbed[1], glm::vec3(5.7119140625f, 0.240234375f, 48.328125f));
  EXPECT_EQ(slabbed[3540], glm::vec3(10.83203125f, 10.7705078125f, 198.8515625f));
  EXPECT_EQ(slabbed[7079], glm::vec3(0.103515625f, 7.45703125f, 392.845703125f));
}

TEST(Sparsity, NoneIsAllWhite) {
  const auto mask = makeSparsityMask(paramsFor(SparsityDistribution::None), kOddDims);
  ASSERT_TRUE(mask.ok());
  EXPECT_EQ(mask->dims, kOddDims);
  EXPECT_EQ(mask->black.size(), voxelCount(kOddDims));
  EXPECT_EQ(mask->blackCount, 0u);
  EXPECT_EQ(std::count(mask->black.begin(), mask->black.end(), 1), 0);
}

TEST(Sparsity, ClassicCheckerboardAtOneHalf) {
  SparsityParams params = paramsFor(SparsityDistribution::Checkerboard);
  params.ratio = 0.5f;
  EXPECT_EQ(checkerboardPattern(0.5f, kOddDims), (CheckerboardPattern{1, 2}));
  const auto mask = makeSparsityMask(params, kOddDims);
  ASSERT_TRUE(mask.ok());
  EXPECT_EQ(mask->blackCount, voxelCount(kOddDims) / 2);
  for (int k = 0; k < kOddDims.z; ++k)
    for (int j = 0; j < kOddDims.y; ++j)
      for (int i = 0; i < kOddDims.x; ++i)
        ASSERT_EQ(mask->black[voxelIndex(kOddDims, i, j, k)], (i + j + k) % 2 == 0 ? 1 : 0);
}

TEST(Sparsity, CheckerboardMatchesTheRatioAsCloselyAsItsPatternsAllow) {
  for (const Dims dims : {Dims{64, 64, 64}, kOddDims}) {
    // Exact voxel counts of every pattern ((i+j+k) * b mod P < b, P <= 64) on this grid.
    std::vector<std::uint64_t> perPlane(static_cast<std::size_t>(dims.x + dims.y + dims.z), 0);
    for (int k = 0; k < dims.z; ++k)
      for (int j = 0; j < dims.y; ++j)
        for (int i = 0; i < dims.x; ++i) ++perPlane[static_cast<std::size_t>(i + j + k)];
    const auto fractionOf = [&](const CheckerboardPattern& pattern) {
      std::uint64_t black = 0;
      for (std::size_t s = 0; s < perPlane.size(); ++s)
        if (s * static_cast<std::uint64_t>(pattern.black) %
                static_cast<std::uint64_t>(pattern.period) <
            static_cast<std::uint64_t>(pattern.black))
          black += perPlane[s];
      return static_cast<double>(black) / static_cast<double>(voxelCount(dims));
    };
    for (const float ratio : {0.05f, 0.02f, 0.1f, 0.25f, 0.3f, 0.37f, 0.5f, 0.75f, 0.9f}) {
      double closest = 1.0;
      for (int period = 2; period <= kMaxCheckerboardPeriod; ++period)
        for (int black = 1; black < period; ++black)
          closest = std::min(closest, std::abs(fractionOf({black, period}) - ratio));
      SparsityParams params = paramsFor(SparsityDistribution::Checkerboard);
      params.ratio = ratio;
      const auto mask = makeSparsityMask(params, dims);
      ASSERT_TRUE(mask.ok());
      const double fraction = blackFraction(*mask);
      const CheckerboardPattern pattern = checkerboardPattern(ratio, dims);
      EXPECT_DOUBLE_EQ(fraction, fractionOf(pattern)) << ratio;
      // The closest pattern, or a shorter one within 1 % of the rarer colour's fraction.
      EXPECT_LE(std::abs(fraction - ratio),
                std::max(closest, 0.01 * std::min<double>(ratio, 1.0 - ratio)) + 1e-12)
          << ratio << " on " << dims.x << "x" << dims.y << "x" << dims.z;
      EXPECT_NEAR(fraction, ratio, 0.005) << ratio;
    }
  }
  EXPECT_EQ(checkerboardPattern(0.05f, {64, 64, 64}), (CheckerboardPattern{1, 20}));
  EXPECT_EQ(checkerboardPattern(0.75f, {64, 64, 64}), (CheckerboardPattern{3, 4}));
}

TEST(Sparsity, AutomaticParametersAimAtTheDefaultFraction) {
  const Dims dims{64, 64, 64};
  for (const SparsityDistribution distribution :
       {SparsityDistribution::Poisson, SparsityDistribution::PoissonApprox,
        SparsityDistribution::Jitter, SparsityDistribution::Halton,
        SparsityDistribution::Hammersley}) {
    const auto mask = makeSparsityMask(paramsFor(distribution), dims);
    ASSERT_TRUE(mask.ok()) << enumName(distribution) << ": " << mask.error().message;
    const double fraction = blackFraction(*mask);
    const double target = kDefaultBlackFraction;  // every automatic count reaches it
    EXPECT_GT(fraction, 0.5 * target) << enumName(distribution);
    EXPECT_LT(fraction, 2.0 * target) << enumName(distribution);
    EXPECT_EQ(static_cast<std::size_t>(std::count(mask->black.begin(), mask->black.end(), 1)),
              mask->blackCount);
  }
}

TEST(Sparsity, PoissonMaskWithACountIsEvenAndKeepsTheRadius) {
  // A count is met by a random subset of a maximal set, not by stopping the sampling (which
  // grows along z and would leave the top empty).
  SparsityParams params = paramsFor(SparsityDistribution::Poisson);
  params.points = 3000;
  const Dims dims{48, 48, 96};
  const auto mask = makeSparsityMask(params, dims);
  ASSERT_TRUE(mask.ok());
  EXPECT_EQ(mask->blackCount, 3000u);
  std::size_t bottom = 0, top = 0;
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const bool black = mask->black[voxelIndex(dims, i, j, k)] != 0;
        bottom += black && k < dims.z / 4;
        top += black && k >= dims.z - dims.z / 4;
      }
  EXPECT_NEAR(static_cast<double>(top), 750.0, 100.0);
  EXPECT_NEAR(static_cast<double>(bottom), 750.0, 100.0);
  // Black voxels are at least the radius apart, less a voxel diagonal.
  std::vector<glm::vec3> centres;
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        if (mask->black[voxelIndex(dims, i, j, k)]) centres.emplace_back(i, j, k);
  const double radius = std::cbrt(kPoissonDensity * 48 * 48 * 96 / (1.1 * 3000));
  EXPECT_GE(PointGrid(dims, 2.0f, centres).minimumPairDistance(), radius - std::sqrt(3.0) - 0.01);
}

TEST(Sparsity, MaskBlackensTheVoxelOfEachPoint) {
  SparsityParams params = paramsFor(SparsityDistribution::Halton);
  params.points = 300;
  const auto mask = makeSparsityMask(params, kOddDims);
  ASSERT_TRUE(mask.ok());
  std::set<std::size_t> voxels;
  for (const glm::vec3& p : haltonPoints(kOddDims, 300)) {
    const std::size_t voxel =
        voxelIndex(kOddDims, static_cast<int>(p.x), static_cast<int>(p.y), static_cast<int>(p.z));
    EXPECT_EQ(mask->black[voxel], 1);
    voxels.insert(voxel);
  }
  EXPECT_EQ(mask->blackCount, voxels.size());
  // Point 1 is (12, 10.67, 8): voxel (12, 10, 8).
  EXPECT_EQ(mask->black[voxelIndex(kOddDims, 12, 10, 8)], 1);

  params.distribution = SparsityDistribution::Jitter;
  params.radius = 3.0f;
  const auto jitter = makeSparsityMask(params, kOddDims);
  ASSERT_TRUE(jitter.ok());
  EXPECT_EQ(jitter->blackCount, jitteredPoints(kOddDims, 3.0f, params.seed).size())
      << "points 3 apart never share a voxel";

  params.distribution = SparsityDistribution::Poisson;
  params.radius = 0.0f;
  params.points = 200;
  const auto poisson = makeSparsityMask(params, kOddDims);
  ASSERT_TRUE(poisson.ok());
  EXPECT_EQ(poisson->blackCount, 200u) << "points given, radius derived from them";
}

// The engine names the parameter by its session key (the CLI shows its flag instead: see
// CliTest.EngineErrorsNameTheFlag).
TEST(Sparsity, ValidateNamesTheParameter) {
  const auto expectError = [](const SparsityParams& params, Dims dims, const std::string& key) {
    const Result<void> result = validate(params, dims);
    ASSERT_FALSE(result.ok()) << key;
    EXPECT_EQ(result.error().kind, ErrorKind::InvalidInput);
    EXPECT_EQ(result.error().parameter, key);
    EXPECT_NE(result.error().message.find(key), std::string::npos) << result.error().message;
    EXPECT_FALSE(makeSparsityMask(params, dims).ok());
  };
  SparsityParams params = paramsFor(SparsityDistribution::Halton);
  EXPECT_TRUE(validate(params, kOddDims).ok());
  params.points = -1;
  expectError(params, kOddDims, "lic.sparsity.points");
  params.points = 24 * 32 * 40 + 1;
  expectError(params, kOddDims, "lic.sparsity.points");
  params.points = 24 * 32 * 40;
  EXPECT_TRUE(validate(params, kOddDims).ok());

  params = paramsFor(SparsityDistribution::PoissonApprox);
  params.points = static_cast<int>(kMaxBestCandidatePoints) + 1;
  expectError(params, {64, 64, 64}, "lic.sparsity.points");

  params = paramsFor(SparsityDistribution::Jitter);
  for (const float radius : {-1.0f, 0.25f, 40.5f, std::numeric_limits<float>::quiet_NaN()}) {
    params.radius = radius;
    expectError(params, kOddDims, "lic.sparsity.radius");
  }
  params.radius = 40.0f;
  EXPECT_TRUE(validate(params, kOddDims).ok());
  // Too many cells for the memory limits: the message says which radius would do.
  params.radius = 0.5f;
  expectError(params, {1024, 1024, 1024}, "lic.sparsity.radius");
  params.distribution = SparsityDistribution::Poisson;
  expectError(params, {1024, 1024, 1024}, "lic.sparsity.radius");
  params.radius = 0.0f;
  params.points = 1 << 30;
  expectError(params, {1024, 1024, 1024}, "lic.sparsity.points");

  params = paramsFor(SparsityDistribution::Checkerboard);
  for (const float ratio : {0.0f, 1.0f, -0.5f, std::numeric_limits<float>::quiet_NaN()}) {
    params.ratio = ratio;
    expectError(params, kOddDims, "lic.sparsity.ratio");
  }

  EXPECT_FALSE(validate(paramsFor(SparsityDistribution::None), {0, 4, 4}).ok());
  EXPECT_FALSE(validate(paramsFor(SparsityDistribution::None), {4, -1, 4}).ok());
}

TEST(Sparsity, AutomaticValuesOnHugeGridsMoveToTheLimits) {
  // 2^31 voxels: 2 % would be 43M points, and radius 3 a Poisson grid of 400M cells. Automatic
  // values give way (fewer points, a larger radius) instead of failing; nothing is generated.
  const Dims huge{2048, 2048, 512};
  for (const SparsityDistribution distribution :
       {SparsityDistribution::Poisson, SparsityDistribution::PoissonApprox,
        SparsityDistribution::Jitter, SparsityDistribution::Halton,
        SparsityDistribution::Hammersley, SparsityDistribution::Checkerboard}) {
    const Result<void> result = validate(paramsFor(distribution), huge);
    EXPECT_TRUE(result.ok()) << enumName(distribution) << ": " << result.error().message;
  }
}

}  // namespace
}  // namespace lic3d
