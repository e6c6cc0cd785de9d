// SPDX-License-Identifier: BSD-3-Clause
// The CPU work spread over threads (core/parallel.h) gives what one thread gives, bit for bit,
// and --threads bounds the threads.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <mutex>
#include <set>
#include <stop_token>
#include <thread>
#include <vector>

#include "core/parallel.h"
#include "core/stage_times.h"
#include "core/value_histogram.h"
#include "lic/analytic_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"

namespace lic3d {
namespace {

struct Made {
  VectorField field;
  NoiseVolume noise;
  ValueHistogram speeds;
  double min = 0.0, max = 0.0, voxelSpeed = 0.0;
};

Made make(unsigned threads) {
  setThreadLimit(threads);
  Made m;
  m.field = makeAnalyticField(AnalyticField::Tornado, {37, 29, 41}, 3.0);
  m.noise = makeWhiteNoise(m.field.dims, 7);
  m.speeds = speedHistogram(m.field);
  m.min = minMagnitude(m.field);
  m.max = maxMagnitude(m.field);
  m.voxelSpeed = maxVoxelSpeedOverVoxels(m.field);
  setThreadLimit(0);
  return m;
}

TEST(Parallel, FieldsNoiseAndStatisticsAreTheSameOnOneThreadAndOnMany) {
  const Made one = make(1);
  const Made many = make(8);
  EXPECT_EQ(one.field.vectors, many.field.vectors);
  EXPECT_EQ(one.noise.bytes, many.noise.bytes);
  EXPECT_EQ(one.speeds.counts, many.speeds.counts);
  EXPECT_EQ(one.speeds.min, many.speeds.min);
  EXPECT_EQ(one.speeds.max, many.speeds.max);
  EXPECT_EQ(one.min, many.min);
  EXPECT_EQ(one.max, many.max);
  EXPECT_EQ(one.voxelSpeed, many.voxelSpeed);
  EXPECT_GT(one.max, one.min);
}

// resizeLarge faults a large array's new pages in on all threads first: the items it had stay,
// the new ones are zero, and so is a range it grows into again.
TEST(Parallel, ResizeLargeKeepsTheOldItemsAndZeroesTheNew) {
  std::vector<std::uint32_t> values(1000);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<std::uint32_t>(i + 1);
  const std::size_t count = (std::size_t{80} << 20) / sizeof(std::uint32_t);
  resizeLarge(values, count);
  ASSERT_EQ(values.size(), count);
  std::size_t wrong = 0;
  for (std::size_t i = 0; i < count; ++i)
    wrong += values[i] != (i < 1000 ? static_cast<std::uint32_t>(i + 1) : 0u) ? 1 : 0;
  EXPECT_EQ(wrong, 0u);
  values.resize(1000);
  values[999] = 7;
  resizeLarge(values, count);  // within its capacity: the old item kept again
  EXPECT_EQ(values[999], 7u);
  EXPECT_EQ(std::count(values.begin() + 1000, values.end(), 0u),
            static_cast<std::ptrdiff_t>(count - 1000));
}

TEST(Parallel, TheThreadLimitBoundsTheThreadsThatRun) {
  const unsigned all = availableThreads();
  setThreadLimit(1);
  EXPECT_EQ(availableThreads(), 1u);
  std::mutex mutex;
  std::set<std::thread::id> ids;
  parallelChunks(
      1 << 20,
      [&](std::size_t, std::size_t) {
        const std::scoped_lock lock(mutex);
        ids.insert(std::this_thread::get_id());
      },
      1024);
  EXPECT_EQ(ids.size(), 1u);
  setThreadLimit(0);
  EXPECT_EQ(availableThreads(), all);
  // Every item once, in chunks of at least the grain.
  std::vector<std::atomic<int>> seen(100000);
  parallelChunks(
      seen.size(),
      [&](std::size_t begin, std::size_t end) {
        EXPECT_TRUE(end - begin >= 1000 || end == seen.size());
        for (std::size_t i = begin; i < end; ++i) ++seen[i];
      },
      1000);
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](const auto& n) { return n == 1; }));
}

TEST(Parallel, AStopRequestStartsNoFurtherTaskAndTheReferenceIsCancelled) {
  std::stop_source stop;
  int ran = 0;
  parallelFor(
      1000, 1, [&](std::size_t) { ++ran; },
      ProgressCallback([&](double) { stop.request_stop(); }, stop.get_token()));
  EXPECT_EQ(ran, 1);
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {8, 8, 8});
  stop = std::stop_source();
  int reports = 0;
  const Result<ScalarVolume> lic =
      computeLicReference(field, makeWhiteNoise(field.dims, 1), LicParams{}, 1,
                          ProgressCallback(
                              [&](double) {
                                ++reports;
                                stop.request_stop();
                              },
                              stop.get_token()));
  ASSERT_FALSE(lic.ok());
  EXPECT_EQ(lic.error().kind, ErrorKind::Cancelled);
  EXPECT_EQ(reports, 1);
}

TEST(StageTimes, StagesAddUpInTheOrderTheyFirstRan) {
  clearStageTimings();
  addStageTime("field", 0.25);
  addStageTime("LIC", 1.0);
  addStageTime("field", 0.5);
  { const StageTimer timer("write"); }
  const StageTimings timings = stageTimings();
  ASSERT_EQ(timings.size(), 3u);
  EXPECT_EQ(timings[0].first, "field");
  EXPECT_DOUBLE_EQ(timings[0].second, 0.75);
  EXPECT_EQ(timings[1].first, "LIC");
  EXPECT_EQ(timings[2].first, "write");
  EXPECT_GE(timings[2].second, 0.0);
  clearStageTimings();
  EXPECT_TRUE(stageTimings().empty());
}

}  // namespace
}  // namespace lic3d
