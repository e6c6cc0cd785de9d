// SPDX-License-Identifier: BSD-3-Clause
// The read-back ring (gpu/readback.h): a region of an image comes back slab by slab, in order,
// through staging buffers reused across slabs and reads, and the image is left as it was, also
// when the caller stops part way.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <vector>

#include "gpu/readback.h"
#include "gpu/submit.h"
#include "gpu_test_support.h"

namespace lic3d {
namespace {

using test::GpuTest;

constexpr Dims kGrid{20, 12, 30};

// A 3D R32_UINT image whose texel holds its own index in the grid.
Image indexImage(const Context& context) {
  ImageDesc desc;
  desc.format = VK_FORMAT_R32_UINT;
  desc.extent = {static_cast<std::uint32_t>(kGrid.x), static_cast<std::uint32_t>(kGrid.y),
                 static_cast<std::uint32_t>(kGrid.z)};
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
               VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.name = "index image";
  Result<Image> image = Image::create(context, desc);
  EXPECT_TRUE(image.ok());
  std::vector<std::uint32_t> texels(voxelCount(kGrid));
  for (std::size_t i = 0; i < texels.size(); ++i) texels[i] = static_cast<std::uint32_t>(i);
  EXPECT_TRUE(uploadImage(context, *image, texels.data(), texels.size() * 4).ok());
  return std::move(*image);
}

TEST_F(GpuTest, TheReadbackRingReturnsARegionSlabBySlab) {
  const Image image = indexImage(context());
  const Dims offset{3, 2, 1};
  const Dims extent{15, 9, 26};
  const std::size_t layerBytes = static_cast<std::size_t>(extent.x) * extent.y * 4;
  // Slots of 4 layers: 7 slabs through 3 slots, each slot used more than once.
  ReadbackRing ring(4 * layerBytes);
  for (int pass = 0; pass < 2; ++pass) {  // the second read reuses the buffers
    std::vector<int> firsts;
    std::size_t wrong = 0, seen = 0;
    const Result<void> read =
        ring.read(context(), image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4, offset, extent,
                  [&](const void* texels, int firstLayer, int layers) -> Result<void> {
                    firsts.push_back(firstLayer);
                    const auto* values = static_cast<const std::uint32_t*>(texels);
                    for (int k = 0; k < layers; ++k)
                      for (int j = 0; j < extent.y; ++j)
                        for (int i = 0; i < extent.x; ++i, ++seen) {
                          const std::size_t expected = voxelIndex(kGrid, offset.x + i, offset.y + j,
                                                                  offset.z + firstLayer + k);
                          wrong += *values++ != expected ? 1 : 0;
                        }
                    return {};
                  });
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(firsts, (std::vector<int>{0, 4, 8, 12, 16, 20, 24})) << pass;
    EXPECT_EQ(seen, voxelCount(extent));
    EXPECT_EQ(wrong, 0u);
    EXPECT_EQ(ring.bytes(), 3 * 4 * layerBytes);
  }
  // Stopped by its caller after the second slab: the error comes back, the image is returned to
  // its layout (a further read sees it whole), and nothing trips the validation layer.
  int calls = 0;
  const Result<void> stopped =
      ring.read(context(), image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4, offset, extent,
                [&](const void*, int, int) -> Result<void> {
                  if (++calls == 2) return runtimeError("disk full");
                  return {};
                });
  ASSERT_FALSE(stopped);
  EXPECT_EQ(stopped.error().message, "disk full");
  EXPECT_EQ(calls, 2);
  const Result<std::vector<std::byte>> whole =
      readImage(context(), image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4);
  ASSERT_TRUE(whole);
  std::uint32_t last = 0;
  std::memcpy(&last, whole->data() + whole->size() - 4, 4);
  EXPECT_EQ(last, voxelCount(kGrid) - 1);
  EXPECT_EQ(context().validationMessageCount(), 0u);
}

}  // namespace
}  // namespace lic3d
