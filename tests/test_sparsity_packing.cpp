// SPDX-License-Identifier: BSD-3-Clause
// The bit-packed sparsity mask (shaders/sparsity_mask.h) and the exact voxels of the
// low-discrepancy points that the CPU and the GPU both blacken.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <glm/vec3.hpp>

#include "lic/point_sets.h"
#include "lic/sparsity.h"
#include "sparsity_mask.h"

namespace lic3d {
namespace {

TEST(SparsityPacking, EachVoxelHasItsOwnBitInBlocksOfFourByFourByTwo) {
  const Dims dims{7, 9, 4};  // partial blocks along x and y
  // 2 x 3 x 2 blocks.
  EXPECT_EQ(sparsityMaskWords(dims), 12u);
  SparsityMask mask;
  mask.dims = dims;
  mask.black.assign(voxelCount(dims), 0);
  mask.black[voxelIndex(dims, 5, 6, 3)] = 1;
  std::vector<std::uint32_t> words = packSparsityMask(mask);
  ASSERT_EQ(words.size(), 12u);
  // Block (1, 1, 1) is word (1 * 3 + 1) * 2 + 1 = 9; in it x 1, y 2, z 1: bit 16 + 8 + 1 = 25.
  for (std::size_t w = 0; w < words.size(); ++w)
    EXPECT_EQ(words[w], w == 9 ? 1u << 25 : 0u) << "word " << w;
  // Every voxel black: every bit of a voxel inside the grid, and only those.
  mask.black.assign(voxelCount(dims), 1);
  words = packSparsityMask(mask);
  std::size_t bits = 0;
  for (const std::uint32_t w : words) bits += static_cast<std::size_t>(std::popcount(w));
  EXPECT_EQ(bits, voxelCount(dims));
  EXPECT_EQ(words[0], 0xFFFFFFFFu);  // a whole block
  EXPECT_EQ(words[1], 0x77777777u);  // x = 4..6: three of four columns
}

// floor(n phi_b(i)) from the mirrored digits as one 64-bit integer over b^K, independently.
std::uint32_t exactVoxel(std::uint32_t base, std::uint32_t index, std::uint32_t n) {
  std::uint64_t mirrored = 0, denominator = 1;
  for (std::uint32_t i = index; i > 0; i /= base) {
    mirrored = mirrored * base + i % base;
    denominator *= base;
  }
  return static_cast<std::uint32_t>(mirrored * n / denominator);
}

TEST(SparsityPacking, LowDiscrepancyVoxelsAreExactFloors) {
  for (const std::uint32_t base : {2u, 3u, 5u})
    for (const std::uint32_t n : {1u, 7u, 256u, 16384u}) {
      const std::uint32_t count = 200000;
      const std::uint32_t power = radicalInversePower(base, count);
      EXPECT_LE(power, count);
      EXPECT_GT(std::uint64_t{power} * base, count);
      for (std::uint32_t i = 1; i <= count; i += 7)
        ASSERT_EQ(glsl::licScaledRadicalInverse(base, power, i, n), exactVoxel(base, i, n))
            << "base " << base << ", n " << n << ", index " << i;
    }
  // Where the float point lies within its rounding below a voxel face it rounds up into the next
  // voxel; the mask keeps the exact voxel. phi_3(612353) * 256 = 198.999997...
  const std::vector<glm::vec3> points = haltonPoints({1, 256, 1}, 612353);
  EXPECT_EQ(static_cast<int>(points.back().y), 199);
  EXPECT_EQ(glsl::licScaledRadicalInverse(3, radicalInversePower(3, 612353), 612353, 256), 198u);
  EXPECT_EQ(lowDiscrepancyVoxels({1, 256, 1}, 612353, true).back().y, 198);
}

// The CPU's incremental voxels (what makeSparsityMask blackens) are the shared formula's.
TEST(SparsityPacking, MaskVoxelsOfHaltonAndHammersleyFollowTheSharedFormula) {
  const Dims dims{256, 243, 125};
  const std::uint32_t count = 150000;
  for (const bool halton : {true, false}) {
    const std::vector<glm::ivec3> voxels = lowDiscrepancyVoxels(dims, count, halton);
    ASSERT_EQ(voxels.size(), count);
    const std::uint32_t p2 = radicalInversePower(2, count), p3 = radicalInversePower(3, count),
                        p5 = radicalInversePower(5, count);
    for (std::uint32_t i = 1; i <= count; ++i) {
      const glm::ivec3 v = voxels[i - 1];
      const glm::uvec3 expected =
          halton ? glm::uvec3(glsl::licScaledRadicalInverse(2, p2, i, 256),
                              glsl::licScaledRadicalInverse(3, p3, i, 243),
                              glsl::licScaledRadicalInverse(5, p5, i, 125))
                 : glm::uvec3(std::min(glsl::licMulDivFloor(i, 256, count), 255u),
                              glsl::licScaledRadicalInverse(2, p2, i, 243),
                              glsl::licScaledRadicalInverse(3, p3, i, 125));
      ASSERT_EQ(glm::uvec3(v), expected) << (halton ? "halton" : "hammersley") << " point " << i;
    }
  }
}

TEST(SparsityPacking, CheckerboardRuleIsThePatterns) {
  const CheckerboardPattern pattern = checkerboardPattern(0.37f, {20, 20, 20});
  for (std::uint32_t s = 0; s < 200; ++s)
    EXPECT_EQ(glsl::licCheckerboardBlack(s, static_cast<std::uint32_t>(pattern.black),
                                         static_cast<std::uint32_t>(pattern.period)),
              pattern.isBlack(s));
}

}  // namespace
}  // namespace lic3d
