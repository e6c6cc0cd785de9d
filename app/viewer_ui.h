#pragma once
// The desktop app's Dear ImGui panels: every parameter of a Session, with tooltips, plus the
// stats overlay, the colour legend and the help panel. Panels edit the session in place; the
// caller compares sessions to decide between reloading, recomputing and redrawing.

#include <string>

#include "core/error.h"
#include "core/session.h"

namespace lic3d::viewer {

// What the panels show besides the session.
struct Stats {
  float fps = 0.0f;
  double licMs = 0.0;    // GPU time of the last LIC volume, summed over its slabs (timestamps)
  double frameMs = 0.0;  // GPU time of the last frame's volume draw
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
};

// An error for the panels: the widget's label in place of the parameter's session key
// (Error::parameter), e.g. "'step h' must be in [0.001, 8], got 9".
std::string uiMessage(const Error& error);

// Draws every panel for this frame (between ImGui::NewFrame and ImGui::Render).
Actions drawUi(Session& session, UiState& ui, const Stats& stats);

}  // namespace lic3d::viewer
