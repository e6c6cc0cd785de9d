// SPDX-License-Identifier: BSD-3-Clause
#include "gpu/resources.h"

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
  VkDeviceMemory handle = VK_NULL_HANDLE;
  const VkResult result = injectedAllocationFailure()
                              ? VK_ERROR_OUT_OF_DEVICE_MEMORY
                              : vkAllocateMemory(context.device(), &info, nullptr, &handle);
  if (result != VK_SUCCESS)
    return runtimeError("cannot allocate " + std::to_string(needs.size) +
                        " bytes of GPU memory for " + name + ": vkAllocateMemory returned " +
                        vkResultName(result));
  DeviceMemory memory;
  memory.memory_ = {context.device(), handle};
  memory.size_ = needs.size;
  const auto bytes = static_cast<std::int64_t>(needs.size);
  context.allocationCounter() += bytes;
  memory.counted_ = {&context.allocationCounter(), AllocationUncount{bytes}};
  context.setDebugName(handle, VK_OBJECT_TYPE_DEVICE_MEMORY, name + " memory");
  if (use != MemoryUse::DeviceLocal)
    LIC3D_TRY(checkVk(vkMapMemory(context.device(), handle, 0, VK_WHOLE_SIZE, 0, &memory.mapped_),
                      "vkMapMemory"));
  return memory;
}

// ---- Buffer ------------------------------------------------------------------------------------

Result<Buffer> Buffer::create(const Context& context, VkDeviceSize size, VkBufferUsageFlags usage,
                              MemoryUse use, const std::string& name) {
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  VkBuffer handle = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreateBuffer(context.device(), &info, nullptr, &handle), "vkCreateBuffer"));
  Buffer buffer;
  buffer.buffer_ = {context.device(), handle};
  buffer.size_ = size;
  context.setDebugName(handle, VK_OBJECT_TYPE_BUFFER, name);
  VkMemoryRequirements needs;
  vkGetBufferMemoryRequirements(context.device(), handle, &needs);
  LIC3D_TRY_ASSIGN(buffer.memory_, DeviceMemory::allocate(context, needs, use, name));
  LIC3D_TRY(checkVk(vkBindBufferMemory(context.device(), handle, buffer.memory_.handle(), 0),
                    "vkBindBufferMemory"));
  return buffer;
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

  VkImage handle = VK_NULL_HANDLE;
  const VkResult created = vkCreateImage(context.device(), &info, nullptr, &handle);
  if (created != VK_SUCCESS)
    return runtimeError(
        "cannot create image " + desc.name + " (" + std::to_string(desc.extent.width) + "x" +
        std::to_string(desc.extent.height) + "x" + std::to_string(desc.extent.depth) +
        "): vkCreateImage returned " + vkResultName(created));
  Image image;
  image.image_ = {context.device(), handle};
  image.format_ = desc.format;
  image.extent_ = desc.extent;
  context.setDebugName(handle, VK_OBJECT_TYPE_IMAGE, desc.name);

  VkMemoryRequirements needs;
  vkGetImageMemoryRequirements(context.device(), handle, &needs);
  LIC3D_TRY_ASSIGN(image.memory_,
                   DeviceMemory::allocate(context, needs, MemoryUse::DeviceLocal, desc.name));
  LIC3D_TRY(checkVk(vkBindImageMemory(context.device(), handle, image.memory_.handle(), 0),
                    "vkBindImageMemory"));

  VkImageViewCreateInfo viewInfo{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  viewInfo.image = handle;
  viewInfo.viewType = desc.type == VK_IMAGE_TYPE_3D ? VK_IMAGE_VIEW_TYPE_3D : VK_IMAGE_VIEW_TYPE_2D;
  viewInfo.format = desc.format;
  viewInfo.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkImageView view = VK_NULL_HANDLE;
  LIC3D_TRY(
      checkVk(vkCreateImageView(context.device(), &viewInfo, nullptr, &view), "vkCreateImageView"));
  image.view_ = {context.device(), view};
  context.setDebugName(view, VK_OBJECT_TYPE_IMAGE_VIEW, desc.name + " view");
  return image;
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
  VkSampler handle = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreateSampler(context.device(), &info, nullptr, &handle), "vkCreateSampler"));
  Sampler sampler;
  sampler.sampler_ = {context.device(), handle};
  context.setDebugName(handle, VK_OBJECT_TYPE_SAMPLER, name);
  return sampler;
}

bool supportsFormat(const Context& context, VkFormat format, VkFormatFeatureFlags2 features) {
  VkFormatProperties3 properties3{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_3};
  VkFormatProperties2 properties{VK_STRUCTURE_TYPE_FORMAT_PROPERTIES_2, &properties3};
  vkGetPhysicalDeviceFormatProperties2(context.physicalDevice(), format, &properties);
  return (properties3.optimalTilingFeatures & features) == features;
}

}  // namespace lic3d
