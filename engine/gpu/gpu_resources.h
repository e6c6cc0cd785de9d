#pragma once
// Buffers, images and samplers: move-only owners whose destructor frees what create() made.
// Each resource gets its own VkDeviceMemory: lic3d holds a handful of large volumes, far below
// maxMemoryAllocationCount, so a sub-allocator would add nothing.

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/memory_budget.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

enum class MemoryUse {
  DeviceLocal,  // GPU only
  Upload,       // host-visible and coherent, written by the CPU (staging)
  Readback,     // host-visible and coherent, preferably cached, read by the CPU
};

// Owns a VkDeviceMemory and keeps the context's allocation accounting right.
class DeviceMemory {
 public:
  DeviceMemory() = default;
  static Result<DeviceMemory> allocate(const Context& context, const VkMemoryRequirements& needs,
                                       MemoryUse use, const std::string& name);
  DeviceMemory(DeviceMemory&& other) noexcept;
  DeviceMemory& operator=(DeviceMemory&& other) noexcept;
  ~DeviceMemory();

  VkDeviceMemory handle() const { return memory_; }
  VkDeviceSize size() const { return size_; }
  void* mapped() const { return mapped_; }

 private:
  void release();
  VkDevice device_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
  std::atomic<std::int64_t>* counter_ = nullptr;
};

class Buffer {
 public:
  Buffer() = default;
  static Result<Buffer> create(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                               MemoryUse use, const std::string& name);
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;
  ~Buffer();

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  // Persistently mapped pointer for Upload and Readback buffers, null for DeviceLocal.
  void* mapped() const { return memory_.mapped(); }

 private:
  void release();
  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  DeviceMemory memory_;
};

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
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;
  ~Image();

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }
  VkFormat format() const { return format_; }
  VkExtent3D extent() const { return extent_; }
  VkDeviceSize memorySize() const { return memory_.size(); }
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

 private:
  void release();
  VkDevice device_ = VK_NULL_HANDLE;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent3D extent_{};
  DeviceMemory memory_;
};

// A clamp-to-edge sampler without mipmaps: texel centres at (i + 0.5) / size, as the LIC
// semantics want (edge-clamped trilinear interpolation).
class Sampler {
 public:
  Sampler() = default;
  static Result<Sampler> create(const Context& context, VkFilter filter, const std::string& name);
  Sampler(Sampler&& other) noexcept;
  Sampler& operator=(Sampler&& other) noexcept;
  ~Sampler();

  VkSampler handle() const { return sampler_; }

 private:
  VkDevice device_ = VK_NULL_HANDLE;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

// What the device's memory can still give (VK_EXT_memory_budget where present, else the heap
// size), and the host's available memory: the budget of core/memory_budget.h's checks.
MemoryBudget queryMemoryBudget(const Context& context);

// Whether the device can use `format` with optimal tiling for all of `features`.
bool supportsFormat(const Context& context, VkFormat format, VkFormatFeatureFlags2 features);

}  // namespace lic3d
