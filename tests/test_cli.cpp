// SPDX-License-Identifier: BSD-3-Clause
// The command line as a user meets it: flags, help, exit status, files. Real data and the files
// lic3d writes are in test_cli_files.cpp, 2D LIC and time in test_cli_time.cpp.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "core/colormap.h"
#include "core/parameter_ranges.h"
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
using test::pngSize;

TEST_F(CliTest, HelpListsEveryOption) {
  const CommandRun top = run("--help");
  EXPECT_EQ(top.status, 0) << top.output;
  for (const char* command : {"devices", "compute", "render", "bench", "--device", "--validation"})
    EXPECT_NE(top.output.find(command), std::string::npos) << command;

  const char* shared[] = {"--field",
                          "--grid",
                          "--noise",
                          "--seed",
                          "--seed-noise",
                          "--length",
                          "--step",
                          "--bias",
                          "--integrator",
                          "--kernel",
                          "--noise-filter",
                          "--direction",
                          "--field-precision",
                          "--sparsity",
                          "--sparsity-points",
                          "--sparsity-radius",
                          "--sparsity-ratio",
                          "--sparsity-seed",
                          "--cpu",
                          "--output",
                          "--array"};
  const char* view[] = {"--width",
                        "--height",
                        "--slices",
                        "--slicing",
                        "--azimuth",
                        "--elevation",
                        "--distance",
                        "--fov",
                        "--ortho",
                        "--alpha",
                        "--opacity",
                        "--filter",
                        "--background",
                        "--contrast",
                        "--window",
                        "--gain",
                        "--brightness",
                        "--color",
                        "--colormap",
                        "--color-range",
                        "--legend",
                        "--magnitude-opacity",
                        "--magnitude-threshold",
                        "--clip",
                        "--roi",
                        "--axes",
                        "--roi-center",
                        "--roi-size",
                        "--roi-rotate",
                        "--roi-outside",
                        "--fog",
                        "--fog-color",
                        "--stereo",
                        "--eye-separation",
                        "--zero-parallax",
                        "--lighting",
                        "--turntable",
                        "--animate-bias",
                        "--frames",
                        "--video",
                        "--fps",
                        "--rgba-volume"};
  const CommandRun compute = run("compute --help");
  EXPECT_EQ(compute.status, 0);
  for (const char* flag : shared) EXPECT_NE(compute.output.find(flag), std::string::npos) << flag;
  EXPECT_NE(compute.output.find("--slice"), std::string::npos);
  const CommandRun render = run("render --help");
  EXPECT_EQ(render.status, 0);
  for (const char* flag : shared) EXPECT_NE(render.output.find(flag), std::string::npos) << flag;
  for (const char* flag : view) EXPECT_NE(render.output.find(flag), std::string::npos) << flag;
  const CommandRun bench = run("bench --help");
  EXPECT_EQ(bench.status, 0);
  for (const char* flag : {"--sizes", "--lengths", "--frame-sizes", "--frame-volume", "--repeats",
                           "--warmup", "--budget", "--json"})
    EXPECT_NE(bench.output.find(flag), std::string::npos) << flag;
}

TEST_F(CliTest, EveryRenderFlagParses) {
  const CommandRun r =
      run("render --field abc --grid 10,12,14 --seed 3 --length 6 --step 0.75 --bias -2 "
          "--integrator rk4 --kernel hann --noise-filter nearest --direction magnitude "
          "--width 64 --height 48 --slices 20 --slicing axis --azimuth 10 --elevation -30 "
          "--distance 3 --fov 40 --ortho --alpha 0.5 --opacity constant --filter nearest "
          "--background 255,128,0 --window 0.2,0.8 --gain 1.2 --brightness 0.1 -o out.png");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(pngSize(path("out.png")), std::make_pair(64, 48));
  const CommandRun clarity =
      run("render --grid 12 --width 64 --height 48 --sparsity poisson --sparsity-radius 2 "
          "--sparsity-seed 4 --contrast off --color magnitude --colormap viridis "
          "--color-range 0.1,0.4 --legend --magnitude-opacity 1.5 --magnitude-threshold 0.1 "
          "--clip 0,1,0.2,0.9,0,0.7 --roi cylinder --roi-center 0.5,0.4,0.5 --roi-size 0.7 "
          "--roi-rotate 10,20,30 --roi-outside --fog 0.1,0.9 --fog-color 20,20,40 "
          "--stereo side-by-side --eye-separation 0.05 --zero-parallax 2.5 --lighting phong "
          "-o clarity.png");
  ASSERT_EQ(clarity.status, 0) << clarity.output;
  EXPECT_EQ(pngSize(path("clarity.png")), std::make_pair(128, 48)) << "side by side: two eyes";
  for (const char* variant :
       {"--sparsity checkerboard --sparsity-ratio 0.1",
        "--sparsity poisson-approx --sparsity-points 50", "--sparsity jitter --sparsity-radius 2",
        "--sparsity halton --sparsity-points 100", "--sparsity hammersley --sparsity-points 100",
        "--seed-noise 40", "--stereo anaglyph", "--lighting lines", "--roi sphere", "--roi cube",
        "--colormap coolwarm --color magnitude", "--window 0.3,0.7", "--contrast on"}) {
    const CommandRun v = run(std::string("render --grid 10 --width 32 --height 32 -q ") + variant +
                             " -o variant.png");
    EXPECT_EQ(v.status, 0) << variant << "\n" << v.output;
  }
  const CommandRun sparse =
      run("compute --grid 12 --sparsity hammersley --sparsity-points 40 -o s.nrrd");
  ASSERT_EQ(sparse.status, 0) << sparse.output;
  const CommandRun cpu =
      run("--device 0 --validation render --cpu --grid 8 --width 32 --height 32 -q -o cpu.png");
  ASSERT_EQ(cpu.status, 0) << cpu.output;
  EXPECT_TRUE(cpu.output.empty()) << "--quiet: " << cpu.output;
  EXPECT_EQ(pngSize(path("cpu.png")), std::make_pair(32, 32));
}

// --scale makes the same picture larger: its size, the legend's column and the font size times
// the factor, recorded in the session it carries; --legend-title names the legend.
TEST_F(CliTest, ScaleMakesTheSameLayoutLargerAndTheSessionRecordsIt) {
  const std::string args =
      "render -q --grid 8 --width 64 --height 48 --color magnitude --legend --title T "
      "--legend-title '|B| [T]' --font-size 10 ";
  ASSERT_EQ(run(args + "-o small.png").status, 0);
  const CommandRun big = run(args + "--scale 2 -o big.png");
  ASSERT_EQ(big.status, 0) << big.output;
  const auto [smallWidth, smallHeight] = pngSize(path("small.png"));
  const auto [bigWidth, bigHeight] = pngSize(path("big.png"));
  EXPECT_EQ(bigHeight, 2 * smallHeight);
  EXPECT_NEAR(bigWidth, 2 * smallWidth, 2) << "the legend's column grows with its text";
  const Result<Session> stored = test::sessionInPng(path("big.png"));
  ASSERT_TRUE(stored.ok()) << stored.error().message;
  EXPECT_EQ(stored->view.width, 128);
  EXPECT_EQ(stored->view.fontSize, 20.0f);
  EXPECT_EQ(stored->view.legendTitle, "|B| [T]");
}

TEST_F(CliTest, BenchRunsAndWritesJson) {
  const CommandRun r =
      run("bench --field vortex --sizes 8,12 --lengths 2 --frame-sizes 32 --frame-volume 8 "
          "--repeats 5 --warmup 1 --budget 60 --field-precision half --json bench.json");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("llvmpipe"), std::string::npos) << "names the device";
  EXPECT_NE(r.output.find("12^3"), std::string::npos) << r.output;
  const std::string json = test::readWhole(path("bench.json"));
  for (const char* key : {"\"device\"", "\"lic\"", "\"frame\"", "\"median_ms\"", "\"rgba8\""})
    EXPECT_NE(json.find(key), std::string::npos) << key << " in " << json;
}

// `bench --kernels` times every scheme with the texture it names, the masked pass and the launch
// shapes; `bench --fidelity` gives each scheme's error against the converged LIC.
// A parser's message never echoes a huge argument whole.
// What lic3d writes to stdout must arrive: help, the device list and the summary line into a full
// or closed stdout fail the run (status 1, the reason on stderr); they exited 0.
TEST_F(CliTest, AStdoutThatCannotBeWrittenFailsTheRun) {
  for (const std::string args : {"--help >/dev/full", "devices >/dev/full",
                                 "render --grid 8 --width 16 --height 16 -o out.png >/dev/full",
                                 "render --grid 8 --width 16 --height 16 -o out.png >&-"}) {
    const std::string command =
        "cd '" + folder().string() + "' && '" + LIC3D_EXECUTABLE + "' " + args + " 2>err.txt";
    const int raw = std::system(command.c_str());
    EXPECT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 1) << args << ": " << raw;
    EXPECT_NE(test::readWhole(path("err.txt")).find("cannot write to standard output"),
              std::string::npos)
        << args;
  }
}

TEST_F(CliTest, ErrorsAboutHugeArgumentsAreCut) {
  const CommandRun r = run("render --grid 8 --no-such-flag=" + std::string(100000, 'x'));
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find(" characters)"), std::string::npos) << r.output.substr(0, 400);
  EXPECT_LT(r.output.size(), 600u);
}

TEST_F(CliTest, BenchKernelsAndFidelityReportEverySchemeUnderItsOwnLabels) {
  const CommandRun kernels = run(
      "bench --kernels --sizes 8 --lengths 3 --repeats 5 --warmup 1 --budget 120 --json k.json");
  ASSERT_EQ(kernels.status, 0) << kernels.output;
  const nlohmann::json k = nlohmann::json::parse(test::readWhole(path("k.json")));
  std::set<std::string> seen;
  for (const nlohmann::json& row : k["rows"]) {
    const std::string kernel = row["kernel"], precision = row["precision"];
    EXPECT_TRUE(row.contains("median_ms")) << row.dump();
    if (row["naive"]) continue;
    // The label names the texture the renderer made, and the scheme that ran.
    EXPECT_EQ(kernel, std::string(row["scheme"]) + ", " + precision);
    seen.insert(kernel);
    EXPECT_GT(row["r_naive"].get<double>(), 0.95) << kernel;
  }
  for (const char* expected : {"exact, RGBA16F", "exact, RGBA32F", "ab2, RGBA16F", "ab2, RGBA8",
                               "fused, RGBA16F", "fused, RGBA32F", "fused, RGBA8"})
    EXPECT_EQ(seen.count(expected), 1u) << expected << " in " << kernels.output;
  ASSERT_EQ(k["masked"].size(), 2u);  // the default scheme and the fused one
  for (const nlohmann::json& row : k["masked"]) {
    EXPECT_GT(row["masked_ms"].get<double>(), 0.0);
    EXPECT_GT(row["hidden_fraction"].get<double>(), 0.0);
  }
  EXPECT_EQ(k["launch"].size(), 28u);
  int chosen = 0;
  for (const nlohmann::json& row : k["launch"])
    chosen += row["chosen_for_this_device_type"] ? 1 : 0;
  EXPECT_EQ(chosen, 2) << "one launch per scheme is this device type's";

  const CommandRun fidelity = run("bench --fidelity --sizes 12 --lengths 6 --json f.json");
  ASSERT_EQ(fidelity.status, 0) << fidelity.output;
  const nlohmann::json f = nlohmann::json::parse(test::readWhole(path("f.json")));
  ASSERT_EQ(f["rows"].size(), 5u * 8u);  // five analytic fields, eight scheme-texture pairs
  for (const nlohmann::json& row : f["rows"]) {
    EXPECT_GT(row["mean_abs_error"].get<double>(), 0.0) << row.dump();
    if (row["scheme"] == "exact" && row["texture"] == "CPU double") {
      EXPECT_EQ(row["relative_to_exact"].get<double>(), 1.0);
    }
    // Steps of 2h: the fused scheme's CPU volume lies further from the converged one.
    if (row["field"] == "tornado" && row["scheme"] == "fused" && row["texture"] == "CPU double") {
      EXPECT_GT(row["relative_to_exact"].get<double>(), 1.5) << row.dump();
    }
  }
}

// --scheme and --field-precision byte reach the GPU and the CPU reference: each run matches the
// reference of its own scheme, and the schemes give different volumes.
TEST_F(CliTest, SchemeAndByteTextureFlagsReachTheLicPass) {
  for (const char* scheme : {"exact", "ab2", "fused"}) {
    const std::string s = scheme;
    for (const auto& [extra, suffix] : {std::pair{"", ""}, std::pair{" --cpu", "_cpu"},
                                        std::pair{" --field-precision byte", "_byte"}}) {
      const CommandRun r = run("compute --field abc --grid 12,10,8 --length 8 --scheme " + s +
                               extra + " -o " + s + suffix + ".nrrd");
      ASSERT_EQ(r.status, 0) << r.output;
    }
  }
  LicParams params;
  params.length = 8;
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {12, 10, 8});
  for (const StepScheme scheme : {StepScheme::Exact, StepScheme::Ab2, StepScheme::Fused}) {
    params.scheme = scheme;
    const ScalarVolume reference =
        *computeLicReference(field, makeWhiteNoise(field.dims, 1), params);
    const std::string name(enumName(scheme));
    // GPU with float texels, the CPU reference itself, GPU with 8-bit texels.
    for (const auto& [suffix, tolerance] :
         {std::pair{"", 1e-3}, std::pair{"_cpu", 1e-6}, std::pair{"_byte", 1e-2}}) {
      const Result<NoiseVolume> volume = readNoiseNrrd(path(name + suffix + ".nrrd"));
      ASSERT_TRUE(volume.ok()) << volume.error().message;
      double diff = 0.0;
      for (std::size_t i = 0; i < reference.values.size(); ++i)
        diff += std::abs(volume->value(i) - reference.values[i]);
      EXPECT_LE(diff / static_cast<double>(reference.values.size()), tolerance) << name << suffix;
    }
  }
  EXPECT_NE(test::readWhole(path("exact.nrrd")), test::readWhole(path("ab2.nrrd")));
  EXPECT_NE(test::readWhole(path("exact.nrrd")), test::readWhole(path("fused.nrrd")));
  EXPECT_NE(test::readWhole(path("ab2.nrrd")), test::readWhole(path("fused.nrrd")));
  EXPECT_EQ(run("render --grid 8 --scheme midpoint").status, 2);
  EXPECT_EQ(run("render --grid 8 --field-precision quarter").status, 2);
}

TEST_F(CliTest, ComputeWritesTheLicVolumeOnTheFieldGrid) {
  const CommandRun gpu = run("compute --field abc --grid 12,10,8 --length 8 -o gpu.nrrd");
  ASSERT_EQ(gpu.status, 0) << gpu.output;
  const CommandRun cpu = run("compute --field abc --grid 12,10,8 --length 8 --cpu -o cpu.nrrd");
  ASSERT_EQ(cpu.status, 0) << cpu.output;

  // Float NRRD volumes read back through the noise reader (values in [0,1] are kept as they are).
  const Result<NoiseVolume> a = readNoiseNrrd(path("gpu.nrrd"));
  const Result<NoiseVolume> b = readNoiseNrrd(path("cpu.nrrd"));
  ASSERT_TRUE(a.ok()) << a.error().message;
  ASSERT_TRUE(b.ok()) << b.error().message;
  EXPECT_EQ(a->dims, Dims(12, 10, 8));
  EXPECT_EQ(a->type, NoiseType::Float32);

  LicParams params;
  params.length = 8;
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {12, 10, 8});
  const ScalarVolume reference = *computeLicReference(field, makeWhiteNoise(field.dims, 1), params);
  double gpuDiff = 0.0, cpuDiff = 0.0;
  for (std::size_t i = 0; i < reference.values.size(); ++i) {
    gpuDiff += std::abs(a->value(i) - reference.values[i]);
    cpuDiff = std::max(cpuDiff, static_cast<double>(std::abs(b->value(i) - reference.values[i])));
  }
  EXPECT_LE(gpuDiff / static_cast<double>(reference.values.size()), 1e-3);
  EXPECT_EQ(cpuDiff, 0.0) << "--cpu writes the reference itself";
}

// Every output's folder is written to before any work: one that cannot be written (here a
// pseudo file system, which refuses even root) stops the run before the PNG is written, and the
// check leaves nothing behind when it passes.
TEST_F(CliTest, AnOutputThatCannotBeWrittenStopsTheRunBeforeAnyOutput) {
  const CommandRun r = run("render --grid 8 --rgba-volume /proc/self/v.vti -o out.png");
  EXPECT_EQ(r.status, 2) << r.output;
  EXPECT_NE(r.output.find("cannot write in folder /proc/self"), std::string::npos) << r.output;
  EXPECT_EQ(listFolder().size(), 0u);
  ASSERT_EQ(run("render --grid 8 -q -o out.png").status, 0);
  EXPECT_EQ(listFolder(), std::vector<std::string>{"out.png"});
}

TEST_F(CliTest, BadArgumentsExitWithStatusTwoAndLeaveNothing) {
  const char* cases[] = {
      "",       // no subcommand
      "paint",  // unknown subcommand
      "render --no-such-flag",
      "render --integrator rk3",
      "render --kernel triangle",
      "render --length -1",
      "render --length 10 --bias 11",
      "render --step 0",
      "render --grid 0",
      "render --grid 8,8",
      "render --grid 8,x,8",
      "render --grid 5000",
      "render --width 0",
      "render --background 1,2",
      "render --background 300,0,0",
      "render --window 0.8,0.2",
      "render --window high",
      "render --slicing diagonal",
      "render --elevation 120",
      "render --seed -1",
      "render --sparsity-seed -5",
      "render --azimuth nan",
      "render --time inf",
      "render --field hurricane",
      "render --field missing.nrrd",
      "render --field data.vtk --grid 32",
      "render --noise missing.nrrd --grid 8",
      "render --grid 8 -o picture.jpg",
      "render --grid 8 -o no/such/folder/out.png",
      "compute --grid 8 -o volume.png",
      "render --sparsity spiral",
      "render --sparsity checkerboard --sparsity-ratio 1.5",
      "render --sparsity poisson --sparsity-radius -1",
      "render --grid 8 --sparsity halton --sparsity-points 100000",  // more points than voxels
      "render --seed-noise -5",
      "render --grid 8 --seed-noise 4 --noise noise.nrrd",
      "render --contrast maybe",
      "render --color rainbow",
      "render --colormap jet",
      "render --color-range 1",
      "render --color-range 0.5,0.2",
      "render --look dense --legend",  // a legend needs --color magnitude
      "render --font-size -1",
      "render --scale 0",
      "render --width 8000 --scale 4",  // beyond the largest picture
      "render --magnitude-opacity -1",
      "render --magnitude-threshold 2",
      "render --clip 0,1,0,1",
      "render --clip 0.5,0.4,0,1,0,1",
      "render --clip 0,1,0,1,0,2",
      "render --roi torus",
      "render --roi sphere --roi-size 0",
      "render --roi-center 0.5,0.5",
      "render --roi-rotate a,b,c",
      "render --fog 0.8,0.2",
      "render --fog 0.5",
      "render --fog-color 1,1",
      "render --stereo wobble",
      "render --stereo anaglyph --ortho",
      "render --eye-separation -0.1",
      "render --lighting gouraud",
      "render --filter quadratic",
      "bench --sizes 64,abc",
      "bench --repeats 2",
      "--device no-such-device render --grid 8",
      // --array, compute outputs, --slice
      "render --grid 8 --array B",                  // an analytic field has no arrays
      "compute --grid 8 -o volume.png",             // a slice needs --slice
      "compute --grid 8 --slice z -o volume.nrrd",  // a slice is a PNG
      "compute --grid 8 --slice z:8 -o slice.png",  // 8 slices: 0..7
      "compute --grid 8 --slice w:1 -o slice.png",
      "compute --grid 8 --slice z:-1 -o slice.png",
      "compute --grid 8 --slice z:one -o slice.png",
      // animations, frame ranges, frame patterns
      "render --grid 8 --turntable 3 -o frame.png",  // no frame number in the name
      "render --grid 8 --turntable 3 -o 'frame_%s.png'",
      "render --grid 8 --turntable 3 -o 'frame_%d_%d.png'",
      "render --grid 8 --turntable 3 -o 'frame_%5d.png'",
      "render --grid 8 --turntable 3 -o 'frame_%04d.jpg'",
      "render --grid 8 --turntable 3 -o 'no/such/folder/frame_%d.png'",
      "render --grid 8 --turntable 0",
      "render --grid 8 --turntable 3 --animate-bias 3",
      "render --grid 8 --length 0 --animate-bias 4",
      "render --grid 8 --frames 0:2",  // no animation
      "render --grid 8 --turntable 4 --frames 3:3",
      "render --grid 8 --turntable 4 --frames 2:5",
      "render --grid 8 --turntable 4 --frames -1:2",
      "render --grid 8 --turntable 4 --frames a:b",
      "render --grid 8 --turntable 4 --frames 2",
      "render --grid 8 --video movie.mp4",  // no animation
      "render --grid 8 --turntable 3 --video movie.avi",
      "render --grid 8 --turntable 3 --frames 0:2 --video movie.mp4",
      "render --grid 8 --turntable 3 --fps 0 --video movie.mp4",
      "render --grid 8 --rgba-volume volume.raw",
      "render --grid 8 --animate-bias 4 --rgba-volume volume.vti",
      "render --grid 8 --rgba-volume no/such/folder/volume.vti",
  };
  for (const char* args : cases) {
    const CommandRun r = run(args);
    EXPECT_EQ(r.status, 2) << "lic3d " << args << "\n" << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << "lic3d " << args << "\n" << r.output;
    EXPECT_EQ(listFolder().size(), 0u) << "lic3d " << args << " left files behind";
  }
}

TEST_F(CliTest, RefusedValuesNameTheFlagTheValueAndTheRange) {
  // Every kind of numeric flag: a parameter's (its range from core/parameter_ranges.h), whole or
  // not, and a front end's own setting, on each subcommand's parser.
  struct Flag {
    std::string before;  // what comes before the flag
    std::string flag;
    std::string range;
    bool whole;
    std::string after = "";
  };
  const std::vector<Flag> flags = {
      {"", "--threads", "[0, 4096]", true, " devices"},
      {"render", "--length", ranges::kLength.text(), true},
      {"compute", "--length", ranges::kLength.text(), true},
      {"render", "--width", ranges::kImageWidth.text(), true},
      {"compute", "--time-steps", ranges::kTimeSteps.text(), true},
      {"render", "--step", ranges::kStep.text(), false},
      {"render", "--fov", ranges::kFov.text(), false},
      {"render", "--turntable", "[1, 1e+06]", true},
      {"render2d", "--animate-time", "[1, 1e+06]", true},
      {"render", "--fps", "[0.1, 1000]", false},
      {"bench", "--repeats", "[5, 1000]", true},
      {"bench", "--budget", "[1, 86400]", false},
      {"render", "--grid", ranges::kGrid.text(), true},
  };
  const std::vector<std::string> values = {"abc", "-1", "1e999",
                                           "nan", "",   "99999999999999999999999999"};
  for (const Flag& f : flags) {
    for (const std::string& value : values) {
      const std::string args = f.before + " " + f.flag + " '" + value + "'" + f.after;
      const CommandRun r = run(args);
      EXPECT_EQ(r.status, 2) << "lic3d " << args << "\n" << r.output;
      for (const std::string& part : {f.flag + ": ", "got '" + value + "'", f.range})
        EXPECT_NE(r.output.find(part), std::string::npos)
            << "lic3d " << args << " does not say " << part << ":\n"
            << r.output;
      for (const char* internal :
           {"Could not convert", "not in range", "FAILED", "Value ", "INT", "FLOAT", "TEXT"})
        EXPECT_EQ(r.output.find(internal), std::string::npos)
            << "lic3d " << args << " speaks CLI11:\n"
            << r.output;
    }
    if (f.whole) {
      // A fraction inside the range.
      const CommandRun r = run(f.before + " " + f.flag + " 7.5" + f.after);
      for (const std::string& part :
           {f.flag + ": ", "a whole number in " + f.range, std::string("got '7.5'")})
        EXPECT_NE(r.output.find(part), std::string::npos)
            << f.flag << " 7.5 does not say " << part << ":\n"
            << r.output;
    }
  }
}

TEST_F(CliTest, BadFilesExitWithStatusTwoNamingTheFile) {
  {
    std::ofstream truncated(path("truncated.nrrd"), std::ios::binary);
    truncated << "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 8 8 8\nencoding: raw\n"
                 "endian: little\n\n"
              << std::string(100, '\0');
  }
  {
    std::ofstream garbage(path("garbage.vtk"), std::ios::binary);
    garbage << "this is not a VTK file\n";
  }
  {
    std::ofstream noise(path("noise.nrrd"), std::ios::binary);
    noise << "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 4 4 4\nencoding: raw\n\n"
          << std::string(64, 'x');
  }
  const std::pair<const char*, const char*> cases[] = {
      {"render --field truncated.nrrd -o out.png", "truncated.nrrd"},
      {"compute --field garbage.vtk -o out.nrrd", "garbage.vtk"},
      {"render --grid 8 --noise noise.nrrd -o out.png", "noise.nrrd"},  // 4^3 noise, 8^3 field
  };
  for (const auto& [args, file] : cases) {
    const CommandRun r = run(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(file), std::string::npos) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(path("out.png")) || fs::exists(path("out.nrrd"))) << args;
  }
}

TEST_F(CliTest, RealFieldFromFile) {
  const CommandRun r =
      run("render --field '" + (test::dataFolder() / "example-femm-3d.vtk").string() +
          "' --width 64 --height 64 -o femm.png");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(pngSize(path("femm.png")), std::make_pair(64, 64));
}

TEST_F(CliTest, NoVulkanDriverIsAClearErrorNotACrash) {
  const CommandRun r = run("render --grid 8", "VK_DRIVER_FILES=/nonexistent/icd.json");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("no Vulkan"), std::string::npos) << r.output;
  EXPECT_EQ(listFolder().size(), 0u);
  const CommandRun devices = run("devices", "VK_DRIVER_FILES=/nonexistent/icd.json");
  EXPECT_EQ(devices.status, 1) << devices.output;
}

TEST_F(CliTest, DevicesListsTheDriver) {
  const CommandRun r = run("devices");
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("llvmpipe"), std::string::npos) << r.output;
}

TEST_F(CliTest, RenderWithNoOptionsWritesLic3dPng) {
  const CommandRun r = run("render");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(pngSize(path("lic3d.png")), std::make_pair(1024, 1024));
  EXPECT_NE(r.output.find("tornado"), std::string::npos) << r.output;
}

// A session file written by hand (as the viewer would save it) makes the same pixels as the
// same parameters given as flags; flags after --session override it.
TEST_F(CliTest, RenderSessionReproducesTheImageOfTheSameFlags) {
  writeBytes("s.json", R"({
  "lic3d_session": 1,
  "field": {"source": "abc", "grid": [12, 10, 14]},
  "noise": {"seed": 5},
  "lic": {"length": 6, "step": 0.75, "bias": 2, "kernel": "hann",
          "sparsity": {"distribution": "halton", "points": 40, "seed": 3}},
  "view": {"width": 48, "height": 40, "camera": {"azimuth": 70, "elevation": -10},
           "alpha": 0.5, "color": "magnitude", "colormap": "viridis",
           "clip_min": [0.1, 0, 0], "fog": true, "background": [0.2, 0.1, 0]}
})");
  const std::string flags =
      "--look dense --field abc --grid 12,10,14 --seed 5 --length 6 --step 0.75 --bias 2 "
      "--kernel hann --sparsity halton --sparsity-points 40 --sparsity-seed 3 --width 48 --height "
      "40 "
      "--azimuth 70 --elevation -10 --alpha 0.5 --color magnitude --colormap viridis "
      "--clip 0.1,1,0,1,0,1 --fog 0,1 --background 0.2,0.1,0";
  ASSERT_EQ(run("render -q --session s.json -o from_session.png").status, 0);
  ASSERT_EQ(run("render -q " + flags + " -o from_flags.png").status, 0);
  const test::RgbaPixels a = test::readRgbaPng(path("from_session.png"));
  const test::RgbaPixels b = test::readRgbaPng(path("from_flags.png"));
  ASSERT_EQ(a.width, 48);
  ASSERT_EQ(a.height, 40);
  EXPECT_TRUE(a.rgba == b.rgba) << "the session and the flags make different images";

  // A flag after the session overrides it: another azimuth is another picture.
  ASSERT_EQ(run("render -q --session s.json --azimuth 10 -o override.png").status, 0);
  EXPECT_FALSE(test::readRgbaPng(path("override.png")).rgba == a.rgba);

  // A session with a misspelt key is refused, naming the file and the key.
  writeBytes("bad.json", R"({"lic": {"lenght": 6}})");
  const CommandRun bad = run("render -q --session bad.json -o bad.png");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("bad.json"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("lenght"), std::string::npos) << bad.output;
  EXPECT_FALSE(fs::exists(path("bad.png")));
}

// Tests leave nothing outside the build folder: each test's folder and the temporary folder of
// the lic3d it starts (TMPDIR) lie in it, not in /tmp.
TEST_F(CliTest, ScratchLiesInTheBuildFolder) {
  const fs::path build = fs::weakly_canonical(fs::path(LIC3D_EXECUTABLE).parent_path());
  const auto inBuild = [&](const fs::path& path) {
    const fs::path relative = fs::weakly_canonical(path).lexically_relative(build);
    return !relative.empty() && *relative.begin() != "..";
  };
  EXPECT_TRUE(inBuild(folder())) << folder() << " is outside " << build;
  EXPECT_TRUE(inBuild(fs::temp_directory_path())) << fs::temp_directory_path();
  const CommandRun child = shell("printf %s \"$TMPDIR\"");
  ASSERT_EQ(child.status, 0);
  EXPECT_TRUE(inBuild(child.output)) << "TMPDIR of a child: '" << child.output << "'";
}

// Progress names the device: "on the GPU" was printed for llvmpipe, a CPU (hardening, class 15).
TEST_F(CliTest, ProgressNamesTheDevice) {
  const CommandRun r = run("compute --grid 8 -o v.nrrd", "", test::Streams::StderrOnly);
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("LIC 8x8x8 on llvmpipe"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("on the GPU"), std::string::npos) << r.output;
}

// Where the time goes: --timings prints the stages on stderr, the summary has them as
// "timings"; --threads bounds the CPU threads.
TEST_F(CliTest, TimingsNameEveryStageAndThreadsAreBounded) {
  const CommandRun r =
      run("render --timings --threads 1 --grid 16 --width 32 --height 32 -o a.png");
  ASSERT_EQ(r.status, 0) << r.output;
  // An analytic field with white noise is made on the device; colour by vorticity needs the
  // field on the host, which makes, measures, packs and uploads it.
  for (const char* stage : {"device", "field and noise (on the device)", "LIC", "frame",
                            "frame read-back", "png encode and write", "other", "total"})
    EXPECT_NE(r.output.find("  " + std::string(stage) + " "), std::string::npos) << stage;
  EXPECT_EQ(r.output.find("  field packing "), std::string::npos) << r.output;
  const CommandRun host =
      run("render --timings --grid 16 --width 32 --height 32 --color-by vorticity -o host.png");
  ASSERT_EQ(host.status, 0) << host.output;
  for (const char* stage :
       {"field (analytic)", "noise", "field statistics", "field packing", "field upload"})
    EXPECT_NE(host.output.find("  " + std::string(stage) + " "), std::string::npos) << stage;
  const std::size_t at = r.output.find("\"timings\":{");
  ASSERT_NE(at, std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"LIC\":", at), std::string::npos);
  // The volume's write is a stage of its own, with its bytes and rate.
  const CommandRun compute = run("compute --timings --grid 16 -o v.nrrd");
  ASSERT_EQ(compute.status, 0) << compute.output;
  EXPECT_NE(compute.output.find("\"volume write\":"), std::string::npos) << compute.output;
  const std::size_t write = compute.output.find("  volume write ");
  ASSERT_NE(write, std::string::npos) << compute.output;
  const std::string line = compute.output.substr(write, compute.output.find('\n', write) - write);
  EXPECT_NE(line.find("(16384 bytes, "), std::string::npos) << line;
  EXPECT_NE(line.find(" GB/s)"), std::string::npos) << line;
  EXPECT_NE(compute.output.find("\"volume read-back\":"), std::string::npos) << compute.output;
  const CommandRun bad = run("render --threads -2 -o b.png");
  EXPECT_EQ(bad.status, 2) << bad.output;
  EXPECT_NE(bad.output.find("--threads"), std::string::npos) << bad.output;
}

}  // namespace
}  // namespace lic3d
