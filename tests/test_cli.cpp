// The command line as a user meets it: flags, help, exit status, files.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

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

struct CommandRun {
  int status = -1;
  std::string output;  // stdout and stderr together, or the one stream asked for
};

// Which of lic3d's output streams a run captures.
enum class Streams { Both, StdoutOnly, StderrOnly };

class CliTest : public test::TempFolderTest {
 protected:
  CommandRun run(const std::string& args, const std::string& environment = "",
                 Streams streams = Streams::Both) const {
    const char* redirect = streams == Streams::Both         ? " 2>&1"
                           : streams == Streams::StdoutOnly ? " 2>/dev/null"
                                                            : " 2>&1 >/dev/null";
    const std::string command = "cd '" + folder().string() + "' && " + environment + " '" +
                                LIC3D_EXECUTABLE + "' " + args + redirect;
    CommandRun result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    std::size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
      result.output.append(buffer.data(), n);
    const int raw = pclose(pipe);
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    return result;
  }
};

// Width and height from a PNG's IHDR chunk.
std::pair<int, int> pngSize(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 24> header{};
  in.read(reinterpret_cast<char*>(header.data()), header.size());
  if (!in || header[1] != 'P' || header[2] != 'N' || header[3] != 'G') return {0, 0};
  auto be32 = [&](int at) {
    return (header[at] << 24) | (header[at + 1] << 16) | (header[at + 2] << 8) | header[at + 3];
  };
  return {be32(16), be32(20)};
}

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

// --scheme and --field-precision byte reach the GPU and the CPU reference: each run matches the
// reference of its own scheme, and the two schemes give different volumes.
TEST_F(CliTest, SchemeAndByteTextureFlagsReachTheLicPass) {
  for (const char* scheme : {"exact", "ab2"}) {
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
  for (const StepScheme scheme : {StepScheme::Exact, StepScheme::Ab2}) {
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
      "render --legend",  // a legend needs --color magnitude
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
      "render --filter cubic",
      "bench --sizes 64,abc",
      "bench --repeats 2",
      "--device no-such-device render --grid 8",
      // --array, compute outputs, --slice
      "render --grid 8 --array B",  // an analytic field has no arrays
      "compute --grid 8 -o volume.raw",
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
      "--field abc --grid 12,10,14 --seed 5 --length 6 --step 0.75 --bias 2 --kernel hann "
      "--sparsity halton --sparsity-points 40 --sparsity-seed 3 --width 48 --height 40 "
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

// The session stored in a PNG written by lic3d.
Result<Session> sessionInPng(const fs::path& file) {
  const test::DecodedPng png = test::decodePng(file);
  const auto text = png.text.find("lic3d-session");
  if (!png.ok || text == png.text.end()) return inputError(file.string() + ": no lic3d-session");
  return sessionFromJson(text->second, file.string());
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

  // Voxels that sparsity hides are NaN in both.
  ASSERT_EQ(
      run("compute -q --grid 12 --sparsity hammersley --sparsity-points 40 -o sparse.vti").status,
      0);
  const Result<ScalarVolume> sparse = readScalarVti(path("sparse.vti"));
  ASSERT_TRUE(sparse.ok()) << sparse.error().message;
  const auto nans = std::count_if(sparse->values.begin(), sparse->values.end(),
                                  [](float v) { return std::isnan(v); });
  EXPECT_GT(nans, 0);
  EXPECT_LT(nans, static_cast<std::ptrdiff_t>(sparse->values.size()));
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
      run("render -q --field abc --grid 12,10,8 --seed 5 --length 6 --kernel hann --width 40 "
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
      "render -q --cpu --field abc --grid 10 --length 4 --width 16 --height 16 --window 0,1 "
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
  ASSERT_EQ(run("render -q " + sparse +
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

// A request the device cannot hold is refused with exit status 3 before anything is allocated:
// under a 4 GB address-space limit, making the 700^3 field (4 GB of vectors) would fail with
// status 1 instead. The message names the request, the bytes and the largest grid that fits.
TEST_F(CliTest, RequestsThatCannotFitAreRefusedBeforeAllocating) {
  for (const char* command : {"render --grid 700 -o big.png", "compute --grid 700 -o big.nrrd",
                              "render --grid 2048 -o big.png"}) {
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
// and no output file at all.
TEST_F(CliTest, ALostDeviceIsReportedAndLeavesNothing) {
  for (const char* command : {"render --grid 8 --width 32 --height 32 -q -o out.png",
                              "compute --grid 8 -q -o out.nrrd"}) {
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
// frame is written to a temporary name in the same folder and renamed once complete.
TEST_F(CliTest, KillingABatchRenderLeavesOnlyCompleteFrames) {
  int complete = 0;
  for (const char* delay : {"0.3", "0.6", "0.9", "1.3", "1.8"}) {
    for (const fs::directory_entry& e : fs::directory_iterator(folder())) fs::remove(e.path());
    run(std::string("--device 0 render --grid 20 --width 96 --height 96 --turntable 40 -q "
                    "-o frame_%02d.png"),
        std::string("timeout -s KILL ") + delay);
    for (const fs::directory_entry& e : fs::directory_iterator(folder())) {
      const std::string name = e.path().filename().string();
      if (name.rfind("frame_", 0) != 0 || e.path().extension() != ".png") continue;
      const test::RgbaPixels frame = test::readRgbaPng(e.path());
      EXPECT_EQ(frame.width, 96) << name << " is not a complete PNG (killed after " << delay
                                 << " s)";
      ++complete;
    }
  }
  EXPECT_GT(complete, 0) << "no frame was finished before the kills: lengthen the delays";
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
  EXPECT_EQ(pngSize(path("plane.png")), std::make_pair(40, 40));
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
  const std::string common = "render --width 48 --height 48 --length 6 ";
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
