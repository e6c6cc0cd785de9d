// SPDX-License-Identifier: BSD-3-Clause
// Fields larger than the device: --memory-budget caps the device memory, and compute makes a LIC
// that does not fit in bricks with ghost layers, reported as "bricks" in the summary. And the
// app's frames while a LIC slider is dragged, as `bench --drag` times them for large volumes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "io/nrrd.h"
#include "render/lic_volume_job.h"

namespace lic3d {
namespace {

using test::CliTest;
using test::CommandRun;

int bricksIn(const std::string& output) {
  const std::size_t at = output.find("\"bricks\":");
  return at == std::string::npos ? -1 : std::stoi(output.substr(at + 9));
}

TEST_F(CliTest, ALicLargerThanTheBudgetIsMadeInBricks) {
  const std::string field = "compute --field tornado --grid 40,32,24 --length 12 --bias 2 ";
  const CommandRun whole = run(field + "-o whole.nrrd");
  ASSERT_EQ(whole.status, 0) << whole.output;
  EXPECT_EQ(bricksIn(whole.output), 1) << whole.output;
  const CommandRun bricked = run(field + "--memory-budget 400kB -o bricked.nrrd");
  ASSERT_EQ(bricked.status, 0) << bricked.output;
  const int bricks = bricksIn(bricked.output);
  EXPECT_GT(bricks, 1) << bricked.output;
  EXPECT_NE(bricked.output.find("bricks of"), std::string::npos) << bricked.output;

  const Result<ScalarVolume> a = readScalarNrrd(path("whole.nrrd"));
  const Result<ScalarVolume> b = readScalarNrrd(path("bricked.nrrd"));
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->dims, b->dims);
  EXPECT_EQ(a->geometry, b->geometry);
  // As for the ParaView plugin's pieces on the GPU (test_field_piece_gpu.cpp): a brick's texture
  // coordinates are its own, so single voxels may drift; the mean and 99.9 % stay close.
  std::vector<double> differences;
  double sum = 0.0;
  for (std::size_t i = 0; i < a->values.size(); ++i) {
    differences.push_back(std::abs(static_cast<double>(a->values[i]) - b->values[i]));
    sum += differences.back();
  }
  std::sort(differences.begin(), differences.end());
  EXPECT_LE(sum / static_cast<double>(differences.size()), 1e-3);
  EXPECT_LE(differences[differences.size() * 999 / 1000], 2e-2);
}

TEST_F(CliTest, ABudgetTooSmallOrNotBrickableIsRefused) {
  // Not even one voxel and its ghost layers fit.
  const CommandRun tiny = run("compute --grid 24 --memory-budget 1kB -o tiny.nrrd");
  EXPECT_EQ(tiny.status, 3) << tiny.output;
  EXPECT_NE(tiny.output.find("the memory budget given is 1000 bytes;"), std::string::npos)
      << tiny.output;
  // A noise file belongs to the whole grid: it must fit whole.
  ASSERT_EQ(run("compute -q --grid 24 -o ignored.nrrd").status, 0);
  const CommandRun seeded =
      run("compute --grid 24 --seed-noise 40 --memory-budget 100kB -o seeded.nrrd");
  EXPECT_EQ(seeded.status, 3) << seeded.output;
  // render draws the whole volume: it refuses what does not fit.
  const CommandRun picture = run("render --grid 24 --memory-budget 100kB -o picture.png");
  EXPECT_EQ(picture.status, 3) << picture.output;
  // A budget is a size.
  const CommandRun bad = run("compute --grid 24 --memory-budget 12XB -o bad.nrrd");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--memory-budget"), std::string::npos) << bad.output;
  EXPECT_FALSE(std::filesystem::exists(path("tiny.nrrd")));
  EXPECT_FALSE(std::filesystem::exists(path("seeded.nrrd")));
}

// `bench --drag` times the app's frames while a LIC slider is dragged: each size's row has the
// stride the app would pick from the full LIC's time, its coarse grid, and the frame times with
// their verdict against 60 frames per second, consistent with each other whatever the timings.
TEST_F(CliTest, BenchDragTimesTheAppsFramesAtTheStrideItWouldPick) {
  const CommandRun r =
      run("bench --drag --sizes 12,20 --lengths 30 --drag-picture 64 --drag-slices 16 "
          "--drag-frames 10 --warmup 1 --json drag.json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("60 fps"), std::string::npos) << r.output;
  const nlohmann::json report = nlohmann::json::parse(test::readWhole(path("drag.json")));
  ASSERT_EQ(report["drag"].size(), 2u) << report.dump();
  for (const nlohmann::json& row : report["drag"]) {
    const int n = row["n"], stride = row["stride"];
    EXPECT_GT(row["full_lic_ms"].get<double>(), 0.0);
    EXPECT_GE(stride, coarseLicStride(row["full_lic_ms"].get<double>())) << row.dump();
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_EQ(row["coarse_grid"][axis].get<int>(), (n + stride - 1) / stride) << row.dump();
    const double median = row["frame_median_ms"], p95 = row["frame_p95_ms"];
    EXPECT_GT(median, 0.0);
    EXPECT_GE(p95, median);
    EXPECT_GE(median, row["draw_median_ms"].get<double>()) << "a frame includes its draw";
    EXPECT_EQ(row["fits_60_fps"].get<bool>(), p95 <= 1000.0 / 60.0) << row.dump();
  }
}

}  // namespace
}  // namespace lic3d
