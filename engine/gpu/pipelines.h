#pragma once
// Owners of shader modules, pipeline layouts (with their push-descriptor set layout) and
// pipelines, and the few calls every pass makes to build them.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <string>
#include <utility>

#include "core/error.h"
#include "gpu/shader_library.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

// A handle destroyed with vkDestroy<Kind> when its owner goes away. Move-only.
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
  explicit operator bool() const { return handle_ != VK_NULL_HANDLE; }

 private:
  void reset() {
    if (handle_ != VK_NULL_HANDLE) Destroy(device_, handle_, nullptr);
    handle_ = VK_NULL_HANDLE;
  }
  VkDevice device_ = VK_NULL_HANDLE;
  Handle handle_ = VK_NULL_HANDLE;
};

using ShaderModule = DeviceHandle<VkShaderModule, vkDestroyShaderModule>;
using Pipeline = DeviceHandle<VkPipeline, vkDestroyPipeline>;

Result<ShaderModule> loadShader(const Context& context, ShaderId id);

// One push-descriptor set (the pass's bindings) and one push-constant range (none if 0 bytes).
class PipelineLayout {
 public:
  PipelineLayout() = default;
  static Result<PipelineLayout> create(const Context& context,
                                       std::span<const VkDescriptorSetLayoutBinding> bindings,
                                       VkShaderStageFlags pushStages, std::uint32_t pushBytes,
                                       const std::string& name);

  VkPipelineLayout get() const { return layout_.get(); }

 private:
  DeviceHandle<VkDescriptorSetLayout, vkDestroyDescriptorSetLayout> setLayout_;
  DeviceHandle<VkPipelineLayout, vkDestroyPipelineLayout> layout_;
};

Result<Pipeline> createComputePipeline(const Context& context, const ShaderModule& shader,
                                       const PipelineLayout& layout,
                                       const VkSpecializationInfo* specialization,
                                       const std::string& name);

// A descriptor write for vkCmdPushDescriptorSetKHR (no set: dstSet is ignored there).
VkWriteDescriptorSet descriptorWrite(std::uint32_t binding, VkDescriptorType type,
                                     const VkDescriptorImageInfo* image);
VkWriteDescriptorSet descriptorWrite(std::uint32_t binding, VkDescriptorType type,
                                     const VkDescriptorBufferInfo* buffer);

}  // namespace lic3d
