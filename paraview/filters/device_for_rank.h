// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Which Vulkan device each process of a node takes when the filter's Device property is empty:
// the processes of one node share out its devices by node-local rank, one GPU each on a node with
// as many GPUs as processes. Pure functions of lic3d::listDevices()'s answer, so tests can hand in
// any list of devices.

#include <string>
#include <vector>

#include "gpu/vulkan_context.h"

namespace lic3d::paraview {

// The devices the processes of a node share out: the usable ones of the best kind present, in
// lic3d's ranking (discrete GPUs if there is one, else integrated, else virtual, else CPU), as
// indices of `devices` in its order (that of `lic3d devices`). Lesser kinds are left out, as
// lic3d's own choice leaves them out: a process given the integrated GPU or lavapipe beside
// discrete GPUs would take many times longer than the others and hold every process back.
std::vector<int> devicesToShare(const std::vector<DeviceInfo>& devices);

// Which of `deviceCount` devices the process of node-local rank `localRank` takes: round robin,
// so 8 processes on 4 devices take 0, 1, 2, 3, 0, 1, 2, 3. -1 when there is no device.
int deviceForLocalRank(int localRank, int deviceCount);

// The selector (ContextOptions::device, an index of `devices`) for the process of node-local rank
// `localRank`. "" when no device is usable: lic3d's own choice then says why. Node-local rank 0
// gets the device lic3d would choose on its own.
std::string deviceSelectorForLocalRank(const std::vector<DeviceInfo>& devices, int localRank);

}  // namespace lic3d::paraview
