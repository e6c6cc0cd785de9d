// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A swapchain for the context's surface: images to present, recreated on resize. Knows nothing
// of the window system: the surface comes from the front end.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <vector>

#include "core/error.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

class Swapchain {
 public:
  Swapchain() = default;
  // `extent` is the framebuffer size the window reports (used when the surface leaves it open).
  // With vsync the presentation waits for the display (FIFO); without, MAILBOX or IMMEDIATE.
  // `old` (may be null) is retired and its images may still be presented meanwhile.
  static Result<Swapchain> create(const Context& context, VkExtent2D extent, bool vsync,
                                  VkSwapchainKHR old = VK_NULL_HANDLE);
  Swapchain(Swapchain&&) noexcept = default;
  Swapchain& operator=(Swapchain&&) noexcept = default;  // the views go before the swapchain
  ~Swapchain() { views_.clear(); }

  VkSwapchainKHR handle() const { return swapchain_.get(); }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  std::uint32_t imageCount() const { return static_cast<std::uint32_t>(images_.size()); }
  std::uint32_t minImageCount() const { return minImageCount_; }
  VkImage image(std::uint32_t i) const { return images_[i]; }
  VkImageView view(std::uint32_t i) const { return views_[i].get(); }
  VkPresentModeKHR presentMode() const { return presentMode_; }

 private:
  std::vector<DeviceHandle<VkImageView, vkDestroyImageView>> views_;
  DeviceHandle<VkSwapchainKHR, vkDestroySwapchainKHR> swapchain_;
  std::vector<VkImage> images_;  // owned by the swapchain
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  std::uint32_t minImageCount_ = 0;
  VkPresentModeKHR presentMode_ = VK_PRESENT_MODE_FIFO_KHR;
};

}  // namespace lic3d
