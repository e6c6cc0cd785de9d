#include "lic_pass.h"

#include <array>
#include <cstdlib>

#include "shader_library.h"
#include "shared_layout.h"
#include "vk_check.h"

namespace lic3d {

LicSpecialization licSpecialization(const LicParams& params) {
  LicSpecialization s;
  s.integrator = static_cast<std::uint32_t>(params.integrator);
  s.kernel = static_cast<std::uint32_t>(params.kernel);
  s.noiseFilter = static_cast<std::uint32_t>(params.noiseFilter);
  s.direction = static_cast<std::uint32_t>(params.direction);
  return s;
}

Result<LicPass> LicPass::create(const Context& context) {
  LicPass pass;
  pass.context_ = &context;
  VkDevice device = context.device();

  std::array<VkDescriptorSetLayoutBinding, 2> bindings{};
  bindings[0] = {gpu::kLicBindingField, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
                 VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  bindings[1] = {gpu::kLicBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, 1,
                 VK_SHADER_STAGE_COMPUTE_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = static_cast<std::uint32_t>(bindings.size());
  setInfo.pBindings = bindings.data();
  LIC3D_TRY(checkVk(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &pass.setLayout_),
                    "vkCreateDescriptorSetLayout"));
  context.setDebugName(pass.setLayout_, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, "lic set layout");

  VkPushConstantRange range{VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(gpu::LicPushConstants)};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &pass.setLayout_;
  layoutInfo.pushConstantRangeCount = 1;
  layoutInfo.pPushConstantRanges = &range;
  LIC3D_TRY(checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &pass.layout_),
                    "vkCreatePipelineLayout"));
  context.setDebugName(pass.layout_, VK_OBJECT_TYPE_PIPELINE_LAYOUT, "lic pipeline layout");

  LIC3D_TRY_ASSIGN(pass.shader_, createShaderModule(context, ShaderId::LicCompute));
  LIC3D_TRY_ASSIGN(pass.sampler_, Sampler::create(context, VK_FILTER_LINEAR, "lic trilinear sampler"));
  return pass;
}

LicPass::LicPass(LicPass&& other) noexcept { *this = std::move(other); }

LicPass& LicPass::operator=(LicPass&& other) noexcept {
  if (this != &other) {
    release();
    context_ = std::exchange(other.context_, nullptr);
    setLayout_ = std::exchange(other.setLayout_, VK_NULL_HANDLE);
    layout_ = std::exchange(other.layout_, VK_NULL_HANDLE);
    shader_ = std::exchange(other.shader_, VK_NULL_HANDLE);
    sampler_ = std::move(other.sampler_);
    pipelines_ = std::move(other.pipelines_);
    other.pipelines_.clear();
  }
  return *this;
}

LicPass::~LicPass() { release(); }

void LicPass::release() {
  if (!context_) return;
  VkDevice device = context_->device();
  for (auto& [spec, pipeline] : pipelines_) vkDestroyPipeline(device, pipeline, nullptr);
  pipelines_.clear();
  if (shader_) vkDestroyShaderModule(device, shader_, nullptr);
  if (layout_) vkDestroyPipelineLayout(device, layout_, nullptr);
  if (setLayout_) vkDestroyDescriptorSetLayout(device, setLayout_, nullptr);
  sampler_ = Sampler();
  context_ = nullptr;
}

Result<VkPipeline> LicPass::pipelineFor(const LicSpecialization& specialization) {
  for (const auto& [spec, pipeline] : pipelines_)
    if (spec == specialization) return pipeline;

  const Specialization<LicSpecialization> constants(specialization);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = shader_;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = constants.info();
  info.layout = layout_;
  VkPipeline pipeline = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreateComputePipelines(context_->device(), VK_NULL_HANDLE, 1, &info, nullptr,
                                             &pipeline),
                    "vkCreateComputePipelines"));
  const std::string name = std::string("lic ") +
                           std::string(toString(static_cast<Integrator>(specialization.integrator))) +
                           "/" + std::string(toString(static_cast<Kernel>(specialization.kernel))) +
                           "/" +
                           std::string(toString(static_cast<NoiseFilter>(specialization.noiseFilter))) +
                           "/" +
                           std::string(toString(static_cast<DirectionMode>(specialization.direction)));
  context_->setDebugName(pipeline, VK_OBJECT_TYPE_PIPELINE, name);
  pipelines_.emplace_back(specialization, pipeline);
  return pipeline;
}

Result<void> LicPass::record(VkCommandBuffer cmd, const FieldTexture& field, const Image& output,
                             const LicParams& params, int zBegin, int zEnd) {
  const LicSpecialization specialization = licSpecialization(params);
  LIC3D_TRY_ASSIGN(VkPipeline pipeline, pipelineFor(specialization));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);

  const VkDescriptorImageInfo fieldInfo{sampler_.handle(), field.image.view(),
                                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkDescriptorImageInfo outputInfo{VK_NULL_HANDLE, output.view(), VK_IMAGE_LAYOUT_GENERAL};
  std::array<VkWriteDescriptorSet, 2> writes{};
  for (auto& w : writes) {
    w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w.descriptorCount = 1;
  }
  writes[0].dstBinding = gpu::kLicBindingField;
  writes[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  writes[0].pImageInfo = &fieldInfo;
  writes[1].dstBinding = gpu::kLicBindingOutput;
  writes[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
  writes[1].pImageInfo = &outputInfo;
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_, 0,
                                 static_cast<std::uint32_t>(writes.size()), writes.data());

  const Dims dims = field.dims;
  gpu::LicPushConstants push{};
  push.dims = glm::ivec4(dims, zBegin);
  push.invDims = glm::vec4(1.0f / glm::vec3(dims), 0.0f);
  push.licLength = params.length;
  push.bias = params.bias;
  push.step = params.step;
  push.criticalEpsilon = static_cast<float>(kCriticalFraction);
  push.hannDenominator = static_cast<float>(params.length + std::abs(params.bias) + 1);
  push.gaussScale = params.length > 0 ? 1.0f / (0.5f * static_cast<float>(params.length)) : 0.0f;
  vkCmdPushConstants(cmd, layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);

  auto groups = [](int n, std::uint32_t size) {
    return (static_cast<std::uint32_t>(n) + size - 1) / size;
  };
  vkCmdDispatch(cmd, groups(dims.x, specialization.localSizeX),
                groups(dims.y, specialization.localSizeY),
                groups(zEnd - zBegin, specialization.localSizeZ));
  return {};
}

}  // namespace lic3d
