// SPDX-License-Identifier: BSD-3-Clause
// Sparsity masks made on the GPU (sparsity_mask.comp) against the CPU's makeSparsityMask, bit for
// bit in the packed layout the LIC pass reads; and the cache of CPU-made masks.
#include <gtest/gtest.h>

#include <cstring>
#include <vector>

#include "gpu/submit.h"
#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "lic/sparsity.h"
#include "passes/sparsity_mask_pass.h"
#include "render/lic_renderer.h"

namespace lic3d {
namespace {

using test::GpuTest;

struct GpuMask {
  std::vector<std::uint32_t> words;
  std::uint32_t blackCount = 0;
};

GpuMask makeOnGpu(const Context& context, SparsityMaskPass& pass, const SparsityParams& params,
                  Dims dims) {
  const std::size_t bytes = sparsityMaskWords(dims) * sizeof(std::uint32_t);
  constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  Result<Buffer> bits = Buffer::create(context, bytes, kUsage, MemoryUse::DeviceLocal, "bits");
  Result<Buffer> count = Buffer::create(context, 4, kUsage, MemoryUse::DeviceLocal, "count");
  Result<Buffer> readback = Buffer::create(context, bytes + 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                           MemoryUse::Readback, "readback");
  EXPECT_TRUE(bits.ok() && count.ok() && readback.ok());
  // Garbage first: the pass must write every word, not rely on a fresh buffer.
  const std::vector<std::uint32_t> garbage(bytes / 4, 0xA5A5A5A5u);
  EXPECT_TRUE(uploadBuffer(context, *bits, garbage.data(), bytes).ok());
  Result<void> recorded;
  EXPECT_TRUE(submitAndWait(
                  context,
                  [&](VkCommandBuffer cmd) {
                    recorded = pass.record(cmd, params, dims, *bits, *count);
                    const VkBufferCopy words{0, 0, bytes}, black{0, bytes, 4};
                    vkCmdCopyBuffer(cmd, bits->handle(), readback->handle(), 1, &words);
                    vkCmdCopyBuffer(cmd, count->handle(), readback->handle(), 1, &black);
                    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
                  },
                  "test mask")
                  .ok());
  EXPECT_TRUE(recorded.ok());
  GpuMask mask;
  mask.words.resize(bytes / 4);
  const auto* mapped = static_cast<const std::byte*>(readback->mapped());
  std::memcpy(mask.words.data(), mapped, bytes);
  std::memcpy(&mask.blackCount, mapped + bytes, 4);
  return mask;
}

TEST_F(GpuTest, SparsityMasksMadeOnTheGpuAreTheCpuMasksBitForBit) {
  Result<SparsityMaskPass> pass = SparsityMaskPass::create(context());
  ASSERT_TRUE(pass.ok()) << pass.error().message;
  int compared = 0;
  // Odd sizes leave partial blocks on every axis; 64^3 with 10 % black is 26,214 points.
  for (const Dims dims : {Dims{24, 32, 40}, Dims{5, 7, 3}, Dims{1, 1, 1}, Dims{64, 64, 64}}) {
    std::vector<SparsityParams> cases;
    for (const SparsityDistribution d :
         {SparsityDistribution::Checkerboard, SparsityDistribution::Halton,
          SparsityDistribution::Hammersley}) {
      SparsityParams params;
      params.distribution = d;
      cases.push_back(params);  // automatic
      params.ratio = 0.37f;
      params.points = static_cast<int>(voxelCount(dims) / 2);  // many points per voxel row
      params.blackFraction = 0.3;
      cases.push_back(params);
      params.ratio = 0.5f;
      params.points = 1;
      cases.push_back(params);
    }
    for (const SparsityParams& params : cases) {
      if (!validate(params, dims).ok()) continue;
      const Result<SparsityMask> cpu = makeSparsityMask(params, dims);
      ASSERT_TRUE(cpu.ok()) << cpu.error().message;
      const GpuMask gpu = makeOnGpu(context(), *pass, params, dims);
      const std::vector<std::uint32_t> expected = packSparsityMask(*cpu);
      ASSERT_EQ(gpu.words.size(), expected.size());
      std::size_t differing = 0;
      for (std::size_t w = 0; w < expected.size(); ++w) differing += gpu.words[w] != expected[w];
      EXPECT_EQ(differing, 0u) << enumName(params.distribution) << " on " << gridText(dims) << ", "
                               << params.points << " points";
      EXPECT_EQ(gpu.blackCount, cpu->blackCount) << enumName(params.distribution);
      ++compared;
    }
  }
  EXPECT_GE(compared, 30);
}

// A change back to a CPU-made mask seen before takes it from the cache: the same mask, the same
// LIC volume, nothing made again.
TEST_F(GpuTest, SparsityMaskCacheServesAChangeBackToASeenMask) {
  const VectorField field = makeAnalyticField(AnalyticField::Vortex, {24, 24, 24});
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  LicParams lic;
  lic.length = 6;
  lic.sparsity.distribution = SparsityDistribution::Poisson;
  lic.sparsity.amount = 0.5f;
  ASSERT_TRUE(renderer->updateLic(lic).ok());
  const ScalarVolume first = *renderer->readLicVolume();
  lic.sparsity.amount = 0.7f;
  ASSERT_TRUE(renderer->updateLic(lic).ok());
  const ScalarVolume other = *renderer->readLicVolume();
  EXPECT_NE(first.drawn, other.drawn);
  EXPECT_EQ(renderer->maskCacheHits(), 0u);
  lic.sparsity.amount = 0.5f;
  ASSERT_TRUE(renderer->updateLic(lic).ok());
  EXPECT_EQ(renderer->maskCacheHits(), 1u);
  EXPECT_EQ(renderer->maskBuildCount(), 3u);
  const ScalarVolume again = *renderer->readLicVolume();
  EXPECT_EQ(again.drawn, first.drawn);
  EXPECT_EQ(again.values, first.values);
  // Masks made on the GPU are not cached: they are made again, as fast as a copy.
  lic.sparsity.distribution = SparsityDistribution::Halton;
  ASSERT_TRUE(renderer->updateLic(lic).ok());
  lic.sparsity.distribution = SparsityDistribution::Poisson;
  ASSERT_TRUE(renderer->updateLic(lic).ok());
  EXPECT_EQ(renderer->maskCacheHits(), 2u);
  EXPECT_EQ(renderer->maskBuildCount(), 5u);
}

}  // namespace
}  // namespace lic3d
