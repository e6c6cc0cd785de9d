// SPDX-License-Identifier: BSD-3-Clause
// `lic3d render2d`: 2D LIC of a plane (thesis chapter 3), one picture or the frames of an
// animation.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cli/command_support.h"
#include "cli/commands.h"
#include "core/memory_budget.h"
#include "gpu/device_choice.h"
#include "gpu/timer.h"
#include "gpu/vulkan_context.h"
#include "io/png_writer.h"
#include "jobs/plane_picture.h"
#include "lic/analytic_fields.h"
#include "lic/lic2d_reference.h"
#include "options/progress.h"
#include "passes/volume_textures.h"

namespace lic3d::cli {
namespace {

// The checks of a 2D LIC request before anything is read (InvalidInput naming the flag).
Result<void> checkPlaneRequest(const ComputeOptions& options, const TimeDomain& domain) {
  const Session& session = options.inputs.session;
  LIC3D_TRY(checkLic2DParams(session.lic));
  LIC3D_TRY(checkTimeGiven(options.inputs, domain));
  const FieldSource& source = session.field;
  if (parseEnum<AnalyticField2D>(source.field) && options.inputs.grid.given() &&
      std::count(options.inputs.grid.text.begin(), options.inputs.grid.text.end(), ',') == 2)
    return inputError("--grid " + options.inputs.grid.text + ": " + source.field +
                      " is a 2D field; give N or NX,NY");
  if (session.timeSteps > 0)
    return inputError("--time-steps: 2D LIC samples analytic fields at each time exactly");
  return {};
}

// Each frame of `plan` as a PNG of `picture` at the frame's parameters, then the video. `gpuMs`
// gets each frame's LIC time on the GPU.
Result<void> renderPlaneFrames(const GlobalOptions& global, const Session& session,
                               const BatchOptions& batch, const FramePlan& plan,
                               PlanePicture& picture, RunSummary& summary,
                               std::vector<double>& gpuMs) {
  gpuMs.clear();
  const bool animated = plan.animation != Animation::None;
  FrameProgress progress(plan.rendered(), global.quiet || !animated);
  LIC3D_TRY_ASSIGN(const FrameSkips skips, findWholeFrames(plan, batch.skipExisting, global.quiet));
  for (int frame = plan.first; frame < plan.end; ++frame) {
    const std::string path = animated ? framePath(plan.output, frame) : plan.output;
    if (skips.has(plan, frame)) {
      summary.outputs.push_back(path);
      progress.frameDone(frame);
      continue;
    }
    const Session frameParams = frameSession(session, plan, frame);
    LIC3D_TRY(picture.setInputs(frameParams));
    if (picture.onGpu()) {
      LIC3D_TRY(picture.computeLic(frameParams.lic));
      gpuMs.push_back(picture.gpuMilliseconds());
    } else {
      Progress cpu("2D LIC " + sizeText(picture.imageDims()) + " on the CPU",
                   global.quiet || animated);
      LIC3D_TRY(picture.computeLic(frameParams.lic, [&](double f) { cpu.update(f); }));
    }
    const RgbaImage image = picture.colour(frameParams.view);
    LIC3D_TRY_ASSIGN(const PngText text, pngText(frameParams, path));
    LIC3D_TRY(writePng(path, image, text));
    summary.outputs.push_back(path);
    progress.frameDone(frame);
  }
  progress.finish();
  if (!batch.video.empty()) {
    LIC3D_TRY_ASSIGN(const std::filesystem::path ffmpeg, findFfmpeg());
    if (!global.quiet)
      std::fprintf(stderr, "lic3d: encoding %s with %s\n", batch.video.c_str(), ffmpeg.c_str());
    LIC3D_TRY(encodeVideo(ffmpeg, plan, batch.fps, batch.video));
    summary.outputs.push_back(batch.video);
  }
  return {};
}

// The line saying what was written, on stderr.
void printPlaneDone(const Session& session, const FramePlan& plan, const RunSummary& summary,
                    const PlanePicture& picture, const std::vector<double>& gpuMs,
                    const Context* context) {
  const std::string what =
      plan.animation == Animation::None
          ? plan.output
          : std::to_string(plan.rendered()) + " frames " + summary.outputs.front() +
                (plan.rendered() > 1 ? " .. " + framePath(plan.output, plan.end - 1) : "");
  char gpu[64] = "";
  if (!gpuMs.empty())
    std::snprintf(gpu, sizeof gpu, ", LIC %.2f ms on the GPU%s", median(gpuMs),
                  gpuMs.size() > 1 ? " (median)" : "");
  std::fprintf(stderr, "lic3d: wrote %s (%s, 2D LIC of %s %s, on %s%s)\n", what.c_str(),
               sizeText(picture.imageDims()).c_str(), session.field.field.c_str(),
               sizeText(picture.field().dims).c_str(),
               context ? context->deviceInfo().name.c_str() : "the CPU", gpu);
}

}  // namespace

int runRender2D(const GlobalOptions& global, const ComputeOptions& options,
                const BatchOptions& batch) {
  const Clock::time_point start = Clock::now();
  const Session& session = options.inputs.session;
  const Result<TimeDomain> domain = timeDomainOf(session);
  if (!domain) return reportError(domain.error());
  const Result<FramePlan> plan = planFrames(batch, options, *domain, "lic2d_%04d.png");
  if (!plan) return reportError(plan.error());
  if (auto r = checkRenderOutputs(batch, *plan, session); !r) return reportError(r.error());
  if (auto r = checkPlaneRequest(options, *domain); !r) return reportError(r.error());
  std::optional<Context> context;  // outlives the picture's GPU resources
  PlanePicture picture;
  if (auto r = picture.setInputs(session, options.inputs.grid.given()); !r)
    return reportError(r.error());
  {
    const Dims image = picture.imageDims();
    Result<std::vector<OutputBytes>> outputs =
        pictureOutputBytes(batch, *plan, session, image.x, image.y);
    if (auto r = outputs ? checkFreeSpace(*outputs) : Result<void>(outputs.error()); !r)
      return reportError(r.error());
  }
  if (!options.cpu) {
    Result<Context> opened = openContext(global);
    if (!opened) return reportError(opened.error());
    context.emplace(std::move(*opened));
    // A 2D request holds about what a one-voxel-thick volume of the image's size does.
    MemoryRequest request;
    request.dims = picture.imageDims();
    request.precision = resolvePrecision(*context, session.precision);
    if (auto r = checkMemoryBudget(request, queryMemoryBudget(*context),
                                   "the 2D LIC of " + session.field.field);
        !r)
      return finish(*context, reportError(r.error()));
  }
  auto fail = [&](const Error& error) {
    const int status = reportError(error);
    return context ? finish(*context, status) : status;
  };
  if (picture.readInfo().nonFiniteVectors > 0)
    std::fprintf(stderr,
                 "lic3d: warning: %s: %zu vector(s) with a NaN or infinite component were read "
                 "as zero (streamlines stop there)\n",
                 session.field.field.c_str(), picture.readInfo().nonFiniteVectors);

  RunSummary summary;
  summary.command = "render2d";
  summary.field = session.field.field;
  summary.array = picture.readInfo().arrayName;
  summary.grid = picture.field().dims;
  summary.geometry = picture.field().geometry;

  std::vector<double> gpuMs;  // each frame's LIC on the GPU
  if (context) {
    if (auto r = picture.useGpu(*context); !r) return fail(r.error());
  }
  if (auto r = renderPlaneFrames(global, session, batch, *plan, picture, summary, gpuMs); !r)
    return fail(r.error());
  if (!global.quiet)
    printPlaneDone(session, *plan, summary, picture, gpuMs, context ? &*context : nullptr);
  const int status = context ? finish(*context, kExitOk) : kExitOk;
  if (status == kExitOk) {
    summary.frames = plan->rendered();
    summary.device = context ? context->deviceInfo().name : "CPU reference";
    printSummary(global, summary, start);
  }
  return status;
}

}  // namespace lic3d::cli
