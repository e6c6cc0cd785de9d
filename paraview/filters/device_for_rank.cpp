// SPDX-License-Identifier: BSD-3-Clause
#include "device_for_rank.h"

#include "gpu/device_choice.h"

namespace lic3d::paraview {

std::vector<int> devicesToShare(const std::vector<DeviceInfo>& devices) {
  // lic3d's own "all" (gpu/device_choice.h); none when no device is usable.
  Result<std::vector<int>> shared = chooseDevices(devices, "all");
  return shared ? std::move(*shared) : std::vector<int>();
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
