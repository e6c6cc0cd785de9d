// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/swapchain.h"

#include <algorithm>

#include "gpu/vk_check.h"

namespace lic3d {

Result<Swapchain> Swapchain::create(const Context& context, VkExtent2D extent, bool vsync,
                                    VkSwapchainKHR old) {
  VkPhysicalDevice physical = context.physicalDevice();
  VkSurfaceKHR surface = context.surface();
  if (!surface) return unsupportedError("the context has no window surface");
  VkSurfaceCapabilitiesKHR caps;
  LIC3D_TRY(checkVk(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(physical, surface, &caps),
                    "vkGetPhysicalDeviceSurfaceCapabilitiesKHR"));

  std::uint32_t count = 0;
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, nullptr);
  std::vector<VkSurfaceFormatKHR> formats(count);
  vkGetPhysicalDeviceSurfaceFormatsKHR(physical, surface, &count, formats.data());
  // UNORM, not SRGB: lic3d's colours are display values, as in the PNGs it writes.
  VkSurfaceFormatKHR chosen = formats.empty() ? VkSurfaceFormatKHR{} : formats[0];
  for (const VkSurfaceFormatKHR& f : formats)
    if ((f.format == VK_FORMAT_B8G8R8A8_UNORM || f.format == VK_FORMAT_R8G8B8A8_UNORM) &&
        f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) {
      chosen = f;
      break;
    }
  if (chosen.format == VK_FORMAT_UNDEFINED) return unsupportedError("the window offers no format");

  vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, nullptr);
  std::vector<VkPresentModeKHR> modes(count);
  vkGetPhysicalDeviceSurfacePresentModesKHR(physical, surface, &count, modes.data());
  VkPresentModeKHR mode = VK_PRESENT_MODE_FIFO_KHR;  // always available
  if (!vsync) {
    for (VkPresentModeKHR m : {VK_PRESENT_MODE_MAILBOX_KHR, VK_PRESENT_MODE_IMMEDIATE_KHR})
      if (std::find(modes.begin(), modes.end(), m) != modes.end()) {
        mode = m;
        break;
      }
  }

  Swapchain swapchain;
  swapchain.format_ = chosen.format;
  swapchain.presentMode_ = mode;
  swapchain.extent_ =
      caps.currentExtent.width != UINT32_MAX
          ? caps.currentExtent
          : VkExtent2D{
                std::clamp(extent.width, caps.minImageExtent.width, caps.maxImageExtent.width),
                std::clamp(extent.height, caps.minImageExtent.height, caps.maxImageExtent.height)};
  swapchain.minImageCount_ = caps.minImageCount + 1;
  if (caps.maxImageCount > 0)
    swapchain.minImageCount_ = std::min(swapchain.minImageCount_, caps.maxImageCount);

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface;
  info.minImageCount = swapchain.minImageCount_;
  info.imageFormat = chosen.format;
  info.imageColorSpace = chosen.colorSpace;
  info.imageExtent = swapchain.extent_;
  info.imageArrayLayers = 1;
  // The volume is blitted in, the UI drawn on top, and screenshots copied out.
  info.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT |
                    VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
  info.presentMode = mode;
  info.clipped = VK_TRUE;
  info.oldSwapchain = old;
  VkSwapchainKHR handle = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreateSwapchainKHR(context.device(), &info, nullptr, &handle),
                    "vkCreateSwapchainKHR"));
  swapchain.swapchain_ = {context.device(), handle};
  context.setDebugName(handle, VK_OBJECT_TYPE_SWAPCHAIN_KHR, "swapchain");

  vkGetSwapchainImagesKHR(context.device(), handle, &count, nullptr);
  swapchain.images_.resize(count);
  vkGetSwapchainImagesKHR(context.device(), handle, &count, swapchain.images_.data());
  for (std::uint32_t i = 0; i < count; ++i) {
    context.setDebugName(swapchain.images_[i], VK_OBJECT_TYPE_IMAGE,
                         "swapchain image " + std::to_string(i));
    VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    viewInfo.image = swapchain.images_[i];
    viewInfo.viewType = VK_IMAGE_VIEW_TYPE_2D;
    viewInfo.format = chosen.format;
    viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view = VK_NULL_HANDLE;
    LIC3D_TRY(checkVk(vkCreateImageView(context.device(), &viewInfo, nullptr, &view),
                      "vkCreateImageView"));
    swapchain.views_.emplace_back(context.device(), view);
    context.setDebugName(view, VK_OBJECT_TYPE_IMAGE_VIEW, "swapchain view " + std::to_string(i));
  }
  return swapchain;
}

}  // namespace lic3d
