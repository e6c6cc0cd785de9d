// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading large images back at the link's speed: a ring of host-visible (host-cached where the
// device has such memory) staging buffers, allocated once and reused for every read-back of the
// context. A region is copied slab by slab (a few z layers each) into the ring's buffers; while
// the device copies the next slabs, the host hands the one before to the caller, which converts
// it on all threads. Allocating a staging buffer the size of a volume for each read-back pins
// that much host memory every time; that cost, not the link, set the speed before
// (docs/SCALE.md, "Read-back").

#include <vulkan/vulkan.h>

#include <cstddef>
#include <functional>
#include <vector>

#include "core/error.h"
#include "core/volume.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

// The bytes of one staging buffer of the ring, and how many there are: three, so that the device
// fills two while the host converts the third.
inline constexpr std::size_t kReadbackSlotBytes = std::size_t{128} << 20;
inline constexpr int kReadbackSlots = 3;

class ReadbackRing {
 public:
  // Slots of at most `slotBytes` each (at least one z layer of a region).
  explicit ReadbackRing(std::size_t slotBytes = kReadbackSlotBytes) : slotBytes_(slotBytes) {}
  ReadbackRing(ReadbackRing&&) noexcept = default;
  ReadbackRing& operator=(ReadbackRing&&) noexcept = default;
  ~ReadbackRing();

  // The texels of one slab: `layers` z layers of the region from its layer `firstLayer` on,
  // tightly packed (x fastest), valid during the call.
  using SlabUse = std::function<Result<void>(const void* texels, int firstLayer, int layers)>;

  // Copies the region [offset, offset + extent) of `image` (in `layout` after any work of the
  // queue, and returned to it) to the host slab by slab, handing each slab to `use` in order.
  // The ring's buffers are made on the first call (at most kReadbackSlots of the slot bytes,
  // fewer and smaller for a small region) and kept. An error from `use`
  // stops the copies; the image is returned to `layout` before any return.
  Result<void> read(const Context& context, const Image& image, VkImageLayout layout,
                    std::size_t bytesPerTexel, Dims offset, Dims extent, const SlabUse& use);

  // The staging bytes the ring holds (0 before its first read).
  std::size_t bytes() const;
  // Seconds, over every read so far, the host waited for slabs to arrive and spent in `use`.
  double waitSeconds() const { return waitSeconds_; }
  double useSeconds() const { return useSeconds_; }

 private:
  struct Slot {
    Buffer buffer;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    DeviceHandle<VkFence, vkDestroyFence> fence;
    int firstLayer = 0;
    int layers = 0;
    bool pending = false;
  };
  Result<void> prepare(const Context& context, std::size_t slotBytes, int slots);

  std::size_t slotBytes_ = kReadbackSlotBytes;
  double waitSeconds_ = 0.0;
  double useSeconds_ = 0.0;
  DeviceHandle<VkCommandPool, vkDestroyCommandPool> pool_;
  std::vector<Slot> slots_;
};

}  // namespace lic3d
