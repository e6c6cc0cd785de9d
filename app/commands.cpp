// SPDX-License-Identifier: BSD-3-Clause
#include "commands.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <future>
#include <map>
#include <optional>

#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "gpu/gpu_timer.h"
#include "gpu/vulkan_context.h"
#include "inputs/bricks.h"
#include "inputs/plane_inputs.h"
#include "inputs/scalars.h"
#include "io/file_util.h"
#include "io/png_writer.h"
#include "lic/analytic_fields.h"
#include "lic/colouring.h"
#include "lic/derived_fields.h"
#include "lic/field_plane.h"
#include "lic/lic2d_reference.h"
#include "lic/lic_reference.h"
#include "lic/time_series.h"
#include "passes/field_interpolation.h"
#include "passes/lic2d_pass.h"
#include "passes/lic_renderer.h"
#include "progress.h"

namespace lic3d::cli {
namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

Result<Context> openContext(const GlobalOptions& global) {
  ContextOptions options;
  options.validation = global.validation;
  options.device = global.device;
  const StageTimer timer("device");
  return Context::create(options);
}

// With validation on, any message fails the command even if it otherwise succeeded.
int finish(const Context& context, int status) {
  if (context.validationEnabled() && context.validationMessageCount() > 0) {
    std::fprintf(stderr, "lic3d: error: %zu validation message(s)\n",
                 context.validationMessageCount());
    return status == kExitOk ? kExitFailure : status;
  }
  return status;
}

std::string tripleText(glm::dvec3 v) {
  return formatDouble(v.x) + "," + formatDouble(v.y) + "," + formatDouble(v.z);
}

// --time given for a field that has none is a mistake worth naming.
Result<void> checkTimeGiven(const SessionOptions& options, const TimeDomain& domain) {
  if (options.time && options.time->count() > 0 && !domain.timeDependent)
    return inputError("--time: " + options.session.field.field +
                      " does not change with time (the tornado, the 2D wave and series of files "
                      "do)");
  return {};
}

// `fieldOnDevice`: the run needs no host copy of an analytic field (InputOptions::fieldOnDevice).
Result<SessionInputs> loadInputs(const ComputeOptions& options, bool fieldOnDevice) {
  const Session& session = options.inputs.session;
  if (session.twoD)
    return inputError(
        "this session is a 2D one (mode 2d): make it with `lic3d render2d --session`");
  LIC3D_TRY_ASSIGN(const TimeDomain domain, timeDomainOf(session));
  LIC3D_TRY(checkTimeGiven(options.inputs, domain));
  return loadSessionInputs(session, {.gridGiven = options.inputs.grid.given(),
                                     .analyticTimeSteps = session.timeSteps,
                                     .fieldOnDevice = fieldOnDevice});
}

// What a file gave besides the field: which of several arrays was read, and vectors lost to NaN.
void reportFieldFile(const GlobalOptions& global, const FieldSource& source,
                     const SessionInputs& inputs) {
  const FieldReadInfo& info = inputs.info;
  if (info.nonFiniteVectors > 0)
    std::fprintf(stderr,
                 "lic3d: warning: %s: %zu vector(s) with a NaN or infinite component were read "
                 "as zero (streamlines stop there)\n",
                 source.field.c_str(), info.nonFiniteVectors);
  if (global.quiet || !source.array.empty() || info.arrayNames.size() < 2) return;
  std::string others;
  for (const std::string& name : info.arrayNames)
    if (name != info.arrayName) others += (others.empty() ? "'" : ", '") + name + "'";
  std::fprintf(stderr,
               "lic3d: %s has %zu vector arrays: read '%s'; the others are %s (choose one with "
               "--array NAME)\n",
               source.field.c_str(), info.arrayNames.size(), info.arrayName.c_str(),
               others.c_str());
}

// "tornado 128x128x128", or for a file its array, grid, spacing and origin.
std::string fieldText(const FieldSource& source, const SessionInputs& inputs) {
  const VectorField& field = inputs.field;
  if (!inputs.fromFile) return source.field + " " + gridText(field.dims);
  std::string text = inputs.series ? inputs.series->describe() : source.field;
  if (!inputs.info.arrayName.empty()) text += " array '" + inputs.info.arrayName + "'";
  return text + " " + gridText(field.dims) + ", spacing " + tripleText(field.geometry.spacing) +
         ", origin " + tripleText(field.geometry.origin);
}

RunSummary makeSummary(const char* command, const FieldSource& source,
                       const SessionInputs& inputs) {
  RunSummary summary;
  summary.command = command;
  summary.field = source.field;
  summary.array = inputs.info.arrayName;
  summary.grid = inputs.field.dims;
  summary.geometry = inputs.field.geometry;
  summary.nonFiniteVectors = inputs.info.nonFiniteVectors;
  return summary;
}

// The fraction of the voxels that sparsity hid, reported on stderr and in the summary.
void noteHiddenFraction(const GlobalOptions& global, const LicParams& lic,
                        std::optional<double> hidden, RunSummary& summary) {
  if (lic.sparsity.distribution == SparsityDistribution::None || !hidden) return;
  summary.hiddenFraction = hidden;
  if (global.quiet) return;
  std::fprintf(
      stderr, "lic3d: sparsity (%s%s) hid %.1f %% of the voxels\n",
      std::string(enumName(lic.sparsity.distribution)).c_str(),
      lic.sparsity.amount > 0.0f ? (", amount " + formatNumber(lic.sparsity.amount)).c_str() : "",
      100.0 * *hidden);
}

std::optional<double> hiddenFractionOf(const ScalarVolume& volume) {
  if (volume.drawn.empty()) return std::nullopt;
  const auto drawn = std::count(volume.drawn.begin(), volume.drawn.end(), 1);
  return 1.0 - static_cast<double>(drawn) / static_cast<double>(volume.drawn.size());
}

void printSummary(const GlobalOptions& global, RunSummary summary, Clock::time_point start) {
  summary.seconds = secondsSince(start);
  summary.timings = stageTimings();
  if (global.timings) printTimings(summary.seconds);
  if (global.quiet) return;
  std::printf("%s\n", summaryLine(summary).c_str());
  std::fflush(stdout);
}

Result<ScalarVolume> computeOnCpu(const SessionInputs& inputs, const LicParams& lic, bool quiet) {
  Progress progress("LIC " + gridText(inputs.field.dims) + " on the CPU", quiet);
  return computeLicReference(inputs.field, inputs.noise, lic, 0,
                             [&](double f) { progress.update(f); });
}

// Makes the renderer's LIC volume the one of `lic`, on the GPU or (with --cpu) the CPU, unless it
// already is.
Result<void> makeLicVolume(const ComputeOptions& options, const SessionInputs& inputs,
                           const LicParams& lic, LicRenderer& renderer, bool quiet) {
  if (!renderer.needsLic(lic)) return {};
  if (options.cpu) {
    LIC3D_TRY_ASSIGN(const ScalarVolume volume, computeOnCpu(inputs, lic, quiet));
    return renderer.setLicVolume(volume, lic);
  }
  // Named by the device: "on the GPU" would be wrong on a CPU driver such as llvmpipe.
  Progress progress("LIC " + gridText(inputs.field.dims) + " on " + renderer.deviceName(), quiet);
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran,
                   renderer.updateLic(lic, [&](double f) { progress.update(f); }));
  return {};
}

// compute's output: the volume (.nrrd, .vti) or one slice (.png with --slice).
Result<void> writeComputeOutput(const ComputeOptions& options, std::optional<LicSlice> slice,
                                const ScalarVolume& volume) {
  if (!slice) {
    const StageTimer timer("volume write");
    return writeLicVolumeFile(options.output, volume);
  }
  return writeLicSlicePng(options.output, volume, *slice, options.inputs.session);
}

// The frames of `plan` (one picture without an animation), then the RGBA volume and the video.
Result<void> renderFrames(const GlobalOptions& global, const ComputeOptions& options,
                          const BatchOptions& batch, const FramePlan& plan, SessionInputs& inputs,
                          LicRenderer& renderer, std::vector<std::string>& outputs) {
  const Session& session = options.inputs.session;
  const bool animated = plan.animation != Animation::None;
  const auto pathOf = [&](int frame) {
    return animated ? framePath(plan.output, frame) : plan.output;
  };
  const FrameSkips skips = findWholeFrames(plan, batch.skipExisting, global.quiet);
  // Every frame whole already (a requeued task that had finished): no LIC is made.
  const bool makeNothing = skips.count == plan.rendered() && batch.rgbaVolume.empty();
  const double firstTime = frameSession(session, plan, plan.first).time;
  if (!makeNothing) LIC3D_TRY(moveToTime(inputs, session, firstTime, renderer, true, options.cpu));
  // Bias and time animations recompute the volume every frame: the frame lines report that
  // progress.
  if (!makeNothing && plan.animation != Animation::Bias && plan.animation != Animation::Time)
    LIC3D_TRY(makeLicVolume(options, inputs, session.lic, renderer, global.quiet));

  LIC3D_TRY_ASSIGN(ViewScalars scalars, loadViewScalars(session, inputs));
  LIC3D_TRY(setViewScalars(renderer, scalars));
  const bool derivedPerFrame =
      inputs.sampled && (scalars.color || scalars.opacity) && plan.animation == Animation::Time;

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
    const Result<void> made = makeLicVolume(options, inputs, frameParams.lic, renderer, true);
    Result<RgbaImage> image =
        made ? renderer.render(frameParams.lic, frameParams.view) : Result<RgbaImage>(made.error());
    Result<PngText> text =
        image ? pngText(frameParams, pathOf(frame)) : Result<PngText>(image.error());
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
  if (inputs.series && !options.cpu && !global.quiet)
    std::fprintf(stderr,
                 "lic3d: time series: %d step(s) read for %zu blend(s), %.2f ms per blend on the "
                 "GPU (median)\n",
                 inputs.stepsRead, inputs.blendMs.size(), median(inputs.blendMs));

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

int runDevices(const GlobalOptions& global) {
  (void)global;
  const Result<std::vector<DeviceInfo>> devices = listDevices();
  if (!devices) return reportError(devices.error());
  if (devices->empty()) {
    std::fprintf(stderr, "lic3d: no Vulkan device found\n");
    return kExitFailure;
  }
  for (const DeviceInfo& d : *devices) {
    std::printf("%d: %s (%s, Vulkan %u.%u, %s, %.1f GiB device-local)%s%s\n", d.index,
                d.name.c_str(), deviceTypeName(d.type), VK_API_VERSION_MAJOR(d.apiVersion),
                VK_API_VERSION_MINOR(d.apiVersion), d.driver.c_str(),
                static_cast<double>(d.deviceLocalBytes) / (1024.0 * 1024.0 * 1024.0),
                d.usable ? "" : " - unusable: ", d.usable ? "" : d.unusableReason.c_str());
  }
  return kExitOk;
}

int runCompute(const GlobalOptions& global, const ComputeOptions& options,
               const BatchOptions& batch) {
  const Clock::time_point start = Clock::now();
  const Session& session = options.inputs.session;
  const Result<std::optional<LicSlice>> slice =
      checkComputeOutput(options.output, batch, options.inputs);
  if (!slice) return reportError(slice.error());
  if (*slice)
    if (auto r = pngText(session, options.output); !r) return reportError(r.error());
  // On the GPU, the device comes first, so that an analytic field too large for it is refused
  // before it is made (unless it can be made in bricks: white noise, one time).
  std::optional<Result<Context>> context;
  if (!options.cpu) {
    context.emplace(openContext(global));
    if (!*context) return reportError(context->error());
    const bool bricked = session.timeSteps == 0 && isWhiteNoise(session.noise);
    if (parseEnum<AnalyticField>(session.field.field) && !bricked)
      if (auto r = checkRequestMemory(**context, session, session.field.grid,
                                      {.volumeReadback = true,
                                       .timeSeries = session.timeSteps > 0,
                                       .deviceCap = options.memoryBudget});
          !r)
        return finish(**context, reportError(r.error()));
  }
  auto fail = [&](const Error& error) {
    const int status = reportError(error);
    return context ? finish(**context, status) : status;
  };
  Result<SessionInputs> inputs = loadInputs(options, !options.cpu);
  if (!inputs) return fail(inputs.error());
  if (auto r = checkNotAnInput(options.output); !r) return fail(r.error());
  reportFieldFile(global, session.field, *inputs);
  if (const std::optional<LicSlice> chosen = *slice) {
    // The index against the grid, before any work.
    const std::string text =
        std::string(1, static_cast<char>('x' + chosen->axis)) + ":" + std::to_string(chosen->index);
    if (chosen->index >= inputs->field.dims[chosen->axis])
      return fail(inputError("--slice " + text + ": the grid " + gridText(inputs->field.dims) +
                             " has " + std::to_string(inputs->field.dims[chosen->axis]) +
                             " slices along " +
                             std::string(1, static_cast<char>('x' + chosen->axis)) + " (0.." +
                             std::to_string(inputs->field.dims[chosen->axis] - 1) + ")"));
  }
  RunSummary summary = makeSummary("compute", session.field, *inputs);
  summary.outputs = {options.output};

  if (options.cpu) {
    if (inputs->series) {
      Result<VectorField> field = hostFieldAt(*inputs, session, session.time);
      if (!field) return reportError(field.error());
      inputs->field = std::move(*field);
      inputs->fieldStep.reset();
    }
    const Result<ScalarVolume> volume = computeOnCpu(*inputs, session.lic, global.quiet);
    if (!volume) return reportError(volume.error());
    if (auto r = writeComputeOutput(options, *slice, *volume); !r) return reportError(r.error());
    if (!global.quiet)
      std::fprintf(stderr, "lic3d: wrote %s (%s, on the CPU)\n", options.output.c_str(),
                   fieldText(session.field, *inputs).c_str());
    noteHiddenFraction(global, session.lic, hiddenFractionOf(*volume), summary);
    summary.device = "CPU reference";
    printSummary(global, summary, start);
    return kExitOk;
  }

  Context& device = **context;
  int status = kExitOk;
  {
    // In one piece when it fits the device (or --memory-budget), else in bricks.
    Progress progress("LIC " + gridText(inputs->field.dims) + " on " + device.deviceInfo().name,
                      global.quiet);
    Result<LicVolumeRun> run = computeLicVolume(device, session, *inputs, options.memoryBudget,
                                                [&](double f) { progress.update(f); });
    if (run) {
      progress.finish();
    } else {
      progress.cancel();
    }
    Result<void> done =
        run ? writeComputeOutput(options, *slice, run->volume) : Result<void>(run.error());
    if (done) {
      noteHiddenFraction(global, session.lic, hiddenFractionOf(run->volume), summary);
      summary.bricks = run->bricks;
    }
    if (!done)
      status = reportError(done.error());
    else if (!global.quiet)
      std::fprintf(stderr, "lic3d: wrote %s (%s, on %s%s)\n", options.output.c_str(),
                   fieldText(session.field, *inputs).c_str(), device.deviceInfo().name.c_str(),
                   run->bricks > 1 ? (", in " + std::to_string(run->bricks) + " bricks of " +
                                      gridText(run->brickCore) + " and ghost layers")
                                         .c_str()
                                   : "");
  }
  status = finish(device, status);
  if (status == kExitOk) {
    summary.device = device.deviceInfo().name;
    printSummary(global, summary, start);
  }
  return status;
}

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
  Result<Context> context = openContext(global);
  if (!context) return reportError(context.error());
  // An analytic field's grid is known before it is made: refuse what cannot fit first.
  if (parseEnum<AnalyticField>(session.field.field))
    if (auto r = checkRequestMemory(*context, session, session.field.grid,
                                    {.frame = true,
                                     .timeSeries = session.timeSteps > 0 && !options.cpu,
                                     .deviceCap = options.memoryBudget});
        !r)
      return finish(*context, reportError(r.error()));
  // The field is made on the device unless the host needs it: for the CPU LIC, colour or opacity
  // derived from the vectors, or the RGBA volume.
  Result<SessionInputs> inputs = loadInputs(
      options, !options.cpu && batch.rgbaVolume.empty() && !viewDerivesFromField(session.view));
  if (!inputs) return finish(*context, reportError(inputs.error()));
  if (auto r = checkOutputsAreNotInputs(batch, *plan); !r)
    return finish(*context, reportError(r.error()));
  reportFieldFile(global, session.field, *inputs);
  if (inputs->fromFile || inputs->series)
    if (auto r = checkRequestMemory(*context, session, inputs->field.dims,
                                    {.frame = true,
                                     .timeSeries = inputs->series && !options.cpu,
                                     .deviceCap = options.memoryBudget});
        !r)
      return finish(*context, reportError(r.error()));

  RunSummary summary = makeSummary("render", session.field, *inputs);
  int status = kExitOk;
  {
    // A picture and its RGBA volume appear together or not at all (a failure while the volume
    // is made leaves neither); an animation's frames each appear once complete, so a run stopped
    // half way keeps them.
    std::optional<OutputGroup> together;
    if (plan->animation == Animation::None) together.emplace();
    Result<LicRenderer> renderer = LicRenderer::create(*context, {session.precision});
    Result<void> done =
        renderer ? renderFrames(global, options, batch, *plan, *inputs, *renderer, summary.outputs)
                 : Result<void>(renderer.error());
    if (done && together) done = together->commit();
    together.reset();
    if (!done) {
      status = reportError(done.error());
    } else if (!global.quiet) {
      const int width = session.view.stereo == StereoMode::SideBySide ? 2 * session.view.width
                                                                      : session.view.width;
      const std::string what =
          plan->animation == Animation::None
              ? plan->output
              : std::to_string(plan->rendered()) + " frames " + summary.outputs.front() +
                    (plan->rendered() > 1 ? " .. " + framePath(plan->output, plan->end - 1) : "");
      std::fprintf(stderr, "lic3d: wrote %s (%dx%d, %s, on %s)\n", what.c_str(), width,
                   session.view.height, fieldText(session.field, *inputs).c_str(),
                   context->deviceInfo().name.c_str());
    }
    if (done) noteHiddenFraction(global, session.lic, renderer->hiddenFraction(), summary);
    if (renderer) {
      const StageTimer timer("teardown");
      const LicRenderer released = std::move(*renderer);
    }
  }
  status = finish(*context, status);
  if (status == kExitOk) {
    summary.frames = plan->rendered();
    summary.device = context->deviceInfo().name;
    printSummary(global, summary, start);
  }
  return status;
}

}  // namespace lic3d::cli
