// SPDX-License-Identifier: BSD-3-Clause
#include "gpu/submit.h"

#include <atomic>
#include <cstdlib>
#include <cstring>

#include "core/parallel.h"
#include "gpu/vk_check.h"

namespace lic3d {
namespace {

// LIC3D_LOSE_DEVICE=N: the N-th submission of the process; =every:N: every N-th. Read once.
bool injectedDeviceLoss() {
  struct Hook {
    long n = 0;
    bool every = false;
  };
  static const Hook hook = [] {
    Hook h;
    const char* text = std::getenv("LIC3D_LOSE_DEVICE");
    if (!text) return h;
    h.every = std::strncmp(text, "every:", 6) == 0;
    h.n = std::strtol(h.every ? text + 6 : text, nullptr, 10);
    return h;
  }();
  static std::atomic<long> count{0};
  if (hook.n <= 0) return false;
  const long k = ++count;
  return hook.every ? k % hook.n == 0 : k == hook.n;
}

}  // namespace

Result<void> submitToQueue(const Context& context, const VkSubmitInfo2& submit, VkFence fence) {
  const VkResult result = vkQueueSubmit2(context.queue(), 1, &submit, fence);
  if (result == VK_SUCCESS && injectedDeviceLoss())
    return checkVk(VK_ERROR_DEVICE_LOST, "vkQueueSubmit2");
  return checkVk(result, "vkQueueSubmit2");
}

Result<void> submitAndWait(const Context& context,
                           const std::function<void(VkCommandBuffer)>& record, const char* what) {
  VkDevice device = context.device();
  VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  poolInfo.flags = VK_COMMAND_POOL_CREATE_TRANSIENT_BIT;
  poolInfo.queueFamilyIndex = context.queueFamily();
  VkCommandPool pool = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool"));
  context.setDebugName(pool, VK_OBJECT_TYPE_COMMAND_POOL, std::string(what) + " pool");

  VkFence fence = VK_NULL_HANDLE;
  auto cleanup = [&] {
    if (fence) vkDestroyFence(device, fence, nullptr);
    vkDestroyCommandPool(device, pool, nullptr);
  };

  VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  allocInfo.commandPool = pool;
  allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  allocInfo.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  if (auto r =
          checkVk(vkAllocateCommandBuffers(device, &allocInfo, &cmd), "vkAllocateCommandBuffers");
      !r) {
    cleanup();
    return std::move(r).error();
  }
  context.setDebugName(cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, what);

  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  LIC3D_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  record(cmd);
  LIC3D_VK_CHECK(vkEndCommandBuffer(cmd));

  VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (auto r = checkVk(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence"); !r) {
    cleanup();
    return std::move(r).error();
  }
  context.setDebugName(fence, VK_OBJECT_TYPE_FENCE, std::string(what) + " fence");

  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  Result<void> result = submitToQueue(context, submit, fence);
  if (result)
    result = checkVk(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
  if (!result) {
    // The device may be lost; wait for idle so nothing still references the pool.
    vkDeviceWaitIdle(device);
    Error error = std::move(result).error();
    error.message = std::string(what) + ": " + error.message;
    cleanup();
    return error;
  }
  cleanup();
  return {};
}

void beginClearedRendering(VkCommandBuffer cmd, VkImageView view, VkExtent2D extent,
                           glm::vec3 clear) {
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = view;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color = {{clear.r, clear.g, clear.b, 1.0f}};
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &color;
  vkCmdBeginRendering(cmd, &rendering);
}

void setViewportAndScissor(VkCommandBuffer cmd, VkRect2D area) {
  const VkViewport viewport{static_cast<float>(area.offset.x),
                            static_cast<float>(area.offset.y),
                            static_cast<float>(area.extent.width),
                            static_cast<float>(area.extent.height),
                            0.0f,
                            1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &area);
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout oldLayout,
                  VkImageLayout newLayout, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  barrier.oldLayout = oldLayout;
  barrier.newLayout = newLayout;
  barrier.srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.imageMemoryBarrierCount = 1;
  dependency.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = srcStage;
  barrier.srcAccessMask = srcAccess;
  barrier.dstStageMask = dstStage;
  barrier.dstAccessMask = dstAccess;
  VkDependencyInfo dependency{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dependency.memoryBarrierCount = 1;
  dependency.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dependency);
}

Result<void> uploadImage(const Context& context, const Image& image, const void* data,
                         std::size_t bytes) {
  return uploadImageFilled(context, image, bytes,
                           [&](void* staging) { parallelCopy(staging, data, bytes); });
}

Result<void> uploadImageFilled(const Context& context, const Image& image, std::size_t bytes,
                               const std::function<void(void*)>& fill) {
  LIC3D_TRY_ASSIGN(Buffer staging, Buffer::create(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                  MemoryUse::Upload, "upload staging"));
  fill(staging.mapped());
  return submitAndWait(
      context,
      [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, image.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                     VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_WRITE_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = image.extent();
        vkCmdCopyBufferToImage(cmd, staging.handle(), image.handle(),
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
        imageBarrier(
            cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
            VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
            VK_ACCESS_2_TRANSFER_WRITE_BIT,
            VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
            VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
      },
      "image upload");
}

Result<void> uploadBuffer(const Context& context, const Buffer& buffer, const void* data,
                          std::size_t bytes) {
  LIC3D_TRY_ASSIGN(Buffer staging, Buffer::create(context, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                  MemoryUse::Upload, "upload staging"));
  parallelCopy(staging.mapped(), data, bytes);
  return submitAndWait(
      context,
      [&](VkCommandBuffer cmd) {
        // Earlier shader reads of the buffer finish before the copy overwrites it.
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE,
                      VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        const VkBufferCopy region{0, 0, bytes};
        vkCmdCopyBuffer(cmd, staging.handle(), buffer.handle(), 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
      },
      "buffer upload");
}

Result<std::vector<std::byte>> readImage(const Context& context, const Image& image,
                                         VkImageLayout layout, std::size_t bytesPerTexel) {
  std::vector<std::byte> out;
  LIC3D_TRY(readImageWith(context, image, layout, bytesPerTexel,
                          [&](const void* texels, std::size_t bytes) {
                            resizeLarge(out, bytes);
                            parallelCopy(out.data(), texels, bytes);
                          }));
  return out;
}

Result<void> readImageWith(const Context& context, const Image& image, VkImageLayout layout,
                           std::size_t bytesPerTexel,
                           const std::function<void(const void*, std::size_t)>& use) {
  const VkExtent3D e = image.extent();
  const std::size_t bytes = std::size_t{e.width} * e.height * e.depth * bytesPerTexel;
  LIC3D_TRY_ASSIGN(Buffer readback, Buffer::create(context, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                   MemoryUse::Readback, "readback staging"));
  // Every writer and reader of lic3d images is a shader or a copy: wait for all of them.
  const VkPipelineStageFlags2 users = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  const VkAccessFlags2 writes = VK_ACCESS_2_MEMORY_WRITE_BIT;
  LIC3D_TRY(submitAndWait(
      context,
      [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, image.handle(), layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, users,
                     writes, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = e;
        vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               readback.handle(), 1, &region);
        imageBarrier(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                     VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, users,
                     VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
      },
      "image readback"));
  use(readback.mapped(), bytes);
  return {};
}

}  // namespace lic3d
