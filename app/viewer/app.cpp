// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/app.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <glm/trigonometric.hpp>

#include "core/slice_geometry.h"
#include "core/stage_times.h"
#include "gpu/submit.h"
#include "gpu/vk_check.h"
#include "io/png_writer.h"
#include "io/session_file.h"
#include "lic/annotation.h"
#include "lic/legend.h"

namespace lic3d::viewer {

void App::updateCamera(const Input& in) {
  CameraParams& camera = session_.view.camera;
  const VkExtent2D extent = presenter_->extent();
  const float aspect =
      static_cast<float>(extent.width) / static_cast<float>(std::max(extent.height, 1u));
  const glm::vec3 half = boxHalfExtent(renderer_->dims(), renderer_->geometry());
  const CameraMatrices m = computeCamera(camera, half, aspect);
  if (in.orbiting) {
    camera.azimuth -= static_cast<float>(in.dx) * 0.3f;
    camera.elevation =
        std::clamp(camera.elevation + static_cast<float>(in.dy) * 0.3f, -89.0f, 89.0f);
  }
  if (in.panning) {
    // One pixel moves the target by the world size of a pixel at the target's depth.
    const float pixel = 2.0f * m.distance * std::tan(glm::radians(camera.fovY) * 0.5f) /
                        static_cast<float>(std::max(extent.height, 1u));
    camera.target +=
        (-static_cast<float>(in.dx) * m.right + static_cast<float>(in.dy) * m.up) * pixel;
  }
  if (in.scroll != 0.0)
    camera.distance = m.distance * std::pow(0.9f, static_cast<float>(in.scroll));
}

std::optional<LegendSpec> App::legendSpec() const {
  const ViewParams& v = session_.view;
  if (!session_.twoD) return renderer_->hasVolume() ? renderer_->legendFor(v) : std::nullopt;
  if (!v.legend || v.color != ColorMode::Magnitude) return std::nullopt;
  const float low = v.autoColorRange ? stats_.minMagnitude : v.colorLow;
  const float high = v.autoColorRange ? stats_.maxMagnitude : v.colorHigh;
  return LegendSpec{[v](float t) { return viewColor(v, t); }, low, high,
                    viewLegendTitle(v, "speed", "")};
}

PictureLayout App::viewLayout() const {
  const VkExtent2D extent = presenter_->extent();
  const int width = static_cast<int>(extent.width) -
                    static_cast<int>(panelWidth(ui_, static_cast<float>(extent.width)));
  const std::optional<LegendSpec> legend = stopped_ ? std::nullopt : legendSpec();
  return pictureLayout(std::max(width, 1), static_cast<int>(extent.height),
                       legend ? &*legend : nullptr, session_.view.title, session_.view.fontSize);
}

// The legend, the title and the box axes as `lic3d render` draws them, in ImGui's background
// layer over the picture (viewer/overlay.h).
void App::drawAnnotations(const PictureLayout& layout) {
  if (stopped_) return;
  const std::optional<LegendSpec> legend = legendSpec();
  ViewParams view = session_.view;
  view.axes = view.axes && !session_.twoD && renderer_->hasVolume();
  if (!legend && view.title.empty() && !view.axes) return;
  // The annotated area: the picture and the legend's column, left of the panels.
  const int width =
      layout.legend.z > 0 ? layout.legend.x + layout.legend.z : layout.picture.x + layout.picture.z;
  view.width = view.stereo == StereoMode::SideBySide ? std::max(width / 2, 1) : width;
  view.height = static_cast<int>(presenter_->extent().height);
  const VolumeFacts facts = renderer_->volumeFacts();
  const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  for (const OverlayRun& run :
       annotation_.runs(view, legend ? &*legend : nullptr, facts.dims, facts.geometry))
    draw->AddRectFilled(
        ImVec2(static_cast<float>(run.x0) / scale.x, static_cast<float>(run.y) / scale.y),
        ImVec2(static_cast<float>(run.x1) / scale.x, static_cast<float>(run.y + 1) / scale.y),
        IM_COL32(run.color.r, run.color.g, run.color.b, run.color.a));
}

void App::animate(double seconds) {
  if (ui_.playingTime && stats_.timeDependent && stats_.timeEnd > 0.0) {
    // Time runs through its range in ui_.timeSeconds and starts again: a loop for a periodic
    // field, and for a series of files from the last step back to the first.
    const double range = stats_.timeEnd;
    timePhase_ = std::fmod(session_.time + seconds * range / std::max(ui_.timeSeconds, 0.1f),
                           stats_.timePeriodic ? range : range + 1e-9);
    session_.time = timePhase_;
  }
  if (!ui_.playing) return;
  LicParams& lic = session_.lic;
  if (lic.length == 0) return;
  // The CLI's bias cycle, -L..L..-L (4L steps), at ui_.animationSpeed steps per second.
  biasPhase_ = std::fmod(biasPhase_ + seconds * ui_.animationSpeed / (4.0 * lic.length), 1.0);
  lic.bias = biasInCycle(lic.length, biasPhase_);
}

Result<void> App::handleActions(const Actions& actions) {
  if (actions.reloadField) {
    session_.timeSteps = ui_.pendingTimeSteps;
    if (session_.twoD) {  // the 2D picture reads its plane itself
      session_.field = ui_.pendingField;
      session_.noise = ui_.pendingNoise;
    } else {
      LIC3D_TRY(startLoading(ui_.pendingField, ui_.pendingNoise));
    }
  }
  if (actions.resetView) {
    const ViewParams defaults;
    session_.view.camera = defaults.camera;
  }
  if (actions.dismissAlert) stats_.alert.clear();
  if (actions.saveSession) {
    const Result<void> r = writeSession(ui_.sessionPath, session_);
    stats_.message = r ? "saved " + ui_.sessionPath : r.error().message;
  }
  if (actions.loadSession) {
    Result<Session> loaded = readSession(ui_.sessionPath);
    if (!loaded) {
      stats_.message = loaded.error().message;
    } else {
      const bool newInputs = !(loaded->field == session_.field && loaded->noise == session_.noise);
      session_ = std::move(loaded).value();
      ui_.pendingField = session_.field;
      ui_.pendingNoise = session_.noise;
      ui_.pendingTimeSteps = session_.timeSteps;
      if (newInputs && !session_.twoD) LIC3D_TRY(startLoading(session_.field, session_.noise));
      stats_.message = "loaded " + ui_.sessionPath;
    }
  }
  if (actions.renderImage) {
    const Result<void> written = renderImage();
    stats_.message = written ? "wrote " + ui_.imagePath : written.error().message;
  }
  return {};
}

// Each picture carries the session that remakes it (`lic3d render --session picture.png`).
Result<void> App::renderImage() {
  if (session_.twoD) {
    if (!planeView_ || !planeView_->hasPicture()) return runtimeError("no 2D picture to write yet");
    const Session shown = shownSession(0, 0);
    LIC3D_TRY_ASSIGN(const PngText text, cli::pngText(shown, ui_.imagePath));
    return writePng(ui_.imagePath, planeView_->image(shown.view), text);
  }
  if (!renderer_->hasVolume()) return runtimeError("no LIC volume to render yet");
  // The offscreen render shares the renderer's uniform slots with the frames: wait for them.
  vkDeviceWaitIdle(context_->device());
  const Session shown = shownSession(ui_.imageWidth, ui_.imageHeight);
  LIC3D_TRY_ASSIGN(const RgbaImage image, renderer_->render(shown.lic, shown.view));
  LIC3D_TRY_ASSIGN(const PngText text, cli::pngText(shown, ui_.imagePath));
  return writePng(ui_.imagePath, image, text);
}

Session App::shownSession(int width, int height) const {
  Session shown = session_;
  if (shown.twoD) {
    // The plane's picture at the size it was made at (the view's, unless the session gives one).
    if (planeView_ && planeView_->hasPicture()) {
      shown.plane.width = planeView_->imageDims().x;
      shown.plane.height = planeView_->imageDims().y;
    }
    return shown;
  }
  if (renderer_ && renderer_->shownParams()) shown.lic = *renderer_->shownParams();
  shown.view.width = width;
  shown.view.height = height;
  return shown;
}

// A screenshot carries the session of the picture without the panels at the window's size: with
// the panels hidden (H, Tab, --hide-ui) that is the screenshot itself.
Result<void> App::saveScreenshot(const FramePresenter::Frame& f) {
  const std::string path = f.scriptedShot
                               ? options_.screenshot
                               : "lic3d-screenshot-" + std::to_string(++screenshots_) + ".png";
  LIC3D_TRY_ASSIGN(const PngText text, cli::pngText(f.shown, path));
  LIC3D_TRY(writePng(path, presenter_->screenshot(f), text));
  stats_.message = "wrote " + path;
  if (!global_.quiet) std::fprintf(stderr, "lic3d-view: wrote %s\n", path.c_str());
  return {};
}

// Takes what the frame's last submission finished and measured, and its screenshot.
Result<void> App::collectFrame(FramePresenter::Frame& f, std::uint32_t slot) {
  if (f.finishedLic) {
    renderer_->collectStatistics(slot);
    ++soak_.counts.volumes;
  }
  if (f.timed) {
    LIC3D_TRY_ASSIGN(const double slabMs, f.timer.milliseconds(0));
    LIC3D_TRY_ASSIGN(stats_.frameMs, f.timer.milliseconds(1));
    gpuFrameMs_.add(slabMs + stats_.frameMs);
    if (f.licBegan) licSumMs_ = 0.0;  // a job dropped half-way is not part of this one
    if (f.licSlices > 0) {
      licSumMs_ += slabMs;
      // Aim the next slabs at the LIC time budget, from this device's measured speed (of full
      // slices: a coarse job is recorded whole).
      const double msPerSlice = std::max(slabMs / f.licSlices, 1e-3);
      if (f.licStride == 1)
        slicesPerFrame_ = std::clamp(static_cast<int>(kLicBudgetMs / msPerSlice), 1,
                                     std::max(1, renderer_->dims().z));
    }
    if (f.finishedLic) {
      // The whole volume, summed over its slabs.
      stats_.licTimes =
          licTimeText(licSumMs_, f.licStride, coarseDims(renderer_->dims(), f.licStride));
      if (f.licStride == 1) fullLicMs_ = licSumMs_;
      if (f.licStride > 1) licDrag_.noteCoarse(f.licStride, licSumMs_);
      if (scriptedDrag_.scripted() && !global_.quiet)
        std::fprintf(stderr, "lic3d-view: panel: %s\n", stats_.licTimes.c_str());
      licSumMs_ = 0.0;
    }
  }
  f.finishedLic = false;
  if (f.screenshot) {
    LIC3D_TRY(saveScreenshot(f));
    f.screenshot = f.scriptedShot = false;
  }
  return {};
}

// The renderer's state the panels show.
void App::updateStats() {
  const LicStatus status = renderer_->licStatus();
  stats_.computing = status.pending;
  stats_.computeFraction = status.fraction;
  stats_.waitingForMask = status.waitingForMask;
  stats_.volumeMiB = static_cast<double>(renderer_->volumeBytes()) / (1 << 20);
  stats_.frameTimes = frameTimeText(cpuFrameMs_.median(), gpuFrameMs_.median(), gpuFrameMs_.size());
  const VolumeFacts facts = renderer_->volumeFacts();
  stats_.colorValues = facts.colorValues;
  stats_.opacityValues = facts.opacityValues;
  stats_.hiddenFraction = renderer_->hiddenFraction().value_or(-1.0);
  stats_.resolvedAlpha = !session_.twoD && renderer_->hasVolume()
                             ? resolvedAlpha(session_.view, facts.transfer(), facts.dims)
                             : -1.0f;
  stats_.picture2D = session_.twoD;
}

void App::reportProgress(bool waiting) {
  if (!progress_.scripted()) return;
  const std::uint64_t frame = std::min<std::uint64_t>(frameNumber_ + 1, options_.frames);
  stats_.scriptText = progress_.windowText(frame, waiting);
  stats_.scriptFraction = progress_.fraction(frame);
  const std::string line = progress_.update(frame, secondsSince(startTime_), waiting);
  if (!line.empty()) {
    std::fputs(line.c_str(), stderr);
    std::fflush(stderr);
  }
}

// One step of the endurance run (--soak).
void App::stepSoak() {
  const std::optional<TimeSeries>& series = loader_.series();
  const Soak::AppState state{
      .atRest =
          !stats_.loading && !renderer_->licStatus().pending && !loader_.timePending(session_.time),
      .seriesStep = series && !stats_.loading ? series->stepTime(1) - series->stepTime(0) : 0.0,
      .deviceBytes = context_->allocatedBytes()};
  soak_.step(frameNumber_, options_.frames, session_, state, [&](bool larger) {
    glfwSetWindowSize(window_, options_.windowWidth + (larger ? 64 : 0),
                      options_.windowHeight + (larger ? 48 : 0));
  });
}

// Checks the session the panels and input changed and starts the work it asks for: the 2D
// picture, or the field, its time, the scalars and the LIC volume.
Result<void> App::applySession() {
  if (auto r = validate(session_.view); !r) {
    stats_.message = uiMessage(r.error());
    session_.view = drawnSession_.view;
  }
  if (stopped_) {
    // Nothing is read or computed any more: the session stays as it was saved.
  } else if (session_.twoD) {
    updatePlane();
  } else {
    // Back from the 2D mode with another field: the volume's field is read again.
    if (!stats_.loading &&
        (reloadField_ || !(loadedField_ == session_.field && loadedNoise_ == session_.noise)))
      LIC3D_TRY(startLoading(session_.field, session_.noise));
    LIC3D_TRY(updateTime());
    LIC3D_TRY(updateScalars());
    // While a LIC slider is held, a coarse volume; the full one when it is let go.
    const bool changed = !(session_.lic == drawnSession_.lic);
    if (const std::optional<int> stride =
            stats_.loading ? std::nullopt
                           : licDrag_.request(changed, ui_.licDragging, fullLicMs_)) {
      if (auto r = renderer_->requestLic(session_.lic, *stride); !r) {
        stats_.message = uiMessage(r.error());
        session_.lic = drawnSession_.lic;
      }
    }
  }
  drawnSession_ = session_;
  return {};
}

// Whether a scripted run may take its screenshot: the volume for the current parameters is
// shown (stopped: at once, showing the error).
bool App::readyForShot() const {
  if (!stopped_ && !scriptedDrag_.done()) return false;
  return stopped_ ||
         (session_.twoD
              ? planeView_ && planeView_->hasPicture() && planeView_->tried(session_, pictureArea_)
              : !stats_.loading && renderer_->hasVolume() && !renderer_->licStatus().pending &&
                    !loader_.timePending(session_.time));
}

// Draws one frame; false when the app should quit.
Result<bool> App::frame() {
  glfwPollEvents();
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - lastTime_).count();
  lastTime_ = now;
  cpuFrameMs_.add(1000.0 * seconds);
  stats_.fps = static_cast<float>(0.9 * stats_.fps + 0.1 * (seconds > 0.0 ? 1.0 / seconds : 0.0));

  const Input in = input_.take();
  if (in.quit || glfwWindowShouldClose(window_)) return false;
  const VkExtent2D window = windowExtent();
  if (window.width == 0 || window.height == 0) {  // minimised: nothing to draw into
    glfwWaitEvents();
    return true;
  }
  const VkExtent2D shown = presenter_->extent();
  if (in.resized || shown.width != window.width || shown.height != window.height) {
    input_.resized = false;
    LIC3D_TRY(presenter_->recreateSwapchain(window));
    ImGui_ImplVulkan_SetMinImageCount(presenter_->swapchain().minImageCount());
  }

  if (!stopped_) LIC3D_TRY(finishLoading());
  FramePresenter::Frame& f = presenter_->frame(frameNumber_);
  const auto slot = static_cast<std::uint32_t>(frameNumber_ % FramePresenter::kFramesInFlight);
  LIC3D_TRY(presenter_->wait(f));
  LIC3D_TRY(collectFrame(f, slot));

  LIC3D_TRY_ASSIGN(const std::optional<std::uint32_t> imageIndex, presenter_->acquire(f, window));
  if (!imageIndex) {  // out of date: made again, drawn next frame
    ImGui_ImplVulkan_SetMinImageCount(presenter_->swapchain().minImageCount());
    return true;
  }

  // UI and input.
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  if (in.toggleUi) ui_.visible = !ui_.visible;
  if (in.toggleHelp) ui_.help = !ui_.help;
  if (in.togglePlay) ui_.playing = !ui_.playing;
  updateStats();
  // Laid out once per frame: the annotations and the picture's viewport share it.
  const PictureLayout layout = viewLayout();
  pictureArea_ = {layout.picture.z, layout.picture.w};
  reportProgress(options_.frames > 0 &&
                 frameNumber_ + 1 > static_cast<std::uint64_t>(options_.frames));
  drawAnnotations(layout);
  Actions actions = drawUi(session_, ui_, stats_);
  if (stopped_ && actions.dismissAlert) return false;  // the dialog's OK quits
  ImGui::Render();
  actions.resetView = actions.resetView || in.resetView;
  actions.screenshot = actions.screenshot || in.screenshot;
  if (!session_.twoD && renderer_->hasVolume() && !ImGui::GetIO().WantCaptureMouse)
    updateCamera(in);
  if (!stopped_) {
    animate(seconds);
    LIC3D_TRY(handleActions(actions));
  }
  if (options_.soak && !stopped_) stepSoak();
  if (scriptedDrag_.scripted() && !stopped_) {
    const bool volumeShown =
        !stats_.loading && renderer_->hasVolume() && !renderer_->licStatus().pending;
    ui_.licDragging = scriptedDrag_.step(volumeShown, session_.lic) || ui_.licDragging;
  }
  LIC3D_TRY(applySession());

  const bool ready = readyForShot();
  const bool scriptedShot = options_.frames > 0 &&
                            frameNumber_ + 1 >= static_cast<std::uint64_t>(options_.frames) &&
                            ready;
  // It quits after this frame; run() saves the screenshot once the frame has finished.
  const bool quitAfterThis = scriptedShot;
  if (scriptedShot && !stopped_ && !options_.renderImage.empty()) {
    LIC3D_TRY(renderImage());
    if (!global_.quiet) std::fprintf(stderr, "lic3d-view: wrote %s\n", ui_.imagePath.c_str());
  }
  f.scriptedShot = scriptedShot && !options_.screenshot.empty();
  f.screenshot = actions.screenshot || f.scriptedShot;
  if (f.screenshot) {
    const VkExtent2D extent = presenter_->extent();
    const int width = static_cast<int>(extent.width);
    f.shown = shownSession(
        session_.view.stereo == StereoMode::SideBySide ? std::max(width / 2, 1) : width,
        static_cast<int>(extent.height));
  }

  LIC3D_TRY(recordPicture(f, slot, layout));
  LIC3D_TRY_ASSIGN(const bool outOfDate,
                   presenter_->finish(f, *imageIndex, [](VkCommandBuffer cmd) {
                     ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
                   }));
  if (outOfDate) input_.resized = true;
  ++frameNumber_;
  if (options_.frames > 0 && frameNumber_ > static_cast<std::uint64_t>(options_.frames) + 100000)
    return runtimeError("the LIC volume was not ready after 100000 frames");
  return !quitAfterThis;
}

// Records the frame's LIC slab and the picture into the offscreen image, which it leaves ready
// for the blit to the window.
Result<void> App::recordPicture(FramePresenter::Frame& f, std::uint32_t slot,
                                const PictureLayout& layout) {
  LIC3D_TRY_ASSIGN(const VkCommandBuffer cmd, presenter_->begin(f));
  f.timed = f.timer.valid();
  if (f.timed) {
    f.timer.reset(cmd, 0);
    f.timer.reset(cmd, 1);
    f.timer.begin(cmd, 0);
  }
  // A coarse job is recorded whole: its stride was chosen so that it fits the frame.
  const int slices = renderer_->licStatus().stride > 1 ? renderer_->dims().z : slicesPerFrame_;
  LIC3D_TRY_ASSIGN(const LicWork work, renderer_->recordLicWork(cmd, slices, slot));
  if (f.timed) f.timer.end(cmd, 0);
  f.finishedLic = work.finished;
  f.licSlices = work.slicesRecorded;
  f.licStride = work.stride;
  f.licBegan = work.began;

  const VkExtent2D extent = presenter_->extent();
  const Image& offscreen = presenter_->offscreen();
  imageBarrier(cmd, offscreen.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT,
               VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
  if (f.timed) f.timer.begin(cmd, 1);
  const glm::ivec4 picture = layout.picture;
  const VkRect2D area{
      {picture.x, picture.y},
      {static_cast<std::uint32_t>(picture.z), static_cast<std::uint32_t>(picture.w)}};
  const bool drawVolume = !session_.twoD && !stopped_;
  if (drawVolume) LIC3D_TRY(renderer_->prepareDraw(cmd, area, session_.view, 2 * slot));
  beginClearedRendering(cmd, offscreen.view(), extent, session_.view.background);
  const Result<void> drawn = drawVolume
                                 ? renderer_->recordDraw(cmd, FramePresenter::kOffscreenFormat,
                                                         area, session_.view, 2 * slot)
                                 : Result<void>();
  vkCmdEndRendering(cmd);
  if (f.timed) f.timer.end(cmd, 1);
  LIC3D_TRY(drawn);

  if (session_.twoD && planeView_ && !stopped_) {
    planeView_->record(cmd, offscreen.handle(), area);  // leaves it ready for the blit
  } else {
    imageBarrier(cmd, offscreen.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
  }
  return {};
}

int App::run() {
  if (auto r = init(); !r) {
    if (r.error().kind == ErrorKind::Runtime) saveRecovery();
    return cli::reportError(r.error());
  }
  drawnSession_ = session_;
  while (true) {
    Result<bool> more = frame();
    if (!more && more.error().deviceLost) {
      Result<void> recovered = recoverDevice(more.error());
      if (recovered) continue;
      more = std::move(recovered).error();
    }
    if (!more) {
      exitStatus_ = cli::reportError(more.error());
      saveRecovery();
      if (showStopped(more.error())) continue;
      break;
    }
    if (!*more) break;
  }
  if (!context_) return exitStatus_;  // the device was lost and could not be made again
  std::fputs(progress_.finish().c_str(), stderr);
  if (scriptedDrag_.scripted() && !global_.quiet)
    std::fprintf(stderr, "lic3d-view: panel: %s\n", stats_.frameTimes.c_str());
  // Let the last screenshot's frame finish (a scripted run quits right after recording it).
  vkDeviceWaitIdle(context_->device());
  for (std::uint64_t i = 0; i < FramePresenter::kFramesInFlight; ++i) {
    FramePresenter::Frame& f = presenter_->frame(i);
    if (f.screenshot) {
      if (auto r = saveScreenshot(f); !r) exitStatus_ = cli::reportError(r.error());
      f.screenshot = f.scriptedShot = false;
    }
  }
  if (options_.soak && exitStatus_ == cli::kExitOk)
    exitStatus_ =
        soak_.verdict(frameNumber_, presenter_->swapchainsCreated(), renderer_->maskBuildCount());
  if (!options_.saveSession.empty()) {
    if (auto r = writeSession(options_.saveSession, session_); !r)
      exitStatus_ = cli::reportError(r.error());
    else
      std::fprintf(stderr, "lic3d-view: wrote %s\n", options_.saveSession.c_str());
  }
  const std::size_t validationMessages =
      lostValidationMessages_ + context_->validationMessageCount();
  if (context_->validationEnabled() && validationMessages > 0) {
    std::fprintf(stderr, "lic3d-view: error: %zu validation message(s)\n", validationMessages);
    if (exitStatus_ == cli::kExitOk) exitStatus_ = cli::kExitFailure;
  }
  return exitStatus_;
}

int runViewer(const cli::GlobalOptions& global, cli::SessionOptions& inputs,
              const ViewerOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  App app(global, inputs, options);
  const int status = app.run();
  // The stages of the whole session: field loads, uploads, LIC volumes, screenshots.
  if (global.timings) cli::printTimings(secondsSince(start));
  return status;
}

}  // namespace lic3d::viewer
