#include "gpu/gpu_timer.h"

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
  timer.device_ = context.device();
  timer.regions_ = regions;
  timer.nanosecondsPerTick_ = context.properties().limits.timestampPeriod;
  const std::uint32_t bits = context.timestampValidBits();
  timer.tickMask_ = bits >= 64 ? ~0ull : (1ull << bits) - 1;
  LIC3D_TRY(checkVk(vkCreateQueryPool(context.device(), &info, nullptr, &timer.pool_),
                    "vkCreateQueryPool"));
  context.setDebugName(timer.pool_, VK_OBJECT_TYPE_QUERY_POOL, name);
  return timer;
}

GpuTimer::GpuTimer(GpuTimer&& other) noexcept
    : device_(std::exchange(other.device_, VK_NULL_HANDLE)),
      pool_(std::exchange(other.pool_, VK_NULL_HANDLE)),
      regions_(other.regions_),
      nanosecondsPerTick_(other.nanosecondsPerTick_),
      tickMask_(other.tickMask_) {}

GpuTimer& GpuTimer::operator=(GpuTimer&& other) noexcept {
  if (this != &other) {
    if (pool_) vkDestroyQueryPool(device_, pool_, nullptr);
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    pool_ = std::exchange(other.pool_, VK_NULL_HANDLE);
    regions_ = other.regions_;
    nanosecondsPerTick_ = other.nanosecondsPerTick_;
    tickMask_ = other.tickMask_;
  }
  return *this;
}

GpuTimer::~GpuTimer() {
  if (pool_) vkDestroyQueryPool(device_, pool_, nullptr);
}

void GpuTimer::reset(VkCommandBuffer cmd, std::uint32_t region) const {
  vkCmdResetQueryPool(cmd, pool_, 2 * region, 2);
}

void GpuTimer::begin(VkCommandBuffer cmd, std::uint32_t region) const {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 2 * region);
}

void GpuTimer::end(VkCommandBuffer cmd, std::uint32_t region) const {
  vkCmdWriteTimestamp2(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, pool_, 2 * region + 1);
}

Result<double> GpuTimer::milliseconds(std::uint32_t region) const {
  std::uint64_t ticks[2] = {0, 0};
  LIC3D_TRY(checkVk(vkGetQueryPoolResults(device_, pool_, 2 * region, 2, sizeof(ticks), ticks,
                                          sizeof(std::uint64_t),
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
