// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/frames.h"

#include <string>

#include "gpu/submit.h"
#include "gpu/vk_check.h"

namespace lic3d::viewer {

Result<FramePresenter> FramePresenter::create(const Context& context, VkExtent2D windowExtent,
                                              bool vsync) {
  FramePresenter presenter;
  presenter.context_ = &context;
  presenter.vsync_ = vsync;
  LIC3D_TRY(presenter.createFrames());
  LIC3D_TRY(presenter.recreateSwapchain(windowExtent));
  return presenter;
}

FramePresenter::~FramePresenter() {
  if (context_ && frames_[0].pool) vkDeviceWaitIdle(context_->device());
}

Result<void> FramePresenter::createFrames() {
  VkDevice device = context_->device();
  for (Frame& f : frames_) {
    const std::string name = "frame " + std::to_string(&f - frames_.data());
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context_->queueFamily();
    VkCommandPool pool = VK_NULL_HANDLE;
    LIC3D_TRY(
        checkVk(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool"));
    f.pool = {device, pool};
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    LIC3D_TRY(
        checkVk(vkAllocateCommandBuffers(device, &alloc, &f.cmd), "vkAllocateCommandBuffers"));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    VkFence fence = VK_NULL_HANDLE;
    LIC3D_TRY(checkVk(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence"));
    f.fence = {device, fence};
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    LIC3D_TRY(checkVk(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &semaphore),
                      "vkCreateSemaphore"));
    f.imageAvailable = {device, semaphore};
    context_->setDebugName(pool, VK_OBJECT_TYPE_COMMAND_POOL, name + " pool");
    context_->setDebugName(f.cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, name);
    context_->setDebugName(fence, VK_OBJECT_TYPE_FENCE, name + " fence");
    context_->setDebugName(semaphore, VK_OBJECT_TYPE_SEMAPHORE, name + " image available");
    if (context_->supportsTimestamps()) {
      LIC3D_TRY_ASSIGN(f.timer, GpuTimer::create(*context_, 2, name + " timestamps"));
    }
  }
  return {};
}

Result<void> FramePresenter::recreateSwapchain(VkExtent2D windowExtent) {
  ++swapchainsCreated_;
  VkDevice device = context_->device();
  vkDeviceWaitIdle(device);
  framebuffers_.clear();
  renderFinished_.clear();
  LIC3D_TRY_ASSIGN(Swapchain next,
                   Swapchain::create(*context_, windowExtent, vsync_, swapchain_.handle()));
  swapchain_ = std::move(next);

  if (!uiPass_) {
    VkAttachmentDescription attachment{};
    attachment.format = swapchain_.format();
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the blitted picture
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    const std::array<VkSubpassDependency, 2> dependencies{{
        {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
         VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0},
        {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
         VK_ACCESS_TRANSFER_READ_BIT, 0},
    }};
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &attachment;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = static_cast<std::uint32_t>(dependencies.size());
    info.pDependencies = dependencies.data();
    VkRenderPass pass = VK_NULL_HANDLE;
    LIC3D_TRY(checkVk(vkCreateRenderPass(device, &info, nullptr, &pass), "vkCreateRenderPass"));
    uiPass_ = {device, pass};
    context_->setDebugName(pass, VK_OBJECT_TYPE_RENDER_PASS, "imgui pass");
  }
  for (std::uint32_t i = 0; i < swapchain_.imageCount(); ++i) {
    VkImageView view = swapchain_.view(i);
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = uiPass_.get();
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = swapchain_.extent().width;
    info.height = swapchain_.extent().height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    LIC3D_TRY(
        checkVk(vkCreateFramebuffer(device, &info, nullptr, &framebuffer), "vkCreateFramebuffer"));
    framebuffers_.emplace_back(device, framebuffer);
    context_->setDebugName(framebuffer, VK_OBJECT_TYPE_FRAMEBUFFER,
                           "imgui framebuffer " + std::to_string(i));
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    LIC3D_TRY(checkVk(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &semaphore),
                      "vkCreateSemaphore"));
    renderFinished_.emplace_back(device, semaphore);
    context_->setDebugName(semaphore, VK_OBJECT_TYPE_SEMAPHORE,
                           "render finished " + std::to_string(i));
  }

  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.format = kOffscreenFormat;
  desc.extent = {swapchain_.extent().width, swapchain_.extent().height, 1};
  // TRANSFER_DST: the 2D mode blits its picture in.
  desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
               VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "window volume image";
  offscreen_ = Image();
  LIC3D_TRY_ASSIGN(offscreen_, Image::create(*context_, desc));
  const VkDeviceSize bytes =
      static_cast<VkDeviceSize>(swapchain_.extent().width) * swapchain_.extent().height * 4;
  for (Frame& f : frames_) {
    f.readback = Buffer();
    LIC3D_TRY_ASSIGN(f.readback, Buffer::create(*context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                MemoryUse::Readback, "screenshot readback"));
  }
  return {};
}

Result<void> FramePresenter::wait(Frame& f) const {
  VkFence fence = f.fence.get();
  return checkVk(vkWaitForFences(context_->device(), 1, &fence, VK_TRUE, UINT64_MAX),
                 "vkWaitForFences");
}

Result<std::optional<std::uint32_t>> FramePresenter::acquire(Frame& f, VkExtent2D windowExtent) {
  std::uint32_t imageIndex = 0;
  const VkResult acquired =
      vkAcquireNextImageKHR(context_->device(), swapchain_.handle(), UINT64_MAX,
                            f.imageAvailable.get(), VK_NULL_HANDLE, &imageIndex);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    LIC3D_TRY(recreateSwapchain(windowExtent));
    return std::optional<std::uint32_t>();
  }
  if (acquired != VK_SUBOPTIMAL_KHR) LIC3D_TRY(checkVk(acquired, "vkAcquireNextImageKHR"));
  return std::optional<std::uint32_t>(imageIndex);
}

Result<VkCommandBuffer> FramePresenter::begin(Frame& f) const {
  VkFence fence = f.fence.get();
  LIC3D_TRY(checkVk(vkResetFences(context_->device(), 1, &fence), "vkResetFences"));
  LIC3D_TRY(checkVk(vkResetCommandBuffer(f.cmd, 0), "vkResetCommandBuffer"));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  LIC3D_VK_CHECK(vkBeginCommandBuffer(f.cmd, &begin));
  return f.cmd;
}

void FramePresenter::recordBlit(VkCommandBuffer cmd, std::uint32_t imageIndex) const {
  const VkExtent2D extent = swapchain_.extent();
  VkImage target = swapchain_.image(imageIndex);
  // The acquire semaphore is waited for at the blit stage; this barrier chains to it.
  imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_BLIT_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {static_cast<std::int32_t>(extent.width),
                        static_cast<std::int32_t>(extent.height), 1};
  blit.dstSubresource = blit.srcSubresource;
  blit.dstOffsets[1] = blit.srcOffsets[1];
  vkCmdBlitImage(cmd, offscreen_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);
}

void FramePresenter::beginUiPass(VkCommandBuffer cmd, std::uint32_t imageIndex) const {
  VkRenderPassBeginInfo passBegin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  passBegin.renderPass = uiPass_.get();
  passBegin.framebuffer = framebuffers_[imageIndex].get();
  passBegin.renderArea = {{0, 0}, swapchain_.extent()};
  vkCmdBeginRenderPass(cmd, &passBegin, VK_SUBPASS_CONTENTS_INLINE);
}

Result<bool> FramePresenter::submitAndPresent(Frame& f, std::uint32_t imageIndex) {
  VkCommandBuffer cmd = f.cmd;
  if (f.screenshot) {
    const VkExtent2D extent = swapchain_.extent();
    VkImage target = swapchain_.image(imageIndex);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, f.readback.handle(),
                           1, &region);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_NONE,
                 VK_ACCESS_2_NONE);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  }
  LIC3D_VK_CHECK(vkEndCommandBuffer(cmd));

  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = f.imageAvailable.get();
  wait.stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = renderFinished_[imageIndex].get();
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  LIC3D_TRY(submitToQueue(*context_, submit, f.fence.get()));

  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  VkSemaphore finished = renderFinished_[imageIndex].get();
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &finished;
  present.swapchainCount = 1;
  VkSwapchainKHR handle = swapchain_.handle();
  present.pSwapchains = &handle;
  present.pImageIndices = &imageIndex;
  const VkResult presented = vkQueuePresentKHR(context_->queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) return true;
  LIC3D_TRY(checkVk(presented, "vkQueuePresentKHR"));
  return false;
}

RgbaImage FramePresenter::screenshot(const Frame& f) const {
  const VkExtent2D extent = swapchain_.extent();
  RgbaImage image;
  image.width = static_cast<int>(extent.width);
  image.height = static_cast<int>(extent.height);
  image.pixels.resize(static_cast<std::size_t>(extent.width) * extent.height * 4);
  const auto* src = static_cast<const std::uint8_t*>(f.readback.mapped());
  const bool bgra = swapchain_.format() == VK_FORMAT_B8G8R8A8_UNORM;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    image.pixels[i + 0] = src[i + (bgra ? 2 : 0)];
    image.pixels[i + 1] = src[i + 1];
    image.pixels[i + 2] = src[i + (bgra ? 0 : 2)];
    image.pixels[i + 3] = 255;
  }
  return image;
}

}  // namespace lic3d::viewer
