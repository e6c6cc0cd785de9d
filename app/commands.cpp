#include "commands.h"

#include <chrono>
#include <cstdio>
#include <optional>

#include "analytic_fields.h"
#include "file_util.h"
#include "lic_reference.h"
#include "lic_renderer.h"
#include "progress.h"
#include "vulkan_context.h"

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

std::string gridText(Dims d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

std::string tripleText(glm::dvec3 v) {
  return formatDouble(v.x) + "," + formatDouble(v.y) + "," + formatDouble(v.z);
}

struct Inputs {
  VectorField field;
  NoiseVolume noise;
  FieldReadInfo info;  // of a file field
  bool fromFile = false;
};

Result<Inputs> loadInputs(const ComputeOptions& options) {
  const Session& session = options.inputs.session;
  LIC3D_TRY(validate(session.lic));
  Inputs inputs;
  LIC3D_TRY_ASSIGN(inputs.field,
                   loadField(session.field, options.inputs.grid.given(), &inputs.info));
  inputs.fromFile = !parseAnalyticField(session.field.field).has_value();
  LIC3D_TRY(validate(session.lic.sparsity, inputs.field.dims));
  LIC3D_TRY_ASSIGN(inputs.noise, loadNoise(session.noise, inputs.field.dims));
  return inputs;
}

// What a file gave besides the field: which of several arrays was read, and vectors lost to NaN.
void reportFieldFile(const GlobalOptions& global, const FieldSource& source, const Inputs& inputs) {
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
std::string fieldText(const FieldSource& source, const Inputs& inputs) {
  const VectorField& field = inputs.field;
  if (!inputs.fromFile) return source.field + " " + gridText(field.dims);
  std::string text = source.field;
  if (!inputs.info.arrayName.empty()) text += " array '" + inputs.info.arrayName + "'";
  return text + " " + gridText(field.dims) + ", spacing " + tripleText(field.geometry.spacing) +
         ", origin " + tripleText(field.geometry.origin);
}

RunSummary makeSummary(const char* command, const FieldSource& source, const Inputs& inputs) {
  RunSummary summary;
  summary.command = command;
  summary.field = source.field;
  summary.array = inputs.info.arrayName;
  summary.grid = inputs.field.dims;
  summary.geometry = inputs.field.geometry;
  summary.nonFiniteVectors = inputs.info.nonFiniteVectors;
  return summary;
}

void printSummary(const GlobalOptions& global, RunSummary summary, Clock::time_point start) {
  if (global.quiet) return;
  summary.seconds = secondsSince(start);
  std::printf("%s\n", summaryLine(summary).c_str());
  std::fflush(stdout);
}

Result<ScalarVolume> computeOnCpu(const Inputs& inputs, const LicParams& lic, bool quiet) {
  Progress progress("LIC " + gridText(inputs.field.dims) + " on the CPU", quiet);
  return computeLicReference(inputs.field, inputs.noise, lic, 0,
                             [&](double f) { progress.update(f); });
}

// Makes the renderer's LIC volume the one of `lic`, on the GPU or (with --cpu) the CPU, unless it
// already is.
Result<void> makeLicVolume(const ComputeOptions& options, const Inputs& inputs,
                           const LicParams& lic, LicRenderer& renderer, bool quiet) {
  if (renderer.shownParams() && *renderer.shownParams() == lic) return {};
  if (options.cpu) {
    LIC3D_TRY_ASSIGN(const ScalarVolume volume, computeOnCpu(inputs, lic, quiet));
    return renderer.setLicVolume(volume, lic);
  }
  Progress progress("LIC " + gridText(inputs.field.dims) + " on the GPU", quiet);
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran,
                   renderer.updateLic(lic, [&](double f) { progress.update(f); }));
  return {};
}

// compute's output: the volume (.nrrd, .vti) or one slice (.png with --slice).
Result<void> writeComputeOutput(const ComputeOptions& options, const BatchOptions& batch,
                                const ScalarVolume& volume) {
  if (!batch.slice.given()) return writeLicVolumeFile(options.output, volume);
  LIC3D_TRY_ASSIGN(const LicSlice slice, parseSlice(batch.slice.text));
  return writeLicSlicePng(options.output, volume, slice, options.inputs.session);
}

// The frames of `plan` (one picture without an animation), then the RGBA volume and the video.
Result<void> renderFrames(const GlobalOptions& global, const ComputeOptions& options,
                          const BatchOptions& batch, const FramePlan& plan, const Inputs& inputs,
                          LicRenderer& renderer, std::vector<std::string>& outputs) {
  const Session& session = options.inputs.session;
  const bool animated = plan.animation != Animation::None;
  LIC3D_TRY(renderer.setInputs(inputs.field, inputs.noise));
  // A bias cycle recomputes the volume every frame: the frame lines report that progress.
  if (plan.animation != Animation::Bias)
    LIC3D_TRY(makeLicVolume(options, inputs, session.lic, renderer, global.quiet));

  FrameProgress progress(plan.rendered(), global.quiet || !animated);
  for (int frame = plan.first; frame < plan.end; ++frame) {
    const Session frameParams = frameSession(session, plan, frame);
    LIC3D_TRY(makeLicVolume(options, inputs, frameParams.lic, renderer, true));
    LIC3D_TRY_ASSIGN(const RgbaImage image, renderer.render(frameParams.lic, frameParams.view));
    const std::string path = animated ? framePath(plan.output, frame) : plan.output;
    LIC3D_TRY_ASSIGN(const PngText text, pngText(frameParams));
    LIC3D_TRY(writePng(path, image, text));
    outputs.push_back(path);
    progress.frameDone(frame);
  }
  progress.finish();

  if (!batch.rgbaVolume.empty()) {
    LIC3D_TRY_ASSIGN(const ScalarVolume lic, renderer.readLicVolume());
    const RgbaVolume rgba =
        colourLicVolume(lic, inputs.field, session.view, renderer.volumeFacts());
    LIC3D_TRY(writeRgbaVolumeFile(batch.rgbaVolume, rgba));
    outputs.push_back(batch.rgbaVolume);
  }
  if (!batch.video.empty()) {
    LIC3D_TRY_ASSIGN(const std::filesystem::path ffmpeg, findFfmpeg());
    if (!global.quiet)
      std::fprintf(stderr, "lic3d: encoding %s with %s\n", batch.video.c_str(),
                   ffmpeg.c_str());
    LIC3D_TRY(encodeVideo(ffmpeg, plan, batch.fps, batch.video));
    outputs.push_back(batch.video);
  }
  return {};
}

}  // namespace

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
  if (auto r = checkComputeOutput(options.output, batch); !r) return reportError(r.error());
  if (batch.slice.given())
    if (auto r = pngText(session); !r) return reportError(r.error());
  // On the GPU, the device comes first, so that an analytic field too large for it is refused
  // before it is made.
  std::optional<Result<Context>> context;
  if (!options.cpu) {
    context.emplace(openContext(global));
    if (!*context) return reportError(context->error());
    if (parseAnalyticField(session.field.field))
      if (auto r = checkRequestMemory(**context, session, session.field.grid,
                                      {.volumeReadback = true});
          !r)
        return finish(**context, reportError(r.error()));
  }
  auto fail = [&](const Error& error) {
    const int status = reportError(error);
    return context ? finish(**context, status) : status;
  };
  Result<Inputs> inputs = loadInputs(options);
  if (!inputs) return fail(inputs.error());
  reportFieldFile(global, session.field, *inputs);
  if (batch.slice.given()) {
    // The index against the grid, before any work.
    const LicSlice slice = *parseSlice(batch.slice.text);
    if (slice.index >= inputs->field.dims[slice.axis])
      return fail(inputError(
          "--slice " + batch.slice.text + ": the grid " + gridText(inputs->field.dims) +
          " has " + std::to_string(inputs->field.dims[slice.axis]) + " slices along " +
          std::string(1, static_cast<char>('x' + slice.axis)) + " (0.." +
          std::to_string(inputs->field.dims[slice.axis] - 1) + ")"));
  }
  RunSummary summary = makeSummary("compute", session.field, *inputs);
  summary.outputs = {options.output};

  if (options.cpu) {
    const Result<ScalarVolume> volume = computeOnCpu(*inputs, session.lic, global.quiet);
    if (!volume) return reportError(volume.error());
    if (auto r = writeComputeOutput(options, batch, *volume); !r) return reportError(r.error());
    if (!global.quiet)
      std::fprintf(stderr, "lic3d: wrote %s (%s, on the CPU)\n", options.output.c_str(),
                   fieldText(session.field, *inputs).c_str());
    summary.device = "CPU reference";
    printSummary(global, summary, start);
    return kExitOk;
  }

  Context& device = **context;
  // A file's grid is known once it is read (an analytic one was checked above).
  if (inputs->fromFile)
    if (auto r = checkRequestMemory(device, session, inputs->field.dims, {.volumeReadback = true});
        !r)
      return fail(r.error());
  int status = kExitOk;
  {
    Result<LicRenderer> renderer = LicRenderer::create(device, {session.precision});
    Result<void> done = renderer ? renderer->setInputs(inputs->field, inputs->noise)
                                 : Result<void>(renderer.error());
    if (done) done = makeLicVolume(options, *inputs, session.lic, *renderer, global.quiet);
    Result<ScalarVolume> volume =
        done ? renderer->readLicVolume() : Result<ScalarVolume>(done.error());
    if (volume) done = writeComputeOutput(options, batch, *volume);
    else done = volume.error();
    if (!done) status = reportError(done.error());
    else if (!global.quiet)
      std::fprintf(stderr, "lic3d: wrote %s (%s, on %s)\n", options.output.c_str(),
                   fieldText(session.field, *inputs).c_str(), device.deviceInfo().name.c_str());
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
  const Result<FramePlan> plan = planFrames(batch, options);
  if (!plan) return reportError(plan.error());
  if (auto r = checkRenderOutputs(batch, *plan, session); !r) return reportError(r.error());
  Result<Context> context = openContext(global);
  if (!context) return reportError(context.error());
  // An analytic field's grid is known before it is made: refuse what cannot fit first.
  if (parseAnalyticField(session.field.field))
    if (auto r = checkRequestMemory(*context, session, session.field.grid, {.frame = true}); !r)
      return finish(*context, reportError(r.error()));
  Result<Inputs> inputs = loadInputs(options);
  if (!inputs) return finish(*context, reportError(inputs.error()));
  reportFieldFile(global, session.field, *inputs);
  if (inputs->fromFile)
    if (auto r = checkRequestMemory(*context, session, inputs->field.dims, {.frame = true}); !r)
      return finish(*context, reportError(r.error()));

  RunSummary summary = makeSummary("render", session.field, *inputs);
  int status = kExitOk;
  {
    Result<LicRenderer> renderer = LicRenderer::create(*context, {session.precision});
    const Result<void> done =
        renderer ? renderFrames(global, options, batch, *plan, *inputs, *renderer, summary.outputs)
                 : Result<void>(renderer.error());
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
