#include "gpu/gpu_resources.h"

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

#include "core/memory_budget.h"
#include "gpu/vk_check.h"

namespace lic3d {
namespace {

// Test hook (docs/RELIABILITY.md): LIC3D_FAIL_ALLOCATION=N makes the N-th device memory allocation
// of the process fail with VK_ERROR_OUT_OF_DEVICE_MEMORY, as a full device would. Read once.
bool injectedAllocationFailure() {
  static const long failAt = [] {
    const char* text = std::getenv("LIC3D_FAIL_ALLOCATION");
    return text ? std::strtol(text, nullptr, 10) : 0L;
  }();
  static std::atomic<long> count{0};
  return failAt > 0 && ++count == failAt;
}

bool hasDeviceExtension(VkPhysicalDevice physical, const char* name) {
  std::uint32_t count = 0;
  if (vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, nullptr) != VK_SUCCESS)
    return false;
  std::vector<VkExtensionProperties> extensions(count);
  if (vkEnumerateDeviceExtensionProperties(physical, nullptr, &count, extensions.data()) !=
      VK_SUCCESS)
    return false;
  for (const VkExtensionProperties& e : extensions)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

}  // namespace

MemoryBudget queryMemoryBudget(const Context& context) {
  MemoryBudget b;
  VkPhysicalDevice physical = context.physicalDevice();
  VkPhysicalDeviceProperties properties{};
  vkGetPhysicalDeviceProperties(physical, &properties);
  b.unifiedMemory = properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;

  VkPhysicalDeviceMaintenance3Properties maintenance3{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  VkPhysicalDeviceProperties2 properties2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  properties2.pNext = &maintenance3;
  vkGetPhysicalDeviceProperties2(physical, &properties2);
  b.maxAllocation = maintenance3.maxMemoryAllocationSize;

  VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
  VkPhysicalDeviceMemoryProperties2 memory{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
  b.fromBudgetExtension = hasDeviceExtension(physical, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
  if (b.fromBudgetExtension) memory.pNext = &budget;
  vkGetPhysicalDeviceMemoryProperties2(physical, &memory);
  for (std::uint32_t i = 0; i < memory.memoryProperties.memoryHeapCount; ++i) {
    const VkMemoryHeap& heap = memory.memoryProperties.memoryHeaps[i];
    if (!(heap.flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)) continue;
    const std::uint64_t available = b.fromBudgetExtension
                                        ? (budget.heapBudget[i] > budget.heapUsage[i]
                                               ? budget.heapBudget[i] - budget.heapUsage[i]
                                               : 0)
                                        : heap.size;
    b.deviceBytes = std::max<std::uint64_t>(b.deviceBytes, available);
  }
  b.hostBytes = hostAvailableBytes();
  return b;
}

// ---- DeviceMemory ------------------------------------------------------------------------------

Result<DeviceMemory> DeviceMemory::allocate(const Context& context,
                                            const VkMemoryRequirements& needs, MemoryUse use,
                                            const std::string& name) {
  VkMemoryPropertyFlags required = 0, preferred = 0;
  switch (use) {
    case MemoryUse::DeviceLocal: required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryUse::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      break;
    case MemoryUse::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  std::uint32_t type = context.findMemoryType(needs.memoryTypeBits, required, preferred);
  if (type == UINT32_MAX && use == MemoryUse::DeviceLocal)
    type = context.findMemoryType(needs.memoryTypeBits, 0);
  if (type == UINT32_MAX) return unsupportedError("no suitable memory type for " + name);

  VkMemoryAllocateInfo info{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  info.allocationSize = needs.size;
  info.memoryTypeIndex = type;
  DeviceMemory memory;
  const VkResult result = injectedAllocationFailure()
                              ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                              : vkAllocateMemory(context.device(), &info, nullptr, &memory.memory_);
  if (result != VK_SUCCESS)
    return runtimeError("cannot allocate " + std::to_string(needs.size) +
                        " bytes of GPU memory for " + name + ": vkAllocateMemory returned " +
                        vkResultName(result));
  memory.device_ = context.device();
  memory.size_ = needs.size;
  memory.counter_ = &context.allocationCounter();
  *memory.counter_ += static_cast<std::int64_t>(needs.size);
  context.setDebugName(memory.memory_, VK_OBJECT_TYPE_DEVICE_MEMORY, name + " memory");
  if (use != MemoryUse::DeviceLocal)
    LIC3D_TRY(
        checkVk(vkMapMemory(memory.device_, memory.memory_, 0, VK_WHOLE_SIZE, 0, &memory.mapped_),
                "vkMapMemory"));
  return memory;
}

DeviceMemory::DeviceMemory(DeviceMemory&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      memory_(std::exchange(other.memory_, VK_NULL_HANDLE)),
      size_(std::exchange(other.size_, 0)),
      mapped_(std::exchange(other.mapped_, nullptr)),
      counter_(std::exchange(other.counter_, nullptr)) {}

DeviceMemory& DeviceMemory::operator=(DeviceMemory&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
    counter_ = std::exchange(other.counter_, nullptr);
  }
  return *this;
}

DeviceMemory::~DeviceMemory() { release(); }

void DeviceMemory::release() {
  if (memory_ == VK_NULL_HANDLE) return;
  vkFreeMemory(device_, memory_, nullptr);  // unmaps implicitly
  if (counter_) *counter_ -= static_cast<std::int64_t>(size_);
  memory_ = VK_NULL_HANDLE;
  mapped_ = nullptr;
}

// ---- Buffer ------------------------------------------------------------------------------------

Result<Buffer> Buffer::create(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                              MemoryUse use, const std::string& name) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  Buffer buffer;
  buffer.device_ = context.device();
  buffer.size_ = size;
  LIC3D_TRY(
      checkVk(vkCreateBuffer(context.device(), &info, nullptr, &buffer.buffer_), "vkCreateBuffer"));
  context.setDebugName(buffer.buffer_, VK_OBJECT_TYPE_BUFFER, name);
  VkMemoryRequirements needs;
  vkGetBufferMemoryRequirements(context.device(), buffer.buffer_, &needs);
  LIC3D_TRY_ASSIGN(buffer.memory_, DeviceMemory::allocate(context, needs, use, name));
  LIC3D_TRY(
      checkVk(vkBindBufferMemory(context.device(), buffer.buffer_, buffer.memory_.handle(), 0),
              "vkBindBufferMemory"));
  return buffer;
}

Buffer::Buffer(Buffer&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      buffer_(std::exchange(other.buffer_, VK_NULL_HANDLE)),
      size_(std::exchange(other.size_, 0)),
      memory_(std::move(other.memory_)) {}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    memory_ = std::move(other.memory_);
  }
  return *this;
}

Buffer::~Buffer() { release(); }

void Buffer::release() {
  if (buffer_ != VK_NULL_HANDLE) vkDestroyBuffer(device_, buffer_, nullptr);
  buffer_ = VK_NULL_HANDLE;
  memory_ = DeviceMemory();
}

// ---- Image -------------------------------------------------------------------------------------

Result<Image> Image::create(const Context& context, const ImageDesc& desc) {
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = desc.type;
  info.format = desc.format;
  info.extent = desc.extent;
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = desc.usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;

  Image image;
  image.device_ = context.device();
  image.format_ = desc.format;
  image.extent_ = desc.extent;
  const VkResult created = vkCreateImage(context.device(), &info, nullptr, &image.image_);
  if (created != VK_SUCCESS)
    return runtimeError(
        "cannot create image " + desc.name + " (" + std::to_string(desc.extent.width) + "x" +
        std::to_string(desc.extent.height) + "x" + std::to_string(desc.extent.depth) +
        "): vkCreateImage returned " + vkResultName(created));
  context.setDebugName(image.image_, VK_OBJECT_TYPE_IMAGE, desc.name);

  VkMemoryRequirements needs;
  vkGetImageMemoryRequirements(context.device(), image.image_, &needs);
  LIC3D_TRY_ASSIGN(image.memory_,
                   DeviceMemory::allocate(context, needs, MemoryUse::DeviceLocal, desc.name));
  LIC3D_TRY(checkVk(vkBindImageMemory(context.device(), image.image_, image.memory_.handle(), 0),
                    "vkBindImageMemory"));

  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = image.image_;
  viewInfo.viewType = desc.type == VK_IMAGE_TYPE_3D ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = desc.format;
  viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  LIC3D_TRY(checkVk(vkCreateImageView(context.device(), &viewInfo, nullptr, &image.view_),
                    "vkCreateImageView"));
  context.setDebugName(image.view_, VK_OBJECT_TYPE_IMAGE_VIEW, desc.name + " view");
  return image;
}

Image::Image(Image&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      image_(std::exchange(other.image_, VK_NULL_HANDLE)),
      view_(std::exchange(other.view_, VK_NULL_HANDLE)),
      format_(other.format_),
      extent_(other.extent_),
      memory_(std::move(other.memory_)) {}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    release();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    format_ = other.format_;
    extent_ = other.extent_;
    memory_ = std::move(other.memory_);
  }
  return *this;
}

Image::~Image() { release(); }

void Image::release() {
  if (view_ != VK_NULL_HANDLE) vkDestroyImageView(device_, view_, nullptr);
  if (image_ != VK_NULL_HANDLE) vkDestroyImage(device_, image_, nullptr);
  view_ = VK_NULL_HANDLE;
  image_ = VK_NULL_HANDLE;
  memory_ = DeviceMemory();
}

// ---- Sampler -----------------------------------------------------------------------------------

Result<Sampler> Sampler::create(const Context& context, VkFilter filter, const std::string& name) {
  VkSamplerCreateInfo info{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  info.magFilter = filter;
  info.minFilter = filter;
  info.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  info.addressModeU = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeV = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  info.maxLod = 0.0f;
  Sampler sampler;
  sampler.device_ = context.device();
  LIC3D_TRY(checkVk(vkCreateSampler(context.device(), &info, nullptr, &sampler.sampler_),
                    "vkCreateSampler"));
  context.setDebugName(sampler.sampler_, VK_OBJECT_TYPE_SAMPLER, name);
  return sampler;
}

Sampler::Sampler(Sampler&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      sampler_(std::exchange(other.sampler_, VK_NULL_HANDLE)) {}

Sampler& Sampler::operator=(Sampler&& other) noexcept {
  if (this != &other) {
    if (sampler_ != VK_NULL_HANDLE) vkDestroySampler(device_, sampler_, nullptr);
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
  }
  return *this;
}

Sampler::~Sampler() {
  if (sampler_ != VK_NULL_HANDLE) vkDestroySampler(device_, sampler_, nullptr);
}

bool supportsFormat(const Context& context, VkFormat format, VkFormatFeatureFlags2 features) {
  VkFormatProperties3 properties3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
  VkFormatProperties2 properties{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2, &properties3};
  vkGetPhysicalDeviceFormatProperties2(context.physicalDevice(), format, &properties);
  return (properties3.optimalTilingFeatures & features) == features;
}

}  // namespace lic3d
