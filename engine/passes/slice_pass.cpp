// SPDX-License-Identifier: BSD-3-Clause
#include "passes/slice_pass.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "core/colormap.h"
#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "gpu/vk_check.h"
#include "shared_layout.h"

namespace lic3d {

namespace {

// Euler angles in degrees, applied x, then y, then z.
glm::mat3 rotationFromEuler(glm::vec3 degrees) {
  const glm::vec3 r = glm::radians(degrees);
  const glm::mat4 m = glm::rotate(glm::mat4(1.0f), r.z, glm::vec3(0, 0, 1)) *
                      glm::rotate(glm::mat4(1.0f), r.y, glm::vec3(0, 1, 0)) *
                      glm::rotate(glm::mat4(1.0f), r.x, glm::vec3(1, 0, 0));
  return glm::mat3(m);
}

}  // namespace

float zeroParallaxDistance(const ViewParams& view, const CameraMatrices& central) {
  return view.zeroParallax > 0.0f ? view.zeroParallax : central.distance;
}

float eyeSeparation(const ViewParams& view, const CameraMatrices& central) {
  // A separation of 1/30 of the zero-parallax distance keeps disparities comfortable.
  return view.eyeSeparation > 0.0f ? view.eyeSeparation
                                   : zeroParallaxDistance(view, central) / 30.0f;
}

SliceFrame makeSliceFrame(const ViewParams& view, const VolumeFacts& volume, Eye eye,
                          float aspect) {
  SliceFrame frame;
  frame.halfExtent = boxHalfExtent(volume.dims, volume.geometry);
  const CameraMatrices central = computeCamera(view.camera, frame.halfExtent, aspect);
  float eyeOffset = 0.0f;
  if (eye != Eye::Mono)
    eyeOffset = (eye == Eye::Left ? -0.5f : 0.5f) * eyeSeparation(view, central);
  frame.camera = eyeOffset == 0.0f ? central
                                   : computeCamera(view.camera, frame.halfExtent, aspect, eyeOffset,
                                                   zeroParallaxDistance(view, central));
  // Slices stay perpendicular to the line from the box centre to the central eye, so both eyes
  // of a stereo pair see the same planes.
  const glm::vec3 toViewer =
      view.camera.orthographic ? central.toViewer : glm::normalize(central.eye);
  frame.plan = planSlices(view.slicing, volume.dims, frame.halfExtent, toViewer, view.slices);

  SliceSpecialization& s = frame.specialization;
  s.opacityMode = static_cast<std::uint32_t>(view.opacityMode);
  s.orthographic = view.camera.orthographic ? 1u : 0u;
  s.colorMode = static_cast<std::uint32_t>(view.color);
  s.colormap = view.transfer.colors.empty() ? static_cast<std::uint32_t>(view.colormap)
                                            : static_cast<std::uint32_t>(kCustomColormapRow);
  s.magnitudeOpacity = view.magnitudeOpacity > 0.0f || view.magnitudeThreshold > 0.0f ? 1u : 0u;
  s.opacityTable = view.transfer.opacities.empty() ? 0u : 1u;
  s.clipPlane = view.clipPlane ? 1u : 0u;
  s.colorSource = volume.colorScalar ? 1u : 0u;
  s.opacitySource = volume.opacityScalar ? 1u : 0u;
  s.sparsity = volume.sparsity ? 1u : 0u;
  s.roiShape = static_cast<std::uint32_t>(view.roi);
  s.roiOutside = view.roi != RoiShape::None && view.roiOutside ? 1u : 0u;
  s.fog = view.fog ? 1u : 0u;
  s.lighting = static_cast<std::uint32_t>(view.lighting);
  s.filter = view.filter == VolumeFilter::Nearest ? 0u : 1u;
  if (view.stereo == StereoMode::Anaglyph) s.anaglyph = eye == Eye::Right ? 2u : 1u;
  s.fieldPacking = volume.fieldPrecision == FieldPrecision::Byte ? 1u : 0u;

  gpu::SliceUniforms& u = frame.uniforms;
  const glm::vec3 h = frame.halfExtent;
  u.viewProjection = frame.camera.viewProjection;
  // texture coordinates -> world (box units) -> rotated region frame -> unit-size shape
  const glm::mat3 rotation = rotationFromEuler(view.roiRotation);
  const glm::mat4 toWorld =
      glm::scale(glm::mat4(1.0f), 2.0f * h) * glm::translate(glm::mat4(1.0f), -view.roiCenter);
  u.roiFromTexture = glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / std::max(view.roiSize, 1e-6f))) *
                     glm::mat4(glm::transpose(rotation)) * toWorld;
  const TransferFacts transferFacts = volume.transfer();
  u.halfExtent = glm::vec4(h, resolvedAlpha(view, transferFacts, volume.dims));
  u.clipMin = glm::vec4((glm::clamp(view.clipMin, 0.0f, 1.0f) - 0.5f) * 2.0f * h, 0.0f);
  u.clipMax = glm::vec4((glm::clamp(view.clipMax, 0.0f, 1.0f) - 0.5f) * 2.0f * h, 0.0f);
  u.planeNormal = glm::vec4(frame.plan.normal, frame.plan.firstOffset);
  u.eyePosition = glm::vec4(frame.camera.eye, frame.plan.spacing);
  u.toViewer = glm::vec4(central.toViewer, 0.0f);
  u.transfer = glm::vec4(greyTransfer(view, transferFacts), frame.plan.voxelSize, 0.0f);
  u.magnitude = glm::vec4(magnitudeTransfer(colorRange(view, transferFacts)), 0.0f, 0.0f);
  u.texelToPhysical = texelToPhysicalForShader(glm::dvec3(volume.texelToPhysical));
  u.magnitudeOpacity = glm::vec4(view.magnitudeOpacity, view.magnitudeThreshold,
                                 magnitudeTransfer(opacityRange(view, transferFacts)));
  if (view.clipPlane) {
    // The plane through the point (box fractions) with the normal in box axes, in world units.
    const glm::vec3 point = (view.clipPlanePoint - 0.5f) * 2.0f * h;
    const glm::vec3 normal = glm::normalize(view.clipPlaneNormal / (2.0f * h));
    u.clipPlane = glm::vec4(normal, glm::dot(normal, point));
  }

  // Fog depths from the nearest to the farthest point of the volume's bounding sphere.
  const float radius = glm::length(h);
  const float centreDepth = glm::dot(frame.camera.eye, central.toViewer);
  const float nearDepth = centreDepth - radius;
  const float span = 2.0f * radius;
  const float fogStart = nearDepth + view.fogStart * span;
  const float fogEnd = nearDepth + view.fogEnd * span;
  u.fog = glm::vec4(fogStart, 1.0f / std::max(fogEnd - fogStart, 1e-6f), 0.0f, 0.0f);
  u.fogColor = glm::vec4(view.fogColorFromBackground ? view.background : view.fogColor, 1.0f);

  // A headlight from above left of the camera.
  const glm::vec3 toLight =
      glm::normalize(central.toViewer + 0.5f * central.up - 0.35f * central.right);
  u.light = glm::vec4(toLight, view.light.shininess);
  u.lightTerms = glm::vec4(view.light.ambient, view.light.diffuse, view.light.specular, 0.0f);
  u.voxelSize = glm::vec4(2.0f * h / glm::vec3(volume.dims), 0.0f);
  const std::uint32_t* modes = reinterpret_cast<const std::uint32_t*>(&s);
  // Every mode after `colormap` but the field packing, in order: the runtime-mode shader's.
  for (int i = 0; i < 12; ++i) u.modes[i / 4][i % 4] = modes[i];
  u.modes[3] = glm::uvec4(s.opacityTable, s.clipPlane, s.colorSource, s.opacitySource);
  u.scalarRange = volume.scalarRange;
  return frame;
}

Result<SlicePass> SlicePass::create(const Context& context, bool runtimeModes) {
  SlicePass pass;
  pass.context_ = &context;
  pass.runtimeModes_ = runtimeModes;
  constexpr VkShaderStageFlags kBothStages =
      VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  constexpr Binding bindings[] = {
      {gpu::kSliceBindingVolume, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
      {gpu::kSliceBindingField, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
      {gpu::kSliceBindingColormap, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
      {gpu::kSliceBindingUniforms, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kBothStages},
      {gpu::kSliceBindingScalars, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
  };
  LIC3D_TRY_ASSIGN(pass.layout_, PipelineLayout::create(context, bindings, 0, 0, "slice"));
  LIC3D_TRY_ASSIGN(pass.vertexShader_, loadShader(context, ShaderId::SliceVertex));
  LIC3D_TRY_ASSIGN(pass.fragmentShader_,
                   loadShader(context, runtimeModes ? ShaderId::SliceFragmentRuntimeModes
                                                    : ShaderId::SliceFragment));
  LIC3D_TRY_ASSIGN(pass.linear_,
                   Sampler::create(context, VK_FILTER_LINEAR, "slice linear sampler"));

  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.format = VK_FORMAT_R8G8B8A8_UNORM;
  desc.extent = {kColormapWidth, kColormapRows, 1};
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "colour maps";
  LIC3D_TRY_ASSIGN(pass.colormaps_, Image::create(context, desc));
  const std::vector<std::uint8_t> table = colormapTable(pass.tableTransfer_, pass.tableMap_);
  LIC3D_TRY(uploadImage(context, pass.colormaps_, table.data(), table.size()));

  const VkDeviceSize alignment = context.properties().limits.minUniformBufferOffsetAlignment;
  pass.slotSize_ = (sizeof(gpu::SliceUniforms) + alignment - 1) / alignment * alignment;
  LIC3D_TRY_ASSIGN(pass.uniforms_, Buffer::create(context, pass.slotSize_ * kUniformSlots,
                                                  VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT,
                                                  MemoryUse::Upload, "slice uniforms"));
  return pass;
}

Result<void> SlicePass::setTransferFunction(const TransferFunction& tf, Colormap map) {
  if (tf == tableTransfer_ && (map == tableMap_ || !tf.colors.empty())) return {};
  // Frames still in flight may sample the table.
  vkQueueWaitIdle(context_->queue());
  const std::vector<std::uint8_t> table = colormapTable(tf, map);
  LIC3D_TRY(uploadImage(*context_, colormaps_, table.data(), table.size()));
  tableTransfer_ = tf;
  tableMap_ = map;
  return {};
}

Result<Pipeline> SlicePass::createPipeline(const SliceVariant& variant) const {
  const SliceSpecialization& specialization = variant.specialization;
  const VkFormat format = variant.format;
  const Specialization<SliceSpecialization> constants(specialization);
  std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
  stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO};
  stages[0].stage = VK_SHADER_STAGE_VERTEX_BIT;
  stages[0].module = vertexShader_.get();
  stages[0].pName = "main";
  stages[0].pSpecializationInfo = constants.info();
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
  // Anaglyph: the left eye writes red, the right eye green and blue, into one image.
  blendAttachment.colorWriteMask = specialization.anaglyph == 1 ? VK_COLOR_COMPONENT_R_BIT
                                   : specialization.anaglyph == 2
                                       ? VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT
                                       : VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT |
                                             VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
  VkPipelineColorBlendStateCreateInfo blend{
      VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
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
  LIC3D_TRY(checkVk(
      vkCreateGraphicsPipelines(context_->device(), VK_NULL_HANDLE, 1, &info, nullptr, &pipeline),
      "vkCreateGraphicsPipelines"));
  std::string name = "slices";
  const std::uint32_t* fields = reinterpret_cast<const std::uint32_t*>(&specialization);
  for (std::size_t i = 0; i < sizeof(specialization) / 4; ++i)
    name += " " + std::to_string(fields[i]);
  context_->setDebugName(pipeline, VK_OBJECT_TYPE_PIPELINE, name);
  return Pipeline(context_->device(), pipeline);
}

Result<void> SlicePass::record(VkCommandBuffer cmd, VkFormat colorFormat, VkRect2D viewport,
                               const Image& volume, const FieldTexture& field, const Image& scalars,
                               const SliceFrame& frame, std::uint32_t slot) {
  LIC3D_ASSERT(slot < kUniformSlots);
  // The runtime-mode shader needs one pipeline per colour write mask only.
  SliceSpecialization key = frame.specialization;
  if (runtimeModes_)
    key = SliceSpecialization{.anaglyph = frame.specialization.anaglyph,
                              .fieldPacking = frame.specialization.fieldPacking};
  LIC3D_TRY_ASSIGN(
      VkPipeline pipeline,
      pipelines_.get({key, colorFormat}, [&](const SliceVariant& v) { return createPipeline(v); }));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);

  const VkViewport vp{static_cast<float>(viewport.offset.x),
                      static_cast<float>(viewport.offset.y),
                      static_cast<float>(viewport.extent.width),
                      static_cast<float>(viewport.extent.height),
                      0.0f,
                      1.0f};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &viewport);

  const VkDeviceSize offset = slotSize_ * slot;
  std::memcpy(static_cast<std::byte*>(uniforms_.mapped()) + offset, &frame.uniforms,
              sizeof(frame.uniforms));

  // Nearest filtering happens in the shader (texelFetch); the sampler is always linear.
  DescriptorWrites()
      .sampledImage(gpu::kSliceBindingVolume, linear_, volume.view())
      .sampledImage(gpu::kSliceBindingField, linear_, field.image.view())
      .sampledImage(gpu::kSliceBindingColormap, linear_, colormaps_.view())
      .uniformBuffer(gpu::kSliceBindingUniforms, uniforms_, offset, sizeof(gpu::SliceUniforms))
      .sampledImage(gpu::kSliceBindingScalars, linear_, scalars.view())
      .push(*context_, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_);
  vkCmdDraw(cmd, gpu::kSliceVerticesPerSlice, static_cast<std::uint32_t>(frame.plan.count), 0, 0);
  return {};
}

}  // namespace lic3d
