#include "gpu/pipelines.h"

#include "gpu/vk_check.h"

namespace lic3d {

Result<ShaderModule> loadShader(const Context& context, ShaderId id) {
  LIC3D_TRY_ASSIGN(VkShaderModule module, createShaderModule(context, id));
  return ShaderModule(context.device(), module);
}

Result<PipelineLayout> PipelineLayout::create(
    const Context& context, std::span<const VkDescriptorSetLayoutBinding> bindings,
    VkShaderStageFlags pushStages, std::uint32_t pushBytes, const std::string& name) {
  VkDevice device = context.device();
  PipelineLayout result;

  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = static_cast<std::uint32_t>(bindings.size());
  setInfo.pBindings = bindings.data();
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreateDescriptorSetLayout(device, &setInfo, nullptr, &setLayout),
                    "vkCreateDescriptorSetLayout"));
  result.setLayout_ = {device, setLayout};
  context.setDebugName(setLayout, VK_OBJECT_TYPE_DESCRIPTOR_SET_LAYOUT, name + " set layout");

  const VkPushConstantRange range{pushStages, 0, pushBytes};
  VkPipelineLayoutCreateInfo layoutInfo{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  layoutInfo.setLayoutCount = 1;
  layoutInfo.pSetLayouts = &setLayout;
  layoutInfo.pushConstantRangeCount = pushBytes > 0 ? 1 : 0;
  layoutInfo.pPushConstantRanges = &range;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreatePipelineLayout(device, &layoutInfo, nullptr, &layout),
                    "vkCreatePipelineLayout"));
  result.layout_ = {device, layout};
  context.setDebugName(layout, VK_OBJECT_TYPE_PIPELINE_LAYOUT, name + " pipeline layout");
  return result;
}

Result<Pipeline> createComputePipeline(const Context& context, const ShaderModule& shader,
                                       const PipelineLayout& layout,
                                       const VkSpecializationInfo* specialization,
                                       const std::string& name) {
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = shader.get();
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = specialization;
  info.layout = layout.get();
  VkPipeline pipeline = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(
      vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
      "vkCreateComputePipelines"));
  context.setDebugName(pipeline, VK_OBJECT_TYPE_PIPELINE, name);
  return Pipeline(context.device(), pipeline);
}

VkWriteDescriptorSet descriptorWrite(std::uint32_t binding, VkDescriptorType type,
                                     const VkDescriptorImageInfo* image) {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  write.pImageInfo = image;
  return write;
}

VkWriteDescriptorSet descriptorWrite(std::uint32_t binding, VkDescriptorType type,
                                     const VkDescriptorBufferInfo* buffer) {
  VkWriteDescriptorSet write{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  write.pBufferInfo = buffer;
  return write;
}

}  // namespace lic3d
