// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The desktop app itself: one App owns the window, the device, the renderer and the frames, and
// runs the frame loop (viewer/app.cpp) around the device's lifetime, the field's loading and the
// recovery from lost devices (viewer/device.cpp). Input, frame presentation, field loading and
// the endurance run are parts of their own (viewer/input.h, viewer/frames.h, viewer/loading.h,
// viewer/soak.h).

#include <vulkan/vulkan.h>

#include <chrono>
#include <cstdint>
#include <optional>
#include <utility>

#include "core/session.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "loading/session_inputs.h"
#include "options/session_options.h"
#include "render/lic_renderer.h"
#include "viewer/drag.h"
#include "viewer/frames.h"
#include "viewer/input.h"
#include "viewer/loading.h"
#include "viewer/overlay.h"
#include "viewer/plane.h"
#include "viewer/script_progress.h"
#include "viewer/soak.h"
#include "viewer/ui.h"
#include "viewer/viewer.h"

struct GLFWwindow;

namespace lic3d::viewer {

// GPU time the frame-paced LIC may take per frame: the UI stays responsive while the volume is
// recomputed in slabs, even on a CPU driver.
inline constexpr double kLicBudgetMs = 12.0;
// Where the session goes when the app stops on an error or loses its device.
inline constexpr const char* kRecoveryFile = "lic3d-recovery.json";
// A device lost more than kMaxLossStreak times with fewer than kLossStreakFrames frames between
// the losses is given up on: the app exits with the error (the session is in the recovery file).
inline constexpr int kMaxLossStreak = 3;
inline constexpr std::uint64_t kLossStreakFrames = 100;
// Steps of a time-dependent analytic field (the tornado) over its period when the session names
// none: the app blends steps on the GPU as it does a series of files (docs/TIME.md).
inline constexpr int kDefaultTimeSteps = 64;

class App {
 public:
  App(const cli::GlobalOptions& global, cli::SessionOptions& inputs, const ViewerOptions& options)
      : global_(global), inputs_(inputs), options_(options), session_(inputs.session) {}
  ~App();
  int run();

 private:
  Result<void> init();
  Result<void> createGpu();
  void destroyGpu();
  Result<void> recoverDevice(const Error& error);
  bool showStopped(const Error& error);
  VkExtent2D windowExtent() const;
  // Reads or makes the field on a worker thread. An analytic field whose grid cannot fit is
  // refused first, before it is made: an error when nothing is shown yet (exit status 3), an
  // alert otherwise.
  Result<void> startLoading(const FieldSource& field, const NoiseSource& noise);
  // Whether a field of `dims` fits beside everything the app keeps (checkRequestMemory).
  Result<void> checkFieldFits(Dims dims, bool series) const;
  Result<void> finishLoading();
  Result<void> updateTime();
  Result<bool> frame();
  Result<void> collectFrame(FramePresenter::Frame& f, std::uint32_t slot);
  void updateStats();
  void stepSoak();
  // The scripted run's progress, in the window and on stderr.
  void reportProgress(bool waiting);
  Result<void> applySession();
  bool readyForShot() const;
  Result<void> recordPicture(FramePresenter::Frame& f, std::uint32_t slot,
                             const PictureLayout& layout);
  void updateCamera(const Input& in);
  // Where the picture, its legend and its title go in the window: the part left of the panels.
  PictureLayout viewLayout() const;
  std::optional<LegendSpec> legendSpec() const;
  void drawAnnotations(const PictureLayout& layout);
  // Colour and opacity follow the session's colorBy and opacityBy (loaded when they change).
  Result<void> updateScalars();
  void animate(double seconds);
  Result<void> handleActions(const Actions& actions);
  void updatePlane();
  // The session that remakes the picture shown, at `width` x `height` pixels (per eye for
  // side-by-side stereo; ignored in 2D, where the plane's picture keeps the size it was made at):
  // the LIC parameters of the volume on screen, which lag the panels' while a new one is made.
  Session shownSession(int width, int height) const;
  Result<void> saveScreenshot(const FramePresenter::Frame& f);
  // "Render image": the picture shown without the UI, to ui_.imagePath with its session (in 3D
  // at ui_.imageWidth x ui_.imageHeight, rendered offscreen; in 2D the plane's picture).
  Result<void> renderImage();
  void saveRecovery() const;

  const cli::GlobalOptions& global_;
  cli::SessionOptions& inputs_;
  ViewerOptions options_;
  Session session_;
  Session drawnSession_;  // what the frames were made with: changes are compared against it
  UiState ui_;
  Stats stats_;
  Input input_;

  GLFWwindow* window_ = nullptr;
  std::optional<Context> context_;
  // Made on the context, destroyed before it (destroyGpu).
  std::optional<LicRenderer> renderer_;
  std::optional<FramePresenter> presenter_;
  DeviceHandle<VkDescriptorPool, vkDestroyDescriptorPool> uiPool_;
  bool imguiReady_ = false;        // Dear ImGui's context and GLFW backend
  bool imguiVulkanReady_ = false;  // its Vulkan backend, made again with the device
  std::uint64_t frameNumber_ = 0;
  int slicesPerFrame_ = 4;
  double licSumMs_ = 0.0;   // GPU time of the LIC slabs of the volume being computed
  double fullLicMs_ = 0.0;  // GPU time of the last full LIC volume (the drag's stride)
  LicDrag licDrag_{options_.dragStride};
  ScriptedDrag scriptedDrag_{options_.dragLic};
  RecentMedian cpuFrameMs_;  // the time between frames
  RecentMedian gpuFrameMs_;  // the frames' LIC work and volume draw
  double biasPhase_ = 0.0;
  int screenshots_ = 0;
  FieldLoader loader_;
  double timePhase_ = 0.0;
  bool loadedOnce_ = false;   // a field load has completed (or the app started in 2D)
  bool reloadField_ = false;  // the volume's field must be read again (a new device has none)
  int deviceLosses_ = 0;
  // Set when the app has stopped on an error it cannot carry on from: it then only shows the
  // error in a dialog, on a fresh device, until the window is closed (see showStopped).
  bool stopped_ = false;
  std::size_t lostValidationMessages_ = 0;  // validation messages of devices made before this one
  int lossStreak_ = 0;
  std::uint64_t lastLossFrame_ = 0;
  // The 2D mode's picture.
  std::optional<PlaneView> planeView_;
  std::optional<std::pair<FieldSource, TimeDomain>> planeDomain_;
  glm::ivec2 pictureArea_{0};  // the view's size in pixels this frame
  SettledSize planeArea_;      // the view's size the 2D picture is made for
  FieldSource loadedField_;
  NoiseSource loadedNoise_;
  // The inputs of the field shown (without the noise): colour-by scalars are made from them.
  std::optional<SessionInputs> shownInputs_;
  std::optional<std::pair<std::string, std::string>> shownScalars_;  // colour, opacity
  std::chrono::steady_clock::time_point lastTime_ = std::chrono::steady_clock::now();
  const std::chrono::steady_clock::time_point startTime_ = std::chrono::steady_clock::now();
  ScriptProgress progress_;
  int exitStatus_ = cli::kExitOk;
  Soak soak_;
  AnnotationLayer annotation_;
};

}  // namespace lic3d::viewer
