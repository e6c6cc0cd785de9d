// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Programming errors abort loudly with file, line and VkResult. Calls that can fail for reasons
// outside the program (allocation, submission, device loss) return Result values instead: see
// checkVk().

#include <vulkan/vulkan.h>

#include <string>

#include "core/error.h"

namespace lic3d {

const char* vkResultName(VkResult result);

[[noreturn]] void abortOnVkError(const char* call, VkResult result, const char* file, int line);
[[noreturn]] void abortOnAssert(const char* condition, const char* file, int line);

// Turns a VkResult of a call that may legitimately fail into a Result naming the call.
Result<void> checkVk(VkResult result, const char* call);

}  // namespace lic3d

#define LIC3D_VK_CHECK(call)                                             \
  do {                                                                   \
    const VkResult lic3dVkResult = (call);                               \
    if (lic3dVkResult != VK_SUCCESS)                                     \
      ::lic3d::abortOnVkError(#call, lic3dVkResult, __FILE__, __LINE__); \
  } while (false)

#define LIC3D_ASSERT(condition)                                               \
  do {                                                                        \
    if (!(condition)) ::lic3d::abortOnAssert(#condition, __FILE__, __LINE__); \
  } while (false)
