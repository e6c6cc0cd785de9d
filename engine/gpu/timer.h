// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// GPU timestamps around regions of a command buffer: what the benchmark and the stats report.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

class GpuTimer {
 public:
  GpuTimer() = default;
  static Result<GpuTimer> create(const Context& context, std::uint32_t regions,
                                 const std::string& name);

  bool valid() const { return static_cast<bool>(pool_); }
  // Record reset, begin and end of one region in one command buffer, then read it once that
  // command buffer completed.
  void reset(VkCommandBuffer cmd, std::uint32_t region) const;
  void begin(VkCommandBuffer cmd, std::uint32_t region) const;
  void end(VkCommandBuffer cmd, std::uint32_t region) const;
  Result<double> milliseconds(std::uint32_t region) const;

 private:
  DeviceHandle<VkQueryPool, vkDestroyQueryPool> pool_;
  std::uint32_t regions_ = 0;
  double nanosecondsPerTick_ = 1.0;
  std::uint64_t tickMask_ = ~0ull;  // timestampValidBits of the queue
};

// The median of repeated timings (the mean of the two middle ones for an even count; 0 for none).
double median(std::vector<double> values);

}  // namespace lic3d
