// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The desktop app's Dear ImGui panels: every parameter of a Session, with tooltips, plus the
// stats overlay and the help panel (the legend is the engine's: viewer/overlay.h). Panels edit the
// session in place; the caller compares sessions to decide between reloading, recomputing and
// redrawing.

#include <imgui.h>

#include <cstdint>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/session.h"
#include "core/value_histogram.h"
#include "lic/legend.h"

namespace lic3d::viewer {

// What the panels show besides the session.
struct Stats {
  float fps = 0.0f;
  double frameMs = 0.0;    // GPU time of the last frame's volume draw
  std::string frameTimes;  // frameTimeText (viewer/drag.h)
  std::string licTimes;    // licTimeText of the last LIC volume; empty before the first
  std::string device;
  Dims dims{0};
  double volumeMiB = 0.0;
  bool computing = false;
  double computeFraction = 1.0;
  bool waitingForMask = false;
  bool loading = false;
  std::string message;  // the last error or notice, shown until replaced
  std::string alert;    // a refused request or a lost device, shown in a dialog until dismissed
  std::string alertTitle;
  float minMagnitude = 0.0f, maxMagnitude = 1.0f;
  // What colour and opacity can follow (loading/scalars.h), and the values of the ones they
  // follow (the transfer function editor's histograms).
  std::vector<std::string> scalarChoices;
  std::shared_ptr<const ValueHistogram> colorValues;
  std::shared_ptr<const ValueHistogram> opacityValues;
  double hiddenFraction = -1.0;  // of the voxels, by the sparsity mask (< 0: no mask)
  float resolvedAlpha = -1.0f;   // the alpha per voxel the slices use (< 0: unknown)
  bool picture2D = false;        // dims are the 2D picture's, not a volume's
  // A scripted run's progress (viewer/script_progress.h); empty when not scripted.
  std::string scriptText;
  float scriptFraction = 0.0f;
  // The field's time (docs/TIME.md): the slider runs over [0, timeEnd].
  bool timeDependent = false;
  bool timePeriodic = false;  // an analytic field: timeEnd is its period
  double timeEnd = 0.0;
};

// Requests from the panels that are actions, not parameters.
struct Actions {
  bool saveSession = false;
  bool loadSession = false;
  bool screenshot = false;   // at window size, with the UI
  bool renderImage = false;  // offscreen at the chosen size, without the UI
  bool resetView = false;
  bool reloadField = false;  // the field or noise source changed
  bool dismissAlert = false;
};

struct UiState {
  bool visible = true;
  bool help = false;
  bool playing = false;          // bias animation
  float animationSpeed = 10.0f;  // bias steps per second
  std::string sessionPath = "lic3d-session.json";
  std::string imagePath = "lic3d-render.png";
  int imageWidth = 1920;
  int imageHeight = 1080;
  FieldSource pendingField;  // edited until "Load" is pressed
  NoiseSource pendingNoise;
  int pendingTimeSteps = 0;   // steps of a time-dependent analytic field (0: the default)
  bool playingTime = false;   // time animation
  float timeSeconds = 20.0f;  // seconds for the whole time range
  std::string transferPath = "lic3d-transfer.json";  // a ParaView colour-map preset
  int selectedColorPoint = -1;                       // of the transfer function editor
  std::string transferMessage;                       // the preset last loaded or saved
  float lastOpticalDepth = 0.0f;  // restored when the optical depth sets the opacity again
  bool licDragging = false;       // a LIC slider is held this frame (a coarse LIC is shown)
};

// The panels are docked at the right, the full height of the window; the picture takes the
// rest. Their width in pixels for a window `displayWidth` wide (0 while hidden).
float panelWidth(const UiState& ui, float displayWidth);

// A text box for a file's path. While it is not edited, a path wider than the box shows its file
// name with the directory elided in the middle (elidePath), the whole path in its tooltip; a
// click edits the whole path. True when the path changed.
bool pathText(const char* label, std::string& value, const char* help);

// The transfer function editor (viewer/transfer_editor.cpp): colour and opacity control points over
// a histogram of their scalar, a preset file to load or save.
void transferFunctionPanel(ViewParams& view, UiState& ui, const Stats& stats);

// An error for the panels: the widget's label in place of the parameter's session key
// (Error::parameter), e.g. "'step h' must be in [0.001, 8], got 9".
std::string uiMessage(const Error& error);

// Draws every panel for this frame (between ImGui::NewFrame and ImGui::Render).
Actions drawUi(Session& session, UiState& ui, const Stats& stats);

}  // namespace lic3d::viewer
