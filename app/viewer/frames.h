// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The desktop app's frames on the window: two in flight, each with its command buffer, fence,
// acquire semaphore, GPU timer and screenshot buffer; the swapchain with a render-finished
// semaphore and a framebuffer per image; the offscreen image the picture is drawn into and
// blitted from; and the render pass Dear ImGui 1.86's Vulkan backend draws the panels in. Every
// object is owned here (DeviceHandle) and released with the presenter, before the device.

#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/rgba_image.h"
#include "core/session.h"
#include "gpu/resources.h"
#include "gpu/timer.h"
#include "gpu/vulkan_context.h"
#include "viewer/swapchain.h"

namespace lic3d::viewer {

class FramePresenter {
 public:
  static constexpr std::uint32_t kFramesInFlight = 2;
  // The picture is drawn in 16-bit float, so hundreds of faint slices do not band.
  static constexpr VkFormat kOffscreenFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

  struct Frame {
    DeviceHandle<VkCommandPool, vkDestroyCommandPool> pool;
    VkCommandBuffer cmd = VK_NULL_HANDLE;  // freed with its pool
    DeviceHandle<VkFence, vkDestroyFence> fence;
    DeviceHandle<VkSemaphore, vkDestroySemaphore> imageAvailable;
    GpuTimer timer;   // region 0: LIC work, region 1: volume draw
    Buffer readback;  // a screenshot of the window image
    // What the frame's submission did, for when its fence has signalled.
    bool timed = false;
    bool finishedLic = false;
    int licSlices = 0;      // z slices of LIC work recorded
    int licStride = 1;      // of the LIC job they belong to (> 1: coarse)
    bool licBegan = false;  // they began that job
    bool screenshot = false;
    bool scriptedShot = false;  // the screenshot asked for by --screenshot
    Session shown;              // what the screenshot shows: the session its PNG carries
  };

  // `context` (made with the window's surface) must outlive the presenter.
  static Result<FramePresenter> create(const Context& context, VkExtent2D windowExtent, bool vsync);
  FramePresenter(FramePresenter&&) noexcept = default;
  FramePresenter& operator=(FramePresenter&&) noexcept = default;
  ~FramePresenter();

  // After a resize (or an out-of-date swapchain): the swapchain and what depends on its size.
  Result<void> recreateSwapchain(VkExtent2D windowExtent);

  Frame& frame(std::uint64_t number) { return frames_[number % kFramesInFlight]; }
  const Swapchain& swapchain() const { return swapchain_; }
  VkExtent2D extent() const { return swapchain_.extent(); }
  const Image& offscreen() const { return offscreen_; }
  VkRenderPass uiPass() const { return uiPass_.get(); }
  int swapchainsCreated() const { return swapchainsCreated_; }

  // Waits until the frame's last submission is done.
  Result<void> wait(Frame& f) const;
  // The next swapchain image, acquired with the frame's semaphore; nothing when the swapchain
  // was out of date (it is made again: skip this frame).
  Result<std::optional<std::uint32_t>> acquire(Frame& f, VkExtent2D windowExtent);
  // Resets the frame's fence and command buffer and begins recording.
  Result<VkCommandBuffer> begin(Frame& f) const;
  // With the picture in the offscreen image (TRANSFER_SRC_OPTIMAL): blits it into image
  // `imageIndex`, records `drawUi` in the UI render pass over it, copies the window for a
  // screenshot when f.screenshot, submits and presents. True when the swapchain needs making
  // again (out of date or suboptimal).
  template <class DrawUi>
  Result<bool> finish(Frame& f, std::uint32_t imageIndex, const DrawUi& drawUi) {
    recordBlit(f.cmd, imageIndex);
    beginUiPass(f.cmd, imageIndex);
    drawUi(f.cmd);
    vkCmdEndRenderPass(f.cmd);
    return submitAndPresent(f, imageIndex);
  }
  // The frame's screenshot as RGBA, once its fence has signalled.
  RgbaImage screenshot(const Frame& f) const;

 private:
  FramePresenter() = default;
  Result<void> createFrames();
  void recordBlit(VkCommandBuffer cmd, std::uint32_t imageIndex) const;
  void beginUiPass(VkCommandBuffer cmd, std::uint32_t imageIndex) const;
  Result<bool> submitAndPresent(Frame& f, std::uint32_t imageIndex);

  const Context* context_ = nullptr;
  bool vsync_ = true;
  // Destroyed in reverse: the swapchain's dependants, then the swapchain, then the frames.
  std::array<Frame, kFramesInFlight> frames_;
  DeviceHandle<VkRenderPass, vkDestroyRenderPass> uiPass_;
  Swapchain swapchain_;
  std::vector<DeviceHandle<VkSemaphore, vkDestroySemaphore>> renderFinished_;  // per image
  std::vector<DeviceHandle<VkFramebuffer, vkDestroyFramebuffer>> framebuffers_;
  Image offscreen_;
  int swapchainsCreated_ = 0;
};

}  // namespace lic3d::viewer
