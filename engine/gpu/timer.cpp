// SPDX-License-Identifier: BSD-3-Clause
#include "gpu/timer.h"

#include <algorithm>
#include <utility>

#include "gpu/vk_check.h"

namespace lic3d {

Result<GpuTimer> GpuTimer::create(const Context& context, std::uint32_t regions,
                                  const std::string& name) {
  if (!context.supportsTimestamps())
    return unsupportedError(context.deviceInfo().name + " has no timestamp queries on its queue");
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2 * regions;
  GpuTimer timer;
  timer.regions_ = regions;
  timer.nanosecondsPerTick_ = context.properties().limits.timestampPeriod;
  const std::uint32_t bits = context.timestampValidBits();
  timer.tickMask_ = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  VkQueryPool pool = VK_NULL_HANDLE;
  LIC3D_TRY(
      checkVk(vkCreateQueryPool(context.device(), &info, nullptr, &pool), "vkCreateQueryPool"));
  timer.pool_ = {context.device(), pool};
  context.setDebugName(pool, VK_OBJECT_TYPE_QUERY_POOL, name);
  return timer;
}

void GpuTimer::reset(VkCommandBuffer cmd, std::uint32_t region) const {
  vkCmdResetQueryPool(cmd, pool_.get(), 2 * region, 2);
}

void GpuTimer::begin(VkCommandBuffer cmd, std::uint32_t region) const {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_.get(), 2 * region);
}

void GpuTimer::end(VkCommandBuffer cmd, std::uint32_t region) const {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_.get(), 2 * region + 1);
}

Result<double> GpuTimer::milliseconds(std::uint32_t region) const {
  std::uint64_t ticks[2] = {0, 0};
  LIC3D_TRY(checkVk(vkGetQueryPoolResults(pool_.device(), pool_.get(), 2 * region, 2, sizeof(ticks),
                                          ticks, sizeof(std::uint64_t),
                                          VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT),
                    "vkGetQueryPoolResults"));
  const std::uint64_t elapsed = (ticks[1] - ticks[0]) & tickMask_;
  return static_cast<double>(elapsed) * nanosecondsPerTick_ * 1e-6;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace lic3d
