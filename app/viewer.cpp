#include "viewer.h"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <optional>
#include <vector>

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui_impl_glfw.h>
#include <imgui_impl_vulkan.h>

#include <glm/trigonometric.hpp>

#include "core/rgba_image.h"
#include "core/slice_geometry.h"
#include "gpu/gpu_submit.h"
#include "gpu/gpu_timer.h"
#include "gpu/vk_check.h"
#include "io/png_writer.h"
#include "io/session_file.h"
#include "lic/legend.h"
#include "lic/time_series.h"
#include "passes/lic_renderer.h"
#include "swapchain.h"
#include "viewer_plane.h"
#include "viewer_ui.h"

namespace lic3d::viewer {
namespace {

constexpr std::uint32_t kFramesInFlight = 2;
// GPU time the frame-paced LIC may take per frame: the UI stays responsive while the volume is
// recomputed in slabs, even on a CPU driver.
constexpr double kLicBudgetMs = 12.0;
// Where the session goes when the app stops on an error or loses its device.
constexpr const char* kRecoveryFile = "lic3d-recovery.json";
// A device lost more than kMaxLossStreak times with fewer than kLossStreakFrames frames between
// the losses is given up on: the app exits with the error (the session is in the recovery file).
constexpr int kMaxLossStreak = 3;
constexpr std::uint64_t kLossStreakFrames = 100;
// --soak (tests/test_viewer.cpp, docs/RELIABILITY.md).
constexpr std::uint64_t kSoakChangeEvery = 10;
constexpr std::uint64_t kSoakResizeEvery = 250;
constexpr std::uint64_t kSoakSampleEvery = 50;
constexpr std::uint64_t kSoakWarmupFrames = 100;
constexpr std::uint64_t kSoakRssSlack = 8u << 20;
constexpr VkFormat kOffscreenFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
// Steps of a time-dependent analytic field (the tornado) over its period when the session names
// none: the app blends steps on the GPU as it does a series of files (docs/TIME.md).
constexpr int kDefaultTimeSteps = 64;

// Mouse and keyboard events between two frames.
struct Input {
  bool orbiting = false;
  bool panning = false;
  double lastX = 0.0, lastY = 0.0;
  double dx = 0.0, dy = 0.0;  // cursor motion while dragging, in pixels
  double scroll = 0.0;
  bool resetView = false, togglePlay = false, screenshot = false, toggleUi = false,
       toggleHelp = false, quit = false, resized = false;
};

Input& inputOf(GLFWwindow* window) {
  return *static_cast<Input*>(glfwGetWindowUserPointer(window));
}

void onMouseButton(GLFWwindow* window, int button, int action, int mods) {
  Input& in = inputOf(window);
  if (ImGui::GetIO().WantCaptureMouse && action == GLFW_PRESS) return;
  const bool pressed = action == GLFW_PRESS;
  if (button == GLFW_MOUSE_BUTTON_LEFT) {
    in.orbiting = pressed && !(mods & GLFW_MOD_SHIFT);
    in.panning = pressed && (mods & GLFW_MOD_SHIFT);
  } else if (button == GLFW_MOUSE_BUTTON_MIDDLE) {
    in.panning = pressed;
  }
  glfwGetCursorPos(window, &in.lastX, &in.lastY);
}

void onCursor(GLFWwindow* window, double x, double y) {
  Input& in = inputOf(window);
  if (in.orbiting || in.panning) {
    in.dx += x - in.lastX;
    in.dy += y - in.lastY;
  }
  in.lastX = x;
  in.lastY = y;
}

void onScroll(GLFWwindow* window, double, double y) {
  if (!ImGui::GetIO().WantCaptureMouse) inputOf(window).scroll += y;
}

void onKey(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS || ImGui::GetIO().WantCaptureKeyboard) return;
  Input& in = inputOf(window);
  switch (key) {
    case GLFW_KEY_R: in.resetView = true; break;
    case GLFW_KEY_SPACE: in.togglePlay = true; break;
    case GLFW_KEY_F12: in.screenshot = true; break;
    case GLFW_KEY_H:
    case GLFW_KEY_TAB: in.toggleUi = true; break;
    case GLFW_KEY_F1: in.toggleHelp = true; break;
    case GLFW_KEY_ESCAPE: in.quit = true; break;
    default: break;
  }
}

void onFramebufferSize(GLFWwindow* window, int, int) { inputOf(window).resized = true; }

void checkImguiVk(VkResult result) {
  if (result != VK_SUCCESS) abortOnVkError("Dear ImGui Vulkan backend", result, __FILE__, __LINE__);
}

// Per frame in flight.
struct Frame {
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  VkSemaphore imageAvailable = VK_NULL_HANDLE;
  GpuTimer timer;  // region 0: LIC work, region 1: volume draw
  bool timed = false;
  bool finishedLic = false;
  int licSlices = 0;  // z-slices of LIC work this frame recorded
  bool screenshot = false;
  bool scriptedShot = false;  // the screenshot asked for by --screenshot
  Buffer readback;
};

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
  Result<void> createSwapchain();
  Result<void> startLoading(const FieldSource& field, const NoiseSource& noise);
  Result<void> finishLoading();
  Result<bool> frame();
  void updateCamera(const Input& in);
  void drawAxes() const;
  void animate(double seconds);
  Result<void> handleActions(const Actions& actions);
  Result<void> updateTime();
  void updatePlane();
  bool timePending() const;
  Result<void> saveScreenshot(const Frame& f);
  void destroySwapchainObjects();

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
  std::optional<LicRenderer> renderer_;
  Swapchain swapchain_;
  std::vector<VkSemaphore> renderFinished_;  // per swapchain image
  std::vector<VkFramebuffer> framebuffers_;
  VkRenderPass uiPass_ = VK_NULL_HANDLE;
  VkDescriptorPool uiPool_ = VK_NULL_HANDLE;
  bool imguiReady_ = false;        // Dear ImGui's context and GLFW backend
  bool imguiVulkanReady_ = false;  // its Vulkan backend, made again with the device
  Image offscreen_;
  std::array<Frame, kFramesInFlight> frames_;
  std::uint64_t frameNumber_ = 0;
  int slicesPerFrame_ = 4;
  double licSumMs_ = 0.0;  // GPU time of the LIC slabs of the volume being computed
  double biasPhase_ = 0.0;
  int screenshots_ = 0;
  struct Loaded {
    VectorField field;  // steady; for a series empty (the steps hold the grid)
    NoiseVolume noise;
    std::optional<TimeSeries> series;
    std::vector<std::pair<int, VectorField>> steps;  // the two around the session's time
  };
  std::future<Result<Loaded>> loading_;
  // Unsteady 3D fields (docs/TIME.md): the series, what the field texture was blended from, and
  // steps being read for the current time.
  std::optional<TimeSeries> series_;
  std::optional<TimeBracket> blended_;
  std::future<Result<std::vector<std::pair<int, VectorField>>>> stepLoading_;
  std::vector<int> stepsLoading_;  // what stepLoading_ reads
  std::vector<int> failedSteps_;   // steps that could not be read: not read again every frame
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
  std::optional<std::pair<FieldSource, cli::TimeDomain>> planeDomain_;
  FieldSource loadedField_;
  NoiseSource loadedNoise_;
  std::chrono::steady_clock::time_point lastTime_ = std::chrono::steady_clock::now();
  int exitStatus_ = cli::kExitOk;

  // --soak: parameter changes, resizes and memory samples (see soakStep).
  struct MemorySample {
    std::uint64_t frame;
    std::uint64_t rssBytes;
    std::uint64_t deviceBytes;
  };
  std::vector<MemorySample> soakSamples_;
  std::optional<Session> soakBase_;  // the session the soak's changes are set from and undone to
  bool soakSampleDue_ = false;
  struct SoakCounts {
    std::uint64_t masks = 0;       // sparsity masks asked for
    std::uint64_t volumes = 0;     // LIC volumes finished and shown
    std::uint64_t fieldReads = 0;  // fields read on the loading thread
    std::uint64_t stepReads = 0;   // time steps read on a worker thread
  } soak_;
  int swapchainsCreated_ = 0;
  void soakStep();
  void saveRecovery() const;
  int soakVerdict() const;
};

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
  VkDevice device = context_->device();
  vkDeviceWaitIdle(device);
  if (imguiVulkanReady_) ImGui_ImplVulkan_Shutdown();
  imguiVulkanReady_ = false;
  destroySwapchainObjects();
  for (Frame& f : frames_) {
    if (f.fence) vkDestroyFence(device, f.fence, nullptr);
    if (f.imageAvailable) vkDestroySemaphore(device, f.imageAvailable, nullptr);
    if (f.pool) vkDestroyCommandPool(device, f.pool, nullptr);
    f = Frame();
  }
  if (uiPass_) vkDestroyRenderPass(device, uiPass_, nullptr);
  uiPass_ = VK_NULL_HANDLE;
  if (uiPool_) vkDestroyDescriptorPool(device, uiPool_, nullptr);
  uiPool_ = VK_NULL_HANDLE;
  offscreen_ = Image();
  planeView_.reset();
  renderer_.reset();
  swapchain_ = Swapchain();
  context_.reset();
}

void App::destroySwapchainObjects() {
  VkDevice device = context_->device();
  for (VkFramebuffer fb : framebuffers_) vkDestroyFramebuffer(device, fb, nullptr);
  framebuffers_.clear();
  for (VkSemaphore s : renderFinished_) vkDestroySemaphore(device, s, nullptr);
  renderFinished_.clear();
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
  glfwSetWindowUserPointer(window_, &input_);
  glfwSetMouseButtonCallback(window_, onMouseButton);
  glfwSetCursorPosCallback(window_, onCursor);
  glfwSetScrollCallback(window_, onScroll);
  glfwSetKeyCallback(window_, onKey);
  glfwSetFramebufferSizeCallback(window_, onFramebufferSize);

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
  ui_.pendingField = session_.field;
  ui_.pendingNoise = session_.noise;
  ui_.pendingTimeSteps = session_.timeSteps;
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
  LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(*context_, rendererOptions));
  renderer_.emplace(std::move(renderer));

  for (Frame& f : frames_) {
    VkCommandPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    poolInfo.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    poolInfo.queueFamilyIndex = context_->queueFamily();
    LIC3D_TRY(
        checkVk(vkCreateCommandPool(device, &poolInfo, nullptr, &f.pool), "vkCreateCommandPool"));
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = f.pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    LIC3D_TRY(
        checkVk(vkAllocateCommandBuffers(device, &alloc, &f.cmd), "vkAllocateCommandBuffers"));
    VkFenceCreateInfo fenceInfo{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fenceInfo.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    LIC3D_TRY(checkVk(vkCreateFence(device, &fenceInfo, nullptr, &f.fence), "vkCreateFence"));
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    LIC3D_TRY(checkVk(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &f.imageAvailable),
                      "vkCreateSemaphore"));
    const std::string name = "frame " + std::to_string(&f - frames_.data());
    context_->setDebugName(f.pool, VK_OBJECT_TYPE_COMMAND_POOL, name + " pool");
    context_->setDebugName(f.cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, name);
    context_->setDebugName(f.fence, VK_OBJECT_TYPE_FENCE, name + " fence");
    context_->setDebugName(f.imageAvailable, VK_OBJECT_TYPE_SEMAPHORE, name + " image available");
    if (context_->supportsTimestamps()) {
      LIC3D_TRY_ASSIGN(f.timer, GpuTimer::create(*context_, 2, name + " timestamps"));
    }
  }
  LIC3D_TRY(createSwapchain());

  // Dear ImGui 1.86's Vulkan backend draws inside a classic render pass; the volume before it
  // uses dynamic rendering into an offscreen image that is blitted to the swapchain image.
  const std::array<VkDescriptorPoolSize, 1> sizes{
      {{VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 16}}};
  VkDescriptorPoolCreateInfo poolInfo{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  poolInfo.flags = VK_DESCRIPTOR_POOL_CREATE_FREE_DESCRIPTOR_SET_BIT;
  poolInfo.maxSets = 16;
  poolInfo.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  poolInfo.pPoolSizes = sizes.data();
  LIC3D_TRY(checkVk(vkCreateDescriptorPool(device, &poolInfo, nullptr, &uiPool_),
                    "vkCreateDescriptorPool"));
  context_->setDebugName(uiPool_, VK_OBJECT_TYPE_DESCRIPTOR_POOL, "imgui descriptors");

  ImGui_ImplVulkan_InitInfo info{};
  info.Instance = context_->instance();
  info.PhysicalDevice = context_->physicalDevice();
  info.Device = device;
  info.QueueFamily = context_->queueFamily();
  info.Queue = context_->queue();
  info.DescriptorPool = uiPool_;
  info.MinImageCount = swapchain_.minImageCount();
  info.ImageCount = swapchain_.imageCount();
  info.MSAASamples = VK_SAMPLE_COUNT_1_BIT;
  info.CheckVkResultFn = checkImguiVk;
  ImGui_ImplVulkan_Init(&info, uiPass_);
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
  if (stepLoading_.valid()) stepLoading_.wait();
  stepLoading_ = {};
  series_.reset();
  blended_.reset();
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

Result<void> App::createSwapchain() {
  ++swapchainsCreated_;
  VkDevice device = context_->device();
  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  vkDeviceWaitIdle(device);
  destroySwapchainObjects();
  LIC3D_TRY_ASSIGN(Swapchain next, Swapchain::create(*context_,
                                                     {static_cast<std::uint32_t>(width),
                                                      static_cast<std::uint32_t>(height)},
                                                     options_.vsync, swapchain_.handle()));
  swapchain_ = std::move(next);

  if (!uiPass_) {
    VkAttachmentDescription attachment{};
    attachment.format = swapchain_.format();
    attachment.samples = VK_SAMPLE_COUNT_1_BIT;
    attachment.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;  // the blitted volume
    attachment.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    attachment.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    attachment.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    attachment.initialLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    attachment.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
    VkAttachmentReference reference{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
    VkSubpassDescription subpass{};
    subpass.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpass.colorAttachmentCount = 1;
    subpass.pColorAttachments = &reference;
    const std::array<VkSubpassDependency, 2> dependencies{{
        {VK_SUBPASS_EXTERNAL, 0, VK_PIPELINE_STAGE_TRANSFER_BIT,
         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT, VK_ACCESS_TRANSFER_WRITE_BIT,
         VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, 0},
        {0, VK_SUBPASS_EXTERNAL, VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT,
         VK_PIPELINE_STAGE_TRANSFER_BIT, VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT,
         VK_ACCESS_TRANSFER_READ_BIT, 0},
    }};
    VkRenderPassCreateInfo info{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
    info.attachmentCount = 1;
    info.pAttachments = &attachment;
    info.subpassCount = 1;
    info.pSubpasses = &subpass;
    info.dependencyCount = static_cast<std::uint32_t>(dependencies.size());
    info.pDependencies = dependencies.data();
    LIC3D_TRY(checkVk(vkCreateRenderPass(device, &info, nullptr, &uiPass_), "vkCreateRenderPass"));
    context_->setDebugName(uiPass_, VK_OBJECT_TYPE_RENDER_PASS, "imgui pass");
  }
  for (std::uint32_t i = 0; i < swapchain_.imageCount(); ++i) {
    VkImageView view = swapchain_.view(i);
    VkFramebufferCreateInfo info{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    info.renderPass = uiPass_;
    info.attachmentCount = 1;
    info.pAttachments = &view;
    info.width = swapchain_.extent().width;
    info.height = swapchain_.extent().height;
    info.layers = 1;
    VkFramebuffer framebuffer = VK_NULL_HANDLE;
    LIC3D_TRY(
        checkVk(vkCreateFramebuffer(device, &info, nullptr, &framebuffer), "vkCreateFramebuffer"));
    framebuffers_.push_back(framebuffer);
    context_->setDebugName(framebuffer, VK_OBJECT_TYPE_FRAMEBUFFER,
                           "imgui framebuffer " + std::to_string(i));
    VkSemaphoreCreateInfo semaphoreInfo{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore semaphore = VK_NULL_HANDLE;
    LIC3D_TRY(checkVk(vkCreateSemaphore(device, &semaphoreInfo, nullptr, &semaphore),
                      "vkCreateSemaphore"));
    renderFinished_.push_back(semaphore);
    context_->setDebugName(semaphore, VK_OBJECT_TYPE_SEMAPHORE,
                           "render finished " + std::to_string(i));
  }
  if (imguiVulkanReady_) ImGui_ImplVulkan_SetMinImageCount(swapchain_.minImageCount());

  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.format = kOffscreenFormat;
  desc.extent = {swapchain_.extent().width, swapchain_.extent().height, 1};
  // TRANSFER_DST: the 2D mode blits its picture in.
  desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
               VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "window volume image";
  offscreen_ = Image();
  LIC3D_TRY_ASSIGN(offscreen_, Image::create(*context_, desc));
  const VkDeviceSize bytes =
      static_cast<VkDeviceSize>(swapchain_.extent().width) * swapchain_.extent().height * 4;
  for (Frame& f : frames_) {
    f.readback = Buffer();
    LIC3D_TRY_ASSIGN(f.readback, Buffer::create(*context_, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                MemoryUse::Readback, "screenshot readback"));
  }
  return {};
}

Result<void> App::startLoading(const FieldSource& field, const NoiseSource& noise) {
  loadedField_ = field;
  loadedNoise_ = noise;
  stats_.loading = true;
  // Reading a large file or sampling a large grid takes a while: off the drawing thread.
  // --grid with a file field is an error on the command line only, not when loading later.
  const bool gridGiven = !renderer_->hasVolume() && deviceLosses_ == 0 && inputs_.grid.given();
  reloadField_ = false;
  const double time = session_.time;
  const int timeSteps = session_.timeSteps > 0 ? session_.timeSteps : kDefaultTimeSteps;
  loading_ = std::async(
      std::launch::async, [field, noise, gridGiven, time, timeSteps]() -> Result<Loaded> {
        Loaded loaded;
        // An unsteady field is a series: the tornado's steps over its period, or numbered files.
        const std::optional<AnalyticField> analytic = parseEnum<AnalyticField>(field.field);
        if (analytic && timePeriod(*analytic) > 0.0) {
          LIC3D_TRY(cli::checkHostMemory(field.grid));
          LIC3D_TRY_ASSIGN(loaded.series, analyticSeries(*analytic, field.grid, timeSteps));
        } else if (!analytic && !parseEnum<AnalyticField2D>(field.field) &&
                   isFieldSeriesPattern(field.field)) {
          LIC3D_TRY_ASSIGN(loaded.series, fileSeries(field.field));
        }
        if (!loaded.series) {
          LIC3D_TRY_ASSIGN(loaded.field, cli::loadField(field, gridGiven));
          LIC3D_TRY_ASSIGN(loaded.noise, cli::loadNoise(noise, loaded.field.dims));
          return loaded;
        }
        const TimeBracket b = loaded.series->bracket(time);
        for (const int k : {b.first, b.second}) {
          LIC3D_TRY_ASSIGN(VectorField step, loaded.series->loadStep(k, field.array));
          if (!loaded.steps.empty() && step.dims != loaded.steps.front().second.dims)
            return inputError(field.field + ": the steps of a time series must share their grid");
          loaded.steps.emplace_back(k, std::move(step));
        }
        LIC3D_TRY_ASSIGN(loaded.noise, cli::loadNoise(noise, loaded.steps.front().second.dims));
        return loaded;
      });
  return {};
}

Result<void> App::finishLoading() {
  if (!loading_.valid() || loading_.wait_for(std::chrono::seconds(0)) != std::future_status::ready)
    return {};
  Result<Loaded> loaded = loading_.get();
  stats_.loading = false;
  if (loaded) ++soak_.fieldReads;
  // The app's first field failing to load ends it (nothing to show); later failures are messages.
  const bool firstLoad = !renderer_->hasVolume() && !loadedOnce_;
  loadedOnce_ = true;
  if (!loaded) {
    stats_.message = loaded.error().message;
    if (firstLoad) return std::move(loaded).error();  // nothing to show at all
    loadedField_ = session_.field;                    // not read again until the field changes
    loadedNoise_ = session_.noise;
    return {};
  }
  // The new field must fit beside everything the app keeps; if not, the old volume stays.
  const VkExtent2D extent = swapchain_.extent();
  const VectorField& grid = loaded->series ? loaded->steps.front().second : loaded->field;
  if (auto r = cli::checkRequestMemory(*context_, session_, grid.dims,
                                       {.doubleBuffered = true,
                                        .frame = true,
                                        .frameWidth = static_cast<int>(extent.width),
                                        .frameHeight = static_cast<int>(extent.height),
                                        .timeSeries = loaded->series.has_value()});
      !r) {
    if (!renderer_->hasVolume()) return std::move(r).error();  // nothing to keep: exit status 3
    stats_.alertTitle = "lic3d: not done";
    stats_.alert = r.error().message + ". The previous field stays loaded.";
    ui_.pendingField = session_.field;
    return {};
  }
  if (auto r = validate(session_.lic.sparsity, grid.dims); !r) {
    session_.lic.sparsity = SparsityParams{};
    stats_.message = r.error().message + " (sparsity turned off)";
  }
  series_ = loaded->series;
  blended_.reset();
  stepLoading_ = {};
  failedSteps_.clear();
  if (series_) {
    // The two steps around the time, blended on the GPU by updateTime.
    LIC3D_TRY(renderer_->setTimeNoise(loaded->noise));
    const auto& [first, stepA] = loaded->steps.front();
    const auto& [second, stepB] = loaded->steps.back();
    LIC3D_TRY(renderer_->setTimeStep(first, stepA, second));
    LIC3D_TRY(renderer_->setTimeStep(second, stepB, first));
    session_.timeSteps = series_->analytic ? series_->steps : 0;
    ui_.pendingTimeSteps = session_.timeSteps;
    stats_.timeEnd = series_->endTime();
    stats_.timePeriodic = series_->periodic();
  } else {
    LIC3D_TRY(renderer_->setInputs(loaded->field, loaded->noise));
  }
  stats_.timeDependent = series_.has_value();
  session_.field = loadedField_;
  session_.noise = loadedNoise_;
  stats_.dims = grid.dims;
  stats_.minMagnitude = static_cast<float>(minMagnitude(grid));
  stats_.maxMagnitude = static_cast<float>(maxMagnitude(grid));
  if (series_) return updateTime();
  return renderer_->requestLic(session_.lic);
}

void App::updateCamera(const Input& in) {
  CameraParams& camera = session_.view.camera;
  const VkExtent2D extent = swapchain_.extent();
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

// The box's edges and axis ranges (--axes) over the volume, in ImGui's background layer.
void App::drawAxes() const {
  if (!session_.view.axes || !renderer_->hasVolume() ||
      session_.view.stereo == StereoMode::SideBySide)
    return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  if (display.x < 1.0f || display.y < 1.0f) return;
  const VolumeFacts facts = renderer_->volumeFacts();
  const SliceFrame frame = makeSliceFrame(session_.view, facts, Eye::Mono, display.x / display.y);
  const BoxAxes axes =
      projectBoxAxes(frame.camera.viewProjection, frame.halfExtent, facts.dims, facts.geometry,
                     static_cast<int>(display.x), static_cast<int>(display.y));
  const glm::vec3 bg = session_.view.background;
  const bool dark = 0.2126f * bg.r + 0.7152f * bg.g + 0.0722f * bg.b > 0.5f;
  const ImU32 line = dark ? IM_COL32(0, 0, 0, 160) : IM_COL32(255, 255, 255, 160);
  const ImU32 ink = dark ? IM_COL32(0, 0, 0, 255) : IM_COL32(255, 255, 255, 255);
  ImDrawList* draw = ImGui::GetBackgroundDrawList();
  for (const auto& [a, b] : axes.edges) draw->AddLine(ImVec2(a.x, a.y), ImVec2(b.x, b.y), line);
  for (const AxisLabel& label : axes.labels) {
    const float width = ImGui::CalcTextSize(label.text.c_str()).x;
    const float x = std::clamp(label.leftOfBox ? label.at.x - width - 6.0f : label.at.x + 6.0f,
                               2.0f, std::max(2.0f, display.x - width - 2.0f));
    draw->AddText(ImVec2(x, label.at.y - 0.5f * ImGui::GetFontSize()), ink, label.text.c_str());
  }
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

// Blends the field at the session's time from the two steps around it, reading the steps that
// are not resident on a worker thread; the LIC volume follows (frame-paced, as any change).
Result<void> App::updateTime() {
  if (!series_ || stats_.loading) return {};
  const TimeBracket b = series_->bracket(session_.time);
  if (stepLoading_.valid()) {
    if (stepLoading_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return {};
    Result<std::vector<std::pair<int, VectorField>>> steps = stepLoading_.get();
    if (!steps) {
      stats_.message = steps.error().message;
      failedSteps_ = stepsLoading_;
      return {};
    }
    soak_.stepReads += steps->size();
    // Steps for a time already left behind are not uploaded: they would evict the ones in use.
    for (const auto& [k, step] : *steps)
      if (k == b.first || k == b.second)
        LIC3D_TRY(renderer_->setTimeStep(k, step, k == b.first ? b.second : b.first));
  }
  if (blended_ && *blended_ == b) return {};
  std::vector<int> missing;
  for (const int k : {b.first, b.second})
    if (!renderer_->hasTimeStep(k)) missing.push_back(k);
  if (!missing.empty()) {
    if (missing == failedSteps_) return {};  // the message says why; another time may work
    stepsLoading_ = missing;
    stepLoading_ = std::async(
        std::launch::async, [series = *series_, missing, array = session_.field.array]() {
          Result<std::vector<std::pair<int, VectorField>>> steps =
              std::vector<std::pair<int, VectorField>>{};
          for (const int k : missing) {
            Result<VectorField> step = series.loadStep(k, array);
            if (!step) return Result<std::vector<std::pair<int, VectorField>>>(step.error());
            steps->emplace_back(k, std::move(*step));
          }
          return steps;
        });
    return {};
  }
  // The time moves on once the volume of the last blend is shown: a new blend restarts the LIC,
  // and where a volume takes more than a frame, blending every frame would never show one.
  if (blended_ && renderer_->licStatus().pending) return {};
  if (auto r = renderer_->interpolateTime(b.first, b.second, b.weight); !r) {
    stats_.message = r.error().message;
    return {};
  }
  blended_ = b;
  return renderer_->requestLic(session_.lic);
}

bool App::timePending() const {
  return series_ &&
         (stepLoading_.valid() || !blended_ || !(*blended_ == series_->bracket(session_.time)));
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
  if (auto r = planeView_->update(session_); !r) {
    stats_.message = r.error().message;
    return;
  }
  // A series' files are listed once per field, not every frame.
  if (!planeDomain_ || !(planeDomain_->first == session_.field)) {
    const Result<cli::TimeDomain> domain = cli::timeDomainOf(session_);
    planeDomain_.emplace(session_.field, domain ? *domain : cli::TimeDomain{});
  }
  stats_.timeDependent = planeDomain_->second.timeDependent;
  stats_.timeEnd = planeDomain_->second.end;
  stats_.timePeriodic = planeDomain_->second.periodic;
  stats_.dims = planeView_->imageDims();
  stats_.minMagnitude = planeView_->minMagnitude();
  stats_.maxMagnitude = planeView_->maxMagnitude();
  stats_.licMs = planeView_->licMilliseconds();
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
  if (actions.renderImage && session_.twoD && planeView_ && planeView_->hasPicture()) {
    const Result<void> written = writePng(ui_.imagePath, planeView_->image(session_.view));
    stats_.message = written ? "wrote " + ui_.imagePath : written.error().message;
  } else if (actions.renderImage && renderer_->hasVolume()) {
    // The offscreen render shares the renderer's uniform slots with the frames: wait for them.
    vkDeviceWaitIdle(context_->device());
    ViewParams view = session_.view;
    view.width = ui_.imageWidth;
    view.height = ui_.imageHeight;
    Result<RgbaImage> image = renderer_->render(*renderer_->shownParams(), view);
    const Result<void> written =
        image ? writePng(ui_.imagePath, *image) : Result<void>(image.error());
    stats_.message = written ? "wrote " + ui_.imagePath : written.error().message;
  }
  return {};
}

Result<void> App::saveScreenshot(const Frame& f) {
  const VkExtent2D extent = swapchain_.extent();
  RgbaImage image;
  image.width = static_cast<int>(extent.width);
  image.height = static_cast<int>(extent.height);
  image.pixels.resize(static_cast<std::size_t>(extent.width) * extent.height * 4);
  const auto* src = static_cast<const std::uint8_t*>(f.readback.mapped());
  const bool bgra = swapchain_.format() == VK_FORMAT_B8G8R8A8_UNORM;
  for (std::size_t i = 0; i < image.pixels.size(); i += 4) {
    image.pixels[i + 0] = src[i + (bgra ? 2 : 0)];
    image.pixels[i + 1] = src[i + 1];
    image.pixels[i + 2] = src[i + (bgra ? 0 : 2)];
    image.pixels[i + 3] = 255;
  }
  const std::string path = f.scriptedShot
                               ? options_.screenshot
                               : "lic3d-screenshot-" + std::to_string(++screenshots_) + ".png";
  LIC3D_TRY(writePng(path, image));
  stats_.message = "wrote " + path;
  if (!global_.quiet) std::fprintf(stderr, "lic3d-view: wrote %s\n", path.c_str());
  return {};
}

// Draws one frame; false when the app should quit.
Result<bool> App::frame() {
  glfwPollEvents();
  const auto now = std::chrono::steady_clock::now();
  const double seconds = std::chrono::duration<double>(now - lastTime_).count();
  lastTime_ = now;
  stats_.fps = static_cast<float>(0.9 * stats_.fps + 0.1 * (seconds > 0.0 ? 1.0 / seconds : 0.0));

  Input in = input_;
  input_.dx = input_.dy = input_.scroll = 0.0;
  input_.resetView = input_.togglePlay = input_.screenshot = input_.toggleUi = input_.toggleHelp =
      false;
  if (in.quit || glfwWindowShouldClose(window_)) return false;

  int width = 0, height = 0;
  glfwGetFramebufferSize(window_, &width, &height);
  if (width == 0 || height == 0) {  // minimised: nothing to draw into
    glfwWaitEvents();
    return true;
  }
  if (in.resized || swapchain_.extent().width != static_cast<std::uint32_t>(width) ||
      swapchain_.extent().height != static_cast<std::uint32_t>(height)) {
    input_.resized = false;
    LIC3D_TRY(createSwapchain());
  }

  if (!stopped_) LIC3D_TRY(finishLoading());
  Frame& f = frames_[frameNumber_ % kFramesInFlight];
  const std::uint32_t slot = static_cast<std::uint32_t>(frameNumber_ % kFramesInFlight);
  VkDevice device = context_->device();
  LIC3D_TRY(checkVk(vkWaitForFences(device, 1, &f.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences"));
  if (f.finishedLic) {
    renderer_->collectStatistics(slot);
    ++soak_.volumes;
  }
  if (f.timed) {
    LIC3D_TRY_ASSIGN(const double slabMs, f.timer.milliseconds(0));
    LIC3D_TRY_ASSIGN(stats_.frameMs, f.timer.milliseconds(1));
    if (f.licSlices > 0) {
      licSumMs_ += slabMs;
      // Aim the next slabs at the LIC time budget, from this device's measured speed.
      const double msPerSlice = std::max(slabMs / f.licSlices, 1e-3);
      slicesPerFrame_ = std::clamp(static_cast<int>(kLicBudgetMs / msPerSlice), 1,
                                   std::max(1, renderer_->dims().z));
    }
    if (f.finishedLic) {
      stats_.licMs = licSumMs_;  // the whole volume, summed over its slabs
      licSumMs_ = 0.0;
    }
  }
  f.finishedLic = false;
  if (f.screenshot) {
    LIC3D_TRY(saveScreenshot(f));
    f.screenshot = f.scriptedShot = false;
  }

  std::uint32_t imageIndex = 0;
  const VkResult acquired = vkAcquireNextImageKHR(device, swapchain_.handle(), UINT64_MAX,
                                                  f.imageAvailable, VK_NULL_HANDLE, &imageIndex);
  if (acquired == VK_ERROR_OUT_OF_DATE_KHR) {
    LIC3D_TRY(createSwapchain());
    return true;
  }
  if (acquired != VK_SUBOPTIMAL_KHR) LIC3D_TRY(checkVk(acquired, "vkAcquireNextImageKHR"));
  LIC3D_TRY(checkVk(vkResetFences(device, 1, &f.fence), "vkResetFences"));

  // UI and input.
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  ImGui::NewFrame();
  if (in.toggleUi) ui_.visible = !ui_.visible;
  if (in.toggleHelp) ui_.help = !ui_.help;
  if (in.togglePlay) ui_.playing = !ui_.playing;
  const LicStatus status = renderer_->licStatus();
  stats_.computing = status.pending;
  stats_.computeFraction = status.fraction;
  stats_.waitingForMask = status.waitingForMask;
  stats_.volumeMiB = static_cast<double>(renderer_->volumeBytes()) / (1 << 20);
  if (!session_.twoD && !stopped_) drawAxes();
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
  if (options_.soak && !stopped_) soakStep();
  if (auto r = validate(session_.view); !r) {
    stats_.message = r.error().message;
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
    if (!(session_.lic == drawnSession_.lic) && !stats_.loading) {
      if (auto r = renderer_->requestLic(session_.lic); !r) {
        stats_.message = r.error().message;
        session_.lic = drawnSession_.lic;
      }
    }
  }
  drawnSession_ = session_;

  // A scripted run takes its screenshot once the volume for the current parameters is shown
  // (stopped: at once, showing the error).
  const bool ready =
      stopped_ || (session_.twoD ? planeView_ && planeView_->hasPicture()
                                 : !stats_.loading && renderer_->hasVolume() &&
                                       !renderer_->licStatus().pending && !timePending());
  const bool scriptedShot = options_.frames > 0 &&
                            frameNumber_ + 1 >= static_cast<std::uint64_t>(options_.frames) &&
                            ready;
  // It quits after this frame; run() saves the screenshot once the frame has finished.
  const bool quitAfterThis = scriptedShot;
  f.scriptedShot = scriptedShot && !options_.screenshot.empty();
  f.screenshot = actions.screenshot || f.scriptedShot;

  // Record.
  VkCommandBuffer cmd = f.cmd;
  LIC3D_TRY(checkVk(vkResetCommandBuffer(cmd, 0), "vkResetCommandBuffer"));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  LIC3D_VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  f.timed = f.timer.valid();
  if (f.timed) {
    f.timer.reset(cmd, 0);
    f.timer.reset(cmd, 1);
    f.timer.begin(cmd, 0);
  }
  LIC3D_TRY_ASSIGN(const LicWork work, renderer_->recordLicWork(cmd, slicesPerFrame_, slot));
  if (f.timed) f.timer.end(cmd, 0);
  f.finishedLic = work.finished;
  f.licSlices = work.slicesRecorded;

  const VkExtent2D extent = swapchain_.extent();
  imageBarrier(cmd, offscreen_.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_BLIT_BIT,
               VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
  if (f.timed) f.timer.begin(cmd, 1);
  beginClearedRendering(cmd, offscreen_.view(), extent, session_.view.background);
  const Result<void> drawn =
      session_.twoD || stopped_
          ? Result<void>()
          : renderer_->recordDraw(cmd, kOffscreenFormat, extent, session_.view, 2 * slot);
  vkCmdEndRendering(cmd);
  if (f.timed) f.timer.end(cmd, 1);
  LIC3D_TRY(drawn);

  VkImage target = swapchain_.image(imageIndex);
  if (session_.twoD && planeView_ && !stopped_) {
    planeView_->record(cmd, offscreen_.handle(), extent);  // leaves it ready for the blit below
  } else {
    imageBarrier(cmd, offscreen_.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                 VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_BLIT_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
  }
  // The acquire semaphore is waited for at the blit stage; this barrier chains to it.
  imageBarrier(cmd, target, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_PIPELINE_STAGE_2_BLIT_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_BLIT_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT);
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  blit.srcOffsets[1] = {static_cast<std::int32_t>(extent.width),
                        static_cast<std::int32_t>(extent.height), 1};
  blit.dstSubresource = blit.srcSubresource;
  blit.dstOffsets[1] = blit.srcOffsets[1];
  vkCmdBlitImage(cmd, offscreen_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, target,
                 VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_NEAREST);

  VkRenderPassBeginInfo passBegin{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  passBegin.renderPass = uiPass_;
  passBegin.framebuffer = framebuffers_[imageIndex];
  passBegin.renderArea = {{0, 0}, extent};
  vkCmdBeginRenderPass(cmd, &passBegin, VK_SUBPASS_CONTENTS_INLINE);
  ImGui_ImplVulkan_RenderDrawData(ImGui::GetDrawData(), cmd);
  vkCmdEndRenderPass(cmd);

  if (f.screenshot) {
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                 VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {extent.width, extent.height, 1};
    vkCmdCopyImageToBuffer(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, f.readback.handle(),
                           1, &region);
    imageBarrier(cmd, target, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR,
                 VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_NONE,
                 VK_ACCESS_2_NONE);
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
  }
  LIC3D_VK_CHECK(vkEndCommandBuffer(cmd));

  VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait.semaphore = f.imageAvailable;
  wait.stageMask = VK_PIPELINE_STAGE_2_BLIT_BIT;
  VkSemaphoreSubmitInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal.semaphore = renderFinished_[imageIndex];
  signal.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkCommandBufferSubmitInfo cmdInfo{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmdInfo.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.waitSemaphoreInfoCount = 1;
  submit.pWaitSemaphoreInfos = &wait;
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmdInfo;
  submit.signalSemaphoreInfoCount = 1;
  submit.pSignalSemaphoreInfos = &signal;
  LIC3D_TRY(submitToQueue(*context_, submit, f.fence));

  VkPresentInfoKHR present{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  present.waitSemaphoreCount = 1;
  present.pWaitSemaphores = &renderFinished_[imageIndex];
  present.swapchainCount = 1;
  VkSwapchainKHR handle = swapchain_.handle();
  present.pSwapchains = &handle;
  present.pImageIndices = &imageIndex;
  const VkResult presented = vkQueuePresentKHR(context_->queue(), &present);
  if (presented == VK_ERROR_OUT_OF_DATE_KHR || presented == VK_SUBOPTIMAL_KHR) {
    input_.resized = true;
  } else {
    LIC3D_TRY(checkVk(presented, "vkQueuePresentKHR"));
  }
  ++frameNumber_;
  if (options_.frames > 0 && frameNumber_ > static_cast<std::uint64_t>(options_.frames) + 100000)
    return runtimeError("the LIC volume was not ready after 100000 frames");
  return !quitAfterThis;
}

// Resident set size of this process, from /proc/self/statm.
std::uint64_t residentBytes() {
  std::FILE* f = std::fopen("/proc/self/statm", "r");
  if (!f) return 0;
  unsigned long long size = 0, resident = 0;
  const int n = std::fscanf(f, "%llu %llu", &size, &resident);
  std::fclose(f);
  return n == 2 ? resident * static_cast<std::uint64_t>(sysconf(_SC_PAGESIZE)) : 0;
}

// One frame of the soak: a parameter change every kSoakChangeEvery frames, alternately of the LIC
// and of the view (redraw), a window resize every kSoakResizeEvery frames, and a memory sample
// every kSoakSampleEvery frames. The LIC changes take turns among everything the app recomputes
// asynchronously: the length (LIC slabs over frames), sparsity (the mask on a worker thread), the
// noise seed (field and noise read again on the loading thread) and, for an unsteady field, the
// time (steps read on a worker thread and blended on the GPU). Each is set and undone in turn.
void App::soakStep() {
  if (options_.frames <= 0 || frameNumber_ >= static_cast<std::uint64_t>(options_.frames)) return;
  if (!soakBase_) soakBase_ = session_;
  const Session& base = *soakBase_;
  const std::uint64_t n = frameNumber_;
  if (n > 0 && n % kSoakChangeEvery == 0) {
    if ((n / kSoakChangeEvery) % 2 == 1) {
      switch ((n / (2 * kSoakChangeEvery)) % 4) {
        case 0:
          session_.lic.length =
              session_.lic.length == base.lic.length ? base.lic.length + 1 : base.lic.length;
          break;
        case 1:
          if (session_.lic.sparsity == base.lic.sparsity) {
            // A new seed each time: the mask is made again, not taken from the last one.
            session_.lic.sparsity = SparsityParams{};
            session_.lic.sparsity.distribution = SparsityDistribution::Poisson;
            session_.lic.sparsity.seed = ++soak_.masks;
          } else {
            session_.lic.sparsity = base.lic.sparsity;
          }
          break;
        case 2:
          session_.noise.seed =
              session_.noise.seed == base.noise.seed ? base.noise.seed + 1 : base.noise.seed;
          break;
        default:
          // Two and a half steps on: neither step of the bracket is resident.
          if (series_ && !stats_.loading) {
            const double step = series_->stepTime(1) - series_->stepTime(0);
            session_.time = session_.time == base.time ? base.time + 2.5 * step : base.time;
          }
          break;
      }
    } else {
      session_.view.camera.azimuth = std::fmod(session_.view.camera.azimuth + 7.0f, 360.0f);
    }
  }
  // A resize every kSoakResizeEvery frames, undone 10 frames later: both recreate the swapchain,
  // and the memory samples (multiples of 50) all see the window at its own size.
  if (n > 0 && (n % kSoakResizeEvery == 0 || n % kSoakResizeEvery == 10)) {
    const bool larger = n % kSoakResizeEvery == 0;
    glfwSetWindowSize(window_, options_.windowWidth + (larger ? 64 : 0),
                      options_.windowHeight + (larger ? 48 : 0));
  }
  // Memory is sampled at rest: the first frame from each multiple of kSoakSampleEvery on at which
  // nothing is being read, masked or recomputed (work in flight holds old and new at once).
  if (n % kSoakSampleEvery == 0) soakSampleDue_ = true;
  if (soakSampleDue_ && !stats_.loading && !renderer_->licStatus().pending && !timePending()) {
    soakSamples_.push_back({n, residentBytes(), context_->allocatedBytes()});
    soakSampleDue_ = false;
  }
}

// After the warm-up, memory must not grow: the largest sample of the second half may exceed the
// largest of the first half by kSoakRssSlack of RSS (allocator and driver caches) and not at all
// in device memory (the allocator's own count).
int App::soakVerdict() const {
  std::vector<MemorySample> s;
  for (const MemorySample& m : soakSamples_)
    if (m.frame >= kSoakWarmupFrames) s.push_back(m);
  if (s.size() < 4) {
    std::fprintf(stderr, "lic3d-view: error: --soak needs --frames of at least %d\n",
                 static_cast<int>(kSoakWarmupFrames + 4 * kSoakSampleEvery));
    return cli::kExitBadInput;
  }
  const std::size_t half = s.size() / 2;
  auto maxOf = [&](std::size_t from, std::size_t to, auto member) {
    std::uint64_t m = 0;
    for (std::size_t i = from; i < to; ++i) m = std::max(m, s[i].*member);
    return m;
  };
  const std::uint64_t rss1 = maxOf(0, half, &MemorySample::rssBytes);
  const std::uint64_t rss2 = maxOf(half, s.size(), &MemorySample::rssBytes);
  const std::uint64_t dev1 = maxOf(0, half, &MemorySample::deviceBytes);
  const std::uint64_t dev2 = maxOf(half, s.size(), &MemorySample::deviceBytes);
  const double mib = 1.0 / (1 << 20);
  std::printf(
      "lic3d-view soak: %llu frames, samples every %d after %d warm-up frames; RSS max "
      "%.1f MiB (first half) -> %.1f MiB (second half); device memory max %.1f -> %.1f MiB; "
      "%d swapchains; %llu LIC volumes, %llu of %llu sparsity masks, %llu field reads, "
      "%llu time steps read\n",
      static_cast<unsigned long long>(frameNumber_), static_cast<int>(kSoakSampleEvery),
      static_cast<int>(kSoakWarmupFrames), static_cast<double>(rss1) * mib,
      static_cast<double>(rss2) * mib, static_cast<double>(dev1) * mib,
      static_cast<double>(dev2) * mib, swapchainsCreated_,
      static_cast<unsigned long long>(soak_.volumes),
      static_cast<unsigned long long>(renderer_->maskBuildCount()),
      static_cast<unsigned long long>(soak_.masks),
      static_cast<unsigned long long>(soak_.fieldReads),
      static_cast<unsigned long long>(soak_.stepReads));
  if (rss2 > rss1 + kSoakRssSlack || dev2 > dev1) {
    std::fprintf(stderr,
                 "lic3d-view: error: memory grew during the soak (tolerance: %.0f MiB of "
                 "RSS, no device memory)\n",
                 static_cast<double>(kSoakRssSlack) * mib);
    return cli::kExitFailure;
  }
  return cli::kExitOk;
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
  // Let the last screenshot's frame finish (a scripted run quits right after recording it).
  vkDeviceWaitIdle(context_->device());
  for (Frame& f : frames_)
    if (f.screenshot) {
      if (auto r = saveScreenshot(f); !r) exitStatus_ = cli::reportError(r.error());
      f.screenshot = f.scriptedShot = false;
    }
  if (options_.soak && exitStatus_ == cli::kExitOk) exitStatus_ = soakVerdict();
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

}  // namespace

int runViewer(const cli::GlobalOptions& global, cli::SessionOptions& inputs,
              const ViewerOptions& options) {
  App app(global, inputs, options);
  return app.run();
}

}  // namespace lic3d::viewer
