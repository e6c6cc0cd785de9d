// SPDX-License-Identifier: BSD-3-Clause
// The desktop app's parts that need no window (app/viewer/panel_logic.h, plane.h,
// script_progress.h): how a long path is shortened, which control sets the opacity, the preset
// file the panel names, the 2D picture's size for the view, and a scripted run's progress.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "core/look.h"
#include "core/view_params.h"
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

}  // namespace
}  // namespace lic3d::viewer
