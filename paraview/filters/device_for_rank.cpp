// SPDX-License-Identifier: BSD-3-Clause
#include "device_for_rank.h"

namespace lic3d::paraview {
namespace {

// lic3d's ranking of device kinds (ContextOptions::device: discrete, integrated, virtual, CPU).
int kindRank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

}  // namespace

std::vector<int> devicesToShare(const std::vector<DeviceInfo>& devices) {
  int best = -1;
  for (const DeviceInfo& d : devices) {
    if (d.usable && kindRank(d.type) > best) {
      best = kindRank(d.type);
    }
  }
  std::vector<int> shared;
  for (const DeviceInfo& d : devices) {
    if (d.usable && kindRank(d.type) == best) {
      shared.push_back(d.index);
    }
  }
  return shared;
}

int deviceForLocalRank(int localRank, int deviceCount) {
  if (deviceCount <= 0) {
    return -1;
  }
  return (localRank % deviceCount + deviceCount) % deviceCount;
}

std::string deviceSelectorForLocalRank(const std::vector<DeviceInfo>& devices, int localRank) {
  const std::vector<int> shared = devicesToShare(devices);
  const int chosen = deviceForLocalRank(localRank, static_cast<int>(shared.size()));
  return chosen < 0 ? std::string() : std::to_string(shared[static_cast<std::size_t>(chosen)]);
}

}  // namespace lic3d::paraview
