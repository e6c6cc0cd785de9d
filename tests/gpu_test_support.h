#pragma once
// A fixture for tests that use the GPU: a Vulkan context with validation and synchronization
// validation on; any validation message fails the test.

#include <optional>

#include <gtest/gtest.h>

#include "volume.h"
#include "vulkan_context.h"

namespace lic3d::test {

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  const Context& context() const { return *context_; }

 private:
  std::optional<Context> context_;
};

struct VolumeDifference {
  double mean = 0.0;
  double max = 0.0;
  double quantile999 = 0.0;  // 99.9th percentile of |a - b|
  std::size_t argMax = 0;
};

VolumeDifference compareVolumes(const ScalarVolume& a, const ScalarVolume& b);

}  // namespace lic3d::test
