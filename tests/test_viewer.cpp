// SPDX-License-Identifier: BSD-3-Clause
// The desktop app under a virtual X server (xvfb-run) on lavapipe: it starts, runs a scripted
// number of frames with validation on, and its screenshot shows the volume and the panels.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "core/session.h"
#include "io/session_file.h"
#include "png_read.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

struct CommandRun {
  int status = -1;
  std::string output;
};

CommandRun runShell(const std::string& command) {
  CommandRun result;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return result;
  std::array<char, 4096> buffer;
  std::size_t n;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
    result.output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  return result;
}

constexpr int kWidth = 1024;
constexpr int kHeight = 640;

class ViewerTest : public test::TempFolderTest {
 protected:
  void SetUp() override {
    test::TempFolderTest::SetUp();
    if (runShell("command -v xvfb-run").status != 0)
      FAIL() << "xvfb-run is missing: install xvfb and xauth (cmake/install-deps.sh does)";
  }

  // lic3d-view in a fresh virtual screen, in the test's folder. The X authority file lies in the
  // test's folder (-f): without it xvfb-run makes a temporary folder of its own, and under load
  // its removal can fail after the app has exited, turning the app's status into xvfb-run's 5.
  // `environment`: assignments put before the command (test hooks).
  CommandRun view(const std::string& args, const std::string& size = "",
                  const std::string& environment = "") const {
    return runShell("cd '" + folder().string() + "' && " + environment +
                    " xvfb-run -a -f .Xauthority -s '-screen 0 1280x800x24' '" +
                    std::string(LIC3D_VIEWER) + "' --validation --window-size " +
                    (size.empty() ? std::to_string(kWidth) + "x" + std::to_string(kHeight) : size) +
                    " " + args);
  }
};

struct Box {
  int x0, y0, x1, y1;
};

// Fraction of the box's pixels for which `test` holds.
template <class Test>
double fraction(const test::RgbaPixels& image, Box box, Test test) {
  int hits = 0, total = 0;
  for (int y = box.y0; y < box.y1; ++y)
    for (int x = box.x0; x < box.x1; ++x, ++total) {
      const std::uint8_t* p = &image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)];
      if (test(p[0], p[1], p[2])) ++hits;
    }
  return total ? static_cast<double>(hits) / total : 0.0;
}

bool lit(int r, int g, int b) { return r + g + b > 30; }
// Dear ImGui's dark style: headers and the title bar are a saturated blue no LIC grey reaches.
bool imguiBlue(int r, int g, int b) { return b > 100 && b > r + 50 && b > g + 20; }

// Where the panels go (docked at the right edge, 380 pixels wide in a 1024 window), where the
// volume projects (the middle of what is left; the window's middle with the panels hidden), and
// the stats at the top of the panel.
constexpr int kPanelWidth = 380;
const Box kPanel{kWidth - 300, 0, kWidth, kHeight / 2};
const Box kVolume{kWidth / 2 - 60, kHeight / 2 - 60, kWidth / 2 + 60, kHeight / 2 + 60};
constexpr int kViewCentre = (kWidth - kPanelWidth) / 2;
const Box kDockedVolume{kViewCentre - 60, kHeight / 2 - 60, kViewCentre + 60, kHeight / 2 + 60};
const Box kStats{kWidth - kPanelWidth, 20, kWidth, 70};

// The columns [first, last] of the box that hold a lit pixel.
std::pair<int, int> litColumns(const test::RgbaPixels& image, Box box) {
  int first = box.x1, last = box.x0 - 1;
  for (int y = box.y0; y < box.y1; ++y)
    for (int x = box.x0; x < box.x1; ++x) {
      const std::uint8_t* p = &image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)];
      if (lit(p[0], p[1], p[2])) {
        first = std::min(first, x);
        last = std::max(last, x);
      }
    }
  return {first, last};
}

TEST_F(ViewerTest, ScriptedRunShowsTheVolumeAndThePanelsAndQuits) {
  // The dense look: an opaque block whose outline is easy to find.
  const CommandRun r = view("--look dense --grid 32 --frames 4 --screenshot shot.png");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
  const test::RgbaPixels shot = test::readRgbaPng(path("shot.png"));
  ASSERT_EQ(shot.width, kWidth) << r.output;
  ASSERT_EQ(shot.height, kHeight);
  // With the panels shown the screenshot carries the session of the picture without them, at
  // the window's size.
  Result<Session> carried = readSession(path("shot.png"));
  ASSERT_TRUE(carried) << carried.error().message;
  EXPECT_EQ(carried->view.width, kWidth);
  EXPECT_EQ(carried->view.height, kHeight);

  EXPECT_GT(fraction(shot, kDockedVolume, [](int r_, int g, int b) { return lit(r_, g, b); }), 0.9)
      << "the volume should cover the middle of the view left of the panels";
  // The panels are docked beside the volume, not over it: the volume is centred in what is left
  // (within 20 pixels: the perspective box is not symmetric), not in the window (512).
  const auto [first, last] =
      litColumns(shot, {0, kHeight / 4, kWidth - kPanelWidth, kHeight * 3 / 4});
  EXPECT_GT(first, 0);
  EXPECT_LT(last, kWidth - kPanelWidth - 1);
  EXPECT_NEAR(0.5 * (first + last), kViewCentre, 20.0) << first << ".." << last;
  // LIC, not a flat block: the grey values spread.
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = kDockedVolume.y0; y < kDockedVolume.y1; ++y)
    for (int x = kDockedVolume.x0; x < kDockedVolume.x1; ++x, ++n) {
      const double v = shot.rgba[4 * (static_cast<std::size_t>(y) * kWidth + x)];
      sum += v;
      sum2 += v * v;
    }
  const double deviation = std::sqrt(sum2 / n - (sum / n) * (sum / n));
  EXPECT_GT(deviation, 10.0) << "the volume looks flat: is the LIC texture there?";
  // Contrast stretch in effect: the volume is grey texture, not saturated white.
  EXPECT_LT(fraction(shot, kDockedVolume, [](int r_, int g, int b) { return r_ + g + b > 735; }),
            0.2);

  EXPECT_GT(fraction(shot, kPanel, imguiBlue), 0.02) << "the parameter panels are missing";
  EXPECT_GT(
      fraction(shot, kStats, [](int r_, int g, int b) { return r_ > 200 && g > 200 && b > 200; }),
      0.02)
      << "the stats' text is missing from the top of the panel";
}

TEST_F(ViewerTest, HiddenUiLeavesOnlyTheVolume) {
  const CommandRun r = view("--grid 24 --frames 3 --hide-ui --screenshot shot.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const test::RgbaPixels shot = test::readRgbaPng(path("shot.png"));
  ASSERT_EQ(shot.width, kWidth) << r.output;
  EXPECT_EQ(fraction(shot, kPanel, imguiBlue), 0.0);
  EXPECT_GT(fraction(shot, kVolume, [](int r_, int g, int b) { return lit(r_, g, b); }), 0.9);
}

// The largest difference of a colour channel between two pictures of one size, and how many
// channels differ by more than one level.
struct PixelDifference {
  int largest = 0;
  std::size_t beyondOne = 0;
};
PixelDifference difference(const test::RgbaPixels& a, const test::RgbaPixels& b) {
  PixelDifference d;
  for (std::size_t i = 0; i < a.rgba.size() && i < b.rgba.size(); ++i) {
    if (i % 4 == 3) continue;
    const int step = std::abs(static_cast<int>(a.rgba[i]) - static_cast<int>(b.rgba[i]));
    d.largest = std::max(d.largest, step);
    if (step > 1) ++d.beyondOne;
  }
  return d;
}

// Every PNG the app writes carries the session that made it, as the CLI's do: `lic3d render
// --session` remakes a screenshot taken with the panels hidden, and the "Render image" picture,
// pixel for pixel (within one level): the same camera and aspect at the window's size, the LIC
// parameters shown, the same look, and the legend, title and axes the engine draws in both.
TEST_F(ViewerTest, ScreenshotsAndRenderedImagesRemakeThemselves) {
  const CommandRun r = view(
      "--grid 32 --azimuth 50 --elevation 20 --length 12 --legend --axes --title Remade "
      "--hide-ui --frames 3 --screenshot shot.png --render-image image.png --image-size 96x72",
      "160x120");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
  for (const auto& [name, width, height] :
       {std::tuple<std::string, int, int>{"shot", 160, 120}, {"image", 96, 72}}) {
    SCOPED_TRACE(name);
    const test::RgbaPixels made = test::readRgbaPng(path(name + ".png"));
    ASSERT_EQ(made.width, width) << r.output;
    ASSERT_EQ(made.height, height);
    EXPECT_GT(
        fraction(made, {0, 0, width, height}, [](int r_, int g, int b) { return lit(r_, g, b); }),
        0.2)
        << "no volume in the picture";
    Result<Session> carried = readSession(path(name + ".png"));
    ASSERT_TRUE(carried) << carried.error().message;
    EXPECT_EQ(carried->view.width, width);
    EXPECT_EQ(carried->view.height, height);
    EXPECT_EQ(carried->lic.length, 12);
    EXPECT_EQ(test::decodePng(path(name + ".png")).text["Software"], "lic3d 0.1.0");

    const CommandRun again =
        runShell("cd '" + folder().string() + "' && '" + std::string(LIC3D_EXECUTABLE) +
                 "' render -q --session " + name + ".png -o " + name + "-again.png");
    ASSERT_EQ(again.status, 0) << again.output;
    const test::RgbaPixels remade = test::readRgbaPng(path(name + "-again.png"));
    ASSERT_EQ(remade.width, width);
    ASSERT_EQ(remade.height, height);
    const PixelDifference d = difference(made, remade);
    std::printf("%s.png remade: largest difference %d, %zu channels beyond one level\n",
                name.c_str(), d.largest, d.beyondOne);
    EXPECT_LE(d.largest, 1) << d.beyondOne << " channels differ by more than one level";
  }

  // The app's contrast stretch follows the whole grid (its LIC makes every voxel), the CLI's the
  // bricks the view can show (docs/VISIBLE_WORK.md): where the view hides whole bricks (a clip
  // box) the remake takes --visible-work off.
  const CommandRun clipped = view(
      "--grid 32 --clip 0,0.5,0,1,0,1 --hide-ui --frames 3 --screenshot clipped.png", "160x120");
  ASSERT_EQ(clipped.status, 0) << clipped.output;
  const CommandRun again =
      runShell("cd '" + folder().string() + "' && '" + std::string(LIC3D_EXECUTABLE) +
               "' render -q --session clipped.png --visible-work off -o clipped-again.png");
  ASSERT_EQ(again.status, 0) << again.output;
  const test::RgbaPixels made = test::readRgbaPng(path("clipped.png"));
  const test::RgbaPixels remade = test::readRgbaPng(path("clipped-again.png"));
  ASSERT_EQ(remade.width, made.width);
  ASSERT_EQ(remade.height, made.height);
  const PixelDifference d = difference(made, remade);
  std::printf("clipped.png remade with --visible-work off: largest difference %d\n", d.largest);
  EXPECT_LE(d.largest, 1) << d.beyondOne << " channels differ by more than one level";
}

// The app starts from a session and saves the same session back; `lic3d render` reads it.
TEST_F(ViewerTest, SessionRoundTripsThroughTheApp) {
  Session original;
  original.field.field = "abc";
  original.field.grid = Dims{20, 18, 16};
  original.lic.length = 7;
  original.lic.kernel = Kernel::Hann;
  original.view.color = ColorMode::Magnitude;
  original.view.colormap = Colormap::CoolWarm;
  original.view.camera.azimuth = 60.0f;
  original.view.clipMax = {0.75f, 1.0f, 1.0f};
  original.view.width = 64;
  original.view.height = 48;
  ASSERT_TRUE(writeSession(path("in.json"), original));

  const CommandRun r = view("--session in.json --frames 2 --save-session out.json");
  ASSERT_EQ(r.status, 0) << r.output;
  Result<Session> saved = readSession(path("out.json"));
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_EQ(*saved, original) << sessionToJson(*saved);

  const CommandRun render =
      runShell("cd '" + folder().string() + "' && '" + std::string(LIC3D_EXECUTABLE) +
               "' render -q --session out.json -o out.png");
  ASSERT_EQ(render.status, 0) << render.output;
  EXPECT_EQ(test::readRgbaPng(path("out.png")).width, 64);
}

// A large colour-map preset loaded in the app: the session it saves reads back in `lic3d render`
// (a 290 KB preset once made 1.2 MB of session, beyond the 1 MiB the reader took).
TEST_F(ViewerTest, ASessionWithALargePresetReadsBack) {
  writeBytes("big.json", test::shortNumberPreset(8000));
  const CommandRun r =
      view("--field abc --grid 16 --tf big.json --frames 2 --save-session out.json");
  ASSERT_EQ(r.status, 0) << r.output;
  const CommandRun render =
      runShell("cd '" + folder().string() + "' && '" + std::string(LIC3D_EXECUTABLE) +
               "' render -q --width 32 --height 32 --session out.json -o out.png");
  ASSERT_EQ(render.status, 0) << render.output;
  Result<Session> saved = readSession(path("out.json"));
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_EQ(saved->view.transfer.colors.size(), 8000u);
}

// How much neighbouring pixels of the box differ (mean over both directions, red channel): LIC
// made at the screen's pixels has the noise's grain; a smaller image stretched over the view is
// smooth.
double grain(const test::RgbaPixels& image, Box box) {
  double sum = 0.0;
  int n = 0;
  const auto red = [&](int x, int y) {
    return static_cast<double>(image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)]);
  };
  for (int y = box.y0; y < box.y1 - 1; ++y)
    for (int x = box.x0; x < box.x1 - 1; ++x, ++n)
      sum += std::abs(red(x + 1, y) - red(x, y)) + std::abs(red(x, y + 1) - red(x, y));
  return n ? sum / (2.0 * n) : 0.0;
}

// The 2D mode (thesis chapter 3): the 2D LIC picture of the circle fills the window's height,
// centred, keeping its aspect, made at the view's pixels (the session's image size stays 0); an
// image size given is kept and stretched over the view. The panels switch to the plane's
// controls.
TEST_F(ViewerTest, TwoDModeShowsThePictureOfAPlaneAtTheViewsResolution) {
  const std::string args =
      "--look dense --mode 2d --field circle --grid 64 --frames 3 --hide-ui "
      "--save-session out.json --screenshot shot.png";
  const CommandRun r = view(args + " --render-image plane.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const test::RgbaPixels shot = test::readRgbaPng(path("shot.png"));
  ASSERT_EQ(shot.width, kWidth) << r.output;
  // A 640x640 picture in a 1024x640 window: 192 columns of background either side.
  const Box left{0, 0, 180, kHeight}, right{kWidth - 180, 0, kWidth, kHeight};
  EXPECT_EQ(fraction(shot, left, [](int r_, int g, int b) { return lit(r_, g, b); }), 0.0);
  EXPECT_EQ(fraction(shot, right, [](int r_, int g, int b) { return lit(r_, g, b); }), 0.0);
  double sum = 0, sum2 = 0;
  int n = 0;
  for (int y = kVolume.y0; y < kVolume.y1; ++y)
    for (int x = kVolume.x0; x < kVolume.x1; ++x, ++n) {
      const double v = shot.rgba[4 * (static_cast<std::size_t>(y) * kWidth + x)];
      sum += v;
      sum2 += v * v;
    }
  EXPECT_GT(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 20.0) << "no LIC texture in the middle";
  Result<Session> saved = readSession(path("out.json"));
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_TRUE(saved->twoD);
  EXPECT_EQ(saved->plane.width, 0) << "the view's size is not the session's";
  // "Render image" writes the plane's picture at the size it was made at, and carries that size:
  // `lic3d render2d --session` remakes it.
  const CommandRun again =
      runShell("cd '" + folder().string() + "' && '" + std::string(LIC3D_EXECUTABLE) +
               "' render2d -q --session plane.png -o plane-again.png");
  ASSERT_EQ(again.status, 0) << again.output;
  const test::RgbaPixels plane = test::readRgbaPng(path("plane.png"));
  const test::RgbaPixels remade = test::readRgbaPng(path("plane-again.png"));
  EXPECT_EQ(plane.width, kHeight);
  ASSERT_EQ(remade.width, plane.width);
  ASSERT_EQ(remade.height, plane.height);
  EXPECT_LE(difference(plane, remade).largest, 1);

  // The same plane as a 64x64 image, stretched ten times: its grain is a fraction of the one
  // made at the view's pixels.
  const CommandRun small = view(args + " --image-size 64x64");
  ASSERT_EQ(small.status, 0) << small.output;
  const test::RgbaPixels stretched = test::readRgbaPng(path("shot.png"));
  ASSERT_EQ(stretched.width, kWidth) << small.output;
  const double sharp = grain(shot, kVolume), smooth = grain(stretched, kVolume);
  EXPECT_GT(sharp, 3.0 * smooth) << "grain " << sharp << " at the view's size, " << smooth
                                 << " stretched from 64x64";
  saved = readSession(path("out.json"));
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_EQ(saved->plane.width, 64);
}

// Colour by a derived quantity with its legend: the legend has a column of its own between the
// volume and the panels, and the session keeps the choice.
TEST_F(ViewerTest, TheLegendStandsBesideTheVolumeAndColourFollowsTheChosenScalar) {
  const CommandRun r = view(
      "--field abc --grid 24 --color-by helicity --legend --frames 3 --save-session out.json "
      "--screenshot shot.png");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
  const test::RgbaPixels shot = test::readRgbaPng(path("shot.png"));
  ASSERT_EQ(shot.width, kWidth) << r.output;
  // The colour bar: saturated colours in a narrow column just left of the panels.
  const auto saturated = [](int r_, int g, int b) {
    return std::max({r_, g, b}) - std::min({r_, g, b}) > 80;
  };
  int barColumn = -1;
  for (int x = kWidth - kPanelWidth - 1; x > kWidth - kPanelWidth - 200 && barColumn < 0; --x)
    if (fraction(shot, {x, kHeight / 3, x + 1, kHeight * 2 / 3}, saturated) > 0.95) barColumn = x;
  ASSERT_GE(barColumn, 0) << "no colour bar beside the panels";
  const auto [first, last] = litColumns(shot, {0, kHeight / 4, barColumn - 40, kHeight * 3 / 4});
  EXPECT_GT(last, first) << "no volume left of the legend";
  // Nothing of the volume reaches the legend's column.
  EXPECT_EQ(fraction(shot, {barColumn - 30, 0, barColumn - 20, kHeight}, saturated), 0.0);
  Result<Session> saved = readSession(path("out.json"));
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_EQ(saved->view.colorBy, "helicity");
}

// An unsteady field (docs/TIME.md): the tornado at a time between two of its steps, blended on
// the GPU; the time is part of the session the app saves, with the steps it used.
TEST_F(ViewerTest, TheTimeOfAnUnsteadyFieldIsShownAndSaved) {
  const CommandRun r = view(
      "--look dense --grid 24 --time 100 --frames 3 --save-session out.json "
      "--screenshot shot.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const test::RgbaPixels shot = test::readRgbaPng(path("shot.png"));
  ASSERT_EQ(shot.width, kWidth) << r.output;
  EXPECT_GT(fraction(shot, kDockedVolume, [](int r_, int g, int b) { return lit(r_, g, b); }), 0.9);
  Result<Session> saved = readSession(path("out.json"));
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_EQ(saved->time, 100.0);
  EXPECT_EQ(saved->timeSteps, 64);
}

// The short soak (docs/RELIABILITY.md has the 10,000-frame run): 500 frames with a LIC or view
// change every 10 and a resize at 250, undone at 260 (the swapchain is recreated each time); RSS
// and device memory do not grow after the warm-up, and validation stays clean throughout.
TEST_F(ViewerTest, SoakKeepsMemoryFlat) {
  const CommandRun r = view("--grid 16 --frames 500 --soak", "320x240");
  ASSERT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("lic3d-view soak: 5"), std::string::npos) << r.output;
  // A long scripted run reports its progress on stderr, a line every tenth of it in a log.
  EXPECT_NE(r.output.find("lic3d-view: frame 250 of 500 (50 %)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("lic3d-view: frame 500 of 500 (100 %)"), std::string::npos) << r.output;
  // The first swapchain and one after each resize.
  const std::size_t at = r.output.find(" swapchains");
  ASSERT_NE(at, std::string::npos) << r.output;
  const std::size_t start = r.output.rfind(' ', at - 1);
  EXPECT_GE(std::stoi(r.output.substr(start + 1, at - start - 1)), 3) << r.output;
  // The LIC changes reached every kind of asynchronous work (tsan-app runs this under
  // ThreadSanitizer): volumes recomputed, sparsity masks made on a worker thread, the field read
  // again on the loading thread, time steps of the (unsteady) tornado read on a worker thread.
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m,
                                std::regex("(\\d+) LIC volumes, (\\d+) of (\\d+) sparsity masks, "
                                           "(\\d+) field reads, (\\d+) time steps read")))
      << r.output;
  EXPECT_GE(std::stoi(m[1]), 10) << r.output;
  EXPECT_GE(std::stoi(m[2]), 2) << r.output;
  EXPECT_GE(std::stoi(m[4]), 3) << r.output;
  EXPECT_GE(std::stoi(m[5]), 4) << r.output;
}

// A LIC slider dragged (viewer/drag.h, scripted by --drag-lic): while the length slider is held
// the app shows coarse LIC volumes (every 2nd voxel, forced here: on lavapipe the measured time
// would choose too), and the full one once it is let go; each volume's line of the panel, with its
// GPU time, and the panel's frame times go to stderr as the panel shows them.
TEST_F(ViewerTest, ADraggedLicSliderShowsCoarseVolumesThenTheFullOne) {
  const CommandRun r = view(
      "--grid 32 -L 6 --frames 4 --drag-lic 6 --drag-stride 2 --save-session out.json", "480x320");
  ASSERT_EQ(r.status, 0) << r.output;
  const std::regex licLine(
      "lic3d-view: panel: LIC ([0-9.]+) ms GPU, (coarse|full) (\\d+)x(\\d+)x(\\d+)");
  std::vector<std::pair<std::string, int>> volumes;  // kind and grid x of each finished volume
  for (auto it = std::sregex_iterator(r.output.begin(), r.output.end(), licLine);
       it != std::sregex_iterator(); ++it) {
    const std::smatch& m = *it;
    EXPECT_GT(std::stod(m[1]), 0.0) << m.str();
    EXPECT_EQ(m[3], m[4]);
    EXPECT_EQ(m[4], m[5]);
    volumes.emplace_back(m[2], std::stoi(m[3]));
  }
  ASSERT_GE(volumes.size(), 4u) << r.output;
  // The first volume, full; coarse ones while the slider is held; the full one at the end.
  EXPECT_EQ(volumes.front(), std::make_pair(std::string("full"), 32)) << r.output;
  EXPECT_EQ(volumes.back(), std::make_pair(std::string("full"), 32)) << r.output;
  for (std::size_t i = 1; i + 1 < volumes.size(); ++i)
    EXPECT_EQ(volumes[i], std::make_pair(std::string("coarse"), 16)) << r.output;
  std::smatch frame;
  ASSERT_TRUE(std::regex_search(
      r.output, frame,
      std::regex(
          "lic3d-view: panel: frame ([0-9.]+) ms CPU, ([0-9.]+) ms GPU \\(median of (\\d+)\\)")))
      << r.output;
  EXPECT_GT(std::stod(frame[1]), 0.0);
  EXPECT_GT(std::stod(frame[2]), 0.0);
  EXPECT_GE(std::stoi(frame[3]), 6);
  Result<Session> saved = readSession(path("out.json"));
  ASSERT_TRUE(saved) << saved.error().message;
  EXPECT_EQ(saved->lic.length, 6 + 6) << "the drag's last length is kept";

  const CommandRun refused = runShell("'" + std::string(LIC3D_VIEWER) + "' --drag-lic 5");
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_NE(refused.output.find("--drag-lic needs --frames"), std::string::npos) << refused.output;
}

// A soak without --frames cannot end: refused.
TEST_F(ViewerTest, SoakNeedsFrames) {
  const CommandRun r = runShell("'" + std::string(LIC3D_VIEWER) + "' --soak");
  EXPECT_EQ(r.status, 2) << r.output;
}

// A device allocation that fails while the app runs (the allocator's test hook) stops it with
// the call named, and the session is saved to lic3d-recovery.json first. The window then shows
// the error in a dialog (a scripted run for one frame, in its screenshot) and exits with status 1.
TEST_F(ViewerTest, AFatalErrorSavesTheSessionToARecoveryFile) {
  writeBytes("in.json",
             R"({"field": {"source": "abc", "grid": [16, 16, 16]}, "lic": {"length": 9}})");
  bool sawRecovery = false, sawDialog = false;
  for (int n : {12, 14, 16}) {
    std::filesystem::remove(path("lic3d-recovery.json"));
    // The app's own exit status goes to a file: xvfb-run's status can also report a failure to
    // clean up its temporary folder, which happens under load and says nothing about the app.
    std::filesystem::remove(path("status.txt"));
    std::filesystem::remove(path("shot.png"));
    const CommandRun failed =
        runShell("cd '" + folder().string() + "' && LIC3D_FAIL_ALLOCATION=" + std::to_string(n) +
                 " xvfb-run -a -f .Xauthority -s '-screen 0 1280x800x24' sh -c '\"$0\" \"$@\"; "
                 "echo $? > status.txt' '" +
                 std::string(LIC3D_VIEWER) +
                 "' --window-size 640x480 --session in.json --frames 3 "
                 "--screenshot shot.png");
    const std::string status = test::readWhole(path("status.txt"));
    ASSERT_FALSE(status.empty()) << failed.output;
    if (std::stoi(status) == 0) continue;
    EXPECT_EQ(std::stoi(status), 1) << failed.output;
    EXPECT_NE(failed.output.find("VK_ERROR_OUT_OF_DEVICE_MEMORY"), std::string::npos)
        << failed.output;
    Result<Session> saved = readSession(path("lic3d-recovery.json"));
    ASSERT_TRUE(saved) << failed.output;
    EXPECT_EQ(saved->field.field, "abc");
    EXPECT_EQ(saved->lic.length, 9);
    if (failed.output.find("lic3d-view: wrote shot.png") != std::string::npos) {
      const test::RgbaPixels shot = test::readRgbaPng(path("shot.png"));
      EXPECT_GT(fraction(shot, {100, 160, 540, 320}, imguiBlue), 0.01)
          << "the dialog showing the error is missing";
      sawDialog = true;
    }
    sawRecovery = true;
  }
  EXPECT_TRUE(sawRecovery) << "none of the injected failures hit the running app";
  EXPECT_TRUE(sawDialog) << "no failure was shown in the window";
}

// A lost device (the submission hook reports VK_ERROR_DEVICE_LOST, as a driver reset would): the
// app saves the session, makes the device again, reads the field and recomputes the LIC from the
// session, and says so in a dialog. Lost while the first volume is computed and after it is shown,
// the picture outside the dialog is the undisturbed run's, pixel for pixel.
TEST_F(ViewerTest, ALostDeviceIsMadeAgainAndTheSessionRestored) {
  writeBytes("in.json",
             R"({"field": {"source": "tornado", "grid": [24, 24, 24]}, "lic": {"length": 9}})");
  constexpr int kW = 640, kH = 480;
  const std::string size = std::to_string(kW) + "x" + std::to_string(kH);
  const std::string args = "--session in.json --frames 30 --hide-ui --screenshot shot.png";
  const CommandRun reference = view(args, size);
  ASSERT_EQ(reference.status, 0) << reference.output;
  fs::rename(path("shot.png"), path("reference.png"));
  const test::RgbaPixels expected = test::readRgbaPng(path("reference.png"));
  ASSERT_EQ(expected.width, kW);

  // The dialog sits in the middle of the window; the rows above and below it are compared.
  const Box top{0, 0, kW, kH / 2 - 80}, bottom{0, kH / 2 + 80, kW, kH};
  for (const int n : {4, 14}) {
    SCOPED_TRACE("lost at submission " + std::to_string(n));
    fs::remove(path("lic3d-recovery.json"));
    const CommandRun r =
        view("--save-session after.json " + args, size, "LIC3D_LOSE_DEVICE=" + std::to_string(n));
    ASSERT_EQ(r.status, 0) << r.output;
    EXPECT_NE(r.output.find("vkQueueSubmit2 failed: VK_ERROR_DEVICE_LOST: making the device again"),
              std::string::npos)
        << r.output;
    EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
    for (const char* file : {"lic3d-recovery.json", "after.json"}) {
      Result<Session> saved = readSession(path(file));
      ASSERT_TRUE(saved) << file << "\n" << r.output;
      EXPECT_EQ(saved->field.grid, Dims(24)) << file;
      EXPECT_EQ(saved->lic.length, 9) << file;
    }
    const test::RgbaPixels shot = test::readRgbaPng(path("shot.png"));
    ASSERT_EQ(shot.width, kW);
    ASSERT_EQ(shot.height, kH);
    EXPECT_GT(fraction(shot, {0, kH / 2 - 80, kW, kH / 2 + 80}, imguiBlue), 0.01)
        << "the dialog saying the device was lost is missing";
    for (const Box& box : {top, bottom}) {
      EXPECT_GT(fraction(expected, box, lit), 0.2) << "the compared rows should show the volume";
      int differing = 0;
      for (int y = box.y0; y < box.y1; ++y)
        for (int x = box.x0; x < box.x1; ++x)
          for (int c = 0; c < 3; ++c) {
            const std::size_t i = 4 * (static_cast<std::size_t>(y) * kW + x) + c;
            if (shot.rgba[i] != expected.rgba[i]) ++differing;
          }
      EXPECT_EQ(differing, 0) << "the restored picture differs from the undisturbed one";
    }
  }
}

// A device lost again and again (every 6th submission) is given up on: exit status 1 with the
// error, the session in the recovery file.
TEST_F(ViewerTest, ADeviceLostAgainAndAgainIsGivenUpOn) {
  writeBytes("in.json",
             R"({"field": {"source": "abc", "grid": [16, 16, 16]}, "lic": {"length": 7}})");
  const CommandRun r =
      view("--session in.json --frames 200", "320x240", "LIC3D_LOSE_DEVICE=every:6");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("giving up"), std::string::npos) << r.output;
  Result<Session> saved = readSession(path("lic3d-recovery.json"));
  ASSERT_TRUE(saved) << r.output;
  EXPECT_EQ(saved->lic.length, 7);
}

TEST_F(ViewerTest, BadArgumentsExitWithStatusTwoBeforeOpeningAWindow) {
  for (const char* args :
       {"--window-size 10x10", "--screenshot shot.png", "--frames 2 --screenshot shot.jpg",
        "--session missing.json", "--render-image image.png", "--frames 2 --render-image x.jpg"}) {
    const CommandRun r =
        runShell("cd '" + folder().string() + "' && '" + std::string(LIC3D_VIEWER) + "' " + args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_NE(r.output.find("error"), std::string::npos) << args;
  }
  // A field file that cannot be read is found once the window is open: still status 2.
  const CommandRun missing = view("--field missing.nrrd --frames 1");
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("missing.nrrd"), std::string::npos) << missing.output;

  // An analytic grid that cannot fit is refused before the field is made (hardening, class 4):
  // status 3, and no process of the run ever held the 768 MB of a 400^3 field (it held 1.6 GB).
  const CommandRun tooLarge = view("--grid 400 --frames 1");
  EXPECT_EQ(tooLarge.status, 3) << tooLarge.output;
  EXPECT_NE(tooLarge.output.find("400"), std::string::npos) << tooLarge.output;
  struct rusage children {};
  ASSERT_EQ(getrusage(RUSAGE_CHILDREN, &children), 0);
  EXPECT_LT(children.ru_maxrss, 600 * 1024) << "KiB";

  // `lic3d view` starts the app with the same options.
  const CommandRun help = runShell(std::string("'") + LIC3D_EXECUTABLE + "' view --help");
  EXPECT_EQ(help.status, 0) << help.output;
  EXPECT_NE(help.output.find("--frames"), std::string::npos) << help.output;
}

}  // namespace
}  // namespace lic3d
