// SPDX-License-Identifier: BSD-3-Clause
#include "gpu/readback.h"

#include <algorithm>
#include <chrono>
#include <string>

#include "gpu/submit.h"
#include "gpu/vk_check.h"

namespace lic3d {
namespace {
using Clock = std::chrono::steady_clock;
}  // namespace

ReadbackRing::~ReadbackRing() {
  // Command buffers go with the pool; nothing is pending between reads.
  slots_.clear();
  pool_.reset();
}

std::size_t ReadbackRing::bytes() const {
  std::size_t total = 0;
  for (const Slot& slot : slots_) total += static_cast<std::size_t>(slot.buffer.size());
  return total;
}

Result<void> ReadbackRing::prepare(const Context& context, std::size_t slotBytes, int slots) {
  const bool enough = static_cast<int>(slots_.size()) >= slots &&
                      std::all_of(slots_.begin(), slots_.end(), [&](const Slot& slot) {
                        return slot.buffer.size() >= slotBytes;
                      });
  if (enough) return {};
  VkDevice device = context.device();
  slots_.clear();
  if (!pool_) {
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context.queueFamily();
    VkCommandPool pool = VK_NULL_HANDLE;
    LIC3D_TRY(
        checkVk(vkCreateCommandPool(device, &poolInfo, nullptr, &pool), "vkCreateCommandPool"));
    pool_ = DeviceHandle<VkCommandPool, vkDestroyCommandPool>(device, pool);
    context.setDebugName(pool, VK_OBJECT_TYPE_COMMAND_POOL, "readback ring pool");
  } else {
    LIC3D_TRY(checkVk(vkResetCommandPool(device, pool_.get(), 0), "vkResetCommandPool"));
  }
  for (int s = 0; s < slots; ++s) {
    Slot slot;
    const std::string name = "readback ring slot " + std::to_string(s);
    LIC3D_TRY_ASSIGN(slot.buffer,
                     Buffer::create(context, slotBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                    MemoryUse::Readback, name));
    VkCommandBufferAllocateInfo allocInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    allocInfo.commandPool = pool_.get();
    allocInfo.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    allocInfo.commandBufferCount = 1;
    LIC3D_TRY(checkVk(vkAllocateCommandBuffers(device, &allocInfo, &slot.cmd),
                      "vkAllocateCommandBuffers"));
    context.setDebugName(slot.cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, name);
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VkFence fence = VK_NULL_HANDLE;
    LIC3D_TRY(checkVk(vkCreateFence(device, &fenceInfo, nullptr, &fence), "vkCreateFence"));
    slot.fence = DeviceHandle<VkFence, vkDestroyFence>(device, fence);
    context.setDebugName(fence, VK_OBJECT_TYPE_FENCE, name + " fence");
    slots_.push_back(std::move(slot));
  }
  return {};
}

Result<void> ReadbackRing::read(const Context& context, const Image& image, VkImageLayout layout,
                                std::size_t bytesPerTexel, Dims offset, Dims extent,
                                const SlabUse& use) {
  const std::size_t layerBytes =
      static_cast<std::size_t>(extent.x) * static_cast<std::size_t>(extent.y) * bytesPerTexel;
  const int layersPerSlab = static_cast<int>(
      std::clamp<std::size_t>(slotBytes_ / layerBytes, 1, static_cast<std::size_t>(extent.z)));
  const int slabs = (extent.z + layersPerSlab - 1) / layersPerSlab;
  const int slots = std::min(kReadbackSlots, slabs);
  LIC3D_TRY(prepare(context, layerBytes * static_cast<std::size_t>(layersPerSlab), slots));
  VkDevice device = context.device();
  const VkPipelineStageFlags2 users = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  const VkAccessFlags2 writes = VK_ACCESS_2_MEMORY_WRITE_BIT;

  // Records and submits slab `s` into its slot: the first takes the image to TRANSFER_SRC, the
  // last returns it to `layout`.
  const auto issue = [&](int s) -> Result<void> {
    Slot& slot = slots_[static_cast<std::size_t>(s % slots)];
    slot.firstLayer = s * layersPerSlab;
    slot.layers = std::min(layersPerSlab, extent.z - slot.firstLayer);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    LIC3D_TRY(checkVk(vkResetCommandBuffer(slot.cmd, 0), "vkResetCommandBuffer"));
    LIC3D_TRY(checkVk(vkBeginCommandBuffer(slot.cmd, &begin), "vkBeginCommandBuffer"));
    if (s == 0)
      imageBarrier(slot.cmd, image.handle(), layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, users,
                   writes, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
    // The slot's buffer was last written by an earlier copy and read by the host since.
    memoryBarrier(slot.cmd, VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_HOST_BIT,
                  VK_ACCESS_2_TRANSFER_WRITE_BIT | VK_ACCESS_2_HOST_READ_BIT,
                  VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageOffset = {offset.x, offset.y, offset.z + slot.firstLayer};
    region.imageExtent = {static_cast<std::uint32_t>(extent.x),
                          static_cast<std::uint32_t>(extent.y),
                          static_cast<std::uint32_t>(slot.layers)};
    vkCmdCopyImageToBuffer(slot.cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                           slot.buffer.handle(), 1, &region);
    if (s == slabs - 1)
      imageBarrier(slot.cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, users,
                   VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
    memoryBarrier(slot.cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
    LIC3D_TRY(checkVk(vkEndCommandBuffer(slot.cmd), "vkEndCommandBuffer"));
    VkFence fence = slot.fence.get();
    LIC3D_TRY(checkVk(vkResetFences(device, 1, &fence), "vkResetFences"));
    VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmdInfo.commandBuffer = slot.cmd;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmdInfo;
    LIC3D_TRY(submitToQueue(context, submit, fence));
    slot.pending = true;
    return {};
  };

  int issued = 0;
  Result<void> result;
  for (int consumed = 0; consumed < slabs && result;) {
    while (result && issued < slabs && issued - consumed < slots) {
      result = issue(issued);
      if (result) ++issued;
    }
    if (!result) break;
    Slot& slot = slots_[static_cast<std::size_t>(consumed % slots)];
    VkFence fence = slot.fence.get();
    const Clock::time_point waiting = Clock::now();
    result = checkVk(vkWaitForFences(device, 1, &fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    slot.pending = false;
    const Clock::time_point using_ = Clock::now();
    waitSeconds_ += std::chrono::duration<double>(using_ - waiting).count();
    if (result) result = use(slot.buffer.mapped(), slot.firstLayer, slot.layers);
    useSeconds_ += std::chrono::duration<double>(Clock::now() - using_).count();
    ++consumed;
  }
  if (result) return {};
  // Stopped part way: nothing may still write the slots, and the image goes back to `layout`.
  vkDeviceWaitIdle(device);
  for (Slot& slot : slots_) slot.pending = false;
  if (issued > 0 && issued < slabs)
    if (Result<void> back = submitAndWait(
            context,
            [&](VkCommandBuffer cmd) {
              imageBarrier(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, layout,
                           VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, users,
                           VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT);
            },
            "readback layout back");
        !back)
      return back;
  return result;
}

}  // namespace lic3d
