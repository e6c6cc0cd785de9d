// SPDX-License-Identifier: BSD-3-Clause
// `lic3d render2d`: 2D LIC of a plane (thesis chapter 3), one picture or the frames of an
// animation.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <future>
#include <map>
#include <optional>

#include "cli/command_support.h"
#include "cli/commands.h"
#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "gpu/device_choice.h"
#include "gpu/gpu_timer.h"
#include "gpu/vulkan_context.h"
#include "inputs/plane_inputs.h"
#include "io/file_util.h"
#include "io/png_writer.h"
#include "lic/analytic_fields.h"
#include "lic/colouring.h"
#include "lic/field_plane.h"
#include "lic/lic2d_reference.h"
#include "lic/noise.h"
#include "lic/time_series.h"
#include "options/progress.h"
#include "passes/field_interpolation.h"
#include "passes/lic2d_pass.h"

namespace lic3d::cli {
namespace {

// ---- 2D LIC -------------------------------------------------------------------------------------

// What the frames of render2d are made from: the plane at `time` and the noise at the image's
// size.
struct PlaneInputs {
  PlaneSource source;
  VectorField field;
  NoiseVolume noise;
  bool timeDependent = false;
  double time = 0.0;
};

Result<PlaneInputs> loadPlaneInputs(const ComputeOptions& options, const TimeDomain& domain) {
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
  PlaneInputs inputs;
  inputs.timeDependent = domain.timeDependent;
  inputs.time = session.time;
  LIC3D_TRY_ASSIGN(inputs.field,
                   planeField(session, options.inputs.grid.given(), session.time, inputs.source));
  const Dims image = imageSize(inputs.field.dims, session.plane);
  LIC3D_TRY(checkHostMemory(image));
  LIC3D_TRY_ASSIGN(inputs.noise, loadNoise(session.noise, image));
  return inputs;
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
  Result<PlaneInputs> inputs = loadPlaneInputs(options, *domain);
  if (!inputs) return reportError(inputs.error());
  std::optional<Context> context;
  if (!options.cpu) {
    Result<Context> opened = openContext(global);
    if (!opened) return reportError(opened.error());
    context.emplace(std::move(*opened));
    // A 2D request holds about what a one-voxel-thick volume of the image's size does.
    MemoryRequest request;
    request.dims = inputs->noise.dims;
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
  if (inputs->source.info.nonFiniteVectors > 0)
    std::fprintf(stderr,
                 "lic3d: warning: %s: %zu vector(s) with a NaN or infinite component were read "
                 "as zero (streamlines stop there)\n",
                 session.field.field.c_str(), inputs->source.info.nonFiniteVectors);

  RunSummary summary;
  summary.command = "render2d";
  summary.field = session.field.field;
  summary.array = inputs->source.info.arrayName;
  summary.grid = inputs->field.dims;
  summary.geometry = inputs->field.geometry;

  std::vector<double> gpuMs;  // each frame's LIC on the GPU
  const Result<void> done = [&]() -> Result<void> {
    std::optional<Lic2DPass> pass;
    std::optional<Lic2DInputs> uploaded;
    gpuMs.clear();
    if (context) {
      LIC3D_TRY_ASSIGN(Lic2DPass created, Lic2DPass::create(*context));
      pass.emplace(std::move(created));
    }
    const bool animated = plan->animation != Animation::None;
    FrameProgress progress(plan->rendered(), global.quiet || !animated);
    bool fresh = true;  // `inputs->field` changed since it was uploaded
    const FrameSkips skips = findWholeFrames(*plan, batch.skipExisting, global.quiet);
    for (int frame = plan->first; frame < plan->end; ++frame) {
      const std::string path = animated ? framePath(plan->output, frame) : plan->output;
      if (skips.has(*plan, frame)) {
        summary.outputs.push_back(path);
        progress.frameDone(frame);
        continue;
      }
      const Session frameParams = frameSession(session, *plan, frame);
      if (inputs->timeDependent && frameParams.time != inputs->time) {
        LIC3D_TRY_ASSIGN(inputs->field,
                         planeField(session, false, frameParams.time, inputs->source));
        inputs->time = frameParams.time;
        fresh = true;
      }
      ScalarVolume lic;
      if (pass) {
        if (fresh) {
          uploaded.reset();
          LIC3D_TRY_ASSIGN(uploaded, uploadLic2DInputs(*context, inputs->field, inputs->noise,
                                                       session.precision));
          fresh = false;
        }
        LIC3D_TRY_ASSIGN(lic, pass->compute(*uploaded, frameParams.lic));
        gpuMs.push_back(pass->lastMilliseconds());
      } else {
        Progress cpu("2D LIC " + sizeText(inputs->noise.dims) + " on the CPU",
                     global.quiet || animated);
        LIC3D_TRY_ASSIGN(lic, computeLic2DReference(inputs->field, inputs->noise, frameParams.lic,
                                                    0, [&](double f) { cpu.update(f); }));
      }
      lic.geometry = imageGeometry(inputs->field, inputs->noise.dims);
      const RgbaImage image =
          colourLic2D(lic, inputs->field, frameParams.view, inputs->source.outside);
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
      LIC3D_TRY(encodeVideo(ffmpeg, *plan, batch.fps, batch.video));
      summary.outputs.push_back(batch.video);
    }
    return {};
  }();
  if (!done) return fail(done.error());
  if (!global.quiet) {
    const std::string what =
        plan->animation == Animation::None
            ? plan->output
            : std::to_string(plan->rendered()) + " frames " + summary.outputs.front() +
                  (plan->rendered() > 1 ? " .. " + framePath(plan->output, plan->end - 1) : "");
    char gpu[64] = "";
    if (!gpuMs.empty())
      std::snprintf(gpu, sizeof gpu, ", LIC %.2f ms on the GPU%s", median(gpuMs),
                    gpuMs.size() > 1 ? " (median)" : "");
    std::fprintf(stderr, "lic3d: wrote %s (%s, 2D LIC of %s %s, on %s%s)\n", what.c_str(),
                 sizeText(inputs->noise.dims).c_str(), session.field.field.c_str(),
                 sizeText(inputs->field.dims).c_str(),
                 context ? context->deviceInfo().name.c_str() : "the CPU", gpu);
  }
  const int status = context ? finish(*context, kExitOk) : kExitOk;
  if (status == kExitOk) {
    summary.frames = plan->rendered();
    summary.device = context ? context->deviceInfo().name : "CPU reference";
    printSummary(global, summary, start);
  }
  return status;
}

}  // namespace lic3d::cli
