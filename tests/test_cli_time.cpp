// SPDX-License-Identifier: BSD-3-Clause
// The command line for 2D LIC and fields that change with time (docs/TIME.md): render2d, time
// flags and animations, and series of field files blended between their steps.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "core/session.h"
#include "io/nrrd.h"
#include "lic/analytic_fields.h"
#include "png_read.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

using test::CliTest;
using test::CommandRun;
using test::pngSize;
using test::sessionInPng;

// ---- 2D LIC and unsteady fields (docs/TIME.md) --------------------------------------------------

TEST_F(CliTest, Render2DAndTheTimeFlagsAreInTheHelp) {
  const CommandRun top = run("--help");
  EXPECT_NE(top.output.find("render2d"), std::string::npos);
  const CommandRun help = run("render2d --help");
  EXPECT_EQ(help.status, 0);
  for (const char* flag : {"--field",        "--grid",       "--slice",
                           "--width",        "--height",     "--time",
                           "--animate-time", "--time-range", "--animate-bias",
                           "--frames",       "--video",      "--fps",
                           "--length",       "--step",       "--bias",
                           "--integrator",   "--kernel",     "--noise-filter",
                           "--direction",    "--color",      "--colormap",
                           "--color-range",  "--legend",     "--contrast",
                           "--window",       "--gain",       "--brightness",
                           "--cpu",          "--output",     "--seed",
                           "circle",         "saddle",       "wave"})
    EXPECT_NE(help.output.find(flag), std::string::npos) << flag;
  for (const char* command : {"render --help", "compute --help"}) {
    const CommandRun r = run(command);
    for (const char* flag : {"--time", "--time-steps", "step_%03d.vti"})
      EXPECT_NE(r.output.find(flag), std::string::npos) << command << " " << flag;
  }
  EXPECT_NE(run("render --help").output.find("--animate-time"), std::string::npos);
}

TEST_F(CliTest, Render2DWritesTheLicImageAtTheGridsOrTheChosenSize) {
  ASSERT_EQ(run("render2d -q --field circle --grid 32 -o grid.png").status, 0);
  EXPECT_EQ(pngSize(path("grid.png")), std::make_pair(32, 32));
  // Noise at the image's size: finer than the field; one side keeps the grid's aspect.
  ASSERT_EQ(run("render2d -q --field saddle --grid 32,16 --width 96 -o wide.png").status, 0);
  EXPECT_EQ(pngSize(path("wide.png")), std::make_pair(96, 48));
  // A plane of a 3D field, and a file: 2D, or a plane of a 3D one.
  const CommandRun plane =
      run("render2d --field tornado --grid 24 --slice y:5 --height 40 --color magnitude "
          "--legend -o plane.png");
  ASSERT_EQ(plane.status, 0) << plane.output;
  // The legend gets a column of its own beside the 40 x 40 picture.
  EXPECT_EQ(pngSize(path("plane.png")).second, 40);
  EXPECT_GT(pngSize(path("plane.png")).first, 40);
  EXPECT_NE(plane.output.find("lic3d-summary {\"command\":\"render2d\""), std::string::npos);
  const fs::path carotid = test::dataFolder() / "carotid.vtk";
  ASSERT_EQ(
      run("render2d -q --field '" + carotid.string() + "' --slice z:20 -o carotid.png").status, 0);
  EXPECT_EQ(pngSize(path("carotid.png")), std::make_pair(76, 49));
  ASSERT_TRUE(
      writeVectorFieldNrrd(path("flat.nrrd"), makeAnalyticField(AnalyticField::Vortex, {20, 1, 12}))
          .ok());
  ASSERT_EQ(run("render2d -q --field flat.nrrd -o flat.png").status, 0);
  EXPECT_EQ(pngSize(path("flat.png")), std::make_pair(20, 12));

  // The session inside remakes the picture, on the GPU or with the CPU reference.
  const Result<Session> stored = sessionInPng(path("wide.png"));
  ASSERT_TRUE(stored.ok()) << stored.error().message;
  EXPECT_TRUE(stored->twoD);
  EXPECT_EQ(stored->plane.width, 96);
  writeBytes("wide.json", test::decodePng(path("wide.png")).text.at("lic3d-session"));
  ASSERT_EQ(run("render2d -q --session wide.json -o again.png").status, 0);
  EXPECT_TRUE(test::readRgbaPng(path("again.png")).rgba ==
              test::readRgbaPng(path("wide.png")).rgba);
  ASSERT_EQ(run("render2d -q --session wide.json --cpu -o cpu.png").status, 0);
  const test::RgbaPixels gpu = test::readRgbaPng(path("wide.png"));
  const test::RgbaPixels cpu = test::readRgbaPng(path("cpu.png"));
  ASSERT_EQ(gpu.rgba.size(), cpu.rgba.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < gpu.rgba.size(); i += 4) sum += std::abs(gpu.rgba[i] - cpu.rgba[i]);
  EXPECT_LT(sum / (96 * 48), 1.0) << "GPU and CPU pictures differ by more than a grey level";
}

// The engine names parameters by their session keys (Error::parameter); the CLI shows its own
// flags in their place, in the leading position and wherever another parameter is mentioned.
TEST_F(CliTest, EngineErrorsNameTheFlag) {
  const std::pair<const char*, const char*> cases[] = {
      {"render --grid 16 --sparsity halton --sparsity-points 5000", "--sparsity-points must be"},
      {"render --grid 16 --sparsity jitter --sparsity-radius 0.25", "--sparsity-radius must be"},
      {"render --grid 16 --length 4 --bias 9", "--bias must satisfy |bias| <= --length (4)"},
      {"render --grid 16 --clip 0,1,0.5,0.5,0,1", "--clip needs min < max"},
      {"render --grid 16 --stereo anaglyph --ortho",
       "--stereo needs a perspective camera, not --ortho"},
      {"render2d --field circle --sparsity poisson", "--sparsity hides voxels"},
      {"render --device no-such-device", "--device no-such-device matches no Vulkan device"},
  };
  for (const auto& [args, expected] : cases) {
    const CommandRun r = run(std::string(args) + " -o out.png");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find("lic."), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(r.output.find("view."), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_EQ(listFolder(), std::vector<std::string>{});
}

TEST_F(CliTest, Render2DBadInputExitsWithStatusTwoNamingTheProblem) {
  const std::pair<const char*, const char*> cases[] = {
      {"render2d --field circle --sparsity poisson", "sparsity"},
      {"render2d --field circle --slice w", "--slice"},
      {"render2d --field tornado --grid 16 --slice z:16", "--slice"},
      {"render2d --field circle --time 0.5", "--time"},
      {"render2d --field circle --grid 8,8,8", "--grid"},
      {"render2d --field missing.vti", "missing.vti"},
      {"render2d --field circle --animate-time 4", "--animate-time"},
      {"render2d --field wave --time-range 0,1", "--time-range"},
      {"render2d --field circle --width 0", "--width"},
      {"render --field circle", "render2d"},
      {"render --field tornado --time-steps 1", "--time-steps"},
      {"render --field abc --time-steps 8", "abc"},
  };
  for (const auto& [args, named] : cases) {
    const CommandRun r = run(std::string(args) + " -o out.png");
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(named), std::string::npos) << args << "\n" << r.output;
  }
  EXPECT_EQ(listFolder(), std::vector<std::string>{});
}

TEST_F(CliTest, Render2DAnimatesTimeAndBiasTogetherAsALoop) {
  // The wave repeats after one unit of time and the bias cycle after 4 frames: 8 frames loop.
  const CommandRun r =
      run("render2d -q --field wave --grid 24 --length 4 --animate-time 8 --animate-bias 4 "
          "-o 'loop_%d.png'");
  ASSERT_EQ(r.status, 0) << r.output;
  const int bias[8] = {-4, 0, 4, 0, -4, 0, 4, 0};
  for (int k = 0; k < 8; ++k) {
    const Result<Session> s = sessionInPng(path("loop_" + std::to_string(k) + ".png"));
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_DOUBLE_EQ(s->time, k / 8.0) << "frame " << k;
    EXPECT_EQ(s->lic.bias, bias[k]) << "frame " << k;
  }
  // Frame 8 would be frame 0: the time and the bias are back where they started.
  ASSERT_EQ(
      run("render2d -q --field wave --grid 24 --length 4 --time 1 --bias -4 -o end.png").status, 0);
  const test::RgbaPixels first = test::readRgbaPng(path("loop_0.png"));
  const test::RgbaPixels end = test::readRgbaPng(path("end.png"));
  int differ = 0;
  for (std::size_t i = 0; i < first.rgba.size(); ++i)
    differ += std::abs(first.rgba[i] - end.rgba[i]) > 2;
  EXPECT_EQ(differ, 0);
}

TEST_F(CliTest, TimeSeriesOfFilesRendersOneFramePerStep) {
  const Dims dims{14, 12, 10};
  for (int k = 0; k < 3; ++k)
    ASSERT_TRUE(writeVectorFieldNrrd(path("step_00" + std::to_string(k) + ".nrrd"),
                                     makeAnalyticField(AnalyticField::Tornado, dims, 60.0 * k))
                    .ok());
  const std::string common = "render --look dense --width 48 --height 48 --length 6 ";
  const CommandRun r = run(common + "--field 'step_%03d.nrrd' --animate-time 3 -o 'f_%d.png'");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("3 files step_000.nrrd .. step_002.nrrd"), std::string::npos) << r.output;
  for (int k = 0; k < 3; ++k) {
    const Result<Session> s = sessionInPng(path("f_" + std::to_string(k) + ".png"));
    ASSERT_TRUE(s.ok());
    EXPECT_DOUBLE_EQ(s->time, k) << "frame " << k << " is step " << k;
  }
  // A step's frame is the picture of that step's file alone; a glob names the same series.
  ASSERT_EQ(run(common + "-q --field step_001.nrrd -o single.png").status, 0);
  EXPECT_TRUE(test::readRgbaPng(path("f_1.png")).rgba ==
              test::readRgbaPng(path("single.png")).rgba);
  ASSERT_EQ(run(common + "-q --field 'step_*.nrrd' --time 0.5 -o half.png").status, 0);
  EXPECT_FALSE(test::readRgbaPng(path("half.png")).rgba == test::readRgbaPng(path("f_0.png")).rgba);
  // compute blends on the GPU as the CPU reference does.
  ASSERT_EQ(run("compute -q --field 'step_%03d.nrrd' --time 1.5 --length 6 -o gpu.nrrd").status, 0);
  ASSERT_EQ(
      run("compute -q --cpu --field 'step_%03d.nrrd' --time 1.5 --length 6 -o cpu.nrrd").status, 0);
  const Result<ScalarVolume> gpu = readScalarNrrd(path("gpu.nrrd"));
  const Result<ScalarVolume> cpu = readScalarNrrd(path("cpu.nrrd"));
  ASSERT_TRUE(gpu.ok() && cpu.ok());
  double mean = 0.0;
  for (std::size_t i = 0; i < gpu->values.size(); ++i)
    mean += std::abs(gpu->values[i] - cpu->values[i]);
  EXPECT_LT(mean / static_cast<double>(gpu->values.size()), 1e-3);

  // A step on another grid is named; so is a pattern that matches one file or none.
  ASSERT_TRUE(
      writeVectorFieldNrrd(path("bad_0.nrrd"), makeAnalyticField(AnalyticField::Tornado, dims))
          .ok());
  ASSERT_TRUE(
      writeVectorFieldNrrd(path("bad_1.nrrd"), makeAnalyticField(AnalyticField::Tornado, {8, 8, 8}))
          .ok());
  const CommandRun mismatch = run(common + "--field 'bad_%d.nrrd' --animate-time 2 -o 'b_%d.png'");
  EXPECT_EQ(mismatch.status, 2) << mismatch.output;
  EXPECT_NE(mismatch.output.find("bad_1.nrrd"), std::string::npos) << mismatch.output;
  const CommandRun none = run(common + "--field 'nothing_%d.nrrd' -o n.png");
  EXPECT_EQ(none.status, 2);
  EXPECT_NE(none.output.find("nothing_%d.nrrd"), std::string::npos) << none.output;
}

TEST_F(CliTest, TheTornadoAsATimeSeriesIsBlendedBetweenItsSteps) {
  // 4 steps over the tornado's period: a time halfway between steps 1 and 2 (on the GPU) is not
  // the field sampled exactly there, but it is at a step's own time.
  const double step = 200.0 * 3.14159265358979323846 / 4.0;
  const std::string common = "render -q --grid 16 --width 48 --height 48 --length 6 ";
  ASSERT_EQ(run(common + "--time " + std::to_string(step) + " -o exact.png").status, 0);
  ASSERT_EQ(run(common + "--time " + std::to_string(step) + " --time-steps 4 -o series.png").status,
            0);
  const test::RgbaPixels exact = test::readRgbaPng(path("exact.png"));
  const test::RgbaPixels series = test::readRgbaPng(path("series.png"));
  int differ = 0;
  for (std::size_t i = 0; i < exact.rgba.size(); ++i)
    differ += std::abs(exact.rgba[i] - series.rgba[i]) > 2;
  EXPECT_LT(differ, 40) << "at a step's time the blend is that step";
  const CommandRun frames = run(common + "--time-steps 4 --animate-time 2 -o 't_%d.png'");
  ASSERT_EQ(frames.status, 0) << frames.output;
  EXPECT_NEAR(sessionInPng(path("t_1.png"))->time, 2 * step, 1e-3);
}

}  // namespace
}  // namespace lic3d
