// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The Vulkan instance, the chosen physical device, the logical device and its one queue.
// Works without any surface; a front end with a window passes its surface extensions in.

#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"

namespace lic3d {

struct ContextOptions {
  // Khronos validation with synchronization validation. Also switched on by LIC3D_VALIDATION=1.
  bool validation = false;
  // Pipelines keep the driver's statistics of their compiled shaders (registers, spills) where
  // the device has VK_KHR_pipeline_executable_properties: `lic3d bench --kernels` prints them.
  bool pipelineStatistics = false;
  // "" picks the best device (discrete, then integrated, then virtual, then CPU); a number picks
  // that index of listDevices(); anything else picks the first device whose name contains it.
  std::string device;
  std::vector<const char*> instanceExtensions;  // e.g. what GLFW needs for a surface
  std::vector<const char*> deviceExtensions;    // e.g. VK_KHR_swapchain
  // For a window: makes the surface once the instance exists. The chosen queue must then be able
  // to present to it, and the context destroys it with the instance.
  std::function<Result<VkSurfaceKHR>(VkInstance)> createSurface;
};

struct DeviceInfo {
  int index = 0;
  std::string name;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  std::uint32_t apiVersion = 0;
  std::string driver;
  VkDeviceSize deviceLocalBytes = 0;
  bool usable = false;
  std::string unusableReason;  // why lic3d cannot run on it, when !usable
};

const char* deviceTypeName(VkPhysicalDeviceType type);

// Whether the physical device offers the device extension `name`.
bool hasDeviceExtension(VkPhysicalDevice device, const char* name);

// Every Vulkan device the loader reports, in the loader's order, with whether lic3d can use it.
Result<std::vector<DeviceInfo>> listDevices();

class Context {
 public:
  static Result<Context> create(const ContextOptions& options = {});

  Context(Context&&) noexcept;
  Context& operator=(Context&&) noexcept;
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;
  ~Context();

  VkInstance instance() const;
  VkPhysicalDevice physicalDevice() const;
  VkDevice device() const;
  VkQueue queue() const;
  std::uint32_t queueFamily() const;
  VkSurfaceKHR surface() const;  // VK_NULL_HANDLE without createSurface
  const DeviceInfo& deviceInfo() const;
  const VkPhysicalDeviceProperties& properties() const;
  bool supportsTimestamps() const;
  std::uint32_t timestampValidBits() const;

  // Finds a memory type allowed by `typeBits` with all `required` flags, preferring one that
  // also has `preferred`. Returns UINT32_MAX when none fits.
  std::uint32_t findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                               VkMemoryPropertyFlags preferred = 0) const;

  // Device memory lic3d holds right now (its own accounting of vkAllocateMemory/vkFreeMemory).
  // The counter lives as long as the device, so resources keep a pointer to it.
  std::uint64_t allocatedBytes() const;
  std::atomic<std::int64_t>& allocationCounter() const;

  // Validation messages (warning or error severity) since creation or the last clear.
  bool validationEnabled() const;
  // Whether pipelines are made with VK_PIPELINE_CREATE_CAPTURE_STATISTICS_BIT_KHR.
  bool capturesPipelineStatistics() const;
  std::size_t validationMessageCount() const;
  std::vector<std::string> validationMessages() const;
  void clearValidationMessages() const;

  // Debug names show in validation messages and captures. No-ops without VK_EXT_debug_utils.
  void setDebugName(VkObjectType type, std::uint64_t handle, const std::string& name) const;
  template <class Handle>
  void setDebugName(Handle handle, VkObjectType type, const std::string& name) const {
    setDebugName(type, reinterpret_cast<std::uint64_t>(handle), name);
  }

  // Dispatchable-command helpers resolved at creation.
  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;

 private:
  struct State;
  explicit Context(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

}  // namespace lic3d
