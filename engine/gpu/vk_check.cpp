// SPDX-License-Identifier: BSD-3-Clause
#include "gpu/vk_check.h"

#include <cstdio>
#include <cstdlib>

namespace lic3d {

const char* vkResultName(VkResult result) {
  switch (result) {
#define LIC3D_RESULT_CASE(r) \
  case r: return #r;
    LIC3D_RESULT_CASE(VK_SUCCESS)
    LIC3D_RESULT_CASE(VK_NOT_READY)
    LIC3D_RESULT_CASE(VK_TIMEOUT)
    LIC3D_RESULT_CASE(VK_EVENT_SET)
    LIC3D_RESULT_CASE(VK_EVENT_RESET)
    LIC3D_RESULT_CASE(VK_INCOMPLETE)
    LIC3D_RESULT_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    LIC3D_RESULT_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    LIC3D_RESULT_CASE(VK_ERROR_INITIALIZATION_FAILED)
    LIC3D_RESULT_CASE(VK_ERROR_DEVICE_LOST)
    LIC3D_RESULT_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    LIC3D_RESULT_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    LIC3D_RESULT_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    LIC3D_RESULT_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    LIC3D_RESULT_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    LIC3D_RESULT_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    LIC3D_RESULT_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    LIC3D_RESULT_CASE(VK_ERROR_FRAGMENTED_POOL)
    LIC3D_RESULT_CASE(VK_ERROR_UNKNOWN)
    LIC3D_RESULT_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    LIC3D_RESULT_CASE(VK_ERROR_INVALID_EXTERNAL_HANDLE)
    LIC3D_RESULT_CASE(VK_ERROR_FRAGMENTATION)
    LIC3D_RESULT_CASE(VK_ERROR_INVALID_OPAQUE_CAPTURE_ADDRESS)
    LIC3D_RESULT_CASE(VK_PIPELINE_COMPILE_REQUIRED)
    LIC3D_RESULT_CASE(VK_ERROR_SURFACE_LOST_KHR)
    LIC3D_RESULT_CASE(VK_ERROR_NATIVE_WINDOW_IN_USE_KHR)
    LIC3D_RESULT_CASE(VK_SUBOPTIMAL_KHR)
    LIC3D_RESULT_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    LIC3D_RESULT_CASE(VK_ERROR_VALIDATION_FAILED_EXT)
#undef LIC3D_RESULT_CASE
    default: return "VK_RESULT_UNKNOWN";
  }
}

void abortOnVkError(const char* call, VkResult result, const char* file, int line) {
  std::fprintf(stderr, "lic3d: fatal: %s failed with %s (%d) at %s:%d\n", call,
               vkResultName(result), static_cast<int>(result), file, line);
  std::abort();
}

void abortOnAssert(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "lic3d: fatal: assertion '%s' failed at %s:%d\n", condition, file, line);
  std::abort();
}

Result<void> checkVk(VkResult result, const char* call) {
  if (result == VK_SUCCESS) return {};
  Error error = runtimeError(std::string(call) + " failed: " + vkResultName(result));
  error.deviceLost = result == VK_ERROR_DEVICE_LOST || result == VK_ERROR_SURFACE_LOST_KHR;
  return error;
}

}  // namespace lic3d
