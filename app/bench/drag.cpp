// SPDX-License-Identifier: BSD-3-Clause
// `lic3d bench --drag`: the desktop app's frames while a LIC slider is dragged, offscreen, so a
// GPU without a display can say whether the drag keeps 60 frames per second. Each frame the LIC
// length moves by one step, the LIC job the app would record goes into the frame's command buffer
// (coarse at the stride the app picks from the measured full LIC, render/lic_volume_job.h), then
// the slices are drawn; GPU timestamps time the whole frame.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench/bench.h"
#include "gpu/submit.h"
#include "gpu/timer.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "render/lic_renderer.h"

namespace lic3d::cli {
namespace {

// A frame at 60 Hz.
constexpr double kFrameBudgetMs = 1000.0 / 60.0;

double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

struct DragFrame {
  double frameMs = 0.0;  // the whole frame: LIC work and slices
  double licMs = 0.0;
  double drawMs = 0.0;
};

// One frame of the drag: the job for `params` at `stride` whole, then the slices of the shown
// volume into `target`. Timer regions: 0 the frame, 1 the LIC, 2 the draw.
Result<DragFrame> dragFrame(const Context& context, LicRenderer& renderer, OffscreenTarget& target,
                            const GpuTimer& timer, const LicParams& params, int stride,
                            const ViewParams& view) {
  LIC3D_TRY(renderer.requestLic(params, stride));
  LIC3D_TRY(renderer.licJob().waitForMask(renderer.fieldTextures()));
  Result<LicWork> work = LicWork{};
  Result<void> drawn;
  LIC3D_TRY(submitAndWait(
      context,
      [&](VkCommandBuffer cmd) {
        for (std::uint32_t r = 0; r < 3; ++r) timer.reset(cmd, r);
        timer.begin(cmd, 0);
        timer.begin(cmd, 1);
        work = renderer.recordLicWork(cmd, renderer.dims().z, 0);
        timer.end(cmd, 1);
        timer.begin(cmd, 2);
        drawn = renderer.recordFrame(cmd, target, view);
        timer.end(cmd, 2);
        timer.end(cmd, 0);
        target.recordUnread(cmd);
      },
      "drag frame"));
  LIC3D_TRY(work);
  LIC3D_TRY(std::move(drawn));
  if (work->finished) renderer.collectStatistics(0);
  DragFrame frame;
  LIC3D_TRY_ASSIGN(frame.frameMs, timer.milliseconds(0));
  LIC3D_TRY_ASSIGN(frame.licMs, timer.milliseconds(1));
  LIC3D_TRY_ASSIGN(frame.drawMs, timer.milliseconds(2));
  return frame;
}

}  // namespace

Result<nlohmann::json> runDragBenchmarks(const Context& context, const BenchOptions& options) {
  LIC3D_TRY_ASSIGN(const std::vector<int> sizes, parseIntList(options.sizes, "--sizes", 4, 4096));
  LIC3D_TRY_ASSIGN(const std::vector<int> lengths,
                   parseIntList(options.lengths, "--lengths", 0, kMaxLicLength));
  const auto fieldKind = parseEnum<AnalyticField>(options.field);
  if (!fieldKind) return inputError("bench: --field must be an analytic field");
  if (!context.supportsTimestamps())
    return unsupportedError(context.deviceInfo().name + " has no timestamp queries");

  nlohmann::json report = newReport(context);
  report["field"] = options.field;
  report["picture"] = options.dragPicture;
  report["slices"] = options.dragSlices;
  report["frames"] = options.dragFrames;
  report["drag"] = nlohmann::json::array();
  const int length = lengths.front();
  std::printf("lic3d bench --drag on %s (%s), %s\n", context.deviceInfo().name.c_str(),
              context.deviceInfo().driver.c_str(), report["date"].get<std::string>().c_str());
  std::printf(
      "A LIC slider dragged: %s field, L from %d, one step longer each frame; per frame the "
      "app's LIC job (coarse at the stride chosen from the full LIC's time, whole) and a %d^2 "
      "picture of %d slices; %d frames after %d warm-up (GPU timestamps)\n",
      options.field.c_str(), length, options.dragPicture, options.dragSlices, options.dragFrames,
      options.warmup);
  std::printf("%8s %12s %7s %12s %10s %10s %12s %12s %8s\n", "volume", "full LIC ms", "stride",
              "coarse grid", "LIC ms", "draw ms", "frame ms", "p95 ms", "60 fps");

  ViewParams view;
  view.width = view.height = options.dragPicture;
  view.slices = options.dragSlices;
  LIC3D_TRY_ASSIGN(const GpuTimer timer, GpuTimer::create(context, 3, "drag timestamps"));
  LIC3D_TRY_ASSIGN(OffscreenTarget target,
                   OffscreenTarget::create(context, FramePrecision::Float16));
  LIC3D_TRY(target.resize(view.width, view.height));
  for (const int n : sizes) {
    RendererOptions rendererOptions;
    rendererOptions.fieldPrecision = options.precision;
    rendererOptions.doubleBuffered = true;  // as the app
    LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, rendererOptions));
    const Dims dims(n);
    LIC3D_TRY(renderer.setInputs(makeAnalyticField(*fieldKind, dims),
                                 makeWhiteNoise(dims, options.seed)));
    LicParams params;
    params.length = length;
    // The full LIC the drag starts from, timed as the app times it: what picks the stride.
    std::vector<double> full;
    for (int i = 0; i < std::max(options.warmup, 1) + 3; ++i) {
      LIC3D_TRY_ASSIGN(const double ms, timeLicDispatch(context, renderer.licJob(),
                                                        renderer.fieldTextures(), timer, params));
      if (i >= std::max(options.warmup, 1)) full.push_back(ms);
    }
    const double fullMs = median(full);
    int stride = coarseLicStride(fullMs);
    std::vector<DragFrame> frames;
    for (int i = 0; i < options.warmup + options.dragFrames; ++i) {
      // Back and forth over 20 steps: every frame asks for another volume.
      const int step = i % 40 < 20 ? i % 20 : 20 - i % 20;
      params.length = std::min(length + 1 + step, kMaxLicLength);
      LIC3D_TRY_ASSIGN(const DragFrame frame,
                       dragFrame(context, renderer, target, timer, params, stride, view));
      if (i >= options.warmup) frames.push_back(frame);
      // As the app: a coarse job over the budget makes the next ones coarser (nextCoarseStride);
      // the frames timed are those after the warm-up, at the stride reached then.
      if (stride > 1 && i < options.warmup) stride = nextCoarseStride(stride, frame.licMs);
    }
    std::vector<double> frameMs, licMs, drawMs;
    for (const DragFrame& f : frames) {
      frameMs.push_back(f.frameMs);
      licMs.push_back(f.licMs);
      drawMs.push_back(f.drawMs);
    }
    const double frameMedian = median(frameMs);
    const double frameP95 = percentile(frameMs, 0.95);
    const bool fits = frameP95 <= kFrameBudgetMs;
    const Dims grid = coarseDims(dims, stride);
    const std::string gridText =
        std::to_string(grid.x) + "x" + std::to_string(grid.y) + "x" + std::to_string(grid.z);
    std::printf("%6d^3 %12.3f %7d %12s %10.3f %10.3f %12.3f %12.3f %8s\n", n, fullMs, stride,
                gridText.c_str(), median(licMs), median(drawMs), frameMedian, frameP95,
                fits ? "yes" : "no");
    std::fflush(stdout);
    report["drag"].push_back({{"n", n},
                              {"length", length},
                              {"full_lic_ms", fullMs},
                              {"stride", stride},
                              {"coarse_grid", {grid.x, grid.y, grid.z}},
                              {"lic_median_ms", median(licMs)},
                              {"draw_median_ms", median(drawMs)},
                              {"frame_median_ms", frameMedian},
                              {"frame_p95_ms", frameP95},
                              {"fits_60_fps", fits}});
  }
  return report;
}

}  // namespace lic3d::cli
