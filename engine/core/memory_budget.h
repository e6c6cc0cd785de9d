// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How much memory a request needs, and whether the device and the host have it, decided before
// anything is allocated. A request that does not fit is an ErrorKind::ResourceLimit error naming
// the request, the bytes needed and available, and the largest cubic grid that would fit.

#include <cstdint>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/field_precision.h"
#include "core/volume.h"

namespace lic3d {

struct MemoryRequest {
  Dims dims{0};
  FieldPrecision precision = FieldPrecision::Half;  // resolved: not Auto
  bool sparsity = false;                            // a sparsity mask (a bit per voxel) too
  bool scalars = false;         // colour or opacity by a scalar other than speed (ScalarTexture)
  bool doubleBuffered = false;  // two LIC volumes (the desktop app recomputes into the second)
  bool volumeReadback = false;  // the LIC volume is read back to the host (`lic3d compute`)
  // A LIC volume made in bricks, gathered on the host and uploaded to be drawn (render over
  // several devices, or a reduced copy: jobs/reduced_volume.h).
  bool licOnHost = false;
  // An unsteady field (docs/TIME.md): two resident time steps and the noise as R32F, from which
  // the GPU writes the field texture; steps are uploaded one at a time instead of the texture.
  bool timeSeries = false;
  int frameWidth = 0;  // 0: no frame (`compute`)
  int frameHeight = 0;
};

// Device memory, Vulkan staging memory (host-visible: system memory on a discrete GPU, the one
// heap of a CPU driver), or plain host memory.
enum class MemoryPlace { Device, Staging, Host };

struct MemoryPart {
  std::string what;
  std::uint64_t bytes = 0;
  MemoryPlace place = MemoryPlace::Device;
};

struct MemoryEstimate {
  std::vector<MemoryPart> parts;
  std::uint64_t deviceBytes = 0;   // device-local at the peak
  std::uint64_t stagingBytes = 0;  // upload and readback buffers
  std::uint64_t hostBytes = 0;     // host copies: the field, the noise, packed texels, images
  std::uint64_t largestImage = 0;  // the largest single Vulkan allocation
};

// Bytes per voxel and per pixel as lic3d allocates them (docs/RELIABILITY.md has the table).
MemoryEstimate estimateMemory(const MemoryRequest& request);

struct MemoryBudget {
  std::uint64_t deviceBytes = 0;     // what the device-local heap can still give
  std::uint64_t hostBytes = 0;       // MemAvailable of the host
  std::uint64_t maxAllocation = 0;   // maxMemoryAllocationSize
  bool unifiedMemory = false;        // a CPU driver: device memory is host memory
  bool fromBudgetExtension = false;  // VK_EXT_memory_budget, else the heap size
  // deviceBytes is the budget the user gave (--memory-budget), below what the device has: the
  // message names that budget rather than the device.
  bool deviceCapped = false;
};

// MemAvailable of /proc/meminfo, else the physical memory; at most what the address-space limit
// (`ulimit -v`) leaves the process.
std::uint64_t hostAvailableBytes();
// Host memory only (no device yet): MemAvailable, else the physical memory.
MemoryBudget hostMemoryBudget();

// ResourceLimit error if `request` does not fit `budget`; `what` names the request in the message.
Result<void> checkMemoryBudget(const MemoryRequest& request, const MemoryBudget& budget,
                               const std::string& what);

// The largest N for which an N^3 grid with the request's other settings fits `budget` (0: none).
int largestCubicGrid(MemoryRequest request, const MemoryBudget& budget);

}  // namespace lic3d
