// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The desktop app: a GLFW window with a Vulkan swapchain, the engine's passes drawing the LIC
// volume, and Dear ImGui panels on top.

#include <string>

#include "options/session_options.h"

namespace lic3d::viewer {

struct ViewerOptions {
  int windowWidth = 1280;
  int windowHeight = 800;
  bool vsync = true;
  bool hideUi = false;
  // Scripted runs: after `frames` frames (and once the LIC volume for the current parameters is
  // shown) save a screenshot of the window to `screenshot`, if given, and quit. 0 runs until
  // the window closes.
  int frames = 0;
  std::string screenshot;
  // Scripted runs: also save the picture "Render image" makes (offscreen, without the UI) to this
  // PNG, at `imageWidth` x `imageHeight` in 3D (0: the panel's size), before quitting.
  std::string renderImage;
  int imageWidth = 0;
  int imageHeight = 0;
  // On quit, save the session (every parameter as shown) to this JSON file, if given.
  std::string saveSession;
  // With `frames`: change a LIC or a view parameter every 10 frames and resize the window every
  // 250 (for 10 frames), sample RSS and device memory, and fail if they grow after the warm-up.
  bool soak = false;
  // The stride of the LIC while a LIC slider is dragged: 0 from the last full LIC's GPU time
  // (coarseLicStride), 1 always the full LIC, 2, 4 or 8 that stride.
  int dragStride = 0;
  // With `frames`: once the first volume is shown, hold the LIC length slider for this many
  // frames, one step longer each, then let go; each LIC volume's line of the panel and, at the
  // end, the frame times go to stderr.
  int dragLic = 0;
};

// Runs the app until the window closes; returns the process exit status.
int runViewer(const cli::GlobalOptions& global, cli::SessionOptions& inputs,
              const ViewerOptions& options);

}  // namespace lic3d::viewer
