// SPDX-License-Identifier: BSD-3-Clause
#include "passes/sparsity_mask_pass.h"

#include <algorithm>

#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "gpu/vk_check.h"
#include "lic/point_sets.h"
#include "lic/sparsity.h"
#include "lic/sparsity_automatic.h"

namespace lic3d {

bool madeOnGpu(SparsityDistribution distribution) {
  return distribution == SparsityDistribution::Checkerboard ||
         distribution == SparsityDistribution::Halton ||
         distribution == SparsityDistribution::Hammersley;
}

Result<SparsityMaskPass> SparsityMaskPass::create(const Context& context) {
  SparsityMaskPass pass;
  pass.context_ = &context;
  constexpr Binding bindings[] = {
      {gpu::kMaskBindingBits, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {gpu::kMaskBindingCount, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
  };
  LIC3D_TRY_ASSIGN(pass.layout_,
                   PipelineLayout::create(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT,
                                          sizeof(gpu::SparsityMaskPushConstants), "sparsity mask"));
  LIC3D_TRY_ASSIGN(pass.shader_, loadShader(context, ShaderId::SparsityMask));
  return pass;
}

Result<void> SparsityMaskPass::record(VkCommandBuffer cmd, const SparsityParams& params, Dims dims,
                                      const Buffer& bits, const Buffer& count) {
  LIC3D_ASSERT(madeOnGpu(params.distribution));
  const std::size_t words = sparsityMaskWords(dims);
  LIC3D_ASSERT(bits.size() >= words * sizeof(std::uint32_t));
  const SparsityMaskSpecialization key{static_cast<std::uint32_t>(params.distribution)};
  LIC3D_TRY_ASSIGN(
      const VkPipeline pipeline, pipelines_.get(key, [&](const SparsityMaskSpecialization& k) {
        const Specialization<SparsityMaskSpecialization> spec(k);
        return createComputePipeline(
            *context_, shader_, layout_, spec.info(),
            std::string("sparsity mask ") + std::string(enumName(params.distribution)));
      }));

  gpu::SparsityMaskPushConstants push{};
  push.dims = glm::ivec4(dims, 0);
  push.powers.w = static_cast<std::uint32_t>(words);
  std::size_t invocations = words;
  const bool checkerboard = params.distribution == SparsityDistribution::Checkerboard;
  if (checkerboard) {
    const CheckerboardPattern pattern = checkerboardPattern(params.ratio, dims);
    push.pattern = glm::uvec4(static_cast<std::uint32_t>(pattern.black),
                              static_cast<std::uint32_t>(pattern.period), 0u, 0u);
  } else {
    const std::size_t points = points::resolve(params, dims).points;
    push.pattern.x = static_cast<std::uint32_t>(points);
    push.powers.x = radicalInversePower(2, points);
    push.powers.y = radicalInversePower(3, points);
    push.powers.z = radicalInversePower(5, points);
    invocations = points;
  }

  // Earlier readers of the mask (LIC passes) and of the count (its copy) are done first.
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT,
                VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  vkCmdFillBuffer(cmd, count.handle(), 0, sizeof(std::uint32_t), 0);
  // The points OR their bits into a white mask; the checkerboard writes every word.
  if (!checkerboard) vkCmdFillBuffer(cmd, bits.handle(), 0, words * sizeof(std::uint32_t), 0);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);

  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  DescriptorWrites()
      .storageBuffer(gpu::kMaskBindingBits, bits)
      .storageBuffer(gpu::kMaskBindingCount, count)
      .push(*context_, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
  const std::size_t groups = (invocations + gpu::kMaskLocalSize - 1) / gpu::kMaskLocalSize;
  if (groups > 0) {
    const std::size_t row = std::min<std::size_t>(groups, gpu::kMaskGroupsPerRow);
    vkCmdDispatch(cmd, static_cast<std::uint32_t>(row),
                  static_cast<std::uint32_t>((groups + row - 1) / row), 1);
  }
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  return {};
}

}  // namespace lic3d
