// SPDX-License-Identifier: BSD-3-Clause
// The command line when things fail: requests that cannot fit, allocations that fail, a device
// lost at any submission and a render killed at any moment all leave no output behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "png_read.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

using test::CliTest;
using test::CommandRun;

// A request the device cannot hold is refused with exit status 3 before anything is allocated:
// under a 4 GB address-space limit, making the 700^3 field (4 GB of vectors) would fail with
// status 1 instead. The message names the request, the bytes and the largest grid that fits.
// These requests must fit whole (seed noise and time steps belong to the whole grid); one that
// can go in bricks is made so (SCALE.md, test_cli_bricks.cpp).
TEST_F(CliTest, RequestsThatCannotFitAreRefusedBeforeAllocating) {
  for (const char* command : {"render --grid 700 --seed-noise 40 -o big.png",
                              "compute --grid 700 --time-steps 4 -o big.nrrd",
                              "render --grid 2048 --seed-noise 40 -o big.png"}) {
    const CommandRun r = run(command, "ulimit -v 4000000;");
    EXPECT_EQ(r.status, 3) << command << "\n" << r.output;
    EXPECT_NE(r.output.find("MiB"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("the largest cubic grid that fits is "), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("big.png")) || fs::exists(path("big.nrrd")));
  }
  // The same limit leaves room for a grid that fits.
  const CommandRun small =
      run("render --grid 16 --width 32 --height 32 -q -o small.png", "ulimit -v 4000000;");
  EXPECT_EQ(small.status, 0) << small.output;
}

// Every device allocation of a render, made to fail in turn through the allocator's test hook
// (LIC3D_FAIL_ALLOCATION=N): each run names the call and its result, exits with status 1, leaves
// no output file and no validation message (everything made so far is released cleanly).
TEST_F(CliTest, EveryAllocationFailureIsReportedAndLeavesNothing) {
  const std::string args = "--validation render --grid 8 --width 32 --height 32 -q -o out.png";
  int failures = 0;
  for (int n = 1; n <= 60; ++n) {
    const CommandRun r = run(args, "LIC3D_FAIL_ALLOCATION=" + std::to_string(n));
    if (r.status == 0) break;  // past the last allocation
    ++failures;
    EXPECT_EQ(r.status, 1) << "allocation " << n << ": " << r.output;
    EXPECT_NE(r.output.find("vkAllocateMemory returned VK_ERROR_OUT_OF_DEVICE_MEMORY"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("alidation"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(path("out.png"))) << "allocation " << n;
    EXPECT_EQ(listFolder(), std::vector<std::string>{}) << "allocation " << n;
  }
  EXPECT_GT(failures, 5) << "the hook should reach every allocation of a render";
  EXPECT_TRUE(fs::exists(path("out.png"))) << "the run past the last allocation succeeds";
}

// A device lost at any submission of a render or a volume export (the submission hook, as a
// driver reset would): status 1 naming the call and VK_ERROR_DEVICE_LOST, no validation message,
// and no output file at all. A picture and its RGBA volume appear together or not at all: a device
// lost while the volume is read back left the picture (hardening, class 10).
TEST_F(CliTest, ALostDeviceIsReportedAndLeavesNothing) {
  for (const char* command :
       {"render --grid 8 --width 32 --height 32 -q -o out.png", "compute --grid 8 -q -o out.nrrd",
        "render --grid 8 --width 32 --height 32 -q -o out.png --rgba-volume volume.vti"}) {
    int lost = 0;
    for (int n = 1; n <= 40; ++n) {
      for (const fs::directory_entry& e : fs::directory_iterator(folder())) fs::remove(e.path());
      const CommandRun r =
          run(std::string("--validation ") + command, "LIC3D_LOSE_DEVICE=" + std::to_string(n));
      if (r.status == 0) break;  // past the last submission
      ++lost;
      EXPECT_EQ(r.status, 1) << command << ", submission " << n << ": " << r.output;
      EXPECT_NE(r.output.find("vkQueueSubmit2 failed: VK_ERROR_DEVICE_LOST"), std::string::npos)
          << r.output;
      EXPECT_EQ(r.output.find("alidation"), std::string::npos) << r.output;
      EXPECT_EQ(listFolder(), std::vector<std::string>{}) << command << ", submission " << n;
    }
    EXPECT_GT(lost, 2) << command << ": the hook should reach every submission";
    EXPECT_FALSE(listFolder().empty()) << command << ": the run past the last submission succeeds";
  }
}

// Killed at any moment, a batch render never leaves a truncated file under a real name: each
// frame is written to a temporary name in the same folder and renamed once complete. The kills
// follow events, not the clock: when the first temporary file shows (a frame being written), and
// right after the 1st, 3rd and 6th frames are complete, so the verdict does not depend on the
// machine's speed.
TEST_F(CliTest, KillingABatchRenderLeavesOnlyCompleteFrames) {
  const std::string frames = "$(ls frame_*.png 2>/dev/null | wc -l)";
  const std::string writing = "ls -a | grep -q '^[.]frame_.*[.]tmp-'";
  int complete = 0;
  for (const std::string& event :
       {writing + " || [ " + frames + " -ge 1 ]", "[ " + frames + " -ge 1 ]",
        "[ " + frames + " -ge 3 ]", "[ " + frames + " -ge 6 ]"}) {
    for (const fs::directory_entry& e : fs::directory_iterator(folder())) fs::remove(e.path());
    // The render goes on in the background until the event, then is killed outright; kill -0
    // ends the wait should the render finish first (then nothing was cut short).
    const CommandRun r = shell(
        "'" + std::string(LIC3D_EXECUTABLE) +
        "' --device 0 render --grid 20 --width 96 --height 96 --turntable 40 -q "
        "-o frame_%02d.png & pid=$!; until " +
        event + "; do kill -0 $pid 2>/dev/null || break; sleep 0.005; done; kill -KILL $pid; " +
        "wait $pid; true");
    int here = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(folder())) {
      const std::string name = e.path().filename().string();
      if (name.rfind("frame_", 0) != 0 || e.path().extension() != ".png") continue;
      const test::RgbaPixels frame = test::readRgbaPng(e.path());
      EXPECT_EQ(frame.width, 96) << name << " is not a complete PNG (killed at `" << event << "`)\n"
                                 << r.output;
      ++here;
    }
    complete += here;
  }
  EXPECT_GT(complete, 0) << "no frame was complete: the render failed";
}

}  // namespace
}  // namespace lic3d
