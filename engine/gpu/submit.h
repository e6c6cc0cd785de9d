// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The one recipe for GPU work from the CPU's point of view: record, submit, wait on a fence.
// Uploads and read-backs go through it; so do the LIC and slice passes when run offscreen.

#include <vulkan/vulkan.h>

#include <cstddef>
#include <functional>
#include <glm/vec3.hpp>
#include <vector>

#include "core/error.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

// Records into a fresh primary command buffer, submits it to the context's queue and waits.
// Fails (with the call and VkResult) on device loss or out-of-memory at submission.
Result<void> submitAndWait(const Context& context,
                           const std::function<void(VkCommandBuffer)>& record, const char* what);

// vkQueueSubmit2 of one submission to the context's queue, checked. Every submission of lic3d goes
// through here. Test hook (docs/RELIABILITY.md): LIC3D_LOSE_DEVICE=N reports the N-th submission
// of the process as VK_ERROR_DEVICE_LOST (after making it, so nothing is left half-submitted);
// LIC3D_LOSE_DEVICE=every:N reports every N-th.
Result<void> submitToQueue(const Context& context, const VkSubmitInfo2& submit, VkFence fence);

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageLayout oldLayout,
                  VkImageLayout newLayout, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Begins dynamic rendering into one colour attachment (in COLOR_ATTACHMENT_OPTIMAL) cleared to
// the opaque colour `clear`, over the whole extent.
void beginClearedRendering(VkCommandBuffer cmd, VkImageView view, VkExtent2D extent,
                           glm::vec3 clear);

// Viewport and scissor both `area` (depth 0 to 1): the dynamic state of every graphics pass.
void setViewportAndScissor(VkCommandBuffer cmd, VkRect2D area);

void memoryBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                   VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// Copies `bytes` into the whole of `image` (tightly packed texels) through a staging buffer and
// leaves it in SHADER_READ_ONLY_OPTIMAL, visible to compute and fragment shaders.
Result<void> uploadImage(const Context& context, const Image& image, const void* data,
                         std::size_t bytes);
// The same with the staging buffer filled by `fill(staging)` (`bytes` of tightly packed texels):
// data made straight into the buffer the device copies from, with no host array between.
Result<void> uploadImageFilled(const Context& context, const Image& image, std::size_t bytes,
                               const std::function<void(void*)>& fill);

// Copies `bytes` into the start of `buffer` (with TRANSFER_DST usage) through a staging buffer,
// visible to compute shaders' storage reads afterwards.
Result<void> uploadBuffer(const Context& context, const Buffer& buffer, const void* data,
                          std::size_t bytes);

// Reads the whole of `image`, which must be in `layout` after work that `srcStage`/`srcAccess`
// describe, back into tightly packed texels of `bytesPerTexel`. The image returns to `layout`.
Result<std::vector<std::byte>> readImage(const Context& context, const Image& image,
                                         VkImageLayout layout, std::size_t bytesPerTexel);
// The same, handing the texels to `use(texels, bytes)` in the read-back buffer itself (valid
// during the call): for callers that convert them, with no host copy of the whole image.
Result<void> readImageWith(const Context& context, const Image& image, VkImageLayout layout,
                           std::size_t bytesPerTexel,
                           const std::function<void(const void*, std::size_t)>& use);

}  // namespace lic3d
