#include "passes/lic_pass.h"

#include <array>
#include <cstdlib>

#include "gpu/shader_library.h"
#include "gpu/vk_check.h"
#include "passes/lic_push.h"
#include "shared_layout.h"

namespace lic3d {

LicSpecialization licSpecialization(const LicParams& params, FieldPrecision precision) {
  LicSpecialization s;
  s.integrator = static_cast<std::uint32_t>(params.integrator);
  s.kernel = static_cast<std::uint32_t>(params.kernel);
  s.noiseFilter = static_cast<std::uint32_t>(params.noiseFilter);
  s.direction = static_cast<std::uint32_t>(params.direction);
  s.sparsity = params.sparsity.distribution == SparsityDistribution::None ? 0u : 1u;
  s.scheme = static_cast<std::uint32_t>(params.scheme);
  s.packing = precision == FieldPrecision::Byte ? 1u : 0u;
  return s;
}

Result<LicPass> LicPass::create(const Context& context, bool separateNoise) {
  LicPass pass;
  pass.context_ = &context;
  pass.separateNoise_ = separateNoise;
  const std::array<VkDescriptorSetLayoutBinding, 4> bindings{{
      {gpu::kLicBindingField, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
       VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {gpu::kLicBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1, VK_SHADER_STAGE_COMPUTE_BIT,
       nullptr},
      {gpu::kLicBindingMask, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
       VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
      {gpu::kLicBindingNoise, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
       VK_SHADER_STAGE_COMPUTE_BIT, nullptr},
  }};
  const std::span<const VkDescriptorSetLayoutBinding> used(bindings.data(), separateNoise ? 4 : 3);
  LIC3D_TRY_ASSIGN(pass.layout_, PipelineLayout::create(context, used, VK_SHADER_STAGE_COMPUTE_BIT,
                                                        sizeof(gpu::LicPushConstants), "lic"));
  LIC3D_TRY_ASSIGN(pass.shader_,
                   loadShader(context, separateNoise ? ShaderId::LicComputeSeparateNoise
                                                     : ShaderId::LicCompute));
  LIC3D_TRY_ASSIGN(pass.sampler_,
                   Sampler::create(context, VK_FILTER_LINEAR, "lic trilinear sampler"));
  // Integer textures cannot be filtered linearly; the mask is only read with texelFetch.
  LIC3D_TRY_ASSIGN(pass.maskSampler_,
                   Sampler::create(context, VK_FILTER_NEAREST, "lic mask sampler"));
  return pass;
}

Result<VkPipeline> LicPass::pipelineFor(const LicSpecialization& specialization) {
  for (const auto& [spec, pipeline] : pipelines_)
    if (spec == specialization) return pipeline.get();

  const Specialization<LicSpecialization> constants(specialization);
  const std::string name = licPipelineName(separateNoise_ ? "naive lic " : "lic ", specialization) +
                           (specialization.packing ? "/byte" : "") +
                           (specialization.sparsity ? "/sparse" : "");
  LIC3D_TRY_ASSIGN(Pipeline pipeline,
                   createComputePipeline(*context_, shader_, layout_, constants.info(), name));
  const VkPipeline handle = pipeline.get();
  pipelines_.emplace_back(specialization, std::move(pipeline));
  return handle;
}

Result<void> LicPass::record(VkCommandBuffer cmd, const FieldTexture& field, const Image& mask,
                             const Image& output, const LicParams& params, int zBegin, int zEnd,
                             const Image* noise) {
  LIC3D_ASSERT(!separateNoise_ || noise);
  LicSpecialization specialization = licSpecialization(params, field.precision);
  specialization.interleave = context_->deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU ? 0u : 1u;
  LIC3D_TRY_ASSIGN(VkPipeline pipeline, pipelineFor(specialization));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);

  const VkDescriptorImageInfo fieldInfo{sampler_.handle(), field.image.view(),
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkDescriptorImageInfo outputInfo{VK_NULL_HANDLE, output.view(), VK_IMAGE_LAYOUT_GENERAL};
  const VkDescriptorImageInfo maskInfo{maskSampler_.handle(), mask.view(),
                                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkDescriptorImageInfo noiseInfo{sampler_.handle(), noise ? noise->view() : VK_NULL_HANDLE,
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const std::array<VkWriteDescriptorSet, 4> writes{
      descriptorWrite(gpu::kLicBindingField, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &fieldInfo),
      descriptorWrite(gpu::kLicBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, &outputInfo),
      descriptorWrite(gpu::kLicBindingMask, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &maskInfo),
      descriptorWrite(gpu::kLicBindingNoise, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                      &noiseInfo)};
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_.get(), 0,
                                 separateNoise_ ? 4u : 3u, writes.data());

  const Dims dims = field.dims;
  gpu::LicPushConstants push{};
  push.dims = glm::ivec4(dims, zBegin);
  push.invDims = glm::vec4(1.0f / glm::vec3(dims), 0.0f);
  setLicPushParams(push, params);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);

  vkCmdDispatch(cmd, groupCount(dims.x, specialization.localSizeX),
                groupCount(dims.y, specialization.localSizeY),
                groupCount(zEnd - zBegin, specialization.localSizeZ));
  return {};
}

}  // namespace lic3d
