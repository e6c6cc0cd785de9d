// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The desktop app's mouse and keyboard: GLFW callbacks gather a frame's events, which the app
// reads once per frame.

struct GLFWwindow;

namespace lic3d::viewer {

// Mouse and keyboard events between two frames.
struct Input {
  bool orbiting = false;
  bool panning = false;
  double lastX = 0.0, lastY = 0.0;
  double dx = 0.0, dy = 0.0;  // cursor motion while dragging, in pixels
  double scroll = 0.0;
  bool resetView = false, togglePlay = false, screenshot = false, toggleUi = false,
       toggleHelp = false, quit = false, resized = false;

  // The events since the last call; clears the one-shot ones (the drag state stays).
  Input take();
};

// Sends the window's events to `input` (the window's user pointer). Clicks and keys that Dear
// ImGui wants are left to it.
void listenForInput(GLFWwindow* window, Input& input);

}  // namespace lic3d::viewer
