// SPDX-License-Identifier: BSD-3-Clause
// Bricks spread over devices (jobs/bricks.h, gpu/device_choice.h): which devices --devices
// names, how workers share the bricks, analytic bricks made on the device, and two contexts on
// lavapipe giving one context's volume.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <thread>
#include <vector>

#include "gpu/device_choice.h"
#include "gpu_test_support.h"
#include "jobs/bricks.h"
#include "lic/analytic_fields.h"
#include "lic/field_piece.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "loading/session_inputs.h"

namespace lic3d {
namespace {

using test::GpuTest;

DeviceInfo fakeDevice(int index, const char* name, VkPhysicalDeviceType type, bool usable = true) {
  DeviceInfo d;
  d.index = index;
  d.name = name;
  d.type = type;
  d.usable = usable;
  if (!usable) d.unusableReason = "no Vulkan 1.3";
  return d;
}

// A node of four GPUs (one unusable), an integrated GPU and lavapipe.
std::vector<DeviceInfo> fakeNode() {
  return {fakeDevice(0, "llvmpipe (LLVM 15.0.6, 256 bits)", VK_PHYSICAL_DEVICE_TYPE_CPU),
          fakeDevice(1, "NVIDIA H100 80GB HBM3", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU),
          fakeDevice(2, "Intel(R) UHD Graphics", VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU),
          fakeDevice(3, "NVIDIA H100 80GB HBM3", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU),
          fakeDevice(4, "NVIDIA H100 80GB HBM3", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, false),
          fakeDevice(5, "NVIDIA H100 80GB HBM3", VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU)};
}

TEST(DeviceChoice, AllIsEveryUsableDeviceOfTheBestType) {
  const Result<std::vector<int>> all = chooseDevices(fakeNode(), "all");
  ASSERT_TRUE(all) << all.error().message;
  EXPECT_EQ(*all, (std::vector<int>{1, 3, 5}));
  // Without a GPU: the CPU driver alone, as on CI.
  const Result<std::vector<int>> cpu = chooseDevices({fakeNode()[0]}, "all");
  ASSERT_TRUE(cpu);
  EXPECT_EQ(*cpu, std::vector<int>{0});
}

TEST(DeviceChoice, AListNamesDevicesByIndexOrNamePartInItsOrder) {
  const Result<std::vector<int>> listed = chooseDevices(fakeNode(), "5,1,uhd");
  ASSERT_TRUE(listed) << listed.error().message;
  EXPECT_EQ(*listed, (std::vector<int>{5, 1, 2}));
  for (const char* bad : {"1,1", "h100,1", "9", "1,", "", "4"}) {
    const Result<std::vector<int>> refused = chooseDevices(fakeNode(), bad);
    ASSERT_FALSE(refused) << bad;
    EXPECT_NE(refused.error().kind, ErrorKind::Runtime) << bad;
  }
  EXPECT_NE(chooseDevices(fakeNode(), "1,1").error().message.find("named twice"),
            std::string::npos);
}

TEST(Bricks, SplittingForDevicesGivesEachDeviceABrick) {
  const Dims whole{64, 48, 40};
  for (int count : {1, 2, 3, 4, 8}) {
    const Dims core = splitCoreForDevices(whole, whole, count);
    EXPECT_GE(planBricks(whole, core, 2).size(), static_cast<std::size_t>(count)) << count;
  }
  EXPECT_EQ(splitCoreForDevices(whole, whole, 1), whole);
}

// Workers (devices) take the next brick not yet taken: each brick is made once, by some
// worker, and the result is one worker's, whatever the share.
TEST(Bricks, WorkersShareTheBricksAndGiveOneWorkersResult) {
  const VectorField tornado = makeAnalyticField(AnalyticField::Tornado, {30, 26, 22});
  LicParams params;
  params.length = 8;
  NoiseSource noise;
  noise.seed = 3;
  const std::vector<Brick> bricks = planBricks(tornado.dims, {8, 8, 8}, licGhostLayers(params));
  const double maxSpeed = maxVoxelSpeedOverVoxels(tornado);
  ScalarVolume one, three;
  for (ScalarVolume* result : {&one, &three}) {
    result->dims = tornado.dims;
    result->values.assign(voxelCount(tornado.dims), -1.0f);
  }
  const auto jobsFor = [&](ScalarVolume& result, std::vector<int>& made) {
    BrickJobs jobs;
    jobs.prepare = [&](const Brick& brick) -> Result<PieceInputs> {
      LIC3D_TRY_ASSIGN(VectorField piece,
                       cutFieldPiece(tornado, brick.offset, brick.dims, maxSpeed));
      return PieceInputs{std::move(piece),
                         makeWhiteNoisePiece(tornado.dims, brick.offset, brick.dims, 3)};
    };
    jobs.lic = [&, params](int worker, const Brick&, std::optional<PieceInputs> in) {
      // Uneven workers: the shares differ, the result must not.
      std::this_thread::sleep_for(std::chrono::milliseconds(worker));
      return computeLicReference(in->field, in->noise, params);
    };
    jobs.take = [&](const Brick& brick, const ScalarVolume& lic) -> Result<void> {
      copyOwnVoxels(brick, lic, result);
      made.push_back(static_cast<int>(&brick - bricks.data()));
      return {};
    };
    return jobs;
  };
  std::vector<int> madeOne, madeThree;
  const Result<std::vector<int>> workersOne = runBricks(1, bricks, jobsFor(one, madeOne));
  const Result<std::vector<int>> workersThree = runBricks(3, bricks, jobsFor(three, madeThree));
  ASSERT_TRUE(workersOne && workersThree);
  EXPECT_EQ(one.values, three.values);
  EXPECT_EQ(std::count(one.values.begin(), one.values.end(), -1.0f), 0);
  std::sort(madeThree.begin(), madeThree.end());
  EXPECT_EQ(madeThree.size(), bricks.size());
  EXPECT_EQ(std::set<int>(madeThree.begin(), madeThree.end()).size(), bricks.size());
  for (const int worker : *workersThree) EXPECT_TRUE(worker >= 0 && worker < 3);
  // The first error stops the run and is returned.
  BrickJobs failing = jobsFor(three, madeThree);
  failing.lic = [](int, const Brick& brick, std::optional<PieceInputs>) -> Result<ScalarVolume> {
    if (brick.ownOffset == Dims(8)) return runtimeError("device lost");
    return ScalarVolume();
  };
  failing.take = [](const Brick&, const ScalarVolume&) -> Result<void> { return {}; };
  const Result<std::vector<int>> failed = runBricks(3, bricks, failing);
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().message, "device lost");
}

test::VolumeDifference differenceOf(const Result<LicVolumeRun>& a, const Result<LicVolumeRun>& b) {
  return test::compareVolumes(a->volume, b->volume);
}

// An analytic field with white noise is made on the device brick by brick: nothing of it on the
// host, and the whole grid's LIC within the bounds of bricks.
TEST_F(GpuTest, AnalyticBricksAreMadeOnTheDevice) {
  Session session;
  session.field.grid = {40, 32, 24};
  session.lic.length = 12;
  session.precision = FieldPrecision::Float;
  Result<SessionInputs> onDevice = loadSessionInputs(session, {.fieldOnDevice = true});
  Result<SessionInputs> onHost = loadSessionInputs(session);
  ASSERT_TRUE(onDevice && onHost);
  ASSERT_TRUE(onDevice->device.has_value());
  EXPECT_TRUE(onDevice->field.vectors.empty());
  const Result<LicVolumeRun> whole = computeLicVolume(context(), session, *onDevice, 0);
  const Result<LicVolumeRun> bricked = computeLicVolume(context(), session, *onDevice, 400000);
  const Result<LicVolumeRun> hostBricks = computeLicVolume(context(), session, *onHost, 400000);
  ASSERT_TRUE(whole && bricked && hostBricks) << (bricked ? "" : bricked.error().message);
  EXPECT_EQ(whole->bricks, 1);
  EXPECT_GT(bricked->bricks, 1);
  EXPECT_EQ(bricked->bricks, hostBricks->bricks);
  const test::VolumeDifference toWhole = differenceOf(whole, bricked);
  EXPECT_LE(toWhole.mean, 1e-3);
  EXPECT_LE(toWhole.quantile999, 2e-2);
  // The same bricks cut from the host's field (double precision): float rounding apart.
  const test::VolumeDifference toHost = differenceOf(hostBricks, bricked);
  EXPECT_LE(toHost.mean, 1e-3);
  EXPECT_LE(toHost.quantile999, 2e-2);
}

// Two contexts (here both on lavapipe) share the bricks; the volume is one context's, bit for
// bit, and each context's share is reported. A grid that fits one device is still split so that
// each gets a brick.
TEST_F(GpuTest, TwoDevicesGiveOneDevicesVolume) {
  ContextOptions options;
  options.validation = true;
  Result<Context> second = Context::create(options);
  ASSERT_TRUE(second) << second.error().message;
  Session session;
  session.field.grid = {40, 32, 24};
  session.lic.length = 12;
  session.precision = FieldPrecision::Float;
  session.lic.sparsity.distribution = SparsityDistribution::Jitter;
  Result<SessionInputs> inputs = loadSessionInputs(session, {.fieldOnDevice = true});
  ASSERT_TRUE(inputs);
  const Context* one[] = {&context()};
  const Context* two[] = {&context(), &*second};
  const LicVolumeOptions budget{.deviceCap = 400000};
  const Result<LicVolumeRun> alone = computeLicVolume(one, session, *inputs, budget);
  const Result<LicVolumeRun> shared = computeLicVolume(two, session, *inputs, budget);
  ASSERT_TRUE(alone && shared) << (shared ? "" : shared.error().message);
  EXPECT_EQ(alone->bricks, shared->bricks);
  EXPECT_EQ(alone->volume.values, shared->volume.values);
  EXPECT_EQ(alone->volume.drawn, shared->volume.drawn);
  ASSERT_EQ(shared->devices.size(), 2u);
  int bricks = 0;
  std::uint64_t voxels = 0;
  for (const DeviceShare& share : shared->devices) {
    bricks += share.bricks;
    voxels += share.voxels;
    EXPECT_GT(share.peakDeviceBytes, 0u);
    EXPECT_LE(share.peakDeviceBytes, budget.deviceCap);
  }
  EXPECT_EQ(bricks, shared->bricks);
  EXPECT_EQ(voxels, voxelCount(session.field.grid));
  // Fits one device: the first device makes it alone, in one piece (a split would add the other
  // device's start-up to work the read-back bounds), so two devices give one device's volume.
  const Result<LicVolumeRun> whole = computeLicVolume(one, session, *inputs, {});
  const Result<LicVolumeRun> alsoWhole = computeLicVolume(two, session, *inputs, {});
  ASSERT_TRUE(whole && alsoWhole);
  EXPECT_EQ(whole->bricks, 1);
  EXPECT_EQ(alsoWhole->bricks, 1);
  EXPECT_EQ(alsoWhole->devices.size(), 1u);
  EXPECT_EQ(whole->volume.values, alsoWhole->volume.values);
  EXPECT_EQ(whole->drawnVoxels, alsoWhole->drawnVoxels);
  EXPECT_LT(whole->drawnVoxels, voxelCount(session.field.grid));  // jitter hides some
  EXPECT_EQ(whole->drawnVoxels, static_cast<std::uint64_t>(std::count(
                                    whole->volume.drawn.begin(), whole->volume.drawn.end(), 1)));
  EXPECT_EQ(alone->drawnVoxels, static_cast<std::uint64_t>(std::count(
                                    alone->volume.drawn.begin(), alone->volume.drawn.end(), 1)));
  EXPECT_EQ(second->validationMessageCount(), 0u);
}

}  // namespace
}  // namespace lic3d
