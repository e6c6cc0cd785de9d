#include "slice_pass.h"

#include <array>

#include "shader_library.h"
#include "shared_layout.h"
#include "vk_check.h"

namespace lic3d {

SliceFrame makeSliceFrame(const ViewParams& view, Dims dims, const GridGeometry& geometry,
                          float windowLow, float windowHigh) {
  SliceFrame frame;
  frame.halfExtent = boxHalfExtent(dims, geometry);
  const float aspect = static_cast<float>(view.width) / static_cast<float>(view.height);
  frame.camera = computeCamera(view.camera, frame.halfExtent, aspect);
  // Perspective slices stay perpendicular to the line from the box centre to the eye.
  const glm::vec3 toViewer = view.camera.orthographic ? frame.camera.toViewer
                                                      : glm::normalize(frame.camera.eye);
  frame.plan = planSlices(view.slicing, dims, frame.halfExtent, toViewer, view.slices);
  frame.alpha = view.alpha;
  const float low = view.autoWindow ? windowLow : view.windowLow;
  const float high = view.autoWindow ? windowHigh : view.windowHigh;
  const float width = std::max(high - low, 1e-6f);
  // grey = 0.5 + contrast * ((I - low) / width - 0.5) + brightness
  frame.transferScale = view.contrast / width;
  frame.transferOffset = 0.5f - view.contrast * (low / width + 0.5f) + view.brightness;
  frame.specialization.opacityMode = static_cast<std::uint32_t>(view.opacityMode);
  frame.specialization.orthographic = view.camera.orthographic ? 1u : 0u;
  frame.filter = view.filter;
  return frame;
}

Result<SlicePass> SlicePass::create(const Context& context) {
  SlicePass pass;
  pass.context_ = &context;
  const std::array<VkDescriptorSetLayoutBinding, 1> bindings{{
      {gpu::kSliceBindingVolume, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1,
       VK_SHADER_STAGE_FRAGMENT_BIT, nullptr},
  }};
  LIC3D_TRY_ASSIGN(pass.layout_,
                   PipelineLayout::create(context, bindings,
                                          VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                                          sizeof(gpu::SlicePushConstants), "slice"));
  LIC3D_TRY_ASSIGN(pass.vertexShader_, loadShader(context, ShaderId::SliceVertex));
  LIC3D_TRY_ASSIGN(pass.fragmentShader_, loadShader(context, ShaderId::SliceFragment));
  LIC3D_TRY_ASSIGN(pass.nearest_, Sampler::create(context, VK_FILTER_NEAREST, "slice nearest sampler"));
  LIC3D_TRY_ASSIGN(pass.linear_, Sampler::create(context, VK_FILTER_LINEAR, "slice linear sampler"));
  return pass;
}

Result<VkPipeline> SlicePass::pipelineFor(const SliceSpecialization& specialization,
                                          VkFormat format) {
  for (const auto& [spec, f, pipeline] : pipelines_)
    if (spec == specialization && f == format) return pipeline.get();

  const Specialization<SliceSpecialization> constants(specialization);
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertexShader_.get();
  stages[0].pName = "main";
  stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[1].stage = VK_SHADER_STAGE_FRAGMENT_BIT;
  stages[1].module = fragmentShader_.get();
  stages[1].pName = "main";
  stages[1].pSpecializationInfo = constants.info();

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
  // Premultiplied "over", slices drawn back to front: dst = src + (1 - src.a) * dst.
  VkPipelineColorBlendAttachmentState blendAttachment{};
  blendAttachment.blendEnable = VK_TRUE;
  blendAttachment.srcColorBlendFactor = VK_BLEND_FACTOR_ONE;
  blendAttachment.dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  blendAttachment.colorBlendOp = VK_BLEND_OP_ADD;
  blendAttachment.srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE;
  blendAttachment.dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
  blendAttachment.alphaBlendOp = VK_BLEND_OP_ADD;
  blendAttachment.colorWriteMask = VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                   VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
  blend.attachmentCount = 1;
  blend.pAttachments = &blendAttachment;
  const std::array<VkDynamicState, 2> dynamicStates{VK_DYNAMIC_STATE_VIEWPORT,
                                                    VK_DYNAMIC_STATE_SCISSOR};
  VkPipelineDynamicStateCreateInfo dynamic{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
  dynamic.dynamicStateCount = static_cast<std::uint32_t>(dynamicStates.size());
  dynamic.pDynamicStates = dynamicStates.data();
  VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachmentFormats = &format;

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
  info.layout = layout_.get();
  VkPipeline pipeline = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreateGraphicsPipelines(context_->device(), VK_NULL_HANDLE, 1, &info,
                                              nullptr, &pipeline),
                    "vkCreateGraphicsPipelines"));
  context_->setDebugName(pipeline, VK_OBJECT_TYPE_PIPELINE,
                         std::string("slices ") +
                             (specialization.opacityMode ? "intensity-alpha" : "constant-alpha") +
                             (specialization.orthographic ? " ortho" : " perspective"));
  pipelines_.emplace_back(specialization, format, Pipeline(context_->device(), pipeline));
  return pipeline;
}

Result<void> SlicePass::record(VkCommandBuffer cmd, VkFormat colorFormat, VkExtent2D extent,
                               const Image& volume, const SliceFrame& frame) {
  LIC3D_TRY_ASSIGN(VkPipeline pipeline, pipelineFor(frame.specialization, colorFormat));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);

  const VkViewport viewport{0.0f, 0.0f, static_cast<float>(extent.width),
                            static_cast<float>(extent.height), 0.0f, 1.0f};
  const VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);

  const Sampler& sampler = frame.filter == VolumeFilter::Nearest ? nearest_ : linear_;
  const VkDescriptorImageInfo volumeInfo{sampler.handle(), volume.view(),
                                         VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  const VkWriteDescriptorSet write = descriptorWrite(
      gpu::kSliceBindingVolume, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, &volumeInfo);
  context_->cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_.get(), 0, 1, &write);

  gpu::SlicePushConstants push{};
  push.viewProjection = frame.camera.viewProjection;
  push.halfExtent = glm::vec4(frame.halfExtent, frame.alpha);
  push.planeNormal = glm::vec4(frame.plan.normal, frame.plan.firstOffset);
  const glm::vec3 eye = frame.specialization.orthographic ? frame.camera.toViewer : frame.camera.eye;
  push.eye = glm::vec4(eye, frame.plan.spacing);
  push.transfer = glm::vec4(frame.transferScale, frame.transferOffset, frame.plan.voxelSize, 0.0f);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0,
                     sizeof(push), &push);
  vkCmdDraw(cmd, gpu::kSliceVerticesPerSlice, static_cast<std::uint32_t>(frame.plan.count), 0, 0);
  return {};
}

}  // namespace lic3d
