// SPDX-License-Identifier: BSD-3-Clause
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "viewer/app.h"

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
#include "lic/legend.h"
#include "loading/scalars.h"
#include "viewer/panel_logic.h"

namespace lic3d::viewer {
namespace {

void checkImguiVk(VkResult result) {
  if (result != VK_SUCCESS) abortOnVkError("Dear ImGui Vulkan backend", result, __FILE__, __LINE__);
}

}  // namespace

App::~App() {
  destroyGpu();
  if (imguiReady_) {
    ImGui_ImplGlfw_Shutdown();
    ImGui::DestroyContext();
  }
  if (window_) glfwDestroyWindow(window_);
  glfwTerminate();
}

// Everything made on the device, and the device. After VK_ERROR_DEVICE_LOST the waits return
// that error at once, and destroying is still valid.
void App::destroyGpu() {
  if (!context_) return;
  vkDeviceWaitIdle(context_->device());
  if (imguiVulkanReady_) ImGui_ImplVulkan_Shutdown();
  imguiVulkanReady_ = false;
  uiPool_.reset();
  planeView_.reset();
  presenter_.reset();
  renderer_.reset();
  context_.reset();
}

VkExtent2D App::windowExtent() const {
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  return {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height)};
}

Result<void> App::init() {
  glfwSetErrorCallback(
      [](int, const char* text) { std::fprintf(stderr, "lic3d-view: GLFW: %s\n", text); });
  if (!glfwInit())
    return unsupportedError(
        "cannot open a window (no display? set DISPLAY, or use `lic3d render`)");
  if (!glfwVulkanSupported()) return unsupportedError("GLFW finds no Vulkan loader for windows");
  glfwWindowHint(GLFW_CLIENT_API, GLFW_NO_API);
  window_ =
      glfwCreateWindow(options_.windowWidth, options_.windowHeight, "lic3d", nullptr, nullptr);
  if (!window_) return unsupportedError("cannot create the window");
  listenForInput(window_, input_);

  IMGUI_CHECKVERSION();
  ImGui::CreateContext();
  ImGui::GetIO().IniFilename = nullptr;  // no imgui.ini next to the user's files
  float scale = 1.0f;
  glfwGetWindowContentScale(window_, &scale, nullptr);
  if (scale > 1.0f) {
    ImGui::GetStyle().ScaleAllSizes(scale);
    ImGui::GetIO().FontGlobalScale = scale;
  }
  ImGui_ImplGlfw_InitForVulkan(window_, true);
  imguiReady_ = true;
  LIC3D_TRY(createGpu());

  ui_.visible = !options_.hideUi;
  if (!options_.renderImage.empty()) ui_.imagePath = options_.renderImage;
  if (options_.imageWidth > 0) {
    ui_.imageWidth = options_.imageWidth;
    ui_.imageHeight = options_.imageHeight;
  }
  ui_.pendingField = session_.field;
  ui_.pendingNoise = session_.noise;
  ui_.pendingTimeSteps = session_.timeSteps;
  // The preset box names the file the transfer function was read from.
  if (const std::string preset = startupPresetFile(inputs_); !preset.empty()) {
    ui_.transferPath = preset;
    ui_.transferMessage = "loaded " + preset;
  } else if (!session_.view.transfer.empty()) {
    ui_.transferMessage =
        "from the session" +
        (session_.view.transfer.name.empty() ? std::string() : ": " + session_.view.transfer.name);
  }
  progress_ = ScriptProgress(options_.frames, isatty(STDERR_FILENO) != 0, global_.quiet);
  // The 2D mode makes its own plane; the volume's field is read when the 3D mode is chosen.
  if (!session_.twoD) LIC3D_TRY(startLoading(session_.field, session_.noise));
  loadedOnce_ = session_.twoD;
  return {};
}

// The device and everything the app draws with: made at the start and again after a lost device.
Result<void> App::createGpu() {
  ContextOptions contextOptions;
  contextOptions.validation = global_.validation;
  contextOptions.device = global_.device;
  std::uint32_t count = 0;
  const char** extensions = glfwGetRequiredInstanceExtensions(&count);
  contextOptions.instanceExtensions.assign(extensions, extensions + count);
  contextOptions.deviceExtensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);
  contextOptions.createSurface = [this](VkInstance instance) -> Result<VkSurfaceKHR> {
    VkSurfaceKHR surface = VK_NULL_HANDLE;
    const VkResult r = glfwCreateWindowSurface(instance, window_, nullptr, &surface);
    if (r != VK_SUCCESS)
      return unsupportedError(std::string("cannot make a Vulkan surface for the window: ") +
                              vkResultName(r));
    return surface;
  };
  LIC3D_TRY_ASSIGN(Context context, Context::create(contextOptions));
  context_.emplace(std::move(context));
  stats_.device = context_->deviceInfo().name;
  VkDevice device = context_->device();

  RendererOptions rendererOptions;
  rendererOptions.fieldPrecision = session_.precision;
  rendererOptions.doubleBuffered = true;
  rendererOptions.haloPipelinePerSlice = false;
  LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(*context_, rendererOptions));
  renderer_.emplace(std::move(renderer));
  LIC3D_TRY_ASSIGN(FramePresenter presenter,
                   FramePresenter::create(*context_, windowExtent(), options_.vsync));
  presenter_.emplace(std::move(presenter));

  // Dear ImGui 1.86's Vulkan backend draws inside a classic render pass; the picture before it
  // uses dynamic rendering into an offscreen image that is blitted to the swapchain image.
  const std::array<VkDescriptorPoolSize, 1> sizes{
      {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  poolInfo.maxSets = 16;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  VkDescriptorPool pool = VK_NULL_HANDLE;
  LIC3D_TRY(
      checkVk(vkCreateDescriptorPool(device, &poolInfo, nullptr, &pool), "vkCreateDescriptorPool"));
  uiPool_ = {device, pool};
  context_->setDebugName(pool, VK_OBJECT_TYPE_DESCRIPTOR_POOL, "imgui descriptors");

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context_->instance();
  info.PhysicalDevice = context_->physicalDevice();
  info.Device = device;
  info.QueueFamily = context_->queueFamily();
  info.Queue = context_->queue();
  info.DescriptorPool = pool;
  info.MinImageCount = presenter_->swapchain().minImageCount();
  info.ImageCount = presenter_->swapchain().imageCount();
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkImguiVk;
  ImGui_ImplVulkan_Init(&info, presenter_->uiPass());
  imguiVulkanReady_ = true;
  LIC3D_TRY(submitAndWait(
      *context_, [](VkCommandBuffer cmd) { ImGui_ImplVulkan_CreateFontsTexture(cmd); },
      "imgui fonts"));
  ImGui_ImplVulkan_DestroyFontUploadObjects();
  return {};
}

// After VK_ERROR_DEVICE_LOST (a driver reset, a GPU fault) nothing made on the device can be used
// again. The session is saved to the recovery file, the device and everything on it are made
// again, the volume's field is read again and its LIC recomputed from the session, and a dialog
// says what happened. A device lost again and again is given up on (the error is returned).
Result<void> App::recoverDevice(const Error& error) {
  saveRecovery();
  lossStreak_ =
      deviceLosses_ > 0 && frameNumber_ - lastLossFrame_ < kLossStreakFrames ? lossStreak_ + 1 : 1;
  if (lossStreak_ > kMaxLossStreak) {
    Error fatal = error;
    fatal.message += " (the device was lost " + std::to_string(lossStreak_) + " times within " +
                     std::to_string(kLossStreakFrames) + " frames of each other: giving up)";
    return fatal;
  }
  ++deviceLosses_;
  lastLossFrame_ = frameNumber_;
  std::fprintf(stderr, "lic3d-view: %s: making the device again\n", error.message.c_str());
  // Steps of a series being read belong to the old blend: the new series is read from scratch.
  // A field being read (stats_.loading) is CPU work: it goes on and is uploaded to the new device.
  loader_.dropSeries();
  licSumMs_ = 0.0;
  lostValidationMessages_ += context_->validationMessageCount();
  destroyGpu();
  LIC3D_TRY(createGpu());
  reloadField_ = !stats_.loading;
  stats_.alertTitle = "lic3d: the GPU device was lost";
  stats_.alert = error.message +
                 ". The device was made again and the session restored; a copy of "
                 "the session is in " +
                 kRecoveryFile + ".";
  return {};
}

Result<void> App::checkFieldFits(Dims dims, bool series) const {
  const VkExtent2D extent = presenter_->extent();
  return checkRequestMemory(*context_, session_, dims,
                            {.doubleBuffered = true,
                             .frame = true,
                             .frameWidth = static_cast<int>(extent.width),
                             .frameHeight = static_cast<int>(extent.height),
                             .timeSeries = series});
}

Result<void> App::startLoading(const FieldSource& field, const NoiseSource& noise) {
  loadedField_ = field;
  loadedNoise_ = noise;
  // An analytic field's grid is known before it is made (the CLI refuses it there too).
  if (const auto analytic = parseEnum<AnalyticField>(field.field))
    if (auto r = checkFieldFits(field.grid, timePeriod(*analytic) > 0.0); !r) {
      if (!renderer_->hasVolume()) return std::move(r).error();  // nothing to keep: status 3
      stats_.alertTitle = "lic3d: not done";
      stats_.alert = r.error().message + ". The previous field stays loaded.";
      ui_.pendingField = session_.field;
      return {};
    }
  stats_.loading = true;
  // --grid with a file field is an error on the command line only, not when loading later.
  const bool gridGiven = !renderer_->hasVolume() && deviceLosses_ == 0 && inputs_.grid.given();
  reloadField_ = false;
  Session wanted = session_;
  wanted.field = field;
  wanted.noise = noise;
  loader_.start(wanted, gridGiven, kDefaultTimeSteps);
  return {};
}

Result<void> App::finishLoading() {
  std::optional<Result<FieldLoader::Loaded>> done = loader_.finished();
  if (!done) return {};
  Result<FieldLoader::Loaded>& loaded = *done;
  stats_.loading = false;
  if (loaded) ++soak_.counts.fieldReads;
  // The app's first field failing to load ends it (nothing to show); later failures are messages.
  const bool firstLoad = !renderer_->hasVolume() && !loadedOnce_;
  loadedOnce_ = true;
  if (!loaded) {
    stats_.message = uiMessage(loaded.error());
    if (firstLoad) return std::move(loaded).error();  // nothing to show at all
    loadedField_ = session_.field;                    // not read again until the field changes
    loadedNoise_ = session_.noise;
    return {};
  }
  // The new field must fit beside everything the app keeps; if not, the old volume stays.
  const VectorField& grid = loaded->inputs.field;
  const bool series = loaded->inputs.series.has_value();
  if (auto r = checkFieldFits(grid.dims, series); !r) {
    if (!renderer_->hasVolume()) return std::move(r).error();  // nothing to keep: exit status 3
    stats_.alertTitle = "lic3d: not done";
    stats_.alert = r.error().message + ". The previous field stays loaded.";
    ui_.pendingField = session_.field;
    return {};
  }
  if (auto r = validate(session_.lic.sparsity, grid.dims); !r) {
    session_.lic.sparsity = SparsityParams{};
    stats_.message = uiMessage(r.error()) + " (sparsity turned off)";
  }
  LIC3D_TRY(loader_.show(*loaded, *renderer_));
  if (series) {
    const TimeSeries& s = *loaded->inputs.series;
    session_.timeSteps = s.analytic ? s.steps : 0;
    ui_.pendingTimeSteps = session_.timeSteps;
    stats_.timeEnd = s.endTime();
    stats_.timePeriodic = s.periodic();
  }
  stats_.timeDependent = series;
  session_.field = loadedField_;
  session_.noise = loadedNoise_;
  stats_.dims = grid.dims;
  stats_.minMagnitude = static_cast<float>(minMagnitude(grid));
  stats_.maxMagnitude = static_cast<float>(maxMagnitude(grid));
  // Kept for the colour-by scalars, which the new field's are made from again.
  shownInputs_ = std::move(loaded->inputs);
  shownInputs_->noise = NoiseVolume();
  stats_.scalarChoices = scalarChoices(*shownInputs_);
  shownScalars_.reset();
  LIC3D_TRY(updateScalars());
  if (series) return updateTime();
  return renderer_->requestLic(session_.lic);
}

Result<void> App::updateScalars() {
  if (!shownInputs_ || stats_.loading) return {};
  ViewParams& v = session_.view;
  if (shownScalars_ && shownScalars_->first == v.colorBy && shownScalars_->second == v.opacityBy)
    return {};
  Result<std::optional<PointScalars>> color =
      loadScalars(v.colorBy, "view.color_by", session_, *shownInputs_);
  Result<std::optional<PointScalars>> opacity =
      v.opacityBy == v.colorBy
          ? color
          : loadScalars(v.opacityBy, "view.opacity_by", session_, *shownInputs_);
  if (!color || !opacity) {
    stats_.message = uiMessage(!color ? color.error() : opacity.error());
    // Back to what is shown (speed for a new field).
    v.colorBy = shownScalars_ ? shownScalars_->first : "speed";
    v.opacityBy = shownScalars_ ? shownScalars_->second : "speed";
    if (shownScalars_) return {};
  }
  const auto pointer = [](const Result<std::optional<PointScalars>>& s) {
    return s && s->has_value() ? &**s : nullptr;
  };
  LIC3D_TRY(renderer_->setScalars(pointer(color), pointer(opacity)));
  shownScalars_.emplace(v.colorBy, v.opacityBy);
  return {};
}

// Blends the field at the session's time (the loader reads missing steps on a worker thread);
// the LIC volume follows, frame-paced as any change.
Result<void> App::updateTime() {
  if (stats_.loading) return {};
  LIC3D_TRY_ASSIGN(const bool blended, loader_.updateTime(*renderer_, session_, stats_.message,
                                                          soak_.counts.stepReads));
  if (blended) return renderer_->requestLic(session_.lic);
  return {};
}

// The 2D mode: the picture follows the session (a failure leaves the previous one and says why).
void App::updatePlane() {
  if (!planeView_) {
    Result<PlaneView> created = PlaneView::create(*context_);
    if (!created) {
      stats_.message = created.error().message;
      return;
    }
    planeView_.emplace(std::move(*created));
  }
  const double now = secondsSince(startTime_);
  if (auto r = planeView_->update(session_, planeArea_.update(pictureArea_, now)); !r) {
    stats_.message = uiMessage(r.error());
    return;
  }
  // A series' files are listed once per field, not every frame.
  if (!planeDomain_ || !(planeDomain_->first == session_.field)) {
    const Result<TimeDomain> domain = timeDomainOf(session_);
    planeDomain_.emplace(session_.field, domain ? *domain : TimeDomain{});
  }
  stats_.timeDependent = planeDomain_->second.timeDependent;
  stats_.timeEnd = planeDomain_->second.end;
  stats_.timePeriodic = planeDomain_->second.periodic;
  stats_.dims = planeView_->imageDims();
  stats_.picture2D = true;
  stats_.minMagnitude = planeView_->minMagnitude();
  stats_.maxMagnitude = planeView_->maxMagnitude();
  stats_.licTimes = licTimeText(planeView_->licMilliseconds(), 1, stats_.dims);
}

// An error the app cannot carry on from (out of device memory while it runs, a device lost
// again and again) ends the session; the window then stays open on a fresh device and shows the
// error in a dialog until it is closed or OK is pressed (a scripted run shows it for one frame).
// False when even that cannot be done (a device that keeps getting lost, or none to be made).
bool App::showStopped(const Error& error) {
  if (stopped_ || error.deviceLost || !imguiReady_) return false;
  stopped_ = true;
  if (context_) lostValidationMessages_ += context_->validationMessageCount();
  destroyGpu();
  if (!createGpu()) return false;
  ui_.visible = false;
  stats_.alertTitle = "lic3d: stopped on an error";
  stats_.alert = error.message + ". The session was saved to " + kRecoveryFile +
                 " (lic3d-view --session " + kRecoveryFile + " resumes it). OK quits.";
  return true;
}

// Nothing the user set up is lost when the app stops on an error: the session goes to a file.
void App::saveRecovery() const {
  if (auto r = writeSession(kRecoveryFile, session_); r)
    std::fprintf(stderr, "lic3d-view: the session was saved to %s (lic3d-view --session %s)\n",
                 kRecoveryFile, kRecoveryFile);
}

}  // namespace lic3d::viewer
