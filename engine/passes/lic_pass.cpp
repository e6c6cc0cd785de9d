// SPDX-License-Identifier: BSD-3-Clause
#include "passes/lic_pass.h"

#include <algorithm>
#include <array>
#include <cstdlib>

#include "gpu/shader_library.h"
#include "gpu/vk_check.h"
#include "passes/lic_push.h"
#include "shared_layout.h"

namespace lic3d {

LicSpecialization licSpecialization(const LicParams& params, FieldPrecision precision,
                                    const LicSpecialization& launch) {
  LicSpecialization s = launch;
  s.integrator = static_cast<std::uint32_t>(params.integrator);
  s.kernel = static_cast<std::uint32_t>(params.kernel);
  s.noiseFilter = static_cast<std::uint32_t>(params.noiseFilter);
  s.direction = static_cast<std::uint32_t>(params.direction);
  s.sparsity = params.sparsity.distribution == SparsityDistribution::None ? 0u : 1u;
  s.scheme = static_cast<std::uint32_t>(params.scheme);
  s.packing = precision == FieldPrecision::Byte ? 1u : 0u;
  return s;
}

LicSpecialization licLaunch(std::uint32_t x, std::uint32_t y, std::uint32_t z, bool interleave) {
  LicSpecialization launch;
  launch.localSizeX = x;
  launch.localSizeY = y;
  launch.localSizeZ = z;
  launch.interleave = interleave ? 1u : 0u;
  return launch;
}

LicSpecialization licLaunchFor(VkPhysicalDeviceType type) {
  // One direction after the other everywhere: walking both at once keeps two fetches in flight
  // but costs registers; on the H100 it tied for the exact scheme and lost 4 % for the fused one
  // (37 registers against 29), and CPU drivers run an invocation's loop as SIMD lanes, where
  // fewer live lanes win. GPUs take cubes (4x4x4, 1 % faster for fused on the H100, whose
  // streamlines leave a row in every direction); CPU drivers take rows of x (8x8x1), whose SIMD
  // lanes then walk neighbouring streamlines: 4x4x4 took twice as long on lavapipe.
  // docs/BENCHMARKS.md, "Launch shapes".
  LicSpecialization launch;  // the defaults: one direction after the other, rows of x
  if (type != VK_PHYSICAL_DEVICE_TYPE_CPU) {
    launch.localSizeX = launch.localSizeY = launch.localSizeZ = 4;
  }
  return launch;
}

Result<LicPass> LicPass::create(const Context& context, bool separateNoise,
                                std::optional<LicSpecialization> launch) {
  LicPass pass;
  pass.context_ = &context;
  pass.separateNoise_ = separateNoise;
  pass.launch_ = launch.value_or(licLaunchFor(context.deviceInfo().type));
  constexpr Binding bindings[] = {
      {gpu::kLicBindingField},
      {gpu::kLicBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
      {gpu::kLicBindingMask, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {gpu::kLicBindingBrickList, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {gpu::kLicBindingMadeBricks, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {gpu::kLicBindingNoise},  // the naive kernel's own noise texture
  };
  const std::span<const Binding> used(bindings, separateNoise ? 6 : 5);
  LIC3D_TRY_ASSIGN(pass.layout_, PipelineLayout::create(context, used, VK_SHADER_STAGE_COMPUTE_BIT,
                                                        sizeof(gpu::LicPushConstants), "lic"));
  LIC3D_TRY_ASSIGN(pass.shader_,
                   loadShader(context, separateNoise ? ShaderId::LicComputeSeparateNoise
                                                     : ShaderId::LicCompute));
  LIC3D_TRY_ASSIGN(pass.sampler_,
                   Sampler::create(context, VK_FILTER_LINEAR, "lic trilinear sampler"));
  LIC3D_TRY_ASSIGN(pass.noBricks_, Buffer::create(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                  MemoryUse::DeviceLocal, "lic no bricks"));
  LIC3D_TRY_ASSIGN(pass.noMask_, Buffer::create(context, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                MemoryUse::DeviceLocal, "lic no mask"));
  return pass;
}

std::vector<std::pair<std::string, std::string>> LicPass::statistics(
    const LicParams& params, FieldPrecision precision) const {
  return pipelineStatistics(*context_,
                            pipelines_.find(licSpecialization(params, precision, launch_)));
}

Result<VkPipeline> LicPass::pipelineFor(const LicSpecialization& specialization) {
  return pipelines_.get(specialization, [&](const LicSpecialization& key) {
    const Specialization<LicSpecialization> constants(key);
    const std::string name = licPipelineName(separateNoise_ ? "naive lic " : "lic ", key) +
                             (key.packing ? "/byte" : "") + (key.sparsity ? "/sparse" : "") +
                             (key.brickList ? "/bricks" : "");
    return createComputePipeline(*context_, shader_, layout_, constants.info(), name);
  });
}

void LicPass::pushDescriptors(VkCommandBuffer cmd, const FieldTexture& field, const Buffer* mask,
                              const Image& output, const Image* noise, const Buffer& lists,
                              const Buffer& made) {
  DescriptorWrites writes;
  writes.sampledImage(gpu::kLicBindingField, sampler_, field.image.view())
      .storageImage(gpu::kLicBindingOutput, output.view())
      .storageBuffer(gpu::kLicBindingMask, mask ? *mask : noMask_)
      .storageBuffer(gpu::kLicBindingBrickList, lists)
      .storageBuffer(gpu::kLicBindingMadeBricks, made);
  if (separateNoise_) writes.sampledImage(gpu::kLicBindingNoise, sampler_, noise->view());
  writes.push(*context_, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_);
}

gpu::LicPushConstants LicPass::pushConstants(Dims dims, const MaskBeyondGrid& beyond,
                                             const LicParams& params, int zBegin, int zEnd,
                                             int stride) const {
  gpu::LicPushConstants push{};
  push.dims = glm::ivec4(dims, zBegin);
  push.zEnd = zEnd;
  push.outputStride = stride;
  push.invDims = glm::vec4(1.0f / glm::vec3(dims), 0.0f);
  setLicPushParams(push, params);
  push.maskBeyond = glm::uvec4(glm::uvec3(beyond.offset), beyond.threshold);
  push.maskSeed = beyond.seed;
  return push;
}

Result<void> LicPass::record(VkCommandBuffer cmd, const FieldTexture& field, const Buffer* mask,
                             const MaskBeyondGrid& beyond, const Image& output,
                             const LicParams& params, int zBegin, int zEnd, const Image* noise,
                             int stride) {
  LIC3D_ASSERT(!separateNoise_ || noise);
  LIC3D_ASSERT(stride >= 1);
  LIC3D_ASSERT(mask || params.sparsity.distribution == SparsityDistribution::None);
  const LicSpecialization specialization = licSpecialization(params, field.precision, launch_);
  LIC3D_TRY_ASSIGN(const VkPipeline pipeline, pipelineFor(specialization));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  pushDescriptors(cmd, field, mask, output, noise, noBricks_, noBricks_);

  const gpu::LicPushConstants push =
      pushConstants(field.dims, beyond, params, zBegin, zEnd, stride);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);

  const Dims dims = coarseDims(field.dims, stride);
  vkCmdDispatch(cmd, groupCount(dims.x, specialization.localSizeX),
                groupCount(dims.y, specialization.localSizeY),
                groupCount(zEnd - zBegin, specialization.localSizeZ));
  return {};
}

Result<void> LicPass::recordBricks(VkCommandBuffer cmd, const FieldTexture& field,
                                   const Buffer* mask, const MaskBeyondGrid& beyond,
                                   const Image& output, const LicParams& params,
                                   const VisibleBricksPass& bricks, int layerBegin, int layerEnd) {
  LIC3D_ASSERT(!separateNoise_);
  LIC3D_ASSERT(mask || params.sparsity.distribution == SparsityDistribution::None);
  LIC3D_ASSERT(brickCounts(field.dims) == bricks.bricks());
  LIC3D_ASSERT(0 <= layerBegin && layerBegin <= layerEnd && layerEnd <= bricks.bricks().z);
  // A workgroup is a slice of a brick: the launch's shape does not apply.
  LicSpecialization specialization = licSpecialization(
      params, field.precision,
      licLaunch(gpu::kVisibleBrickSize, gpu::kVisibleBrickSize, 1, launch_.interleave != 0));
  specialization.brickList = 1;
  LIC3D_TRY_ASSIGN(const VkPipeline pipeline, pipelineFor(specialization));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
  pushDescriptors(cmd, field, mask, output, nullptr, bricks.lists(), bricks.made());

  const Dims dims = field.dims;
  const int size = static_cast<int>(gpu::kVisibleBrickSize);
  for (int layer = layerBegin; layer < layerEnd; ++layer) {
    const int zBegin = layer * size;
    const gpu::LicPushConstants push =
        pushConstants(dims, beyond, params, zBegin, std::min(dims.z, zBegin + size));
    vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
    vkCmdDispatchIndirect(cmd, bricks.dispatch().handle(),
                          static_cast<VkDeviceSize>(layer) * 3 * sizeof(std::uint32_t));
  }
  return {};
}

}  // namespace lic3d
