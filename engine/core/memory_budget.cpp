// SPDX-License-Identifier: BSD-3-Clause
#include "core/memory_budget.h"

#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <optional>

namespace lic3d {
namespace {

constexpr double kMiB = 1.0 / (1 << 20);

// MiB, the unit of device memory, except below 1 MiB, where "0 MiB" would say nothing.
std::string mib(std::uint64_t bytes) {
  char text[32];
  if (bytes < 1024)
    std::snprintf(text, sizeof text, "%llu bytes", static_cast<unsigned long long>(bytes));
  else if (bytes < (1 << 20))
    std::snprintf(text, sizeof text, "%.1f KiB", static_cast<double>(bytes) / 1024.0);
  else
    std::snprintf(text, sizeof text, "%.0f MiB", static_cast<double>(bytes) * kMiB);
  return text;
}

// A CPU driver's one heap holds the device volumes and the staging buffers, and that heap is
// the host's memory; a discrete GPU's staging buffers live in host memory.
std::uint64_t deviceBytesNeeded(const MemoryEstimate& e, const MemoryBudget& b) {
  return b.unifiedMemory ? e.deviceBytes + e.stagingBytes : e.deviceBytes;
}
// maxMemoryAllocationSize is where allocations *may* start to fail: GPU drivers (NVIDIA reports
// 4 GiB) allocate the 8 GiB texture of a 1024^3 field beyond it, so it is a limit for CPU drivers
// only, whose allocations are host allocations; elsewhere a failed allocation is reported as such.
bool singleAllocationLimited(const MemoryBudget& b) {
  return b.unifiedMemory && b.maxAllocation > 0;
}
std::uint64_t hostBytesNeeded(const MemoryEstimate& e, const MemoryBudget& b) {
  return e.hostBytes + e.stagingBytes + (b.unifiedMemory ? e.deviceBytes : 0);
}

}  // namespace

namespace {

// What the address-space limit (`ulimit -v`, RLIMIT_AS) leaves this process, or nothing when
// there is none.
std::optional<std::uint64_t> addressSpaceLeft() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  unsigned long long pages = 0;
  if (std::FILE* f = std::fopen("/proc/self/statm", "r")) {
    if (std::fscanf(f, "%llu", &pages) != 1) pages = 0;
    std::fclose(f);
  }
  const std::uint64_t used =
      static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(sysconf(_SC_PAGE_SIZE));
  const auto cap = static_cast<std::uint64_t>(limit.rlim_cur);
  return cap > used ? cap - used : 0;
}

// MemAvailable from /proc/meminfo, else physical pages.
std::uint64_t memAvailableBytes() {
  if (std::FILE* f = std::fopen("/proc/meminfo", "r")) {
    char line[256];
    unsigned long long kib = 0;
    bool found = false;
    while (std::fgets(line, sizeof line, f))
      if (std::sscanf(line, "MemAvailable: %llu kB", &kib) == 1) {
        found = true;
        break;
      }
    std::fclose(f);
    if (found) return static_cast<std::uint64_t>(kib) * 1024u;
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0
             ? static_cast<std::uint64_t>(pages) * static_cast<std::uint64_t>(page)
             : 0;
}

}  // namespace

// MemAvailable (what the host can give without swapping), within what `ulimit -v` leaves.
std::uint64_t hostAvailableBytes() {
  const std::uint64_t available = memAvailableBytes();
  const std::optional<std::uint64_t> left = addressSpaceLeft();
  return left ? std::min(available, *left) : available;
}

MemoryEstimate estimateMemory(const MemoryRequest& r) {
  MemoryEstimate e;
  const std::uint64_t voxels = voxelCount(r.dims);
  const std::uint64_t texel = fieldTexelBytes(r.precision);
  constexpr MemoryPlace device = MemoryPlace::Device, staging = MemoryPlace::Staging,
                        host = MemoryPlace::Host;
  auto add = [&](std::string what, std::uint64_t bytes, MemoryPlace place) {
    e.parts.push_back({std::move(what), bytes, place});
    (place == device ? e.deviceBytes : place == staging ? e.stagingBytes : e.hostBytes) += bytes;
    if (place != host) e.largestImage = std::max(e.largestImage, bytes);
  };
  // Host: the field as read (3 floats), the noise (one byte), the packed texels and their
  // staging buffer while uploading.
  add("field vectors (host)", voxels * 12, host);
  add("noise (host)", voxels, host);
  if (r.timeSeries) {
    // Steps keep 16 bits per component at least (time_blend_pass.h); one is read and
    // uploaded at a time, and the noise goes up once as float.
    const std::uint64_t step = r.precision == FieldPrecision::Float ? 16 : 8;
    const char* format = r.precision == FieldPrecision::Float ? "RGBA32F" : "RGBA16F";
    add("packed time step texels (host)", voxels * step, host);
    add("time step upload staging", voxels * step, staging);
    for (const char* which : {"first", "second"})
      add(std::string(which) + " resident time step (" + format + ")", voxels * step, device);
    add("time series noise (R32F)", voxels * 4, device);
    add("time series noise as float (host)", voxels * 4, host);
  } else {
    add("packed field texels (host)", voxels * texel, host);
    add("upload staging", voxels * texel, staging);
  }
  // Device: the packed field+noise texture, the LIC volume(s) (RG16: value, drawn), the mask.
  add("field+noise texture (" + std::string(fieldTextureFormatName(r.precision)) + ")",
      voxels * texel, device);
  add("LIC volume (RG16)", voxels * 4, device);
  if (r.doubleBuffered) add("second LIC volume (RG16)", voxels * 4, device);
  if (r.sparsity) {
    // A bit per voxel on the device (shaders/sparsity_mask.h); a mask made on the CPU is a byte
    // per voxel there, then packed and uploaded.
    const std::uint64_t bits = (voxels + 7) / 8;
    add("sparsity mask (1 bit per voxel)", bits, device);
    add("sparsity mask (host)", voxels + bits, host);
    add("sparsity mask upload staging", bits, staging);
  }
  if (r.scalars) {
    add("colour and opacity scalars (RG16F)", voxels * 4, device);
    add("colour and opacity scalars (host, float32)", voxels * 8, host);
  }
  if (r.volumeReadback) {
    add("LIC volume readback", voxels * 4, staging);
    add("LIC volume as float32 (host)", voxels * 4, host);
  }
  if (r.licOnHost) {
    add("LIC volume gathered from bricks (host, float32 and drawn)", voxels * 5, host);
    add("LIC volume upload staging", voxels * 4, staging);
  }
  if (r.frameWidth > 0 && r.frameHeight > 0) {
    const std::uint64_t pixels =
        static_cast<std::uint64_t>(r.frameWidth) * static_cast<std::uint64_t>(r.frameHeight);
    add("frame (RGBA16F)", pixels * 8, device);
    add("frame readback", pixels * 8, staging);
    add("frame image (host)", pixels * 4, host);
  }
  return e;
}

MemoryBudget hostMemoryBudget() {
  MemoryBudget b;
  b.hostBytes = hostAvailableBytes();
  return b;
}

Result<void> checkMemoryBudget(const MemoryRequest& request, const MemoryBudget& budget,
                               const std::string& what) {
  const MemoryEstimate e = estimateMemory(request);
  const std::uint64_t deviceNeeded = deviceBytesNeeded(e, budget);
  const std::uint64_t hostNeeded = hostBytesNeeded(e, budget);
  std::string problem;
  if (budget.deviceBytes > 0 && deviceNeeded > budget.deviceBytes)
    problem =
        "needs " + mib(deviceNeeded) + " of device memory; " +
        (budget.deviceCapped ? "the memory budget given is " + mib(budget.deviceBytes) +
                                   (budget.deviceBytes < 1024
                                        ? ""
                                        : " (" + std::to_string(budget.deviceBytes) + " bytes)")
                             : "the device has " + mib(budget.deviceBytes) +
                                   (budget.fromBudgetExtension ? " free" : ""));
  else if (budget.hostBytes > 0 && hostNeeded > budget.hostBytes)
    problem =
        "needs " + mib(hostNeeded) + " of host memory; " + mib(budget.hostBytes) + " are available";
  else if (singleAllocationLimited(budget) && e.largestImage > budget.maxAllocation)
    problem = "needs a single allocation of " + mib(e.largestImage) + "; the device allows " +
              mib(budget.maxAllocation);
  if (problem.empty()) return {};
  const int largest = largestCubicGrid(request, budget);
  return resourceLimitError(
      what + " (" + gridText(request.dims) + ") " + problem +
      (largest > 0 ? "; the largest cubic grid that fits is " + std::to_string(largest) + "^3"
                   : ""));
}

int largestCubicGrid(MemoryRequest request, const MemoryBudget& budget) {
  auto fits = [&](int n) {
    request.dims = Dims{n, n, n};
    const MemoryEstimate e = estimateMemory(request);
    return (budget.deviceBytes == 0 || deviceBytesNeeded(e, budget) <= budget.deviceBytes) &&
           (budget.hostBytes == 0 || hostBytesNeeded(e, budget) <= budget.hostBytes) &&
           (!singleAllocationLimited(budget) || e.largestImage <= budget.maxAllocation);
  };
  int low = 0, high = 1 << 14;  // fits(low) holds (or low == 0); fits(high) does not
  if (fits(high)) return high;
  while (high - low > 1) {
    const int mid = low + (high - low) / 2;
    (fits(mid) ? low : high) = mid;
  }
  return low;
}

}  // namespace lic3d
