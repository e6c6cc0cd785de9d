// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Which of the listed Vulkan devices (listDevices) a request runs on: one (--device, the
// ParaView filter's Device) or several (--devices, docs/SCALE.md "Several GPUs").
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

// "" picks the best usable device (discrete, then integrated, then virtual, then CPU); a number
// picks that index; anything else the first device whose name contains it (case-insensitively).
// An unknown or unusable device is an error listing what was found.
Result<int> chooseDevice(const std::vector<DeviceInfo>& devices, const std::string& selector);

// "all": every usable device of the best type present (every discrete GPU of a node; lavapipe
// alone where there is no GPU). Else a comma-separated list of selectors as chooseDevice takes
// them, each naming a different device. The indices in the order given.
Result<std::vector<int>> chooseDevices(const std::vector<DeviceInfo>& devices,
                                       std::string_view selectors);

}  // namespace lic3d
