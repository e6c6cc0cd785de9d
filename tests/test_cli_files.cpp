// SPDX-License-Identifier: BSD-3-Clause
// The command line with real data in and results out: vector arrays chosen by name, LIC and RGBA
// volumes, slices, sessions in every PNG, animations and summaries.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "core/colormap.h"
#include "core/session.h"
#include "io/nrrd.h"
#include "io/vti.h"
#include "lic/analytic_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "png_read.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

using test::CliTest;
using test::CommandRun;
using test::sessionInPng;
using test::Streams;

// ---- Real data in, results out ----------------------------------------------------------------

// An 8x8x8 VTK legacy file with two vector arrays: "along" (+x everywhere, with `nanVectors` NaN
// vectors at the start) and "swirl" (around the z axis), on an anisotropic grid off the origin.
std::string twoArrayVtk(int nanVectors = 0) {
  std::ostringstream text;
  text << "# vtk DataFile Version 3.0\ntwo arrays\nASCII\nDATASET STRUCTURED_POINTS\n"
          "DIMENSIONS 8 8 8\nSPACING 0.5 0.25 2\nORIGIN 1 2 3\nPOINT_DATA 512\n";
  text << "VECTORS along float\n";
  for (int i = 0; i < 512; ++i) text << (i < nanVectors ? "nan nan nan\n" : "1 0 0\n");
  text << "VECTORS swirl float\n";
  for (int k = 0; k < 8; ++k)
    for (int j = 0; j < 8; ++j)
      for (int i = 0; i < 8; ++i) text << -(j - 3.5) << " " << (i - 3.5) << " 0.2\n";
  return text.str();
}

// The JSON of the `lic3d-summary` line in `output`, or null when there is not exactly one.
nlohmann::json summaryOf(const std::string& output) {
  nlohmann::json found;
  int count = 0;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("lic3d-summary ", 0) != 0) continue;
    ++count;
    found = nlohmann::json::parse(line.substr(14), nullptr, false);
  }
  return count == 1 ? found : nlohmann::json();
}

std::size_t countOf(const std::string& text, const std::string& part) {
  std::size_t n = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST_F(CliTest, ArrayPicksTheVectorArrayOfAFileAndNamesTheOthers) {
  writeBytes("two.vtk", twoArrayVtk());
  const CommandRun first = run("compute --field two.vtk -o default.nrrd", "", Streams::StderrOnly);
  ASSERT_EQ(first.status, 0) << first.output;
  EXPECT_NE(first.output.find("read 'along'"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("'swirl'"), std::string::npos)
      << "lists the others: " << first.output;
  EXPECT_NE(first.output.find("--array"), std::string::npos) << first.output;
  // The summary names the file's grid, spacing and origin.
  EXPECT_NE(first.output.find("8x8x8, spacing 0.5,0.25,2, origin 1,2,3"), std::string::npos)
      << first.output;

  const CommandRun quiet = run("compute -q --field two.vtk -o quiet.nrrd");
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_TRUE(quiet.output.empty()) << "--quiet: " << quiet.output;

  ASSERT_EQ(run("compute -q --field two.vtk --array along -o along.nrrd").status, 0);
  ASSERT_EQ(run("compute -q --field two.vtk --array swirl -o swirl.nrrd").status, 0);
  EXPECT_EQ(test::readWhole(path("default.nrrd")), test::readWhole(path("along.nrrd")));
  EXPECT_NE(test::readWhole(path("swirl.nrrd")), test::readWhole(path("along.nrrd")))
      << "--array swirl reads another field";
  const CommandRun named = run("compute --field two.vtk --array swirl -o named.nrrd");
  EXPECT_EQ(named.output.find("'along'"), std::string::npos) << "a named array is not discussed";

  // The render summary names the geometry too; --array works there as well.
  const CommandRun render =
      run("render --field two.vtk --array swirl --width 24 --height 24 -o swirl.png");
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_NE(render.output.find("array 'swirl' 8x8x8, spacing 0.5,0.25,2, origin 1,2,3"),
            std::string::npos)
      << render.output;

  const CommandRun missing = run("compute --field two.vtk --array pressure -o missing.nrrd");
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("pressure"), std::string::npos) << missing.output;
  EXPECT_NE(missing.output.find("two.vtk"), std::string::npos) << missing.output;
  EXPECT_FALSE(fs::exists(path("missing.nrrd")));
}

TEST_F(CliTest, NonFiniteVectorsAreCountedInAWarning) {
  writeBytes("nan.vtk", twoArrayVtk(3));
  const CommandRun r = run("compute --field nan.vtk -o nan.nrrd", "", Streams::StderrOnly);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("warning: nan.vtk: 3 vector(s) with a NaN or infinite component"),
            std::string::npos)
      << r.output;
  const CommandRun summary = run("compute --field nan.vtk -o nan.nrrd", "", Streams::StdoutOnly);
  EXPECT_EQ(summaryOf(summary.output)["field"]["non_finite_vectors"], 3) << summary.output;
  const CommandRun clean = run("compute --field nan.vtk --array swirl -o clean.nrrd");
  EXPECT_EQ(clean.output.find("warning"), std::string::npos) << clean.output;
}

// No output may replace an input of the same run, however it is spelt (hardening, class 2): the
// run stops before any work with status 2 and every file is left as it was.
TEST_F(CliTest, NoOutputMayBeAnInputOfTheRun) {
  ASSERT_TRUE(writeVectorFieldNrrd(path("base.nrrd"),
                                   makeAnalyticField(AnalyticField::Abc, Dims(8, 8, 8))));
  ASSERT_TRUE(writeNoiseNrrd(path("n.nrrd"), makeWhiteNoise(Dims(8, 8, 8), 3)));
  fs::create_directory(path("sub"));
  fs::create_hard_link(path("base.nrrd"), path("alias.nrrd"));
  const std::string field = test::readWhole(path("base.nrrd"));
  const std::string noise = test::readWhole(path("n.nrrd"));
  for (const char* args : {"compute -q --field base.nrrd -o base.nrrd",
                           "compute -q --field base.nrrd -o ./sub/../base.nrrd",
                           "compute -q --field base.nrrd -o alias.nrrd",
                           "compute -q --field base.nrrd --noise n.nrrd -o n.nrrd",
                           "render -q --field base.nrrd --rgba-volume base.nrrd -o out.png"}) {
    const CommandRun r = run(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("is an input of this run"), std::string::npos) << r.output;
    EXPECT_EQ(test::readWhole(path("base.nrrd")), field) << args;
    EXPECT_EQ(test::readWhole(path("n.nrrd")), noise) << args;
    EXPECT_FALSE(fs::exists(path("out.png"))) << args;
  }
  // Other names are written as ever.
  const CommandRun fine = run("compute -q --field base.nrrd --noise n.nrrd -o lic.nrrd");
  EXPECT_EQ(fine.status, 0) << fine.output;
}

TEST_F(CliTest, ComputeWritesVtiOrNrrdByExtensionWithTheFieldGeometry) {
  writeBytes("two.vtk", twoArrayVtk());
  ASSERT_EQ(run("compute -q --field two.vtk --array swirl -L 4 -o lic.vti").status, 0);
  ASSERT_EQ(run("compute -q --field two.vtk --array swirl -L 4 -o lic.nrrd").status, 0);
  const Result<ScalarVolume> vti = readScalarVti(path("lic.vti"));
  const Result<ScalarVolume> nrrd = readScalarNrrd(path("lic.nrrd"));
  ASSERT_TRUE(vti.ok()) << vti.error().message;
  ASSERT_TRUE(nrrd.ok()) << nrrd.error().message;
  EXPECT_EQ(vti->dims, Dims(8, 8, 8));
  const GridGeometry expected{{0.5, 0.25, 2.0}, {1.0, 2.0, 3.0}};
  EXPECT_EQ(vti->geometry, expected);
  EXPECT_EQ(nrrd->geometry, expected);
  EXPECT_EQ(vti->values, nrrd->values) << "the same volume in both formats";

  // Voxels that sparsity hides are NaN in every format: the same volume in each.
  for (const char* extension : {".vti", ".nrrd", ".raw"})
    ASSERT_EQ(run(std::string("compute -q --grid 12 --sparsity hammersley --sparsity-points 40 "
                              "-o sparse") +
                  extension)
                  .status,
              0)
        << extension;
  const Result<ScalarVolume> sparse = readScalarVti(path("sparse.vti"));
  ASSERT_TRUE(sparse.ok()) << sparse.error().message;
  const auto nans = std::count_if(sparse->values.begin(), sparse->values.end(),
                                  [](float v) { return std::isnan(v); });
  EXPECT_GT(nans, 0);
  EXPECT_LT(nans, static_cast<std::ptrdiff_t>(sparse->values.size()));
  const std::string raw = test::readWhole(path("sparse.raw"));
  ASSERT_EQ(raw.size(), sparse->values.size() * sizeof(float));
  std::vector<float> rawValues(sparse->values.size());
  std::memcpy(rawValues.data(), raw.data(), raw.size());  // little endian, as the host
  for (std::size_t i = 0; i < rawValues.size(); ++i) {
    EXPECT_EQ(std::isnan(rawValues[i]), std::isnan(sparse->values[i])) << i;
    if (!std::isnan(rawValues[i])) {
      EXPECT_EQ(rawValues[i], sparse->values[i]) << i;
    }
  }
  const std::string sparseNrrd = test::readWhole(path("sparse.nrrd"));
  EXPECT_EQ(sparseNrrd.substr(sparseNrrd.size() - raw.size()), raw) << "the .raw's values";
}

TEST_F(CliTest, ComputeSliceWritesASixteenBitGreyPngWithTheParameters) {
  const std::string flags = "compute -q --cpu --field abc --grid 12,10,8 --length 6 ";
  ASSERT_EQ(run(flags + "-o volume.nrrd").status, 0);
  const CommandRun y = run(flags + "--slice y:3 -o y3.png");
  ASSERT_EQ(y.status, 0) << y.output;
  ASSERT_EQ(run(flags + "--slice z -o middle.png").status, 0);
  const Result<ScalarVolume> volume = readScalarNrrd(path("volume.nrrd"));
  ASSERT_TRUE(volume.ok()) << volume.error().message;

  auto expectSlice = [&](const char* file, int axis, int index) {
    const test::DecodedPng png = test::decodePng(path(file));
    ASSERT_TRUE(png.ok) << file;
    EXPECT_EQ(png.bitDepth, 16) << file;
    EXPECT_EQ(png.colorType, 0) << file << ": grey";
    const int across = axis == 0 ? 1 : 0, up = axis == 2 ? 1 : 2;
    ASSERT_EQ(png.width, static_cast<std::uint32_t>(volume->dims[across])) << file;
    ASSERT_EQ(png.height, static_cast<std::uint32_t>(volume->dims[up])) << file;
    int worst = 0;
    for (std::uint32_t row = 0; row < png.height; ++row)
      for (std::uint32_t column = 0; column < png.width; ++column) {
        const std::size_t at = 2 * (row * png.width + column);
        const int stored = (png.bytes[at] << 8) | png.bytes[at + 1];
        Dims voxel(0);
        voxel[axis] = index;
        voxel[across] = static_cast<int>(column);
        voxel[up] = static_cast<int>(png.height - 1 - row);  // the top row is the highest index
        const float v = volume->at(voxel.x, voxel.y, voxel.z);
        worst = std::max(worst, std::abs(stored - static_cast<int>(std::lround(v * 65535.0f))));
      }
    EXPECT_LE(worst, 1) << file;
  };
  expectSlice("y3.png", 1, 3);
  expectSlice("middle.png", 2, 4);  // 8 slices along z: the middle is 4

  const Result<Session> session = sessionInPng(path("y3.png"));
  ASSERT_TRUE(session.ok()) << session.error().message;
  EXPECT_EQ(session->field.field, "abc");
  EXPECT_EQ(session->field.grid, Dims(12, 10, 8));
  EXPECT_EQ(session->lic.length, 6);
  EXPECT_EQ(test::decodePng(path("y3.png")).text["Software"].rfind("lic3d ", 0), 0u);

  // Without --slice a PNG is refused, naming what to do.
  const CommandRun refused = run("compute --grid 8 -o slice.png");
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.output.find("--slice"), std::string::npos) << refused.output;
}

TEST_F(CliTest, EveryPngCarriesTheSessionThatMadeIt) {
  const CommandRun r =
      run("render -q --look dense --field abc --grid 12,10,8 --seed 5 --length 6 --kernel hann "
          "--width 40 "
          "--height 32 --azimuth 70 --elevation -10 --color magnitude --colormap viridis "
          "--background 0.2,0.1,0 -o picture.png");
  ASSERT_EQ(r.status, 0) << r.output;
  Session expected;
  expected.field.field = "abc";
  expected.field.grid = {12, 10, 8};
  expected.noise.seed = 5;
  expected.lic.length = 6;
  expected.lic.kernel = Kernel::Hann;
  expected.view.width = 40;
  expected.view.height = 32;
  expected.view.camera.azimuth = 70.0f;
  expected.view.camera.elevation = -10.0f;
  expected.view.color = ColorMode::Magnitude;
  expected.view.colormap = Colormap::Viridis;
  expected.view.divergingWhenSigned = false;  // the map was chosen
  expected.view.background = {0.2f, 0.1f, 0.0f};
  const Result<Session> stored = sessionInPng(path("picture.png"));
  ASSERT_TRUE(stored.ok()) << stored.error().message;
  EXPECT_TRUE(*stored == expected) << sessionToJson(*stored);
  const test::DecodedPng png = test::decodePng(path("picture.png"));
  EXPECT_EQ(png.text.at("Software").rfind("lic3d ", 0), 0u);

  // The stored session makes the same picture again.
  writeBytes("again.json", png.text.at("lic3d-session"));
  ASSERT_EQ(run("render -q --session again.json -o again.png").status, 0);
  EXPECT_TRUE(test::readRgbaPng(path("again.png")).rgba ==
              test::readRgbaPng(path("picture.png")).rgba);
}

TEST_F(CliTest, RgbaVolumeHoldsTheColourAndOpacityOfEachVoxel) {
  // --cpu: the LIC volume is the reference itself; --window 0,1: grey = the LIC value.
  const std::string flags =
      "render -q --look dense --cpu --field abc --grid 10 --length 4 --width 16 --height 16 "
      "--window 0,1 "
      "--alpha 0.5 --color magnitude ";
  ASSERT_EQ(run(flags + "--rgba-volume rgba.vti -o a.png").status, 0);
  ASSERT_EQ(run(flags + "--rgba-volume rgba.nrrd -o b.png").status, 0);
  const Result<RgbaVolume> vti = readRgbaVti(path("rgba.vti"));
  const Result<RgbaVolume> nrrd = readRgbaNrrd(path("rgba.nrrd"));
  ASSERT_TRUE(vti.ok()) << vti.error().message;
  ASSERT_TRUE(nrrd.ok()) << nrrd.error().message;
  ASSERT_EQ(vti->dims, Dims(10));
  EXPECT_EQ(vti->rgba, nrrd->rgba);

  LicParams params;
  params.length = 4;
  const VectorField field = makeAnalyticField(AnalyticField::Abc, Dims(10));
  EXPECT_EQ(vti->geometry, field.geometry);
  const ScalarVolume lic = *computeLicReference(field, makeWhiteNoise(field.dims, 1), params);
  const double low = minMagnitude(field), high = maxMagnitude(field);
  int worst = 0;
  for (std::size_t i = 0; i < lic.values.size(); ++i) {
    const float grey = std::clamp(lic.values[i], 0.0f, 1.0f);
    const float t =
        static_cast<float>((glm::length(glm::dvec3(field.vectors[i])) - low) / (high - low));
    const glm::vec3 rgb = sampleColormap(Colormap::Thesis, t) * grey;
    const float expected[4] = {rgb.r, rgb.g, rgb.b, 0.5f * grey};
    for (int c = 0; c < 4; ++c)
      worst = std::max(worst, std::abs(vti->rgba[4 * i + c] -
                                       static_cast<int>(std::lround(expected[c] * 255.0f))));
  }
  EXPECT_LE(worst, 2) << "RGB = colour map at |v| times grey, A = alpha times grey";

  // Grey without colour; with constant opacity A is alpha, or 0 where sparsity hides the voxel,
  // exactly where compute writes NaN.
  const std::string sparse = "--grid 10 --length 4 --sparsity hammersley --sparsity-points 30 ";
  ASSERT_EQ(run("render -q --look dense " + sparse +
                "--width 16 --height 16 --opacity constant --alpha 0.5 --rgba-volume grey.vti "
                "-o c.png")
                .status,
            0);
  ASSERT_EQ(run("compute -q " + sparse + "-o sparse.nrrd").status, 0);
  const Result<RgbaVolume> grey = readRgbaVti(path("grey.vti"));
  const Result<ScalarVolume> hidden = readScalarNrrd(path("sparse.nrrd"));
  ASSERT_TRUE(grey.ok()) << grey.error().message;
  ASSERT_TRUE(hidden.ok()) << hidden.error().message;
  int hiddenCount = 0;
  for (std::size_t i = 0; i < hidden->values.size(); ++i) {
    const std::uint8_t* v = &grey->rgba[4 * i];
    EXPECT_TRUE(v[0] == v[1] && v[1] == v[2]) << "voxel " << i << " is not grey";
    const bool isHidden = std::isnan(hidden->values[i]);
    hiddenCount += isHidden ? 1 : 0;
    EXPECT_EQ(v[3], isHidden ? 0 : 128) << "voxel " << i;
  }
  EXPECT_GT(hiddenCount, 0);
}

TEST_F(CliTest, TurntableWritesNumberedFramesTurningTheCamera) {
  const std::string flags = "render --grid 8 --width 24 --height 24 --azimuth 10 ";
  const CommandRun r = run(flags + "--turntable 4 -o 'turn_%02d.png'", "", Streams::StderrOnly);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(listFolder(),
            (std::vector<std::string>{"turn_00.png", "turn_01.png", "turn_02.png", "turn_03.png"}));
  // Progress: one line per frame in a log, with frames done, elapsed time and ETA.
  EXPECT_EQ(countOf(r.output, "/4 done"), 4u) << r.output;
  EXPECT_EQ(countOf(r.output, "ETA"), 4u) << r.output;
  EXPECT_NE(r.output.find("frame 3: 4/4 done"), std::string::npos) << r.output;

  for (int k = 0; k < 4; ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "turn_%02d.png", k);
    const Result<Session> s = sessionInPng(path(name));
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_FLOAT_EQ(s->view.camera.azimuth, 10.0f + 90.0f * static_cast<float>(k)) << name;
  }
  ASSERT_EQ(run(flags + "-q -o single.png").status, 0);
  const test::RgbaPixels frame0 = test::readRgbaPng(path("turn_00.png"));
  EXPECT_TRUE(frame0.rgba == test::readRgbaPng(path("single.png")).rgba)
      << "frame 0 is the picture at the given azimuth";
  EXPECT_FALSE(frame0.rgba == test::readRgbaPng(path("turn_01.png")).rgba);

  // Without -o the frames are lic3d_0000.png, ...; --quiet prints nothing.
  const CommandRun quiet = run("render -q --grid 8 --width 16 --height 16 --turntable 2");
  ASSERT_EQ(quiet.status, 0) << quiet.output;
  EXPECT_TRUE(quiet.output.empty()) << quiet.output;
  EXPECT_TRUE(fs::exists(path("lic3d_0000.png")) && fs::exists(path("lic3d_0001.png")));
}

TEST_F(CliTest, FrameRangeRendersItsPartOfTheAnimationWithGlobalNumbers) {
  const std::string flags = "render --grid 8 --width 24 --height 24 --turntable 5 ";
  ASSERT_EQ(run(flags + "-q -o 'all_%d.png'").status, 0);
  const CommandRun part = run(flags + "--frames 2:4 -o 'part_%d.png'", "", Streams::StdoutOnly);
  ASSERT_EQ(part.status, 0) << part.output;
  for (const char* absent : {"part_0.png", "part_1.png", "part_4.png"})
    EXPECT_FALSE(fs::exists(path(absent))) << absent;
  for (const char* frame : {"2", "3"})
    EXPECT_TRUE(test::readRgbaPng(path(std::string("part_") + frame + ".png")).rgba ==
                test::readRgbaPng(path(std::string("all_") + frame + ".png")).rgba)
        << "frame " << frame << " of a range is that frame of the whole animation";
  const nlohmann::json summary = summaryOf(part.output);
  EXPECT_EQ(summary["frames"], 2) << part.output;
  EXPECT_EQ(summary["outputs"], nlohmann::json::array({"part_2.png", "part_3.png"}));
}

TEST_F(CliTest, AnimateBiasCyclesTheBiasAndRecomputesTheLicPerFrame) {
  const std::string flags = "render -q --grid 8 --length 4 --width 24 --height 24 ";
  ASSERT_EQ(run(flags + "--animate-bias 8 -o 'bias_%d.png'").status, 0);
  const int expected[8] = {-4, -2, 0, 2, 4, 2, 0, -2};  // up and back: frame 8 would be frame 0
  std::vector<std::vector<std::uint8_t>> frames;
  for (int k = 0; k < 8; ++k) {
    const fs::path file = path("bias_" + std::to_string(k) + ".png");
    const Result<Session> s = sessionInPng(file);
    ASSERT_TRUE(s.ok()) << s.error().message;
    EXPECT_EQ(s->lic.bias, expected[k]) << "frame " << k;
    frames.push_back(test::readRgbaPng(file).rgba);
  }
  EXPECT_TRUE(frames[1] == frames[7]) << "the same bias makes the same frame";
  EXPECT_FALSE(frames[0] == frames[1]) << "the LIC volume follows the bias";
  ASSERT_EQ(run(flags + "--bias -4 -o single.png").status, 0);
  EXPECT_TRUE(frames[0] == test::readRgbaPng(path("single.png")).rgba);
}

TEST_F(CliTest, VideoWithoutFfmpegOnPathFailsBeforeAnyWork) {
  const CommandRun r = run("render --grid 8 --turntable 3 --video movie.mp4", "PATH=/nonexistent");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("ffmpeg"), std::string::npos) << r.output;
  EXPECT_EQ(listFolder().size(), 0u) << "no frame was rendered";
}

// A stand-in ffmpeg records its arguments and writes the file it is given last, so the command
// line and the renaming are tested wherever ffmpeg is missing.
TEST_F(CliTest, VideoRunsFfmpegOnTheFramesAndRenamesItsOutput) {
  fs::create_directories(path("bin"));
  writeBytes("bin/ffmpeg",
             "#!/bin/sh\nprintf '%s\\n' \"$@\" > ffmpeg-args.txt\nfor last; do :; done\n"
             "printf video > \"$last\"\n");
  fs::permissions(path("bin/ffmpeg"), fs::perms::owner_all);
  const std::string withFake = "PATH='" + path("bin").string() + "':\"$PATH\"";
  const CommandRun r =
      run("render --grid 8 --width 20 --height 20 --turntable 3 --fps 12 -o 'f_%03d.png' "
          "--video movie.mp4",
          withFake, Streams::StdoutOnly);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(test::readWhole(path("movie.mp4")), "video");
  const std::string args = test::readWhole(path("ffmpeg-args.txt"));
  for (const char* expected : {"-framerate\n12\n", "-start_number\n0\n", "-i\n./f_%03d.png\n",
                               "-frames:v\n3\n", "libx264", "yuv420p"})
    EXPECT_NE(args.find(expected), std::string::npos) << expected << " in\n" << args;
  EXPECT_EQ(listFolder(), (std::vector<std::string>{"bin", "f_000.png", "f_001.png", "f_002.png",
                                                    "ffmpeg-args.txt", "movie.mp4"}))
      << "no temporary file is left";
  EXPECT_EQ(summaryOf(r.output)["outputs"].back(), "movie.mp4") << r.output;

  // A failing ffmpeg fails the command (status 1) and leaves no video.
  writeBytes("bin/ffmpeg", "#!/bin/sh\nexit 3\n");
  const CommandRun failed =
      run("render -q --grid 8 --width 20 --height 20 --turntable 2 -o 'g_%d.png' --video m.webm",
          withFake);
  EXPECT_EQ(failed.status, 1) << failed.output;
  EXPECT_NE(failed.output.find("ffmpeg"), std::string::npos) << failed.output;
  for (const std::string& name : listFolder())
    EXPECT_EQ(name.find("m.webm"), std::string::npos) << name << " left behind";

  // A rename that fails says why (it said "Success": hardening, class 14).
  writeBytes("bin/ffmpeg",
             "#!/bin/sh\nfor last; do :; done\nprintf video > \"$last\"\nmkdir -p m2.mp4/in\n");
  const CommandRun blocked =
      run("render -q --grid 8 --width 20 --height 20 --turntable 2 -o 'h_%d.png' --video m2.mp4",
          withFake);
  EXPECT_EQ(blocked.status, 1) << blocked.output;
  EXPECT_NE(blocked.output.find("cannot rename"), std::string::npos) << blocked.output;
  EXPECT_EQ(blocked.output.find("Success"), std::string::npos) << blocked.output;
}

TEST_F(CliTest, VideoWithRealFfmpeg) {
  if (std::system("command -v ffmpeg >/dev/null 2>&1") != 0)
    GTEST_SKIP() << "ffmpeg is not installed";
  const std::string flags = "render -q --grid 8 --width 33 --height 20 --turntable 4 ";
  ASSERT_EQ(run(flags + "-o 'a_%04d.png' --video movie.mp4").status, 0);
  ASSERT_EQ(run(flags + "-o 'b_%d.png' --video movie.webm").status, 0);
  const std::string mp4 = test::readWhole(path("movie.mp4"));
  const std::string webm = test::readWhole(path("movie.webm"));
  ASSERT_GT(mp4.size(), 12u);
  EXPECT_EQ(mp4.substr(4, 4), "ftyp");
  ASSERT_GT(webm.size(), 4u);
  EXPECT_EQ(webm.substr(0, 4), "\x1a\x45\xdf\xa3");
}

TEST_F(CliTest, SummaryIsOneJsonLineOnStdout) {
  const CommandRun render =
      run("render --grid 8 --width 16 --height 16 -o s.png", "", Streams::StdoutOnly);
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_EQ(render.output.rfind("lic3d-summary {", 0), 0u) << render.output;
  EXPECT_EQ(countOf(render.output, "\n"), 1u) << "the only line on stdout: " << render.output;
  const nlohmann::json s = summaryOf(render.output);
  ASSERT_TRUE(s.is_object()) << render.output;
  EXPECT_EQ(s["command"], "render");
  EXPECT_EQ(s["frames"], 1);
  EXPECT_GE(s["seconds"].get<double>(), 0.0);
  EXPECT_EQ(s["outputs"], nlohmann::json::array({"s.png"}));
  EXPECT_NE(s["device"].get<std::string>().find("llvmpipe"), std::string::npos);
  EXPECT_EQ(s["field"]["source"], "tornado");
  EXPECT_EQ(s["field"]["grid"], nlohmann::json::array({8, 8, 8}));

  const CommandRun compute = run("compute --grid 8 -o c.vti", "", Streams::StdoutOnly);
  const nlohmann::json c = summaryOf(compute.output);
  EXPECT_EQ(c["command"], "compute") << compute.output;
  EXPECT_EQ(c["frames"], 0);
  EXPECT_EQ(c["outputs"], nlohmann::json::array({"c.vti"}));
  const CommandRun cpu = run("compute --cpu --grid 8 -o c.nrrd", "", Streams::StdoutOnly);
  EXPECT_EQ(summaryOf(cpu.output)["device"], "CPU reference") << cpu.output;

  EXPECT_TRUE(run("render -q --grid 8 --width 16 --height 16 -o q.png", "", Streams::StdoutOnly)
                  .output.empty());
  const CommandRun failed = run("render --grid 8 --length -2", "", Streams::StdoutOnly);
  EXPECT_EQ(failed.status, 2);
  EXPECT_TRUE(failed.output.empty()) << "no summary for a failed run: " << failed.output;
}

// Luminance statistics of a picture, to tell a picture from an empty or flat one.
struct Coverage {
  double litFraction = 0.0;  // pixels brighter than the black background
  double deviation = 0.0;    // of the lit pixels' luminance
};

Coverage measureCoverage(const test::RgbaPixels& image) {
  double sum = 0.0, sumSquares = 0.0;
  std::size_t lit = 0;
  const std::size_t pixels = static_cast<std::size_t>(image.width) * image.height;
  for (std::size_t i = 0; i < pixels; ++i) {
    const double y =
        0.299 * image.rgba[4 * i] + 0.587 * image.rgba[4 * i + 1] + 0.114 * image.rgba[4 * i + 2];
    if (y < 8.0) continue;
    ++lit;
    sum += y;
    sumSquares += y * y;
  }
  Coverage c;
  if (pixels == 0 || lit == 0) return c;
  c.litFraction = static_cast<double>(lit) / static_cast<double>(pixels);
  const double mean = sum / static_cast<double>(lit);
  c.deviation = std::sqrt(std::max(0.0, sumSquares / static_cast<double>(lit) - mean * mean));
  return c;
}

// The two real data sets load and render, with the gallery's settings, as pictures: something
// drawn, not the whole image, and not a flat block.
TEST_F(CliTest, RealDataSetsRenderAsPictures) {
  struct Case {
    const char* file;
    const char* flags;
    const char* geometry;
  };
  const Case cases[] = {
      {"carotid.vtk",
       "--color magnitude --color-range 0,15 --magnitude-threshold 0.03 --magnitude-opacity 0.5 "
       "--alpha 1 --length 10 --distance 1.6 --azimuth 20",
       "array 'vectors' 76x49x45, spacing 1,1,1, origin 100,80,1"},
      {"example-femm-3d.vtk",
       "--color magnitude --color-range 0,0.01 --clip 0,1,0,0.5,0,1 --azimuth 60 --elevation 20",
       "array 'B' 47x47x47, spacing 0.05,0.05,0.125, origin -1.15,-1.15,-0.375"},
  };
  for (const Case& c : cases) {
    const std::string file = (test::dataFolder() / c.file).string();
    const CommandRun r =
        run("render --field '" + file + "' --width 96 --height 96 " + c.flags + " -o real.png");
    ASSERT_EQ(r.status, 0) << c.file << "\n" << r.output;
    EXPECT_NE(r.output.find(c.geometry), std::string::npos) << r.output;
    const test::RgbaPixels image = test::readRgbaPng(path("real.png"));
    ASSERT_EQ(image.width, 96);
    const Coverage coverage = measureCoverage(image);
    EXPECT_GT(coverage.litFraction, 0.05) << c.file << ": almost nothing drawn";
    EXPECT_LT(coverage.litFraction, 0.9) << c.file << ": the image is one block";
    EXPECT_GT(coverage.deviation, 10.0) << c.file << ": flat, no structure";
  }
}

// --axes draws the box's outline and the axis ranges over the picture: a few percent of the
// pixels change, the rest of the picture stays as it was.
TEST_F(CliTest, AxesOutlineTheBoxWithoutChangingThePicture) {
  const std::string common = "render -q --grid 12 --width 200 --height 200 ";
  ASSERT_EQ(run(common + "-o plain.png").status, 0);
  ASSERT_EQ(run(common + "--axes -o axes.png").status, 0);
  const test::RgbaPixels plain = test::readRgbaPng(path("plain.png"));
  const test::RgbaPixels axes = test::readRgbaPng(path("axes.png"));
  ASSERT_EQ(plain.rgba.size(), axes.rgba.size());
  int changed = 0;
  for (std::size_t i = 0; i < plain.rgba.size(); i += 4)
    changed += plain.rgba[i] != axes.rgba[i] || plain.rgba[i + 1] != axes.rgba[i + 1];
  const double fraction = changed / (200.0 * 200.0);
  EXPECT_GT(fraction, 0.01);
  EXPECT_LT(fraction, 0.15);
}

// --skip-existing: a requeued task redoes only what is missing. A frame whose PNG is whole stays
// the same file (lic3d writes by rename, so a redone frame would be a new inode); a missing frame
// and one cut short are made again, byte for byte as before; with every frame whole, nothing is.
TEST_F(CliTest, SkipExistingRedoesOnlyMissingOrCutFrames) {
  const std::string args = "render --grid 8 --width 32 --height 32 --turntable 4 -o 'f_%d.png'";
  ASSERT_EQ(run(args + " -q").status, 0);
  const auto inode = [&](const char* name) {
    struct stat s {};
    return ::stat(path(name).c_str(), &s) == 0 ? s.st_ino : 0;
  };
  const auto kept0 = inode("f_0.png");
  const auto kept1 = inode("f_1.png");
  const std::string original3 = test::readWhole(path("f_3.png"));
  fs::remove(path("f_2.png"));
  writeBytes("f_3.png", original3.substr(0, original3.size() / 2));  // cut short
  const CommandRun again = run(args + " --skip-existing");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_NE(again.output.find("2 of 4 frame(s) already whole"), std::string::npos) << again.output;
  EXPECT_EQ(inode("f_0.png"), kept0);
  EXPECT_EQ(inode("f_1.png"), kept1);
  EXPECT_TRUE(fs::exists(path("f_2.png")));
  EXPECT_EQ(test::readWhole(path("f_3.png")), original3);
  const CommandRun done = run(args + " --skip-existing");
  ASSERT_EQ(done.status, 0) << done.output;
  EXPECT_NE(done.output.find("4 of 4 frame(s) already whole"), std::string::npos) << done.output;
  EXPECT_EQ(done.output.find("LIC "), std::string::npos) << "no LIC for a finished task";
}

// --skip-existing keeps a PNG only if it decodes whole: a forged one (the signature and an IEND
// chunk, 20 bytes) and one zeroed in the middle (start and end intact) are made again.
TEST_F(CliTest, SkipExistingRedoesPngsThatDoNotDecode) {
  const std::string args = "render --grid 8 --width 32 --height 32 --turntable 2 -o 'f_%d.png'";
  ASSERT_EQ(run(args + " -q").status, 0);
  const std::string original0 = test::readWhole(path("f_0.png"));
  const std::string original1 = test::readWhole(path("f_1.png"));
  writeBytes("f_0.png",
             std::string("\x89PNG\r\n\x1a\n", 8) + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12));
  std::string zeroed = original1;
  std::fill(zeroed.begin() + 60, zeroed.end() - 20, '\0');
  writeBytes("f_1.png", zeroed);
  const CommandRun again = run(args + " --skip-existing");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(again.output.find("already whole"), std::string::npos) << again.output;
  EXPECT_EQ(test::readWhole(path("f_0.png")), original0);
  EXPECT_EQ(test::readWhole(path("f_1.png")), original1);
}

}  // namespace
}  // namespace lic3d
