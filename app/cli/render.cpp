// SPDX-License-Identifier: BSD-3-Clause
// `lic3d render`: pictures, animations and RGBA volumes of the 3D LIC.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <future>
#include <map>
#include <optional>

#include "cli/command_support.h"
#include "cli/commands.h"
#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "gpu/device_choice.h"
#include "gpu/vulkan_context.h"
#include "io/file_util.h"
#include "io/png_writer.h"
#include "jobs/bricks.h"
#include "jobs/reduced_volume.h"
#include "lic/analytic_fields.h"
#include "lic/colouring.h"
#include "lic/derived_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "lic/time_series.h"
#include "loading/plane_inputs.h"
#include "loading/scalars.h"
#include "options/progress.h"
#include "render/lic_renderer.h"

namespace lic3d::cli {
namespace {
// Makes the renderer's LIC volume the one of `lic` for pictures of `view`, on the GPU or (with
// --cpu) the CPU, unless it already is.
Result<void> makeLicVolume(const ComputeOptions& options, const SessionInputs& inputs,
                           const LicParams& lic, const ViewParams& view, LicRenderer& renderer,
                           bool quiet) {
  if (options.cpu) {
    if (!renderer.needsLic(lic)) return {};
    LIC3D_TRY_ASSIGN(const ScalarVolume volume, computeOnCpu(inputs, lic, quiet));
    return renderer.setLicVolume(volume, lic);
  }
  // Named by the device: "on the GPU" would be wrong on a CPU driver such as llvmpipe.
  Progress progress("LIC " + gridText(inputs.field.dims) + " on " + renderer.deviceName(), quiet);
  LIC3D_TRY_ASSIGN(const bool needed, renderer.needsLic(lic, view));
  if (!needed) return {};
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran,
                   renderer.updateLic(lic, view, [&](double f) { progress.update(f); }));
  return {};
}

// A LIC volume made before the frames (in bricks, over --devices), possibly a reduced copy, and
// what the pictures then say of it beside their session.
struct GivenLic {
  ScalarVolume volume;
  std::string note;  // empty: the whole volume
};

// A LIC volume made in bricks for render, and the field on its grid where that is not the
// inputs' (a reduced copy).
struct ReducedLic {
  ScalarVolume volume;
  std::string note;                     // what was drawn, for the pictures and the message
  std::optional<SessionInputs> inputs;  // the field on the reduced grid
  int factor = 1;
  int bricks = 1;
  std::vector<DeviceShare> shares;
};

std::string ordinal(int n) {
  const char* suffix = n % 100 >= 11 && n % 100 <= 13 ? "th"
                       : n % 10 == 1                  ? "st"
                       : n % 10 == 2                  ? "nd"
                       : n % 10 == 3                  ? "rd"
                                                      : "th";
  return std::to_string(n) + suffix;
}

// The LIC of `inputs` made in bricks over `contexts`: whole when the first device can draw it
// (`drawable`) and the host can gather it, else every factor-th voxel of it for the smallest
// factor both can (jobs/reduced_volume.h), with the field on that grid. Decided before the LIC.
Result<ReducedLic> makeReducedLic(const GlobalOptions& global, const ComputeOptions& options,
                                  const std::vector<Context>& contexts, SessionInputs& inputs,
                                  bool drawable) {
  const Session& session = options.inputs.session;
  const Dims dims = inputs.field.dims;
  // The draw and the copy the bricks are gathered into, on the device and the host.
  const auto fits = [&](Dims grid) {
    return checkRequestMemory(
        contexts.front(), session, grid,
        {.licOnHost = true, .frame = true, .deviceCap = options.memoryBudget});
  };
  ReducedLic made;
  if (!drawable || !fits(dims)) {
    const std::optional<int> factor =
        chooseReduction(dims, 64, [&](Dims reduced) { return fits(reduced).ok(); });
    if (!factor) {
      const Result<void> coarsest = fits(reducedDims(dims, 64));
      return resourceLimitError(
          "the LIC of " + session.field.field + " (" + gridText(dims) +
          ") cannot be drawn even as every 64th voxel on " + contexts.front().deviceInfo().name +
          (options.memoryBudget > 0
               ? " within --memory-budget " + std::to_string(options.memoryBudget) + " bytes"
               : "") +
          (coarsest ? "" : ": " + coarsest.error().message));
    }
    made.factor = *factor;
  }
  ReducedVolume reduced(dims, inputs.field.geometry, made.factor);
  Progress progress("LIC " + gridText(dims) + " on " + devicesText(contexts), global.quiet);
  LicVolumeOptions how{.deviceCap = options.memoryBudget};
  const VoxelTarget target =
      reduced.target(session.lic.sparsity.distribution != SparsityDistribution::None);
  how.target = &target;
  how.stage = [&](const std::string& stage) { progress.stage(stage); };
  Result<LicVolumeRun> run = computeLicVolume(pointersTo(contexts), session, inputs, how,
                                              [&](double f) { progress.update(f); });
  if (!run) {
    progress.cancel();
    return run.error();
  }
  progress.finish();
  made.bricks = run->bricks;
  made.shares = std::move(run->devices);
  made.volume = reduced.takeVolume();
  if (made.factor == 1) return made;
  Progress reducing(
      "the field on " + gridText(made.volume.dims) + ", every " + ordinal(made.factor) + " voxel",
      global.quiet);
  reducing.stage(inputs.device ? "made on the device" : "reduced on the host");
  made.note = "LIC " + gridText(dims) + " made in " + std::to_string(made.bricks) +
              " bricks, drawn as every " + ordinal(made.factor) +
              " voxel: " + gridText(made.volume.dims);
  if (inputs.device) {
    // The analytic field made on the reduced grid, whose geometry the volume takes.
    Session onReduced = session;
    onReduced.field.grid = made.volume.dims;
    LIC3D_TRY_ASSIGN(made.inputs, loadSessionInputs(onReduced, {.fieldOnDevice = true}));
    made.volume.geometry = made.inputs->field.geometry;
  } else {
    SessionInputs field;
    field.field = reduceField(inputs.field, made.factor);
    field.noise = makeWhiteNoise(field.field.dims, session.noise.seed);
    field.fromFile = inputs.fromFile;
    field.info = inputs.info;
    made.inputs = std::move(field);
  }
  return made;
}

// After the frames: the RGBA volume and the video.
Result<void> writeBatchOutputs(const GlobalOptions& global, const ComputeOptions& options,
                               const BatchOptions& batch, const FramePlan& plan,
                               SessionInputs& inputs, LicRenderer& renderer,
                               const ViewScalars& scalars, std::vector<std::string>& outputs) {
  const Session& session = options.inputs.session;
  if (!batch.rgbaVolume.empty()) {
    LIC3D_TRY_ASSIGN(const ScalarVolume lic, renderer.readLicVolume());
    // The field the volume was made from is inputs.field, except a series blended on the GPU.
    std::optional<VectorField> blend;
    if (inputs.series && !options.cpu) {
      LIC3D_TRY_ASSIGN(VectorField host, hostFieldAt(inputs, session, inputs.time));
      blend = std::move(host);
    }
    const VectorField& field = blend ? *blend : inputs.field;
    const RgbaVolume rgba = colourLicVolume(lic, field, session.view,
                                            renderer.volumeFacts().transfer(), scalars.pointers());
    LIC3D_TRY(writeRgbaVolumeFile(batch.rgbaVolume, rgba));
    outputs.push_back(batch.rgbaVolume);
  }
  if (!batch.video.empty()) {
    LIC3D_TRY_ASSIGN(const std::filesystem::path ffmpeg, findFfmpeg());
    if (!global.quiet)
      std::fprintf(stderr, "lic3d: encoding %s with %s\n", batch.video.c_str(), ffmpeg.c_str());
    LIC3D_TRY(encodeVideo(ffmpeg, plan, batch.fps, batch.video));
    outputs.push_back(batch.video);
  }
  return {};
}

// The frames of `plan` (one picture without an animation), then the RGBA volume and the video.
Result<void> renderFrames(const GlobalOptions& global, const ComputeOptions& options,
                          const BatchOptions& batch, const FramePlan& plan, SessionInputs& inputs,
                          LicRenderer& renderer, std::vector<std::string>& outputs,
                          const GivenLic* given = nullptr) {
  const Session& session = options.inputs.session;
  const bool animated = plan.animation != Animation::None;
  const auto pathOf = [&](int frame) {
    return animated ? framePath(plan.output, frame) : plan.output;
  };
  LIC3D_TRY_ASSIGN(const FrameSkips skips, findWholeFrames(plan, batch.skipExisting, global.quiet));
  // Every frame whole already (a requeued task that had finished): no LIC is made.
  const bool makeNothing = skips.count == plan.rendered() && batch.rgbaVolume.empty();
  const double firstTime = frameSession(session, plan, plan.first).time;
  if (!makeNothing) LIC3D_TRY(moveToTime(inputs, session, firstTime, renderer, true, options.cpu));
  // Bias and time animations recompute the volume every frame: the frame lines report that
  // progress.
  // A LIC made before the frames (in bricks) is large: its upload and its picture take long and
  // say so.
  std::optional<Progress> drawing;
  if (!makeNothing && given) {
    drawing.emplace("drawing " + gridText(given->volume.dims) + " on " + renderer.deviceName(),
                    global.quiet);
    drawing->stage("the LIC volume to the device");
    LIC3D_TRY(renderer.setLicVolume(given->volume, session.lic));
  } else if (!makeNothing && plan.animation != Animation::Bias &&
             plan.animation != Animation::Time) {
    LIC3D_TRY(makeLicVolume(options, inputs, session.lic, session.view, renderer, global.quiet));
  }

  LIC3D_TRY_ASSIGN(ViewScalars scalars, loadViewScalars(session, inputs));
  LIC3D_TRY(setViewScalars(renderer, scalars));
  const bool derivedPerFrame =
      inputs.sampled && (scalars.color || scalars.opacity) && plan.animation == Animation::Time;

  if (drawing && animated) drawing->finish();  // the frame lines follow
  if (drawing && !animated) drawing->stage("the picture");
  FrameProgress progress(plan.rendered(), global.quiet || !animated);
  // PNG encoding and writing run on worker threads while the GPU makes the next frames; at most
  // `inFlight` frames wait, which bounds the host memory they hold.
  std::deque<std::future<Result<void>>> writes;
  const std::size_t inFlight = std::max(2u, availableThreads());
  const auto waitOldest = [&]() -> Result<void> {
    Result<void> written = writes.front().get();
    writes.pop_front();
    return written;
  };
  const auto waitAll = [&]() -> Result<void> {
    Result<void> first;
    while (!writes.empty())
      if (Result<void> written = waitOldest(); !written && first) first = std::move(written);
    return first;
  };
  for (int frame = plan.first; frame < plan.end; ++frame) {
    if (skips.has(plan, frame)) {
      outputs.push_back(pathOf(frame));
      progress.frameDone(frame);
      continue;
    }
    const Session frameParams = frameSession(session, plan, frame);
    LIC3D_TRY(moveToTime(inputs, session, frameParams.time, renderer, false, options.cpu));
    if (derivedPerFrame && frame > plan.first) {
      // An analytic field sampled at each time: its vorticity or helicity changes with it.
      LIC3D_TRY_ASSIGN(scalars, loadViewScalars(session, inputs));
      LIC3D_TRY(setViewScalars(renderer, scalars));
    }
    const Result<void> made =
        makeLicVolume(options, inputs, frameParams.lic, frameParams.view, renderer, true);
    Result<RgbaImage> image =
        made ? renderer.render(frameParams.lic, frameParams.view) : Result<RgbaImage>(made.error());
    Result<PngText> text =
        image ? pngText(frameParams, pathOf(frame)) : Result<PngText>(image.error());
    if (text && given && !given->note.empty()) text->emplace_back(kPngReducedKey, given->note);
    if (!image || !text) {
      (void)waitAll();  // the frames already made are written before the error is reported
      return !image ? std::move(image).error() : std::move(text).error();
    }
    std::string path = pathOf(frame);
    if (writes.size() >= inFlight) LIC3D_TRY(waitOldest());
    writes.push_back(
        std::async(std::launch::async, [path, picture = std::move(*image), png = std::move(*text)] {
          return writePng(path, picture, png);
        }));
    outputs.push_back(std::move(path));
    progress.frameDone(frame);
  }
  LIC3D_TRY(waitAll());
  progress.finish();
  if (drawing) drawing->finish();
  if (inputs.series && !options.cpu && !global.quiet)
    std::fprintf(stderr,
                 "lic3d: time series: %d step(s) read for %zu blend(s), %.2f ms per blend on the "
                 "GPU (median)\n",
                 inputs.stepsRead, inputs.blendMs.size(), median(inputs.blendMs));

  return writeBatchOutputs(global, options, batch, plan, inputs, renderer, scalars, outputs);
}

// The free space for the pictures and, with --rgba-volume, the RGBA volume of `grid` (4 bytes a
// voxel), summed where they share a file system.
Result<void> checkRenderSpace(const BatchOptions& batch, const FramePlan& plan,
                              const Session& session, Dims grid) {
  const int width =
      session.view.stereo == StereoMode::SideBySide ? 2 * session.view.width : session.view.width;
  LIC3D_TRY_ASSIGN(std::vector<OutputBytes> outputs,
                   pictureOutputBytes(batch, plan, session, width, session.view.height));
  if (!batch.rgbaVolume.empty()) outputs.push_back({batch.rgbaVolume, volumeFileBytes(grid, 4)});
  return checkFreeSpace(outputs);
}

// The line saying what was written, on stderr.
void printRenderDone(const Session& session, const FramePlan& plan, const RunSummary& summary,
                     const std::string& field, const std::string& devices, const GivenLic* given) {
  const int width =
      session.view.stereo == StereoMode::SideBySide ? 2 * session.view.width : session.view.width;
  const std::string what =
      plan.animation == Animation::None
          ? plan.output
          : std::to_string(plan.rendered()) + " frames " + summary.outputs.front() +
                (plan.rendered() > 1 ? " .. " + framePath(plan.output, plan.end - 1) : "");
  std::fprintf(stderr, "lic3d: wrote %s (%dx%d, %s, on %s%s%s)\n", what.c_str(), width,
               session.view.height, field.c_str(), devices.c_str(),
               given && !given->note.empty() ? "; " : "", given ? given->note.c_str() : "");
}

}  // namespace

int runRender(const GlobalOptions& global, const ComputeOptions& options,
              const BatchOptions& batch) {
  const Clock::time_point start = Clock::now();
  const Session& session = options.inputs.session;
  // Every flag and output is checked before any work.
  const Result<TimeDomain> domain = timeDomainOf(session);
  if (!domain) return reportError(domain.error());
  const Result<FramePlan> plan = planFrames(batch, options, *domain);
  if (!plan) return reportError(plan.error());
  if (auto r = checkRenderOutputs(batch, *plan, session); !r) return reportError(r.error());
  if (auto r = checkViewScalarNames(session, nullptr); !r) return reportError(r.error());
  // The outputs' free space, before the devices; an RGBA volume's grid is known here only for an
  // analytic field (a file's, once it is read).
  const bool analytic = parseEnum<AnalyticField>(session.field.field).has_value();
  if (batch.rgbaVolume.empty() || analytic)
    if (auto r = checkRenderSpace(batch, *plan, session, session.field.grid); !r)
      return reportError(r.error());
  if (options.cpu && !options.devices.empty())
    return reportError(
        inputError("--devices " + options.devices + ": --cpu computes on the CPU, not on devices"));
  Result<std::vector<Context>> contexts = openContexts(global, options.devices);
  if (!contexts) return reportError(contexts.error());
  const Context& context = contexts->front();  // draws the pictures
  // A LIC that cannot be drawn whole is made in bricks and drawn as a reduced copy: one picture
  // or a turntable (one volume), white noise at one time, coloured by speed.
  const bool reducible =
      !options.cpu && session.timeSteps == 0 && isWhiteNoise(session.noise) &&
      (plan->animation == Animation::None || plan->animation == Animation::Turntable) &&
      batch.rgbaVolume.empty() && session.view.colorBy == "speed" &&
      session.view.opacityBy == "speed";
  const auto fitsWhole = [&](Dims dims, bool series) {
    return checkRequestMemory(
        context, session, dims,
        {.frame = true, .timeSeries = series && !options.cpu, .deviceCap = options.memoryBudget});
  };
  // An analytic field's grid is known before it is made: refuse what cannot fit first.
  if (analytic && !reducible)
    if (auto r = fitsWhole(session.field.grid, session.timeSteps > 0); !r)
      return finish(*contexts, reportError(r.error()));
  // The field is made on the device unless the host needs it: for the CPU LIC, colour or opacity
  // derived from the vectors, or the RGBA volume.
  Result<SessionInputs> inputs = loadInputs(
      options, !options.cpu && batch.rgbaVolume.empty() && !viewDerivesFromField(session.view));
  if (!inputs) return finish(*contexts, reportError(inputs.error()));
  if (auto r = checkViewScalarNames(session, &*inputs); !r)
    return finish(*contexts, reportError(r.error()));
  if (auto r = checkOutputsAreNotInputs(batch, *plan); !r)
    return finish(*contexts, reportError(r.error()));
  if (!batch.rgbaVolume.empty() && !analytic)
    if (auto r = checkRenderSpace(batch, *plan, session, inputs->field.dims); !r)
      return finish(*contexts, reportError(r.error()));
  reportFieldFile(global, session.field, *inputs);
  const Result<void> whole = fitsWhole(inputs->field.dims, inputs->series.has_value());
  if (!whole && !reducible) return finish(*contexts, reportError(whole.error()));

  RunSummary summary = makeSummary("render", session.field, *inputs);
  // In bricks over the devices (and reduced when too large to draw), before the frames.
  std::optional<GivenLic> given;
  std::optional<SessionInputs> drawn;
  if (!whole || contexts->size() > 1) {
    Result<ReducedLic> made = makeReducedLic(global, options, *contexts, *inputs, whole.ok());
    if (!made) return finish(*contexts, reportError(made.error()));
    given = GivenLic{std::move(made->volume), made->note};
    drawn = std::move(made->inputs);
    summary.bricks = made->bricks;
    summary.shares = std::move(made->shares);
    summary.reduction = made->factor > 1 ? made->factor : 0;
    if (made->factor > 1) summary.reducedGrid = given->volume.dims;
  }
  SessionInputs& frameInputs = drawn ? *drawn : *inputs;
  int status = kExitOk;
  {
    // A picture and its RGBA volume appear together or not at all (a failure while the volume
    // is made leaves neither); an animation's frames each appear once complete, so a run stopped
    // half way keeps them.
    std::optional<OutputGroup> together;
    if (plan->animation == Animation::None) together.emplace();
    RendererOptions rendererOptions{session.precision};
    // The RGBA volume colours every voxel, clipped or not: it needs them all.
    rendererOptions.visibleWork = batch.visibleWork == "on" && batch.rgbaVolume.empty();
    Result<LicRenderer> renderer = LicRenderer::create(context, rendererOptions);
    Result<void> done = renderer
                            ? renderFrames(global, options, batch, *plan, frameInputs, *renderer,
                                           summary.outputs, given ? &*given : nullptr)
                            : Result<void>(renderer.error());
    if (done && together) done = together->commit();
    together.reset();
    if (!done) {
      status = reportError(done.error());
    } else if (!global.quiet) {
      printRenderDone(session, *plan, summary, fieldText(session.field, *inputs),
                      devicesText(*contexts), given ? &*given : nullptr);
    }
    if (done) noteHiddenFraction(global, session.lic, renderer->hiddenFraction(), summary);
    if (renderer) {
      const StageTimer timer("teardown");
      const LicRenderer released = std::move(*renderer);
    }
  }
  status = finish(*contexts, status);
  if (status == kExitOk) {
    summary.frames = plan->rendered();
    summary.device = context.deviceInfo().name;
    printSummary(global, summary, start);
  }
  return status;
}

}  // namespace lic3d::cli
