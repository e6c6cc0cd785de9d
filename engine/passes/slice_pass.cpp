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

// Anaglyph: the left eye (1) writes red, the right eye (2) green and blue, into one image.
VkColorComponentFlags anaglyphWriteMask(std::uint32_t anaglyph) {
  if (anaglyph == 1) return VK_COLOR_COMPONENT_R_BIT;
  if (anaglyph == 2) return VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT;
  return kWriteRgba;
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

// How many pixels one voxel (its smallest side) covers at the box's centre.
float pixelsPerVoxel(const CameraMatrices& camera, glm::vec3 voxel, VkExtent2D viewport) {
  const float side = std::min(voxel.x, std::min(voxel.y, voxel.z));
  const glm::vec4 centre = camera.viewProjection * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  const glm::vec4 aside = camera.viewProjection * glm::vec4(side * camera.up, 1.0f);
  return glm::length(glm::vec2(aside) / aside.w - glm::vec2(centre) / centre.w) * 0.5f *
         static_cast<float>(viewport.height);
}

SliceFrame makeSliceFrame(const ViewParams& view, const VolumeFacts& volume, Eye eye,
                          VkExtent2D viewport) {
  const float aspect = static_cast<float>(viewport.width) / static_cast<float>(viewport.height);
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
  VolumeFilter filter = view.filter;
  if (filter == VolumeFilter::Auto)
    filter = pixelsPerVoxel(frame.camera, 2.0f * frame.halfExtent / glm::vec3(volume.dims),
                            viewport) > kCubicFromPixels
                 ? VolumeFilter::Cubic
                 : VolumeFilter::Linear;
  s.filter = static_cast<std::uint32_t>(filter);
  if (view.stereo == StereoMode::Anaglyph) s.anaglyph = eye == Eye::Right ? 2u : 1u;
  s.fieldPacking = volume.fieldPrecision == FieldPrecision::Byte ? 1u : 0u;
  s.halo = view.halo > 0.0f ? 1u : 0u;
  s.occlusion = view.occlusion > 0.0f ? 1u : 0u;
  s.jitter = view.jitter ? 1u : 0u;
  frame.eyeIndex = eye == Eye::Right ? 1 : 0;
  // The box lies within the bounding sphere around the centre, at least distance - |target| -
  // radius from the camera; the near plane is at distance - 2 radius - |target| (computeCamera)
  // unless the camera is that close, and the far plane beyond the sphere.
  frame.groupable = central.distance * (1.0f - 1e-3f) >=
                    2.0f * glm::length(frame.halfExtent) + glm::length(view.camera.target);

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
  u.toViewer = glm::vec4(central.toViewer, static_cast<float>(frame.plan.count));
  u.transfer = glm::vec4(greyTransfer(view, transferFacts), frame.plan.voxelSize, 0.0f);
  u.magnitude =
      glm::vec4(magnitudeTransfer(colorRange(view, transferFacts)), view.opacityFloor, 0.0f);
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
  const glm::vec3 voxel = glm::vec3(u.voxelSize);
  const float smallestVoxel = std::min(voxel.x, std::min(voxel.y, voxel.z));
  u.screenRight = glm::vec4(central.right, view.haloRadius * smallestVoxel);
  u.screenUp = glm::vec4(central.up, view.halo);
  u.haloColor = glm::vec4(view.background, 1.0f);
  u.occlusion = glm::vec4(view.occlusion, 0.0f, 0.0f, 0.0f);  // the rest set per viewport
  const std::uint32_t* modes = reinterpret_cast<const std::uint32_t*>(&s);
  // Every mode after `colormap` but the field packing, in order: the runtime-mode shader's.
  for (int i = 0; i < 12; ++i) u.modes[i / 4][i % 4] = modes[i];
  u.modes[3] = glm::uvec4(s.opacityTable, s.clipPlane, s.colorSource, s.opacitySource);
  u.modes[4] = glm::uvec4(s.halo, s.occlusion, s.jitter, 0u);
  u.scalarRange = volume.scalarRange;
  return frame;
}

Result<SlicePass> SlicePass::create(const Context& context, bool runtimeModes,
                                    bool haloPipelinePerSlice) {
  SlicePass pass;
  pass.context_ = &context;
  pass.runtimeModes_ = runtimeModes;
  pass.haloPipelinePerSlice_ = haloPipelinePerSlice;
  constexpr VkShaderStageFlags kBothStages =
      VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  constexpr VkDescriptorType kSampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  constexpr Binding bindings[] = {
      {gpu::kSliceBindingVolume, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
      {gpu::kSliceBindingField, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
      {gpu::kSliceBindingColormap, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
      {gpu::kSliceBindingUniforms, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kBothStages},
      {gpu::kSliceBindingScalars, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
      {gpu::kSliceBindingOcclusion, kSampled, VK_SHADER_STAGE_FRAGMENT_BIT},
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
  LIC3D_TRY_ASSIGN(pass.occlusion_, OcclusionPass::create(context));
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
  const Specialization<SliceSpecialization> constants(specialization);
  std::string name = "slices";
  const std::uint32_t* fields = reinterpret_cast<const std::uint32_t*>(&specialization);
  for (std::size_t i = 0; i < sizeof(specialization) / 4; ++i)
    name += " " + std::to_string(fields[i]);
  GraphicsPipelineDesc desc{.vertex = vertexShader_.get(),
                            .fragment = fragmentShader_.get(),
                            .specialization = constants.info(),
                            .layout = &layout_,
                            .name = name};
  if (specialization.occlusion == 1) {
    // Front to back into the occlusion pass's image ("under"); the buffer is written as is.
    VkPipelineColorBlendAttachmentState writeBuffer{};
    writeBuffer.colorWriteMask = VK_COLOR_COMPONENT_R_BIT;
    const std::array<VkPipelineColorBlendAttachmentState, 2> blends{blendUnder(), writeBuffer};
    desc.colorFormats = OcclusionPass::kFormats;
    desc.blends = blends;
    return createGraphicsPipeline(*context_, desc);
  }
  // Premultiplied "over", slices drawn back to front. Anaglyph: the left eye writes red, the
  // right eye green and blue, into one image.
  const std::array<VkPipelineColorBlendAttachmentState, 1> blends{
      blendOver(anaglyphWriteMask(specialization.anaglyph))};
  desc.colorFormats = std::span<const VkFormat>(&variant.format, 1);
  desc.blends = blends;
  return createGraphicsPipeline(*context_, desc);
}

Result<VkPipeline> SlicePass::pipelineFor(const SliceFrame& frame, VkFormat format) {
  // The runtime-mode shader needs one pipeline per colour write mask and attachment set only.
  SliceSpecialization key = frame.specialization;
  if (runtimeModes_)
    key = SliceSpecialization{.anaglyph = frame.specialization.anaglyph,
                              .fieldPacking = frame.specialization.fieldPacking,
                              .occlusion = frame.specialization.occlusion,
                              .slicesPerFragment = frame.specialization.slicesPerFragment};
  // The occlusion variant draws into the occlusion pass's attachments, whatever the frame's.
  if (key.occlusion == 1) format = VK_FORMAT_UNDEFINED;
  return pipelines_.get({key, format}, [&](const SliceVariant& v) { return createPipeline(v); });
}

Result<VkPipeline> SlicePass::pipelineWithoutHalo(const SliceFrame& frame, VkFormat format) {
  // Halos are drawn by every other slice (slice.frag). A GPU skips the ring where a whole
  // subgroup is on a slice without; a CPU driver runs both sides of a branch, so there the slices
  // without take the pipeline without halos.
  SliceFrame plain = frame;
  if (frame.specialization.halo == 1 && frame.specialization.slicesPerFragment == 1 &&
      haloPipelinePerSlice_ && !runtimeModes_ &&
      context_->deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU)
    plain.specialization.halo = 0;
  return pipelineFor(plain, format);
}

std::uint32_t SlicePass::slicesPerFragment(const SliceFrame& frame) const {
  if (frame.specialization.occlusion == 1 || !frame.groupable) return 1;
  int k = requestedSlicesPerFragment_;
  if (k <= 0)
    k = context_->deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU ? kSlicesPerFragmentCpu
                                                                   : kSlicesPerFragmentGpu;
  return k >= 4 ? 4u : k >= 2 ? 2u : 1u;
}

void SlicePass::writeUniforms(const gpu::SliceUniforms& uniforms, std::uint32_t slot) const {
  std::memcpy(static_cast<std::byte*>(uniforms_.mapped()) + slotSize_ * slot, &uniforms,
              sizeof(uniforms));
}

void SlicePass::pushDescriptors(VkCommandBuffer cmd, const Image& volume, const FieldTexture& field,
                                const Image& scalars, VkImageView occlusion,
                                std::uint32_t slot) const {
  // Nearest filtering happens in the shader (texelFetch); the sampler is always linear.
  DescriptorWrites()
      .sampledImage(gpu::kSliceBindingVolume, linear_, volume.view())
      .sampledImage(gpu::kSliceBindingField, linear_, field.image.view())
      .sampledImage(gpu::kSliceBindingColormap, linear_, colormaps_.view())
      .uniformBuffer(gpu::kSliceBindingUniforms, uniforms_, slotSize_ * slot,
                     sizeof(gpu::SliceUniforms))
      .sampledImage(gpu::kSliceBindingScalars, linear_, scalars.view())
      .sampledImage(gpu::kSliceBindingOcclusion, occlusion_.sampler(), occlusion)
      .push(*context_, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_);
}

Result<void> SlicePass::prepare(VkCommandBuffer cmd, VkRect2D viewport, const Image& volume,
                                const FieldTexture& field, const Image& scalars,
                                const SliceFrame& frame, std::uint32_t slot) {
  LIC3D_ASSERT(slot < kUniformSlots);
  if (frame.specialization.occlusion == 0) return {};
  LIC3D_TRY_ASSIGN(VkPipeline pipeline, pipelineFor(frame, VK_FORMAT_UNDEFINED));
  LIC3D_TRY_ASSIGN(VkPipeline withoutHalo, pipelineWithoutHalo(frame, VK_FORMAT_UNDEFINED));
  const VkExtent2D extent = viewport.extent;
  gpu::SliceUniforms uniforms = frame.uniforms;
  uniforms.occlusion.z = 1.0f / static_cast<float>(extent.width);
  uniforms.occlusion.w = 1.0f / static_cast<float>(extent.height);
  // The cone's spread over one slice: 45 degrees, one slice spacing sideways, in pixels at the
  // volume's centre.
  const glm::vec4 centre = frame.camera.viewProjection * glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  const glm::vec4 aside =
      frame.camera.viewProjection * glm::vec4(frame.camera.up * frame.plan.spacing, 1.0f);
  const float pixels = glm::length(glm::vec2(aside) / aside.w - glm::vec2(centre) / centre.w) *
                       0.5f * static_cast<float>(extent.height);
  uniforms.occlusion.y = std::max(pixels, 0.5f);
  writeUniforms(uniforms, slot);
  const int count = frame.plan.count;
  return occlusion_.record(cmd, frame.eyeIndex, extent, count,
                           [&](VkCommandBuffer c, int index, VkImageView inFront) {
                             // Slice 0 is the farthest: the index-th from the front is count - 1 -
                             // index.
                             const auto slice = static_cast<std::uint32_t>(count - 1 - index);
                             vkCmdBindPipeline(c, VK_PIPELINE_BIND_POINT_GRAPHICS,
                                               slice % 2 == 0 ? pipeline : withoutHalo);
                             pushDescriptors(c, volume, field, scalars, inFront, slot);
                             vkCmdDraw(c, gpu::kSliceVerticesPerSlice, 1, 0, slice);
                           });
}

Result<void> SlicePass::record(VkCommandBuffer cmd, VkFormat colorFormat, VkRect2D viewport,
                               const Image& volume, const FieldTexture& field, const Image& scalars,
                               const SliceFrame& sliceFrame, std::uint32_t slot) {
  LIC3D_ASSERT(slot < kUniformSlots);
  if (sliceFrame.specialization.occlusion == 1)
    return occlusion_.composite(cmd, sliceFrame.eyeIndex, colorFormat, viewport,
                                anaglyphWriteMask(sliceFrame.specialization.anaglyph));
  SliceFrame frame = sliceFrame;
  const std::uint32_t k = frame.specialization.slicesPerFragment = slicesPerFragment(sliceFrame);
  LIC3D_TRY_ASSIGN(VkPipeline pipeline, pipelineFor(frame, colorFormat));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);

  setViewportAndScissor(cmd, viewport);
  writeUniforms(frame.uniforms, slot);
  // No occlusion buffer without occlusion: any 2D image fills the binding.
  pushDescriptors(cmd, volume, field, scalars, colormaps_.view(), slot);
  const auto count = static_cast<std::uint32_t>(frame.plan.count);
  if (k > 1) {
    // A proxy per group of K slices (slice.vert), the last group perhaps short.
    vkCmdDraw(cmd, gpu::kSliceVerticesPerGroup, (count + k - 1) / k, 0, 0);
    return {};
  }
  LIC3D_TRY_ASSIGN(VkPipeline withoutHalo, pipelineWithoutHalo(frame, colorFormat));
  if (withoutHalo == pipeline) {
    vkCmdDraw(cmd, gpu::kSliceVerticesPerSlice, count, 0, 0);
    return {};
  }
  // One draw per slice, back to front as ever.
  for (std::uint32_t slice = 0; slice < count; ++slice) {
    if (slice > 0)
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                        slice % 2 == 0 ? pipeline : withoutHalo);
    vkCmdDraw(cmd, gpu::kSliceVerticesPerSlice, 1, 0, slice);
  }
  return {};
}

}  // namespace lic3d
