// SPDX-License-Identifier: BSD-3-Clause
#include "gpu/pipelines.h"

#include "gpu/vk_check.h"

namespace lic3d {

Result<ShaderModule> loadShader(const Context& context, ShaderId id) {
  LIC3D_TRY_ASSIGN(VkShaderModule module, createShaderModule(context, id));
  return ShaderModule(context.device(), module);
}

Result<PipelineLayout> PipelineLayout::create(const Context& context,
                                              std::span<const Binding> bindings,
                                              VkShaderStageFlags pushStages,
                                              std::uint32_t pushBytes, const std::string& name) {
  VkDevice device = context.device();
  PipelineLayout result;

  std::vector<VkDescriptorSetLayoutBinding> layoutBindings;
  for (const Binding& b : bindings)
    layoutBindings.push_back({b.binding, b.type, 1, b.stages, nullptr});
  VkDescriptorSetLayoutCreateInfo setInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  setInfo.flags = VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR;
  setInfo.bindingCount = static_cast<std::uint32_t>(layoutBindings.size());
  setInfo.pBindings = layoutBindings.data();
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
  if (context.capturesPipelineStatistics())
    info.flags |= VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR;
  VkPipeline pipeline = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(
      vkCreateComputePipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
      "vkCreateComputePipelines"));
  context.setDebugName(pipeline, VK_OBJECT_TYPE_PIPELINE, name);
  return Pipeline(context.device(), pipeline);
}

Result<Pipeline> createGraphicsPipeline(const Context& context, const GraphicsPipelineDesc& desc) {
  LIC3D_ASSERT(desc.blends.size() == desc.colorFormats.size());
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = desc.vertex;
  stages[0].pName = "main";
  stages[0].pSpecializationInfo = desc.specialization;
  stages[1] = stages[0];
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = desc.fragment;

  VkPipelineVertexInputStateCreateInfo vertexInput{
      VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
  VkPipelineInputAssemblyStateCreateInfo assembly{
      VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
  assembly.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
  VkPipelineViewportStateCreateInfo viewport{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
  viewport.viewportCount = 1;
  viewport.scissorCount = 1;
  VkPipelineRasterizationStateCreateInfo raster{
      VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
  raster.polygonMode = VK_POLYGON_MODE_FILL;
  raster.cullMode = VK_CULL_MODE_NONE;
  raster.lineWidth = 1.0f;
  VkPipelineMultisampleStateCreateInfo multisample{
      VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
  multisample.rasterizationSamples = VK_SAMPLE_COUNT_1_BIT;
  VkPipelineDepthStencilStateCreateInfo depth{
      VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
  VkPipelineColorBlendStateCreateInfo blend{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = static_cast<std::uint32_t>(desc.blends.size());
  blend.pAttachments = desc.blends.data();
  const std::array<VkDynamicState, 2> dynamicStates{VK_DYNAMIC_STATE_VIEWPORT,
                                                    VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamicStates.size());
  dynamic.pDynamicStates = dynamicStates.data();
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = static_cast<std::uint32_t>(desc.colorFormats.size());
  rendering.pColorAttachmentFormats = desc.colorFormats.data();

  VkGraphicsPipelineCreateInfo info{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO, &rendering};
  info.stageCount = static_cast<std::uint32_t>(stages.size());
  info.pStages = stages.data();
  info.pVertexInputState = &vertexInput;
  info.pInputAssemblyState = &assembly;
  info.pViewportState = &viewport;
  info.pRasterizationState = &raster;
  info.pMultisampleState = &multisample;
  info.pDepthStencilState = &depth;
  info.pColorBlendState = &blend;
  info.pDynamicState = &dynamic;
  info.layout = desc.layout->get();
  VkPipeline pipeline = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(
      vkCreateGraphicsPipelines(context.device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
      "vkCreateGraphicsPipelines"));
  context.setDebugName(pipeline, VK_OBJECT_TYPE_PIPELINE, desc.name);
  return Pipeline(context.device(), pipeline);
}

VkPipelineColorBlendAttachmentState blendOver(VkColorComponentFlags writeMask) {
  VkPipelineColorBlendAttachmentState state{};
  state.blendEnable = VK_TRUE;
  state.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
  state.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  state.colorBlendOp = VK_BLEND_OP_ADD;
  state.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  state.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  state.alphaBlendOp = VK_BLEND_OP_ADD;
  state.colorWriteMask = writeMask;
  return state;
}

VkPipelineColorBlendAttachmentState blendUnder() {
  VkPipelineColorBlendAttachmentState state = blendOver(kWriteRgba);
  state.srcColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
  state.dstColorBlendFactor = VK_BLEND_FACTOR_ONE;
  state.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
  state.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  return state;
}

std::vector<std::pair<std::string, std::string>> pipelineStatistics(const Context& context,
                                                                    VkPipeline pipeline) {
  std::vector<std::pair<std::string, std::string>> statistics;
  if (!context.capturesPipelineStatistics() || pipeline == VK_NULL_HANDLE) return statistics;
  auto getProperties = reinterpret_cast<PFN_vkGetPipelineExecutablePropertiesKHR>(
      vkGetDeviceProcAddr(context.device(), "vkGetPipelineExecutablePropertiesKHR"));
  auto getStatistics = reinterpret_cast<PFN_vkGetPipelineExecutableStatisticsKHR>(
      vkGetDeviceProcAddr(context.device(), "vkGetPipelineExecutableStatisticsKHR"));
  if (!getProperties || !getStatistics) return statistics;
  VkPipelineInfoKHR info{VK_STRUCTURE_TYPE_PIPELINE_INFO_KHR};
  info.pipeline = pipeline;
  std::uint32_t executables = 0;
  if (getProperties(context.device(), &info, &executables, nullptr) != VK_SUCCESS)
    return statistics;
  for (std::uint32_t e = 0; e < executables; ++e) {
    VkPipelineExecutableInfoKHR executable{VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_INFO_KHR};
    executable.pipeline = pipeline;
    executable.executableIndex = e;
    std::uint32_t count = 0;
    if (getStatistics(context.device(), &executable, &count, nullptr) != VK_SUCCESS) continue;
    std::vector<VkPipelineExecutableStatisticKHR> values(
        count, {VK_STRUCTURE_TYPE_PIPELINE_EXECUTABLE_STATISTIC_KHR});
    if (getStatistics(context.device(), &executable, &count, values.data()) != VK_SUCCESS) continue;
    for (const VkPipelineExecutableStatisticKHR& v : values) {
      std::string text;
      switch (v.format) {
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_BOOL32_KHR:
          text = v.value.b32 ? "true" : "false";
          break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_INT64_KHR:
          text = std::to_string(v.value.i64);
          break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_UINT64_KHR:
          text = std::to_string(v.value.u64);
          break;
        case VK_PIPELINE_EXECUTABLE_STATISTIC_FORMAT_FLOAT64_KHR:
          text = std::to_string(v.value.f64);
          break;
        default: continue;
      }
      statistics.emplace_back(v.name, text);
    }
  }
  return statistics;
}

VkWriteDescriptorSet& DescriptorWrites::add(std::uint32_t binding, VkDescriptorType type) {
  LIC3D_ASSERT(count_ < kMax);
  VkWriteDescriptorSet& write = writes_[count_++];
  write = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  write.dstBinding = binding;
  write.descriptorCount = 1;
  write.descriptorType = type;
  return write;
}

DescriptorWrites& DescriptorWrites::sampledImage(std::uint32_t binding, const Sampler& sampler,
                                                 VkImageView view) {
  add(binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
  images_[count_ - 1] = {sampler.handle(), view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  return *this;
}

DescriptorWrites& DescriptorWrites::storageImage(std::uint32_t binding, VkImageView view) {
  add(binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE);
  images_[count_ - 1] = {VK_NULL_HANDLE, view, VK_IMAGE_LAYOUT_GENERAL};
  return *this;
}

DescriptorWrites& DescriptorWrites::storageBuffer(std::uint32_t binding, const Buffer& buffer) {
  add(binding, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  buffers_[count_ - 1] = {buffer.handle(), 0, VK_WHOLE_SIZE};
  return *this;
}

DescriptorWrites& DescriptorWrites::uniformBuffer(std::uint32_t binding, const Buffer& buffer,
                                                  VkDeviceSize offset, VkDeviceSize range) {
  add(binding, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  buffers_[count_ - 1] = {buffer.handle(), offset, range};
  return *this;
}

void DescriptorWrites::push(const Context& context, VkCommandBuffer cmd,
                            VkPipelineBindPoint bindPoint, const PipelineLayout& layout) {
  // The info pointers are set here, so a moved or copied DescriptorWrites stays valid.
  for (std::uint32_t i = 0; i < count_; ++i) {
    const bool buffer = writes_[i].descriptorType == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER ||
                        writes_[i].descriptorType == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    writes_[i].pImageInfo = buffer ? nullptr : &images_[i];
    writes_[i].pBufferInfo = buffer ? &buffers_[i] : nullptr;
  }
  context.cmdPushDescriptorSet(cmd, bindPoint, layout.get(), 0, count_, writes_.data());
}

}  // namespace lic3d
