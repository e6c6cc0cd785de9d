// SPDX-License-Identifier: BSD-3-Clause
// The desktop app's parts that need no window (app/viewer/panel_logic.h, plane.h,
// script_progress.h, drag.h): how a long path is shortened, which control sets the opacity, the
// preset file the panel names, the 2D picture's size for the view, a scripted run's progress, and
// which LIC a slider's drag asks for; the annotation layer the app draws over its picture.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "core/look.h"
#include "core/view_params.h"
#include "lic/annotation.h"
#include "viewer/drag.h"
#include "viewer/overlay.h"
#include "viewer/panel_logic.h"
#include "viewer/plane.h"
#include "viewer/script_progress.h"

namespace lic3d::viewer {
namespace {

// A monospaced font of 7 pixels a character, as ImGui's default font is.
float monospace(std::string_view text) { return 7.0f * static_cast<float>(text.size()); }

bool endsWith(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

TEST(ViewerParts, APathThatFitsIsShownWhole) {
  EXPECT_EQ(elidePath("/data/carotid.vtk", 200.0f, monospace), "/data/carotid.vtk");
}

// The box shows the file name whole, the nearest folder, and the start of the path, never wider
// than the box, at every width from a tight box to a wide one.
TEST(ViewerParts, ALongPathKeepsItsFileNameAndElidesTheMiddle) {
  const std::string path =
      "/home/someone/projects/flow-simulations/2024-run-with-a-long-name/output/carotid.vtk";
  const std::string shown = elidePath(path, 40 * 7.0f, monospace);
  EXPECT_LE(monospace(shown), 40 * 7.0f) << shown;
  EXPECT_GE(monospace(shown), 36 * 7.0f) << "the box should be used: " << shown;
  EXPECT_TRUE(endsWith(shown, "/output/carotid.vtk")) << shown;
  EXPECT_EQ(shown.rfind("/home/", 0), 0u) << shown;
  EXPECT_NE(shown.find("..."), std::string::npos) << shown;
  for (std::size_t chars = 16; chars < path.size(); ++chars) {
    const float width = 7.0f * static_cast<float>(chars);
    const std::string s = elidePath(path, width, monospace);
    EXPECT_LE(monospace(s), width) << s;
    EXPECT_TRUE(endsWith(s, "/carotid.vtk")) << s;
    EXPECT_NE(s.find("..."), std::string::npos) << s;
  }
}

TEST(ViewerParts, AFileNameTooLongForTheBoxKeepsItsStartAndExtension) {
  const std::string shown = elidePath(
      "/data/a_very_long_file_name_from_a_simulation_code_step_0001.vti", 24 * 7.0f, monospace);
  EXPECT_LE(monospace(shown), 24 * 7.0f) << shown;
  EXPECT_TRUE(endsWith(shown, ".vti")) << shown;
  EXPECT_EQ(shown.rfind("a_very", 0), 0u) << shown;
  EXPECT_NE(shown.find("..."), std::string::npos) << shown;
}

// The default look sets an optical depth, which wins over alpha: the panel says so, and switching
// to alpha hands the opacity to the alpha slider, starting from the alpha in use.
TEST(ViewerParts, TheOpacityControlThatActsIsTheOneThePanelNames) {
  Session session;
  applyLook(Look::SeeThrough, session);
  ViewParams& view = session.view;
  ASSERT_GT(view.opticalDepth, 0.0f);
  const float lookDepth = view.opticalDepth;
  char depthText[64];
  std::snprintf(depthText, sizeof(depthText), "optical depth %.2f sets the opacity",
                static_cast<double>(lookDepth));
  EXPECT_EQ(opacitySource(view), OpacitySource::OpticalDepth);
  const std::string depthCaption = opacityCaption(view, 0.034f);
  EXPECT_NE(depthCaption.find(depthText), std::string::npos) << depthCaption;
  EXPECT_NE(depthCaption.find("alpha 0.034"), std::string::npos) << depthCaption;

  // Under the optical depth, alpha does not act: the resolved alpha ignores it.
  TransferFacts facts;
  const Dims dims{32, 32, 32};
  const float before = resolvedAlpha(view, facts, dims);
  view.alpha = 0.9f;
  EXPECT_EQ(resolvedAlpha(view, facts, dims), before);

  float lastDepth = 0.0f;
  setOpacitySource(view, OpacitySource::Alpha, before, lastDepth);
  EXPECT_EQ(opacitySource(view), OpacitySource::Alpha);
  EXPECT_EQ(view.alpha, before) << "the picture should not jump when switching";
  EXPECT_EQ(resolvedAlpha(view, facts, dims), before);
  view.alpha = 0.5f;  // now the slider acts
  EXPECT_EQ(resolvedAlpha(view, facts, dims), 0.5f);
  EXPECT_EQ(opacityCaption(view, -1.0f), "alpha 0.500 per voxel sets the opacity");

  setOpacitySource(view, OpacitySource::OpticalDepth, 0.5f, lastDepth);
  EXPECT_EQ(opacitySource(view), OpacitySource::OpticalDepth);
  EXPECT_FLOAT_EQ(view.opticalDepth, lookDepth) << "the depth switched away from comes back";

  // Without a depth to come back to, the default look's.
  Session dense;
  applyLook(Look::Dense, dense);
  EXPECT_EQ(opacitySource(dense.view), OpacitySource::Alpha);
  float none = 0.0f;
  setOpacitySource(dense.view, OpacitySource::OpticalDepth, -1.0f, none);
  EXPECT_FLOAT_EQ(dense.view.opticalDepth, lookDepth);
  EXPECT_NE(opacityCaption(dense.view, -1.0f).find("chosen from the data"), std::string::npos);
}

// The preset box names the file the app read its transfer function from.
TEST(ViewerParts, ThePresetFileIsTheOneGivenOnTheCommandLine) {
  const auto presetOf = [](const std::string& args) {
    CLI::App app;
    cli::SessionOptions inputs;
    cli::addViewOptions(app, inputs);
    app.parse(args);
    return startupPresetFile(inputs);
  };
  EXPECT_EQ(presetOf(""), "");
  EXPECT_EQ(presetOf("--tf presets/cool.json"), "presets/cool.json");
  EXPECT_EQ(presetOf("--colormap viridis"), "");
  EXPECT_EQ(presetOf("--colormap presets/warm.json"), "presets/warm.json");
  EXPECT_EQ(presetOf("--colormap presets/warm.json --tf presets/cool.json"), "presets/cool.json");
}

// Without an image size in the session, the 2D picture has the view's pixels: the largest size
// that fits the view keeping the plane's aspect.
TEST(ViewerParts, TheTwoDPictureIsMadeAtTheViewsSize) {
  const PlaneParams automatic;
  EXPECT_EQ(pictureSize({128, 128, 1}, automatic, {644, 800}), Dims(644, 644, 1));
  EXPECT_EQ(pictureSize({96, 48, 1}, automatic, {1000, 400}), Dims(800, 400, 1));
  EXPECT_EQ(pictureSize({96, 48, 1}, automatic, {300, 400}), Dims(300, 150, 1));
  EXPECT_EQ(pictureSize({96, 48, 1}, automatic, {0, 0}), Dims(96, 48, 1)) << "no view yet";
  // A size the session gives is kept, as `lic3d render2d` makes it.
  PlaneParams given;
  given.width = given.height = 256;
  EXPECT_EQ(pictureSize({128, 128, 1}, given, {644, 800}), Dims(256, 256, 1));
  PlaneParams widthOnly;
  widthOnly.width = 200;
  EXPECT_EQ(pictureSize({96, 48, 1}, widthOnly, {644, 800}), Dims(200, 100, 1));
}

// A window dragged to a new size makes one picture, at the size it settles on.
TEST(ViewerParts, ThePictureFollowsTheViewOnceItsSizeSettles) {
  SettledSize size(0.25);
  EXPECT_EQ(size.update({640, 480}, 0.0), glm::ivec2(640, 480)) << "the first size at once";
  for (int step = 1; step <= 20; ++step)  // dragged for a second
    EXPECT_EQ(size.update({640 + 10 * step, 480}, 0.05 * step), glm::ivec2(640, 480));
  EXPECT_EQ(size.update({840, 480}, 1.1), glm::ivec2(640, 480)) << "not settled yet";
  EXPECT_EQ(size.update({840, 480}, 1.26), glm::ivec2(840, 480));
}

std::vector<std::string> linesOf(ScriptProgress& progress, int frames, double secondsPerFrame) {
  std::vector<std::string> lines;
  for (int k = 1; k <= frames; ++k)
    if (std::string line = progress.update(k, k * secondsPerFrame, false); !line.empty())
      lines.push_back(line);
  return lines;
}

// A long scripted run reports its frames on stderr like the CLI's progress: in a log a line every
// tenth of the run, on a terminal one line rewritten in place; the window says "frame k of n".
TEST(ViewerParts, ALongScriptedRunReportsItsProgress) {
  ScriptProgress log(1000, false, false);
  const std::vector<std::string> lines = linesOf(log, 1000, 0.01);
  ASSERT_EQ(lines.size(), 10u);
  EXPECT_EQ(lines[0].rfind("lic3d-view: frame 100 of 1000 (10 %), 1.0 s elapsed, ETA 9.0 s", 0), 0u)
      << lines[0];
  EXPECT_NE(lines[9].find("frame 1000 of 1000 (100 %)"), std::string::npos) << lines[9];
  EXPECT_NE(log.update(1000, 10.5, true).find("waiting"), std::string::npos);
  EXPECT_EQ(log.update(1000, 10.6, true), "") << "said once";
  EXPECT_EQ(log.finish(), "");

  ScriptProgress terminal(1000, true, false);
  const std::vector<std::string> live = linesOf(terminal, 1000, 0.001);  // a second in all
  EXPECT_GE(live.size(), 4u);
  EXPECT_LE(live.size(), 6u);
  for (const std::string& line : live) EXPECT_EQ(line.front(), '\r');
  EXPECT_NE(live.back().find("frame 1000 of 1000"), std::string::npos);
  EXPECT_EQ(terminal.finish(), "\n");

  ScriptProgress quiet(1000, false, true), shortRun(kProgressMinFrames - 1, false, false);
  EXPECT_TRUE(linesOf(quiet, 1000, 0.01).empty());
  EXPECT_TRUE(linesOf(shortRun, kProgressMinFrames - 1, 0.01).empty());
  EXPECT_EQ(shortRun.windowText(7, false), "scripted run: frame 7 of 99");
  EXPECT_FLOAT_EQ(ScriptProgress(50, false, false).fraction(10), 0.2f);
  EXPECT_FALSE(ScriptProgress().scripted());
}

// A LIC slider's drag: each change while it is held asks for the coarse volume, letting it go
// for the full one (once), and changes without a drag for the full one.
TEST(ViewerParts, ADragAsksForCoarseVolumesThenTheFullOneWhenLetGo) {
  LicDrag drag;  // the stride from the last full LIC's time: 23 ms -> 2, 190 ms -> 4
  EXPECT_EQ(drag.request(false, false, 23.0), std::nullopt) << "nothing changed";
  EXPECT_EQ(drag.request(true, false, 23.0), 1) << "a change without a drag (a typed value)";
  EXPECT_EQ(drag.request(false, true, 23.0), std::nullopt) << "held, not moved yet";
  EXPECT_EQ(drag.request(true, true, 23.0), 2);
  EXPECT_EQ(drag.request(false, true, 23.0), std::nullopt) << "held still: the coarse one stays";
  EXPECT_EQ(drag.request(true, true, 190.0), 4);
  EXPECT_EQ(drag.request(false, false, 190.0), 1) << "let go: the full volume";
  EXPECT_EQ(drag.request(false, false, 190.0), std::nullopt) << "asked for once";
  EXPECT_EQ(drag.request(true, true, 3.0), 1) << "a full LIC fits the frame: no coarse one";
  EXPECT_EQ(drag.request(false, false, 3.0), std::nullopt);
  // A coarse job over the budget: later drags ask for the next stride, whatever the full LIC.
  drag.noteCoarse(4, 47.0);
  EXPECT_EQ(drag.request(true, true, 190.0), 8);
  drag.noteCoarse(8, 6.0);
  EXPECT_EQ(drag.request(true, true, 190.0), 8) << "within the budget: kept";
  EXPECT_EQ(nextCoarseStride(2, 9.0), 4);
  EXPECT_EQ(nextCoarseStride(2, 7.0), 2);
  EXPECT_EQ(nextCoarseStride(8, 90.0), 8) << "8 at most";

  LicDrag forced(2);
  EXPECT_EQ(forced.request(true, true, 0.5), 2);
  EXPECT_EQ(forced.request(false, false, 0.5), 1);
  LicDrag never(1);
  EXPECT_EQ(never.request(true, true, 500.0), 1);
  EXPECT_EQ(never.request(false, false, 500.0), std::nullopt);
}

TEST(ViewerParts, TheScriptedDragHoldsTheLengthSliderThenLetsGo) {
  ScriptedDrag drag(3);
  LicParams lic;
  lic.length = 10;
  EXPECT_FALSE(drag.step(false, lic)) << "waits for the first volume";
  EXPECT_EQ(lic.length, 10);
  EXPECT_FALSE(drag.done());
  for (int i = 1; i <= 3; ++i) {
    EXPECT_TRUE(drag.step(i == 1, lic)) << i;  // held on, whatever is shown
    EXPECT_EQ(lic.length, 10 + i);
  }
  EXPECT_TRUE(drag.done());
  EXPECT_FALSE(drag.step(true, lic));
  EXPECT_EQ(lic.length, 13);
  EXPECT_TRUE(ScriptedDrag().done());
}

TEST(ViewerParts, ThePanelShowsTheMedianFrameTimesAndTheLastLicsTime) {
  RecentMedian times;
  EXPECT_EQ(times.median(), 0.0);
  for (const double ms : {16.0, 40.0, 17.0}) times.add(ms);
  EXPECT_EQ(times.median(), 17.0);
  times.add(15.0);
  EXPECT_EQ(times.median(), 16.5);
  // Only the last kCapacity frames count.
  for (std::size_t i = 0; i < RecentMedian::kCapacity; ++i) times.add(8.0);
  EXPECT_EQ(times.size(), RecentMedian::kCapacity);
  EXPECT_EQ(times.median(), 8.0);

  EXPECT_EQ(frameTimeText(16.66, 9.123, 60), "frame 16.7 ms CPU, 9.12 ms GPU (median of 60)");
  EXPECT_EQ(licTimeText(2.914, 2, {256, 256, 256}), "LIC 2.91 ms GPU, coarse 256x256x256");
  EXPECT_EQ(licTimeText(23.1, 1, {512, 512, 512}), "LIC 23.10 ms GPU, full 512x512x512");
}

// The app draws the legend, the title and the axes as a layer of runs over its picture (ImGui
// blends them): over any picture they give what `lic3d render` draws into it (annotatePicture),
// within one level, on a dark and on a light background, where lines and text cross each other
// and the volume.
TEST(ViewerParts, TheAnnotationLayerDrawsWhatTheCliDraws) {
  for (const glm::vec3 background : {glm::vec3(0.0f), glm::vec3(1.0f)}) {
    ViewParams view;
    view.width = 240;
    view.height = 180;
    view.background = background;
    view.color = ColorMode::Magnitude;
    view.legend = view.axes = true;
    view.title = "Tornado";
    const LegendSpec legend{[](float t) { return glm::vec3(t, 0.5f, 1.0f - t); }, 0.0f, 0.3f,
                            "speed [m/s]"};
    const Dims dims{32, 24, 16};
    const GridGeometry geometry;
    // A busy picture beneath: every level of every channel somewhere.
    RgbaImage picture;
    picture.width = view.width;
    picture.height = view.height;
    picture.pixels.resize(static_cast<std::size_t>(view.width) * view.height * 4);
    for (std::size_t i = 0; i < picture.pixels.size(); ++i)
      picture.pixels[i] = static_cast<std::uint8_t>((i * 37 + i / 4 * 11) % 256);
    RgbaImage cli = picture, app = picture;
    annotatePicture(cli, view, &legend, dims, geometry);
    const std::vector<OverlayRun> runs = annotationRuns(view, &legend, dims, geometry);
    blendRuns(app, runs);
    int largest = 0, changed = 0;
    for (std::size_t i = 0; i < cli.pixels.size(); ++i) {
      if (i % 4 == 3) continue;
      largest = std::max(largest, std::abs(cli.pixels[i] - app.pixels[i]));
      changed += cli.pixels[i] != picture.pixels[i];
    }
    EXPECT_GT(changed, 2000) << "no annotation drawn";
    EXPECT_LE(largest, 1);
    // The layer holds the annotation only: runs, not a pixel each.
    EXPECT_LT(runs.size(), static_cast<std::size_t>(changed));
  }
}

}  // namespace
}  // namespace lic3d::viewer
