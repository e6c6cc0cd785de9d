// SPDX-License-Identifier: BSD-3-Clause
// How the processes of one node share out its Vulkan devices when the filter's Device property is
// empty (paraview/filters/device_for_rank.h), on lists of devices made up for the purpose.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "device_for_rank.h"

namespace lic3d::paraview {
namespace {

DeviceInfo device(int index, VkPhysicalDeviceType type, bool usable = true) {
  DeviceInfo info;
  info.index = index;
  info.name = "device " + std::to_string(index);
  info.type = type;
  info.usable = usable;
  return info;
}

constexpr VkPhysicalDeviceType kDiscrete = VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
constexpr VkPhysicalDeviceType kIntegrated = VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU;
constexpr VkPhysicalDeviceType kCpu = VK_PHYSICAL_DEVICE_TYPE_CPU;

std::vector<std::string> selectorsOfRanks(const std::vector<DeviceInfo>& devices, int ranks) {
  std::vector<std::string> selectors;
  for (int rank = 0; rank < ranks; ++rank) {
    selectors.push_back(deviceSelectorForLocalRank(devices, rank));
  }
  return selectors;
}

TEST(DeviceForRank, RanksGoRoundTheDevices) {
  const std::vector<int> expected{0, 1, 2, 3, 0, 1, 2, 3};
  for (int rank = 0; rank < 8; ++rank) {
    EXPECT_EQ(deviceForLocalRank(rank, 4), expected[static_cast<std::size_t>(rank)]) << rank;
  }
  EXPECT_EQ(deviceForLocalRank(5, 1), 0);
  EXPECT_EQ(deviceForLocalRank(0, 0), -1);
}

TEST(DeviceForRank, FourGpusAndEightRanks) {
  const std::vector<DeviceInfo> devices{device(0, kDiscrete), device(1, kDiscrete),
                                        device(2, kDiscrete), device(3, kDiscrete)};
  EXPECT_EQ(selectorsOfRanks(devices, 8),
            (std::vector<std::string>{"0", "1", "2", "3", "0", "1", "2", "3"}));
}

TEST(DeviceForRank, OnlyTheBestKindIsSharedOut) {
  // The loader's order: lavapipe first, then an integrated GPU between two discrete ones.
  const std::vector<DeviceInfo> devices{device(0, kCpu), device(1, kDiscrete),
                                        device(2, kIntegrated), device(3, kDiscrete)};
  EXPECT_EQ(devicesToShare(devices), (std::vector<int>{1, 3}));
  EXPECT_EQ(selectorsOfRanks(devices, 4), (std::vector<std::string>{"1", "3", "1", "3"}));
}

TEST(DeviceForRank, UnusableDevicesAreLeftOut) {
  // A discrete GPU that cannot run lic3d (too old a driver) does not count: the integrated ones do.
  const std::vector<DeviceInfo> devices{device(0, kDiscrete, false), device(1, kIntegrated),
                                        device(2, kCpu), device(3, kIntegrated)};
  EXPECT_EQ(devicesToShare(devices), (std::vector<int>{1, 3}));
  EXPECT_EQ(selectorsOfRanks(devices, 3), (std::vector<std::string>{"1", "3", "1"}));
}

TEST(DeviceForRank, OneDeviceServesEveryRank) {
  // lavapipe alone (CI) or one GPU bound to each task by the scheduler: every rank gets it.
  const std::vector<DeviceInfo> devices{device(0, kCpu)};
  EXPECT_EQ(selectorsOfRanks(devices, 3), (std::vector<std::string>{"0", "0", "0"}));
}

TEST(DeviceForRank, NoUsableDeviceLeavesTheChoiceToLic3d) {
  EXPECT_EQ(deviceSelectorForLocalRank({}, 0), "");
  EXPECT_EQ(deviceSelectorForLocalRank({device(0, kDiscrete, false)}, 1), "");
}

}  // namespace
}  // namespace lic3d::paraview
