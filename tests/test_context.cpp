// SPDX-License-Identifier: BSD-3-Clause
// Device discovery and selection, and the no-device error.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <regex>
#include <string>

#include "gpu/vulkan_context.h"
#include "gpu_test_support.h"

namespace lic3d {
namespace {

TEST(Devices, ListIncludesAUsableDevice) {
  const Result<std::vector<DeviceInfo>> devices = listDevices();
  ASSERT_TRUE(devices.ok()) << devices.error().message;
  ASSERT_FALSE(devices->empty());
  bool usable = false;
  for (const DeviceInfo& d : *devices) {
    EXPECT_FALSE(d.name.empty());
    usable = usable || d.usable;
  }
  EXPECT_TRUE(usable);
}

using test::GpuTest;

TEST_F(GpuTest, ContextHasAQueueThatDoesGraphicsAndCompute) {
  EXPECT_NE(context().device(), VK_NULL_HANDLE);
  EXPECT_NE(context().queue(), VK_NULL_HANDLE);
  EXPECT_TRUE(context().validationEnabled());
  EXPECT_TRUE(context().deviceInfo().usable);
  EXPECT_GE(context().deviceInfo().apiVersion, VK_API_VERSION_1_3);
}

TEST(Devices, SelectByIndexAndByName) {
  const std::vector<DeviceInfo> devices = *listDevices();
  ContextOptions byIndex;
  byIndex.device = "0";
  const Result<Context> first = Context::create(byIndex);
  ASSERT_TRUE(first.ok()) << first.error().message;
  EXPECT_EQ(first->deviceInfo().name, devices[0].name);

  ContextOptions byName;
  byName.device = devices[0].name.substr(0, 4);  // part of the name, any case
  for (char& c : byName.device) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  const Result<Context> named = Context::create(byName);
  ASSERT_TRUE(named.ok()) << named.error().message;
  EXPECT_EQ(named->deviceInfo().name, devices[0].name);
}

TEST(Devices, UnknownSelectorIsAnInputErrorListingTheDevices) {
  const std::vector<DeviceInfo> devices = *listDevices();
  for (const std::string selector : {"no-such-gpu", "99"}) {
    ContextOptions options;
    options.device = selector;
    const Result<Context> context = Context::create(options);
    ASSERT_FALSE(context.ok()) << selector;
    EXPECT_EQ(context.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(context.error().message.find(devices[0].name), std::string::npos)
        << context.error().message;
  }
}

// The text of a file, empty where it cannot be read.
std::string fileText(const std::string& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Devices, TheDriverStaysLoadedOnceTheLastContextIsGone) {
  // A driver loaded again for each context takes memory it never gives back (NVIDIA's static
  // TLS), until no context finds a driver: it stays mapped, loaded once, for the process's life.
  const char* driverFiles = std::getenv("VK_DRIVER_FILES");
  if (!driverFiles) GTEST_SKIP() << "VK_DRIVER_FILES names no driver to look for";
  std::smatch library;
  const std::string manifest = fileText(driverFiles);
  ASSERT_TRUE(
      std::regex_search(manifest, library, std::regex("\"library_path\"\\s*:\\s*\"([^\"]+)\"")))
      << driverFiles;
  const std::string name = std::filesystem::path(library[1].str()).filename().string();
  for (int i = 0; i < 3; ++i) {
    const Result<Context> context = Context::create({});
    ASSERT_TRUE(context.ok()) << context.error().message;
    EXPECT_NE(fileText("/proc/self/maps").find(name), std::string::npos);
  }
  EXPECT_NE(fileText("/proc/self/maps").find(name), std::string::npos)
      << name << " was unloaded with the last context";
}

TEST(Devices, NoDriverGivesAClearError) {
  // The loader reads VK_DRIVER_FILES at each instance creation; this test runs in its own
  // process (ctest runs each test separately), so changing it here affects nothing else.
  ASSERT_EQ(setenv("VK_DRIVER_FILES", "/nonexistent/lic3d_icd.json", 1), 0);
  const Result<Context> context = Context::create({});
  ASSERT_FALSE(context.ok());
  EXPECT_EQ(context.error().kind, ErrorKind::Unsupported);
  EXPECT_NE(context.error().message.find("no Vulkan"), std::string::npos)
      << context.error().message;
  const Result<std::vector<DeviceInfo>> devices = listDevices();
  EXPECT_TRUE(!devices.ok() || devices->empty());
}

}  // namespace
}  // namespace lic3d
