// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Buffers, images and samplers: move-only owners (DeviceHandle) that free what create() made.
// Each resource gets its own VkDeviceMemory: lic3d holds a handful of large volumes, far below
// maxMemoryAllocationCount, so a sub-allocator would add nothing.

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/memory_budget.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

enum class MemoryUse {
  DeviceLocal,  // GPU only
  Upload,       // host-visible and coherent, written by the CPU (staging)
  Readback,     // host-visible and coherent, preferably cached, read by the CPU
};

// A Vulkan handle destroyed (or freed) with `Destroy` when its owner goes away; the one move-only
// owner every resource, pipeline and pass builds on, so none writes its own moves.
template <class Handle, void (*Destroy)(VkDevice, Handle, const VkAllocationCallbacks*)>
class DeviceHandle {
 public:
  DeviceHandle() = default;
  DeviceHandle(VkDevice device, Handle handle) : device_(device), handle_(handle) {}
  DeviceHandle(DeviceHandle&& other) noexcept
      : device_(other.device_), handle_(std::exchange(other.handle_, VK_NULL_HANDLE)) {}
  DeviceHandle& operator=(DeviceHandle&& other) noexcept {
    if (this != &other) {
      reset();
      device_ = other.device_;
      handle_ = std::exchange(other.handle_, VK_NULL_HANDLE);
    }
    return *this;
  }
  ~DeviceHandle() { reset(); }

  Handle get() const { return handle_; }
  VkDevice device() const { return device_; }
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }
  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

// Takes an allocation off the context's count (Context::allocationCounter) when it is freed.
struct AllocationUncount {
  std::int64_t bytes = 0;
  void operator()(std::atomic<std::int64_t>* counter) const { *counter -= bytes; }
};

// A VkDeviceMemory, counted in the context's allocation accounting while it lives.
class DeviceMemory {
 public:
  DeviceMemory() = default;
  static Result<DeviceMemory> allocate(const Context& context, const VkMemoryRequirements& needs,
                                       MemoryUse use, const std::string& name);

  VkDeviceMemory handle() const { return memory_.get(); }
  VkDeviceSize size() const { return memory_ ? size_ : 0; }
  void* mapped() const { return memory_ ? mapped_ : nullptr; }

 private:
  DeviceHandle<VkDeviceMemory, vkFreeMemory> memory_;  // freeing unmaps it
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  std::unique_ptr<std::atomic<std::int64_t>, AllocationUncount> counted_;
};

class Buffer {
 public:
  Buffer() = default;
  static Result<Buffer> create(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                               MemoryUse use, const std::string& name);
  Buffer(Buffer&&) noexcept = default;
  Buffer& operator=(Buffer&&) noexcept = default;  // the buffer goes before its memory
  ~Buffer() { buffer_.reset(); }

  VkBuffer handle() const { return buffer_.get(); }
  VkDeviceSize size() const { return buffer_ ? size_ : 0; }
  // Persistently mapped pointer for Upload and Readback buffers, null for DeviceLocal.
  void* mapped() const { return memory_.mapped(); }

 private:
  DeviceHandle<VkBuffer, vkDestroyBuffer> buffer_;
  DeviceMemory memory_;
  VkDeviceSize size_ = 0;
};

// The extent of an image of a grid (NX x NY x NZ; a 2D image has NZ = 1).
inline VkExtent3D extentOf(Dims dims) {
  return {static_cast<std::uint32_t>(dims.x), static_cast<std::uint32_t>(dims.y),
          static_cast<std::uint32_t>(dims.z)};
}

struct ImageDesc {
  VkImageType type = VK_IMAGE_TYPE_3D;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkExtent3D extent{1, 1, 1};
  VkImageUsageFlags usage = 0;
  std::string name;
};

// A single-mip, single-layer colour image with one view of its whole extent.
class Image {
 public:
  Image() = default;
  static Result<Image> create(const Context& context, const ImageDesc& desc);
  Image(Image&&) noexcept = default;
  Image& operator=(Image&&) noexcept = default;  // view, image, then memory go
  ~Image() {
    view_.reset();
    image_.reset();
  }

  VkImage handle() const { return image_.get(); }
  VkImageView view() const { return view_.get(); }
  VkFormat format() const { return format_; }
  VkExtent3D extent() const { return extent_; }
  VkDeviceSize memorySize() const { return memory_.size(); }
  explicit operator bool() const { return static_cast<bool>(image_); }

 private:
  DeviceHandle<VkImageView, vkDestroyImageView> view_;
  DeviceHandle<VkImage, vkDestroyImage> image_;
  DeviceMemory memory_;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent3D extent_{};
};

// A clamp-to-edge sampler without mipmaps: texel centres at (i + 0.5) / size, as the LIC
// semantics want (edge-clamped trilinear interpolation).
class Sampler {
 public:
  Sampler() = default;
  static Result<Sampler> create(const Context& context, VkFilter filter, const std::string& name);

  VkSampler handle() const { return sampler_.get(); }

 private:
  DeviceHandle<VkSampler, vkDestroySampler> sampler_;
};

// What the device's memory can still give (VK_EXT_memory_budget where present, else the heap
// size), and the host's available memory: the budget of core/memory_budget.h's checks.
MemoryBudget queryMemoryBudget(const Context& context);

// Whether the device can use `format` with optimal tiling for all of `features`.
bool supportsFormat(const Context& context, VkFormat format, VkFormatFeatureFlags2 features);

}  // namespace lic3d
