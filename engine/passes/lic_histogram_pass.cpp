// SPDX-License-Identifier: BSD-3-Clause
#include "passes/lic_histogram_pass.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <span>

#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "gpu/vk_check.h"
#include "shared_layout.h"

namespace lic3d {

IntensityStatistics intensityStatistics(const std::vector<std::uint32_t>& counts) {
  IntensityStatistics stats;
  double sum = 0.0, sumSquares = 0.0;
  // The last count is of the voxels the sparsity mask hid.
  const std::span<const std::uint32_t> bins(counts.data(), counts.size() - 1);
  stats.maskedVoxels = counts.back();
  for (std::size_t b = 0; b < bins.size(); ++b) {
    const double value = (static_cast<double>(b) + 0.5) / static_cast<double>(bins.size());
    stats.voxels += counts[b];
    sum += counts[b] * value;
    sumSquares += counts[b] * value * value;
  }
  if (stats.voxels == 0) return stats;
  stats.histogram = std::make_shared<const ValueHistogram>(histogramOfCounts(bins, 0.0, 1.0));
  const double n = static_cast<double>(stats.voxels);
  const double mean = sum / n;
  stats.mean = static_cast<float>(mean);
  stats.deviation = static_cast<float>(std::sqrt(std::max(sumSquares / n - mean * mean, 0.0)));
  return stats;
}

Result<LicHistogramPass> LicHistogramPass::create(const Context& context) {
  LicHistogramPass pass;
  pass.context_ = &context;
  constexpr Binding bindings[] = {
      {gpu::kHistogramBindingVolume},
      {gpu::kHistogramBindingCounts, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {gpu::kHistogramBindingField},
      {gpu::kHistogramBindingVisible, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
  };
  LIC3D_TRY_ASSIGN(pass.layout_,
                   PipelineLayout::create(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT,
                                          sizeof(gpu::HistogramPushConstants), "histogram"));
  LIC3D_TRY_ASSIGN(const ShaderModule shader, loadShader(context, ShaderId::LicHistogram));
  LIC3D_TRY_ASSIGN(pass.pipeline_,
                   createComputePipeline(context, shader, pass.layout_, nullptr, "lic histogram"));
  struct VisibleOnly {
    std::uint32_t visibleBricks = 1;
  };
  static_assert(gpu::kHistogramConstVisibleBricks == 0);
  const Specialization<VisibleOnly> visibleOnly(VisibleOnly{});
  LIC3D_TRY_ASSIGN(pass.visiblePipeline_,
                   createComputePipeline(context, shader, pass.layout_, visibleOnly.info(),
                                         "lic histogram of visible bricks"));
  LIC3D_TRY_ASSIGN(pass.noBricks_, Buffer::create(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                  MemoryUse::DeviceLocal, "histogram no bricks"));

  LIC3D_TRY_ASSIGN(pass.sampler_, Sampler::create(context, VK_FILTER_NEAREST, "histogram sampler"));
  const VkDeviceSize bytes = (gpu::kHistogramBins + 1) * sizeof(std::uint32_t);
  LIC3D_TRY_ASSIGN(pass.counts_, Buffer::create(context, bytes,
                                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                    VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                MemoryUse::DeviceLocal, "histogram counts"));
  LIC3D_TRY_ASSIGN(pass.readback_,
                   Buffer::create(context, bytes * kSlots, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  MemoryUse::Readback, "histogram readback"));
  return pass;
}

void LicHistogramPass::record(VkCommandBuffer cmd, const Image& volume, const FieldTexture& field,
                              double emptySpeed, std::uint32_t slot, const Buffer* visibleBricks,
                              int stride) {
  LIC3D_ASSERT(stride >= 1 && (stride == 1 || !visibleBricks));
  const Dims dims = coarseDims(field.dims, stride);
  LIC3D_ASSERT(slot < kSlots);
  // The previous histogram's shader and copy must be done with the buffers before they are reused.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdFillBuffer(cmd, counts_.handle(), 0, VK_WHOLE_SIZE, 0);
  // ALL_TRANSFER: the validation layer of Debian 12 (1.3.239) files vkCmdFillBuffer under COPY,
  // not CLEAR.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE,
                    visibleBricks ? visiblePipeline_.get() : pipeline_.get());
  DescriptorWrites()
      .sampledImage(gpu::kHistogramBindingVolume, sampler_, volume.view())
      .storageBuffer(gpu::kHistogramBindingCounts, counts_)
      .sampledImage(gpu::kHistogramBindingField, sampler_, field.image.view())
      .storageBuffer(gpu::kHistogramBindingVisible, visibleBricks ? *visibleBricks : noBricks_)
      .push(*context_, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_);
  const glm::vec4 toPhysical = texelToPhysicalForShader(field.texelToPhysical);
  const gpu::HistogramPushConstants push{
      glm::ivec4(dims, field.precision == FieldPrecision::Byte ? 1 : 0),
      glm::vec4(glm::vec3(toPhysical), static_cast<float>(emptySpeed / toPhysical.w)),
      glm::ivec4(stride, 0, 0, 0)};
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  vkCmdDispatch(cmd, static_cast<std::uint32_t>(dims.z), 1, 1);

  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkBufferCopy region{0, slot * counts_.size(), counts_.size()};
  vkCmdCopyBuffer(cmd, counts_.handle(), readback_.handle(), 1, &region);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

std::vector<std::uint32_t> LicHistogramPass::counts(std::uint32_t slot) const {
  LIC3D_ASSERT(slot < kSlots);
  std::vector<std::uint32_t> out(gpu::kHistogramBins + 1);
  std::memcpy(out.data(), static_cast<const std::byte*>(readback_.mapped()) + slot * counts_.size(),
              out.size() * sizeof(std::uint32_t));
  return out;
}

}  // namespace lic3d
