// SPDX-License-Identifier: BSD-3-Clause
// `lic3d devices`: the Vulkan devices and why any is unusable.
#include <cstdio>

#include "cli/commands.h"
#include "gpu/device_choice.h"
#include "gpu/vulkan_context.h"

namespace lic3d::cli {

int runDevices(const GlobalOptions& global) {
  (void)global;
  const Result<std::vector<DeviceInfo>> devices = listDevices();
  if (!devices) return reportError(devices.error());
  if (devices->empty()) {
    std::fprintf(stderr, "lic3d: no Vulkan device found\n");
    return kExitFailure;
  }
  for (const DeviceInfo& d : *devices) {
    std::printf("%d: %s (%s, Vulkan %u.%u, %s, %.1f GiB device-local)%s%s\n", d.index,
                d.name.c_str(), deviceTypeName(d.type), VK_API_VERSION_MAJOR(d.apiVersion),
                VK_API_VERSION_MINOR(d.apiVersion), d.driver.c_str(),
                static_cast<double>(d.deviceLocalBytes) / (1024.0 * 1024.0 * 1024.0),
                d.usable ? "" : " - unusable: ", d.usable ? "" : d.unusableReason.c_str());
  }
  return kExitOk;
}

}  // namespace lic3d::cli
