// SPDX-License-Identifier: BSD-3-Clause
#include "passes/occlusion_pass.h"

#include <string>

#include "gpu/submit.h"
#include "gpu/vk_check.h"
#include "shared_layout.h"

namespace lic3d {

namespace {

VkRenderingAttachmentInfo attachment(VkImageView view, VkAttachmentLoadOp load) {
  VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  info.imageView = view;
  info.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  info.loadOp = load;
  info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  info.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
  return info;
}

constexpr VkPipelineStageFlags2 kAttachmentStage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
constexpr VkAccessFlags2 kAttachmentAccess =
    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT;
constexpr VkPipelineStageFlags2 kFragmentStage = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
constexpr VkAccessFlags2 kSampledAccess = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;

}  // namespace

Result<OcclusionPass> OcclusionPass::create(const Context& context) {
  OcclusionPass pass;
  pass.context_ = &context;
  constexpr Binding bindings[] = {{gpu::kOcclusionBindingImage,
                                   VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                                   VK_SHADER_STAGE_FRAGMENT_BIT}};
  LIC3D_TRY_ASSIGN(pass.layout_,
                   PipelineLayout::create(context, bindings, VK_SHADER_STAGE_FRAGMENT_BIT,
                                          sizeof(gpu::OcclusionPushConstants), "occlusion"));
  LIC3D_TRY_ASSIGN(pass.vertexShader_, loadShader(context, ShaderId::FullscreenVertex));
  LIC3D_TRY_ASSIGN(pass.compositeShader_, loadShader(context, ShaderId::OcclusionComposite));
  LIC3D_TRY_ASSIGN(pass.sampler_,
                   Sampler::create(context, VK_FILTER_LINEAR, "occlusion buffer sampler"));
  return pass;
}

Result<void> OcclusionPass::resize(EyeImages& eye, VkExtent2D extent) const {
  if (eye.extent.width == extent.width && eye.extent.height == extent.height) return {};
  // Frames in flight may still sample the old images.
  vkQueueWaitIdle(context_->queue());
  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.extent = {extent.width, extent.height, 1};
  desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
               VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.format = kImageFormat;
  desc.name = "occlusion-shaded image";
  LIC3D_TRY_ASSIGN(eye.image, Image::create(*context_, desc));
  desc.format = kBufferFormat;
  for (int i = 0; i < 2; ++i) {
    desc.name = "occlusion buffer " + std::to_string(i);
    LIC3D_TRY_ASSIGN(eye.buffers[i], Image::create(*context_, desc));
  }
  eye.extent = extent;
  return {};
}

Result<void> OcclusionPass::record(VkCommandBuffer cmd, int eye, VkExtent2D extent, int sliceCount,
                                   const DrawSlice& drawSlice) {
  LIC3D_ASSERT(eye >= 0 && eye < kEyes);
  EyeImages& images = eyes_[eye];
  LIC3D_TRY(resize(images, extent));

  // The previous frame's composite and carries may still read these; their contents go.
  imageBarrier(cmd, images.image.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kFragmentStage, VK_ACCESS_2_NONE,
               kAttachmentStage, kAttachmentAccess);
  // Nothing lies in front of the first slice: both buffers start clear.
  const VkClearColorValue clear{{0.0f, 0.0f, 0.0f, 0.0f}};
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  for (const Image& buffer : images.buffers) {
    imageBarrier(cmd, buffer.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kFragmentStage, VK_ACCESS_2_NONE,
                 VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    vkCmdClearColorImage(cmd, buffer.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &clear, 1,
                         &range);
  }
  imageBarrier(cmd, images.buffers[0].handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, kFragmentStage, kSampledAccess);
  imageBarrier(cmd, images.buffers[1].handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT, kAttachmentStage, kAttachmentAccess);

  const VkRect2D area{{0, 0}, extent};
  for (int k = 0; k < sliceCount; ++k) {
    const Image& inFront = images.buffers[k % 2];
    const Image& behind = images.buffers[(k + 1) % 2];
    const std::array<VkRenderingAttachmentInfo, 2> attachments{
        attachment(images.image.view(),
                   k == 0 ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_LOAD),
        attachment(behind.view(), VK_ATTACHMENT_LOAD_OP_LOAD)};
    VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
    rendering.renderArea = area;
    rendering.layerCount = 1;
    rendering.colorAttachmentCount = static_cast<std::uint32_t>(attachments.size());
    rendering.pColorAttachments = attachments.data();
    vkCmdBeginRendering(cmd, &rendering);
    setViewportAndScissor(cmd, area);
    drawSlice(cmd, k, inFront.view());
    vkCmdEndRendering(cmd);

    // The buffer just written is the next slice's to read, and the one read is the next to write.
    imageBarrier(cmd, behind.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kAttachmentStage,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, kFragmentStage, kSampledAccess);
    imageBarrier(cmd, inFront.handle(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kFragmentStage, VK_ACCESS_2_NONE,
                 kAttachmentStage, kAttachmentAccess);
    // Where this slice was not drawn, the buffer keeps what the slice before last wrote.
    memoryBarrier(cmd, kAttachmentStage, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, kAttachmentStage,
                  kAttachmentAccess);
  }
  imageBarrier(cmd, images.image.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, kAttachmentStage,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, kFragmentStage, kSampledAccess);
  return {};
}

Result<void> OcclusionPass::composite(VkCommandBuffer cmd, int eye, VkFormat format,
                                      VkRect2D viewport, VkColorComponentFlags writeMask) {
  LIC3D_ASSERT(eye >= 0 && eye < kEyes);
  const EyeImages& images = eyes_[eye];
  LIC3D_TRY_ASSIGN(
      VkPipeline pipeline, composites_.get({format, writeMask}, [&](const CompositeVariant& v) {
        const std::array<VkPipelineColorBlendAttachmentState, 1> blends{blendOver(v.writeMask)};
        return createGraphicsPipeline(*context_,
                                      {.vertex = vertexShader_.get(),
                                       .fragment = compositeShader_.get(),
                                       .colorFormats = std::span<const VkFormat>(&v.format, 1),
                                       .blends = blends,
                                       .layout = &layout_,
                                       .name = "occlusion composite"});
      }));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pipeline);
  setViewportAndScissor(cmd, viewport);
  DescriptorWrites()
      .sampledImage(gpu::kOcclusionBindingImage, sampler_, images.image.view())
      .push(*context_, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, layout_);
  gpu::OcclusionPushConstants push{};
  push.offset = glm::ivec4(viewport.offset.x, viewport.offset.y, 0, 0);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(push), &push);
  vkCmdDraw(cmd, 3, 1, 0, 0);
  return {};
}

}  // namespace lic3d
