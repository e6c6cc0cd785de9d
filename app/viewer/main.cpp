// SPDX-License-Identifier: BSD-3-Clause
// lic3d-view: the desktop app. A window shows the LIC volume with blended slices; Dear ImGui
// panels change every parameter, and the LIC volume is recomputed a slab per frame while the old
// one stays on screen.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <new>
#include <string>

#include "core/parallel.h"
#include "options/session_options.h"
#include "viewer/viewer.h"

using namespace lic3d;
using namespace lic3d::cli;

int main(int argc, char** argv) {
  CLI::App app{
      "lic3d-view: the lic3d desktop app. Opens a window with the LIC volume of a vector "
      "field and panels for every parameter.\nMouse: left drag orbits, shift+left or "
      "middle drag pans, wheel zooms. Keys: R reset view, Space play the bias "
      "animation, F12 screenshot, H or Tab hide panels, F1 help, Esc quit."};
  app.set_version_flag("--version", "lic3d-view 0.1.0");
  app.footer(
      "Also started by `lic3d view ...`. Exit status: 0 success, 1 failure (no display, "
      "no device, GPU or validation error), 2 bad arguments or input files, 3 not enough "
      "memory for the request.");

  GlobalOptions global;
  addGlobalOptions(app, global);
  SessionOptions inputs;
  addInputOptions(app, inputs, true);
  addLookOption(app, inputs);
  addViewOptions(app, inputs);

  std::string mode = "3d";
  app.add_option("--mode", mode,
                 "3d: the LIC volume; 2d: 2D LIC of a plane (thesis chapter 3): a 2D field "
                 "(circle, saddle, wave, a 2D file) or a plane of a 3D one (--slice)")
      ->check(CLI::IsMember({"3d", "2d"}))
      ->capture_default_str();
  PlaneOptions plane;
  plane.slice.option = app.add_option(
      "--slice", plane.slice.text,
      "2D mode: the plane of a 3D field, AXIS or AXIS:INDEX (default z, the middle layer)");
  std::string imageSize;
  app.add_option("--image-size", imageSize,
                 "The size WxH of the image \"Render image\" writes: in 2D mode the LIC image "
                 "(default: the view's size, one image pixel per screen pixel), in 3D the "
                 "offscreen picture (default 1920x1080)");

  viewer::ViewerOptions options;
  std::string windowSize;
  app.add_option("--window-size", windowSize, "Window size WxH in screen pixels")
      ->default_str("1280x800");
  app.add_option("--vsync", options.vsync, "Wait for the display's refresh (on|off)")
      ->transform(CLI::CheckedTransformer(std::map<std::string, bool>{{"on", true}, {"off", false}})
                      .description(""))
      ->default_str("on");
  app.add_flag("--hide-ui", options.hideUi, "Start with the panels hidden (H or Tab shows them)");
  app.add_option("--frames", options.frames,
                 "Scripted run: quit after this many frames, once the LIC volume is shown "
                 "(from 100 frames on, progress on stderr)")
      ->check(CLI::Range(1, 1000000));
  app.add_option("--screenshot", options.screenshot,
                 "Scripted run: save the window as this PNG before quitting (needs --frames). "
                 "Like every PNG the app writes it carries its session: `lic3d render --session "
                 "shot.png` remakes the picture without the panels, the same pixels when they "
                 "were hidden (--hide-ui; with a clip box or plane add --visible-work off)");
  app.add_option("--render-image", options.renderImage,
                 "Scripted run: also save what \"Render image\" makes (the picture without the "
                 "UI, offscreen at --image-size, carrying its session) as this PNG before "
                 "quitting (needs --frames)");

  app.add_flag(
      "--soak", options.soak,
      "Scripted endurance run (needs --frames): a LIC or view change every 10 frames, a "
      "resize for 10 frames every 250; fails if RSS or device memory grows after the warm-up");
  app.add_option(
         "--drag-stride", options.dragStride,
         "The LIC while a LIC slider is dragged: every Nth voxel along each axis, the "
         "full LIC once it is let go. auto: 1, 2, 4 or 8, the smallest whose LIC fits "
         "8 ms of the frame, from the last full LIC's GPU time, and twice as coarse after a "
         "coarse LIC took longer; 1: always the full LIC")
      ->transform(CLI::CheckedTransformer(std::map<std::string, int>{
                                              {"auto", 0}, {"1", 1}, {"2", 2}, {"4", 4}, {"8", 8}})
                      .description(""))
      ->default_str("auto");
  app.add_option("--drag-lic", options.dragLic,
                 "Scripted run (needs --frames): once the volume is shown, hold the LIC length "
                 "slider for N frames, one step longer each, then let go; the panel's LIC line "
                 "of each volume and the frame times go to stderr")
      ->check(CLI::Range(1, 100000));
  app.add_option("--save-session", options.saveSession,
                 "Save every parameter as a session JSON file on quit (for `lic3d render "
                 "--session`)");

  if (const std::optional<int> status =
          parseCommandLine(app, argc, argv, "lic3d-view", "Run `lic3d-view --help`.", {&inputs}))
    return *status;
  setThreadLimit(global.threads);

  if (!windowSize.empty()) {
    const Result<glm::ivec2> size = parseSize(windowSize, "--window-size", 64, kMaxImageSize);
    if (!size) return reportError(size.error());
    options.windowWidth = size->x;
    options.windowHeight = size->y;
  }
  if (!options.screenshot.empty()) {
    if (options.frames == 0) {
      std::fprintf(stderr, "lic3d-view: error: --screenshot needs --frames\n");
      return kExitBadInput;
    }
    if (auto r = checkOutputPath(options.screenshot, ".png"); !r) return reportError(r.error());
  }
  if (!options.renderImage.empty()) {
    if (options.frames == 0) {
      std::fprintf(stderr, "lic3d-view: error: --render-image needs --frames\n");
      return kExitBadInput;
    }
    if (auto r = checkOutputPath(options.renderImage, ".png"); !r) return reportError(r.error());
  }
  if (options.dragLic > 0 && options.frames == 0) {
    std::fprintf(stderr, "lic3d-view: error: --drag-lic needs --frames\n");
    return kExitBadInput;
  }
  if (options.soak && options.frames == 0) {
    std::fprintf(stderr, "lic3d-view: error: --soak needs --frames\n");
    return kExitBadInput;
  }
  if (!options.saveSession.empty())
    if (auto r = checkOutputPath(options.saveSession, ".json"); !r) return reportError(r.error());
  if (auto r = finishSessionOptions(inputs, true); !r) return reportError(r.error());
  if (app.count("--mode") > 0) inputs.session.twoD = mode == "2d";
  if (auto r = finishPlaneOptions(plane, inputs.session); !r) return reportError(r.error());
  if (!imageSize.empty()) {
    const Result<glm::ivec2> size = parseSize(imageSize, "--image-size", 1, kMaxImageSize);
    if (!size) return reportError(size.error());
    inputs.session.plane.width = size->x;
    inputs.session.plane.height = size->y;
    options.imageWidth = size->x;
    options.imageHeight = size->y;
  }

  try {
    return viewer::runViewer(global, inputs, options);
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "lic3d-view: error: out of host memory\n");
    return kExitFailure;
  }
}
