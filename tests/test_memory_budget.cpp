// SPDX-License-Identifier: BSD-3-Clause
// The memory estimate of a request and the refusal of requests that do not fit, before anything
// is allocated.
#include <gtest/gtest.h>

#include <string>

#include "core/memory_budget.h"

namespace lic3d {
namespace {

constexpr std::uint64_t kMiB = 1u << 20;

TEST(MemoryBudget, EstimateCountsEveryResidentVolume) {
  MemoryRequest r;
  r.dims = Dims{100, 100, 100};
  r.precision = FieldPrecision::Half;
  MemoryEstimate e = estimateMemory(r);
  // Device: RGBA16F field+noise (8 B) and the RG16 LIC volume (4 B) per voxel.
  EXPECT_EQ(e.deviceBytes, 1'000'000u * 12);
  // Host: vectors (12), noise (1), packed texels (8); staging for the upload (8).
  EXPECT_EQ(e.hostBytes, 1'000'000u * 21);
  EXPECT_EQ(e.stagingBytes, 1'000'000u * 8);

  r.precision = FieldPrecision::Float;
  r.sparsity = true;
  r.doubleBuffered = true;
  e = estimateMemory(r);
  // The sparsity mask: a bit per voxel.
  EXPECT_EQ(e.deviceBytes, 1'000'000u * (16 + 4 + 4) + 125'000u);
  EXPECT_EQ(e.largestImage, 1'000'000u * 16);

  r.frameWidth = 1000;
  r.frameHeight = 500;
  EXPECT_EQ(estimateMemory(r).deviceBytes, e.deviceBytes + 500'000u * 8);
}

// A LIC made in bricks and drawn (render over several devices, or a reduced copy) is gathered on
// the host and uploaded again: the host and staging memory of that copy are part of the request,
// so that the reduction factor is chosen for the host as well as the device, before the LIC.
TEST(MemoryBudget, ALicGatheredOnTheHostCountsItsCopyAndItsUpload) {
  MemoryRequest r;
  r.dims = Dims{100, 100, 100};
  r.frameWidth = 64;
  r.frameHeight = 64;
  const MemoryEstimate drawn = estimateMemory(r);
  r.licOnHost = true;
  const MemoryEstimate gathered = estimateMemory(r);
  EXPECT_EQ(gathered.hostBytes, drawn.hostBytes + 1'000'000u * 5);        // float32 and drawn
  EXPECT_EQ(gathered.stagingBytes, drawn.stagingBytes + 1'000'000u * 4);  // RG16 upload
  EXPECT_EQ(gathered.deviceBytes, drawn.deviceBytes);

  // A host that holds the draw but not the copy refuses it, with both numbers.
  MemoryBudget budget;
  budget.deviceBytes = 1024 * kMiB;
  budget.hostBytes = drawn.hostBytes + drawn.stagingBytes + 1'000'000u;
  EXPECT_TRUE(checkMemoryBudget({.dims = r.dims, .frameWidth = 64, .frameHeight = 64}, budget,
                                "the LIC of tornado")
                  .ok());
  const Result<void> refused = checkMemoryBudget(r, budget, "the LIC of tornado");
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().kind, ErrorKind::ResourceLimit);
  EXPECT_NE(refused.error().message.find("of host memory"), std::string::npos)
      << refused.error().message;
}

TEST(MemoryBudget, TooLargeIsAResourceLimitNamingTheRequestAndTheLargestGridThatFits) {
  MemoryBudget budget;
  budget.deviceBytes = 100 * kMiB;
  budget.hostBytes = 1000 * kMiB;
  MemoryRequest r;
  r.dims = Dims{512, 512, 512};
  const Result<void> refused = checkMemoryBudget(r, budget, "the LIC of tornado");
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::ResourceLimit);
  const std::string& m = refused.error().message;
  EXPECT_NE(m.find("the LIC of tornado (512x512x512)"), std::string::npos) << m;
  EXPECT_NE(m.find("1536 MiB of device memory"), std::string::npos) << m;
  EXPECT_NE(m.find("100 MiB"), std::string::npos) << m;

  const int n = largestCubicGrid(r, budget);
  EXPECT_NE(m.find("largest cubic grid that fits is " + std::to_string(n) + "^3"),
            std::string::npos)
      << m;
  // 12 bytes per voxel on the device: 100 MiB holds 205^3 but not 206^3.
  EXPECT_EQ(n, 205);
  r.dims = Dims{n, n, n};
  EXPECT_TRUE(checkMemoryBudget(r, budget, "x"));
  r.dims = Dims{n + 1, n + 1, n + 1};
  EXPECT_FALSE(checkMemoryBudget(r, budget, "x"));
}

TEST(MemoryBudget, HostMemoryAndSingleAllocationsAreLimitsToo) {
  MemoryBudget budget;
  budget.deviceBytes = 1u << 30;
  budget.hostBytes = 64 * kMiB;
  MemoryRequest r;
  r.dims = Dims{128, 128, 128};  // 2 Mi voxels: 42 MiB host, 16 MiB staging, 24 MiB device
  EXPECT_TRUE(checkMemoryBudget(r, budget, "x"));
  // On a CPU driver device memory comes out of the same pool: 58 + 24 MiB no longer fit.
  budget.unifiedMemory = true;
  const Result<void> unified = checkMemoryBudget(r, budget, "x");
  ASSERT_FALSE(unified);
  EXPECT_NE(unified.error().message.find("host memory"), std::string::npos);

  // A CPU driver's maxMemoryAllocationSize is a limit (the 16 MiB field texture is one
  // allocation); a GPU's is not: GPU drivers allocate beyond it.
  budget.hostBytes = 0;  // unknown: not a limit
  budget.maxAllocation = 8 * kMiB;
  const Result<void> single = checkMemoryBudget(r, budget, "x");
  ASSERT_FALSE(single);
  EXPECT_NE(single.error().message.find("single allocation of 16 MiB"), std::string::npos)
      << single.error().message;
  budget.unifiedMemory = false;
  EXPECT_TRUE(checkMemoryBudget(r, budget, "x"));
}

}  // namespace
}  // namespace lic3d
