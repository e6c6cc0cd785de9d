// SPDX-License-Identifier: BSD-3-Clause
#include "gpu/vulkan_context.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

#include "gpu/device_choice.h"

#if defined(__SANITIZE_ADDRESS__)
#include <dlfcn.h>
#include <link.h>
#endif

#include "gpu/vk_check.h"

namespace lic3d {
namespace {

constexpr const char* kValidationLayer = "VK_LAYER_KHRONOS_validation";
constexpr const char* kNoDeviceHelp =
    "install a Vulkan driver (on Debian: apt-get install mesa-vulkan-drivers gives the CPU driver "
    "lavapipe) or check VK_DRIVER_FILES";

#if defined(__SANITIZE_ADDRESS__)
// In AddressSanitizer builds only (docs/TESTING.md): the Vulkan loader unloads the driver and the
// layers with dlclose when the instance goes, and LeakSanitizer then reports what their globals
// held as leaks it cannot attribute to any module. Made resident (RTLD_NODELETE on the copy
// already loaded), they stay mapped to the end: their globals stay reachable, and what they do
// leak is named by module (tests/lsan.supp) while lic3d's own leaks are still reported.
void keepVulkanModulesLoaded() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, size_t, void* out) {
        const char* name = info->dlpi_name;
        if (name && (std::strstr(name, "libvulkan_") || std::strstr(name, "libVkLayer_")))
          static_cast<std::vector<std::string>*>(out)->push_back(name);
        return 0;
      },
      &names);
  for (const std::string& name : names)
    dlopen(name.c_str(), RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
}
#else
void keepVulkanModulesLoaded() {}
#endif

bool envFlag(const char* name) {
  const char* value = std::getenv(name);
  return value && value[0] != '\0' && std::strcmp(value, "0") != 0;
}

bool hasLayer(const char* name) {
  std::uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(), [&](const VkLayerProperties& l) {
    return std::strcmp(l.layerName, name) == 0;
  });
}

bool hasInstanceExtension(const char* layer, const char* name) {
  std::uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(layer, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateInstanceExtensionProperties(layer, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

// One queue family that does graphics and compute (and presents to `surface`, if any): lic3d
// records every pass on one queue.
std::uint32_t findQueueFamily(VkPhysicalDevice device, VkSurfaceKHR surface = VK_NULL_HANDLE) {
  std::uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (std::uint32_t i = 0; i < count; ++i) {
    const VkQueueFlags needed = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
    if ((families[i].queueFlags & needed) != needed) continue;
    VkBool32 presents = VK_TRUE;
    if (surface) vkGetPhysicalDeviceSurfaceSupportKHR(device, i, surface, &presents);
    if (presents) return i;
  }
  return UINT32_MAX;
}

int typeRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

std::string versionString(std::uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) +
         "." + std::to_string(VK_API_VERSION_PATCH(v));
}

// Checks everything lic3d needs from a device; the reason names what is missing.
DeviceInfo describeDevice(VkPhysicalDevice device, int index,
                          const std::vector<const char*>& extraExtensions,
                          VkSurfaceKHR surface = VK_NULL_HANDLE) {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &driver};
  vkGetPhysicalDeviceProperties2(device, &properties);
  VkPhysicalDeviceMemoryProperties memory;
  vkGetPhysicalDeviceMemoryProperties(device, &memory);

  DeviceInfo info;
  info.index = index;
  info.name = properties.properties.deviceName;
  info.type = properties.properties.deviceType;
  info.apiVersion = properties.properties.apiVersion;
  info.driver = std::string(driver.driverName) + " " + driver.driverInfo;
  for (std::uint32_t i = 0; i < memory.memoryHeapCount; ++i)
    if (memory.memoryHeaps[i].flags & VK_MEMORY_HEAP_DEVICE_LOCAL_BIT)
      info.deviceLocalBytes = std::max(info.deviceLocalBytes, memory.memoryHeaps[i].size);

  std::vector<std::string> missing;
  if (info.apiVersion < VK_API_VERSION_1_3)
    missing.push_back("Vulkan 1.3 (device reports " + versionString(info.apiVersion) + ")");
  else {
    VkPhysicalDeviceVulkan13Features features13{
        VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
    VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
    vkGetPhysicalDeviceFeatures2(device, &features);
    if (!features13.dynamicRendering) missing.push_back("dynamicRendering");
    if (!features13.synchronization2) missing.push_back("synchronization2");
    if (!features13.maintenance4) missing.push_back("maintenance4");
    if (!features.features.shaderStorageImageExtendedFormats)
      missing.push_back("shaderStorageImageExtendedFormats");
    // Occlusion shading blends its image and its buffer differently (passes/occlusion_pass.h).
    if (!features.features.independentBlend) missing.push_back("independentBlend");
  }
  if (findQueueFamily(device, surface) == UINT32_MAX)
    missing.push_back(surface ? "a graphics+compute queue that presents to the window"
                              : "a graphics+compute queue");
  if (!hasDeviceExtension(device, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME))
    missing.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
  for (const char* extension : extraExtensions)
    if (!hasDeviceExtension(device, extension)) missing.push_back(extension);

  info.usable = missing.empty();
  for (std::size_t i = 0; i < missing.size(); ++i)
    info.unusableReason += (i ? ", " : "missing ") + missing[i];
  return info;
}

// The drivers stay loaded for the life of the process, held by a bare instance made once and
// never destroyed. Without it each instance loads the drivers again once the last one is gone,
// and NVIDIA's driver (580.159) takes static TLS that it never gives back each time it is loaded:
// after 30 instances, one after another in one process (a Python session's calls, a ParaView
// session's filter runs), no instance finds a driver ("cannot allocate memory in static TLS
// block"). Best effort: where it fails, the instance that follows says why.
void keepDriversLoaded() {
  static std::once_flag once;
  static VkInstance kept = VK_NULL_HANDLE;
  std::call_once(once, [] {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "lic3d";
    app.apiVersion = VK_API_VERSION_1_3;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    if (vkCreateInstance(&info, nullptr, &kept) != VK_SUCCESS) kept = VK_NULL_HANDLE;
  });
}

Result<VkInstance> createInstance(bool validation, const std::vector<const char*>& extraExtensions,
                                  bool* debugUtils) {
  keepDriversLoaded();
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "lic3d";
  app.pEngineName = "lic3d";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers;
  std::vector<const char*> extensions = extraExtensions;
  *debugUtils = hasInstanceExtension(nullptr, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (validation) {
    if (!hasLayer(kValidationLayer))
      return unsupportedError(std::string("validation requested but ") + kValidationLayer +
                              " is not installed (on Debian: apt-get install "
                              "vulkan-validationlayers)");
    layers.push_back(kValidationLayer);
    *debugUtils =
        *debugUtils || hasInstanceExtension(kValidationLayer, VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
  }
  if (*debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  // Synchronization validation finds missing barriers that the core checks cannot see.
  const VkValidationFeatureEnableEXT enables[] = {
      VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = validation ? &features : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = static_cast<std::uint32_t>(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();

  VkInstance instance = VK_NULL_HANDLE;
  const VkResult result = vkCreateInstance(&info, nullptr, &instance);
  if (result == VK_ERROR_INCOMPATIBLE_DRIVER || result == VK_ERROR_INITIALIZATION_FAILED)
    return unsupportedError(std::string("no Vulkan driver found (vkCreateInstance: ") +
                            vkResultName(result) + "): " + kNoDeviceHelp);
  if (result == VK_ERROR_EXTENSION_NOT_PRESENT)
    return unsupportedError("the Vulkan loader lacks an instance extension lic3d needs");
  if (result != VK_SUCCESS)
    return runtimeError(std::string("vkCreateInstance failed: ") + vkResultName(result));
  return instance;
}

std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  std::uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance, &count, devices.data());
  devices.resize(count);
  return devices;
}

std::string lowercase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

Result<int> chooseDevice(const std::vector<DeviceInfo>& devices, const std::string& selector) {
  if (devices.empty())
    return unsupportedError(std::string("no Vulkan device found: ") + kNoDeviceHelp);
  auto list = [&] {
    std::string text;
    for (const DeviceInfo& d : devices) text += "\n  " + std::to_string(d.index) + ": " + d.name;
    return text;
  };
  if (!selector.empty()) {
    int chosen = -1;
    const bool numeric = std::all_of(selector.begin(), selector.end(),
                                     [](unsigned char c) { return std::isdigit(c); });
    if (numeric) {
      const long index = std::strtol(selector.c_str(), nullptr, 10);
      if (index >= 0 && index < static_cast<long>(devices.size())) chosen = static_cast<int>(index);
    } else {
      for (const DeviceInfo& d : devices)
        if (lowercase(d.name).find(lowercase(selector)) != std::string::npos) {
          chosen = d.index;
          break;
        }
    }
    if (chosen < 0)
      return parameterError("device", selector + " matches no Vulkan device; found:" + list());
    if (!devices[chosen].usable)
      return unsupportedError("device " + std::to_string(chosen) + " (" + devices[chosen].name +
                              ") cannot run lic3d: " + devices[chosen].unusableReason);
    return chosen;
  }
  int best = -1;
  for (const DeviceInfo& d : devices)
    if (d.usable && (best < 0 || typeRank(d.type) > typeRank(devices[best].type))) best = d.index;
  if (best < 0) {
    std::string reasons;
    for (const DeviceInfo& d : devices) reasons += "\n  " + d.name + ": " + d.unusableReason;
    return unsupportedError("no Vulkan device can run lic3d:" + reasons);
  }
  return best;
}

Result<std::vector<int>> chooseDevices(const std::vector<DeviceInfo>& devices,
                                       std::string_view selectors) {
  std::vector<int> chosen;
  if (selectors == "all") {
    LIC3D_TRY_ASSIGN(const int best, chooseDevice(devices, ""));
    for (const DeviceInfo& d : devices)
      if (d.usable && typeRank(d.type) == typeRank(devices[best].type)) chosen.push_back(d.index);
    return chosen;
  }
  std::size_t at = 0;
  for (;;) {
    const std::size_t comma = selectors.find(',', at);
    const std::string selector(selectors.substr(at, comma - at));
    if (selector.empty())
      return parameterError("devices", std::string(selectors) +
                                           ": an empty entry; give all, or indices or name "
                                           "parts separated by commas");
    LIC3D_TRY_ASSIGN(const int index, chooseDevice(devices, selector));
    if (std::find(chosen.begin(), chosen.end(), index) != chosen.end())
      return parameterError("devices", std::string(selectors) + ": device " +
                                           std::to_string(index) + " (" + devices[index].name +
                                           ") is named twice");
    chosen.push_back(index);
    if (comma == std::string_view::npos) return chosen;
    at = comma + 1;
  }
}

namespace {

// Validation messages, appended from whatever thread the layer reports on.
struct MessageLog {
  std::mutex mutex;
  std::vector<std::string> messages;
};

}  // namespace

bool hasDeviceExtension(VkPhysicalDevice device, const char* name) {
  std::uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> extensions(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, extensions.data());
  return std::any_of(extensions.begin(), extensions.end(), [&](const VkExtensionProperties& e) {
    return std::strcmp(e.extensionName, name) == 0;
  });
}

const char* deviceTypeName(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

Result<std::vector<DeviceInfo>> listDevices() {
  bool debugUtils = false;
  LIC3D_TRY_ASSIGN(VkInstance instance, createInstance(false, {}, &debugUtils));
  std::vector<DeviceInfo> devices;
  int index = 0;
  for (VkPhysicalDevice device : physicalDevices(instance))
    devices.push_back(describeDevice(device, index++, {}));
  vkDestroyInstance(instance, nullptr);
  return devices;
}

struct Context::State {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkPhysicalDevice physicalDevice = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  std::uint32_t queueFamily = 0;
  DeviceInfo info;
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory{};
  bool timestamps = false;
  std::uint32_t timestampBits = 0;
  bool validation = false;
  bool pipelineStatistics = false;
  PFN_vkSetDebugUtilsObjectNameEXT setObjectName = nullptr;
  mutable std::atomic<std::int64_t> allocatedBytes{0};
  mutable MessageLog log;

  ~State() {
    if (device) vkDestroyDevice(device, nullptr);
    if (surface) vkDestroySurfaceKHR(instance, surface, nullptr);
    if (messenger) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance, "vkDestroyDebugUtilsMessengerEXT"));
      if (destroy) destroy(instance, messenger, nullptr);
    }
    if (instance) vkDestroyInstance(instance, nullptr);
  }
};

namespace {

VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                              VkDebugUtilsMessageTypeFlagsEXT type,
                                              const VkDebugUtilsMessengerCallbackDataEXT* data,
                                              void* user) {
  (void)type;
  auto& log = *static_cast<MessageLog*>(user);
  const bool error = severity & VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  std::string text = std::string(error ? "validation error: " : "validation warning: ") +
                     (data && data->pMessage ? data->pMessage : "(no message)");
  std::fprintf(stderr, "lic3d: %s\n", text.c_str());
  std::lock_guard lock(log.mutex);
  log.messages.push_back(std::move(text));
  return VK_FALSE;
}

}  // namespace

Context::Context(std::unique_ptr<State> state) : state_(std::move(state)) {}
Context::Context(Context&&) noexcept = default;
Context& Context::operator=(Context&&) noexcept = default;
Context::~Context() = default;

Result<Context> Context::create(const ContextOptions& options) {
  auto state = std::make_unique<State>();
  state->validation = options.validation || envFlag("LIC3D_VALIDATION");
  bool debugUtils = false;
  LIC3D_TRY_ASSIGN(state->instance,
                   createInstance(state->validation, options.instanceExtensions, &debugUtils));

  if (debugUtils) {
    state->setObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(state->instance, "vkSetDebugUtilsObjectNameEXT"));
  }
  if (state->validation && debugUtils) {
    VkDebugUtilsMessengerCreateInfoEXT info{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                           VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                       VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
    info.pfnUserCallback = onDebugMessage;
    info.pUserData = &state->log;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(state->instance, "vkCreateDebugUtilsMessengerEXT"));
    if (create)
      LIC3D_TRY(checkVk(create(state->instance, &info, nullptr, &state->messenger),
                        "vkCreateDebugUtilsMessengerEXT"));
  }

  if (options.createSurface) {
    LIC3D_TRY_ASSIGN(state->surface, options.createSurface(state->instance));
  }
  const std::vector<VkPhysicalDevice> physical = physicalDevices(state->instance);
  std::vector<DeviceInfo> infos;
  for (std::size_t i = 0; i < physical.size(); ++i)
    infos.push_back(
        describeDevice(physical[i], static_cast<int>(i), options.deviceExtensions, state->surface));
  LIC3D_TRY_ASSIGN(const int chosen, chooseDevice(infos, options.device));
  state->physicalDevice = physical[chosen];
  state->info = infos[chosen];
  state->queueFamily = findQueueFamily(state->physicalDevice, state->surface);
  vkGetPhysicalDeviceProperties(state->physicalDevice, &state->properties);
  vkGetPhysicalDeviceMemoryProperties(state->physicalDevice, &state->memory);
  {
    std::uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(state->physicalDevice, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(state->physicalDevice, &count, families.data());
    state->timestampBits = families[state->queueFamily].timestampValidBits;
    state->timestamps = state->timestampBits > 0 && state->properties.limits.timestampPeriod > 0.0f;
  }

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queueInfo{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queueInfo.queueFamilyIndex = state->queueFamily;
  queueInfo.queueCount = 1;
  queueInfo.pQueuePriorities = &priority;

  // maintenance4 is required for local_size_x_id with SPIR-V 1.6 (LocalSizeId).
  VkPhysicalDeviceVulkan13Features features13{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  features13.dynamicRendering = VK_TRUE;
  features13.synchronization2 = VK_TRUE;
  features13.maintenance4 = VK_TRUE;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2, &features13};
  features.features.shaderStorageImageExtendedFormats = VK_TRUE;
  features.features.independentBlend = VK_TRUE;

  std::vector<const char*> extensions = options.deviceExtensions;
  extensions.push_back(VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);
  VkPhysicalDevicePipelineExecutablePropertiesFeaturesKHR executableInfo{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PIPELINE_EXECUTABLE_PROPERTIES_FEATURES_KHR};
  if (options.pipelineStatistics &&
      hasDeviceExtension(state->physicalDevice,
                         VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME)) {
    extensions.push_back(VK_KHR_PIPELINE_EXECUTABLE_PROPERTIES_EXTENSION_NAME);
    executableInfo.pipelineExecutableInfo = VK_TRUE;
    executableInfo.pNext = features.pNext;
    features.pNext = &executableInfo;
    state->pipelineStatistics = true;
  }

  VkDeviceCreateInfo deviceInfo{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO, &features};
  deviceInfo.queueCreateInfoCount = 1;
  deviceInfo.pQueueCreateInfos = &queueInfo;
  deviceInfo.enabledExtensionCount = static_cast<std::uint32_t>(extensions.size());
  deviceInfo.ppEnabledExtensionNames = extensions.data();
  LIC3D_TRY(checkVk(vkCreateDevice(state->physicalDevice, &deviceInfo, nullptr, &state->device),
                    "vkCreateDevice"));
  vkGetDeviceQueue(state->device, state->queueFamily, 0, &state->queue);
  keepVulkanModulesLoaded();

  Context context(std::move(state));
  context.cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetDeviceProcAddr(context.device(), "vkCmdPushDescriptorSetKHR"));
  LIC3D_ASSERT(context.cmdPushDescriptorSet != nullptr);
  context.setDebugName(context.device(), VK_OBJECT_TYPE_DEVICE, "lic3d device");
  context.setDebugName(context.queue(), VK_OBJECT_TYPE_QUEUE, "lic3d queue");
  return context;
}

VkInstance Context::instance() const { return state_->instance; }
VkPhysicalDevice Context::physicalDevice() const { return state_->physicalDevice; }
VkDevice Context::device() const { return state_->device; }
VkQueue Context::queue() const { return state_->queue; }
std::uint32_t Context::queueFamily() const { return state_->queueFamily; }
VkSurfaceKHR Context::surface() const { return state_->surface; }
const DeviceInfo& Context::deviceInfo() const { return state_->info; }
const VkPhysicalDeviceProperties& Context::properties() const { return state_->properties; }
bool Context::supportsTimestamps() const { return state_->timestamps; }
std::uint32_t Context::timestampValidBits() const { return state_->timestampBits; }

std::uint32_t Context::findMemoryType(std::uint32_t typeBits, VkMemoryPropertyFlags required,
                                      VkMemoryPropertyFlags preferred) const {
  std::uint32_t fallback = UINT32_MAX;
  for (std::uint32_t i = 0; i < state_->memory.memoryTypeCount; ++i) {
    if (!(typeBits & (1u << i))) continue;
    const VkMemoryPropertyFlags flags = state_->memory.memoryTypes[i].propertyFlags;
    if ((flags & required) != required) continue;
    if ((flags & preferred) == preferred) return i;
    if (fallback == UINT32_MAX) fallback = i;
  }
  return fallback;
}

std::uint64_t Context::allocatedBytes() const {
  return static_cast<std::uint64_t>(state_->allocatedBytes.load());
}
std::atomic<std::int64_t>& Context::allocationCounter() const { return state_->allocatedBytes; }

bool Context::validationEnabled() const { return state_->validation; }
bool Context::capturesPipelineStatistics() const { return state_->pipelineStatistics; }
std::size_t Context::validationMessageCount() const {
  std::lock_guard lock(state_->log.mutex);
  return state_->log.messages.size();
}
std::vector<std::string> Context::validationMessages() const {
  std::lock_guard lock(state_->log.mutex);
  return state_->log.messages;
}
void Context::clearValidationMessages() const {
  std::lock_guard lock(state_->log.mutex);
  state_->log.messages.clear();
}

void Context::setDebugName(VkObjectType type, std::uint64_t handle, const std::string& name) const {
  if (!state_->setObjectName || handle == 0) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  state_->setObjectName(state_->device, &info);
}

}  // namespace lic3d
