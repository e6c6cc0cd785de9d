// SPDX-License-Identifier: BSD-3-Clause
// `lic3d compute`: the LIC volume (or one slice of it) of a field, in one piece or in bricks over
// one or more devices, read and written brick by brick where the files allow (docs/SCALE.md).
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <future>
#include <limits>
#include <map>
#include <mutex>
#include <optional>

#include "cli/command_support.h"
#include "cli/commands.h"
#include "cli/compute_vdb.h"
#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "gpu/device_choice.h"
#include "gpu/timer.h"
#include "gpu/vulkan_context.h"
#include "io/field_stream.h"
#include "io/file_util.h"
#include "io/png_writer.h"
#include "io/vdb_write.h"
#include "io/volume_stream.h"
#include "jobs/bricks.h"
#include "lic/analytic_fields.h"
#include "lic/colouring.h"
#include "lic/derived_fields.h"
#include "lic/field_plane.h"
#include "lic/lic2d_reference.h"
#include "lic/lic_reference.h"
#include "lic/time_series.h"
#include "loading/plane_inputs.h"
#include "loading/scalars.h"
#include "options/progress.h"
#include "passes/lic2d_pass.h"
#include "passes/time_blend_pass.h"
#include "render/lic_renderer.h"

namespace lic3d::cli {
namespace {

// compute's output: the volume (.nrrd, .vti, .raw; .vdb with `vdb`) or one slice (.png with
// --slice).
Result<void> writeComputeOutput(const ComputeOptions& options, std::optional<LicSlice> slice,
                                const ScalarVolume& volume, const VdbScalars* vdb) {
  if (vdb) return writeLicVdb(options.output, volume, *vdb);
  if (!slice) {
    StageTimer timer("volume write");
    LIC3D_TRY(writeLicVolumeFile(options.output, volume));
    timer.stop();
    addStageBytes("volume write", std::uint64_t{voxelCount(volume.dims)} * sizeof(float));
    return {};
  }
  return writeLicSlicePng(options.output, volume, *slice, options.inputs.session);
}

// A field file read brick by brick (io/field_stream.h) rather than whole: one in a format read by
// sub-extent (raw, raw NRRD, appended-raw VTI), at one time, with white noise and no
// --resolution, when it does not fit the device in one piece or the host could not hold it and
// its LIC. Nothing otherwise: the file is read whole, as its reader says.
std::optional<FieldStream> openFieldStream(const ComputeOptions& options,
                                           const std::vector<Context>& contexts) {
  const Session& session = options.inputs.session;
  // A .vdb is made from the whole volume and field on the host.
  if (parseEnum<AnalyticField>(session.field.field) || session.timeSteps > 0 ||
      !session.field.resolution.empty() || !isWhiteNoise(session.noise) ||
      isVdbOutput(options.output))
    return std::nullopt;
  Result<FieldStream> stream = FieldStream::open(session.field.field, session.field.array);
  if (!stream) return std::nullopt;
  const Dims dims = stream->dims();
  const bool fitsDevice =
      checkRequestMemory(contexts.front(), session, dims,
                         {.volumeReadback = true, .deviceCap = options.memoryBudget})
          .ok();
  // The field, its packed texels and the LIC volume, about 40 bytes a voxel.
  const bool fitsHost = voxelCount(dims) * 40 <= hostAvailableBytes();
  if (fitsDevice && fitsHost) return std::nullopt;
  return std::optional<FieldStream>(std::move(*stream));
}

// The LIC volume written into its file as it is read back, from every device at once (.nrrd,
// .raw or .vti): runs of voxels written in place, hidden voxels NaN, as writeLicVolumeFile writes
// them.
class StreamedOutput {
 public:
  static bool streams(const std::string& path) {
    const std::string extension = std::filesystem::path(path).extension().string();
    return extension == ".nrrd" || extension == ".raw" || extension == ".vti";
  }

  static Result<StreamedOutput> create(const std::string& path, Dims dims,
                                       const GridGeometry& geometry) {
    LIC3D_TRY_ASSIGN(ScalarVolumeStream stream, ScalarVolumeStream::create(path, dims, geometry));
    return StreamedOutput(std::move(stream));
  }

  // Where the read-back writes the voxels.
  const VoxelTarget& target() const { return target_; }

  Result<void> finish() { return stream_->finish(); }

 private:
  explicit StreamedOutput(ScalarVolumeStream stream)
      : stream_(std::make_unique<ScalarVolumeStream>(std::move(stream))) {
    target_.dims = stream_->dims();
    target_.writeStage = "volume write";
    target_.write = [stream = stream_.get()](std::uint64_t first, const float* values,
                                             std::size_t count) -> Result<void> {
      return stream->writeRun(first, values, count);
    };
  }

  std::unique_ptr<ScalarVolumeStream> stream_;
  VoxelTarget target_;
};

// The inputs, from `stream` (read once first for its largest speed, into `scan`) or read whole.
Result<SessionInputs> readComputeInputs(const GlobalOptions& global, const ComputeOptions& options,
                                        std::optional<FieldStream>& stream,
                                        std::optional<StreamScan>& scan) {
  // The speed grid of a .vdb needs the field on the host.
  if (!stream) return loadInputs(options, !options.cpu && !isVdbOutput(options.output));
  {
    Progress progress("reading " + stream->path().string() + " (" + gridText(stream->dims()) +
                          ") for its largest speed",
                      global.quiet);
    LIC3D_TRY_ASSIGN(const StreamScan scanned,
                     scanFieldStream(*stream, [&](double f) { progress.update(f); }));
    progress.finish();
    scan = scanned;
  }
  return streamedInputs(*stream, options.inputs.session, *scan);
}

// --slice's index against the grid, before any work.
Result<void> checkSliceIndex(const std::optional<LicSlice>& slice, Dims dims) {
  if (!slice) return {};
  const std::string axis(1, static_cast<char>('x' + slice->axis));
  const std::string text = axis + ":" + std::to_string(slice->index);
  if (slice->index >= dims[slice->axis])
    return inputError("--slice " + text + ": the grid " + gridText(dims) + " has " +
                      std::to_string(dims[slice->axis]) + " slices along " + axis + " (0.." +
                      std::to_string(dims[slice->axis] - 1) + ")");
  return {};
}

// The bytes compute's output takes: a volume's are known (float32 a voxel and its header or
// sidecar); a slice PNG's are bounded (pngSizeBound, 2 bytes a pixel, with the session's text and
// 1 KiB for the slice it records).
OutputBytes outputBytes(const ComputeOptions& options, const std::optional<LicSlice>& slice,
                        Dims dims) {
  // A .vdb holds at most three float grids (LIC, speed, a colour scalar).
  if (isVdbOutput(options.output)) return {options.output, vdbFileBytesBound(dims, 3), true};
  if (!slice) return {options.output, volumeFileBytes(dims, sizeof(float))};
  const int across = slice->axis == 0 ? 1 : 0;
  const int up = slice->axis == 2 ? 1 : 2;
  const Result<PngText> text = pngText(options.inputs.session, options.output);
  return {options.output, pngSizeBound(dims[across], dims[up], 2, text ? *text : PngText{}) + 1024,
          true};
}

// compute --cpu: the CPU reference at the session's time, then the output.
int computeOnHost(const GlobalOptions& global, const ComputeOptions& options,
                  const std::optional<LicSlice>& slice, SessionInputs& inputs,
                  const VdbScalars* vdb, RunSummary& summary, Clock::time_point start) {
  const Session& session = options.inputs.session;
  if (inputs.series) {
    Result<VectorField> field = hostFieldAt(inputs, session, session.time);
    if (!field) return reportError(field.error());
    inputs.field = std::move(*field);
    inputs.fieldStep.reset();
  }
  const Result<ScalarVolume> volume = computeOnCpu(inputs, session.lic, global.quiet);
  if (!volume) return reportError(volume.error());
  if (auto r = writeComputeOutput(options, slice, *volume, vdb); !r) return reportError(r.error());
  if (!global.quiet)
    std::fprintf(stderr, "lic3d: wrote %s (%s, on the CPU)\n", options.output.c_str(),
                 fieldText(session.field, inputs).c_str());
  noteHiddenFraction(global, session.lic, hiddenFractionOf(*volume), summary);
  summary.device = "CPU reference";
  printSummary(global, summary, start);
  return kExitOk;
}

// The LIC volume on the devices, in one piece when it fits the device (or --memory-budget),
// else in bricks, then the output; the exit status before the devices are finished.
int computeOnDevices(const GlobalOptions& global, const ComputeOptions& options,
                     const std::optional<LicSlice>& slice, const std::vector<Context>& contexts,
                     FieldStream* stream, const StreamScan* scan, SessionInputs& inputs,
                     const VdbScalars* vdb, RunSummary& summary) {
  const Session& session = options.inputs.session;
  const std::string deviceNames = devicesText(contexts);
  Progress progress("LIC " + gridText(inputs.field.dims) + " on " + deviceNames, global.quiet);
  // The voxels go straight into a .nrrd or .raw output as they are read back, so that the host
  // never holds the volume.
  std::optional<StreamedOutput> streamed;
  if (!slice && StreamedOutput::streams(options.output)) {
    Result<StreamedOutput> made =
        StreamedOutput::create(options.output, inputs.field.dims, inputs.field.geometry);
    if (!made) return reportError(made.error());
    streamed.emplace(std::move(*made));
  }
  LicVolumeOptions how{.deviceCap = options.memoryBudget, .stream = stream, .scan = scan};
  if (streamed) how.target = &streamed->target();
  how.stage = [&](const std::string& stage) { progress.stage(stage); };
  Result<LicVolumeRun> run = computeLicVolume(pointersTo(contexts), session, inputs, how,
                                              [&](double f) { progress.update(f); });
  if (run) {
    progress.finish();
  } else {
    progress.cancel();
  }
  Result<void> done = !run       ? Result<void>(run.error())
                      : streamed ? streamed->finish()
                                 : writeComputeOutput(options, slice, run->volume, vdb);
  if (!done) return reportError(done.error());
  const bool sparse = session.lic.sparsity.distribution != SparsityDistribution::None;
  const std::optional<double> hidden =
      !sparse ? std::nullopt
              : std::optional<double>(1.0 - static_cast<double>(run->drawnVoxels) /
                                                static_cast<double>(voxelCount(inputs.field.dims)));
  noteHiddenFraction(global, session.lic, hidden, summary);
  summary.bricks = run->bricks;
  summary.shares = run->devices;
  if (!global.quiet)
    std::fprintf(stderr, "lic3d: wrote %s (%s, on %s%s)\n", options.output.c_str(),
                 fieldText(session.field, inputs).c_str(), deviceNames.c_str(),
                 run->bricks > 1 ? (", in " + std::to_string(run->bricks) + " bricks of " +
                                    gridText(run->brickCore) + " and ghost layers")
                                       .c_str()
                                 : "");
  return kExitOk;
}

}  // namespace

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
  std::vector<Context> contexts;
  if (!options.cpu) {
    Result<std::vector<Context>> opened = openContexts(global, options.devices);
    if (!opened) return reportError(opened.error());
    contexts = std::move(*opened);
    const bool bricked = session.timeSteps == 0 && isWhiteNoise(session.noise);
    if (parseEnum<AnalyticField>(session.field.field) && !bricked)
      if (auto r = checkRequestMemory(contexts.front(), session, session.field.grid,
                                      {.volumeReadback = true,
                                       .timeSeries = session.timeSteps > 0,
                                       .deviceCap = options.memoryBudget});
          !r)
        return finish(contexts, reportError(r.error()));
  } else if (!options.devices.empty()) {
    return reportError(
        inputError("--devices " + options.devices + ": --cpu computes on the CPU, not on devices"));
  }
  auto fail = [&](const Error& error) { return finish(contexts, reportError(error)); };
  // A file too large for the device or the host in one piece is read brick by brick.
  std::optional<FieldStream> stream;
  std::optional<StreamScan> scan;
  if (!options.cpu) stream = openFieldStream(options, contexts);
  // The output's free space as soon as its grid is known: an analytic field's, or a file's read
  // brick by brick (from its header, before the scan); any other file's once it is read.
  const std::optional<Dims> knownGrid = parseEnum<AnalyticField>(session.field.field)
                                            ? std::optional<Dims>(session.field.grid)
                                        : stream ? std::optional<Dims>(stream->dims())
                                                 : std::nullopt;
  if (knownGrid)
    if (auto r = checkFreeSpace({outputBytes(options, *slice, *knownGrid)}); !r)
      return fail(r.error());
  Result<SessionInputs> inputs = readComputeInputs(global, options, stream, scan);
  if (!inputs) return fail(inputs.error());
  if (auto r = checkNotAnInput(options.output); !r) return fail(r.error());
  if (lowerCaseExtension(options.output) == ".raw")
    if (auto r = checkRawSidecarReplaceable(options.output); !r) return fail(r.error());
  reportFieldFile(global, session.field, *inputs);
  if (auto r = checkSliceIndex(*slice, inputs->field.dims); !r) return fail(r.error());
  if (!knownGrid)
    if (auto r = checkFreeSpace({outputBytes(options, *slice, inputs->field.dims)}); !r)
      return fail(r.error());
  // The grids of a .vdb besides the LIC, before the work.
  std::optional<VdbScalars> vdb;
  if (isVdbOutput(options.output)) {
    Result<VdbScalars> loaded = loadVdbScalars(options, *inputs);
    if (!loaded) return fail(fromSessionFile(loaded.error(), options.inputs));
    vdb = std::move(*loaded);
  }
  const VdbScalars* vdbScalars = vdb ? &*vdb : nullptr;
  RunSummary summary = makeSummary("compute", session.field, *inputs);
  summary.readByBricks = stream.has_value();
  summary.outputs = {options.output};

  if (options.cpu)
    return computeOnHost(global, options, *slice, *inputs, vdbScalars, summary, start);

  const Context& device = contexts.front();
  int status = computeOnDevices(global, options, *slice, contexts, stream ? &*stream : nullptr,
                                scan ? &*scan : nullptr, *inputs, vdbScalars, summary);
  status = finish(contexts, status);
  if (status == kExitOk) {
    summary.device = device.deviceInfo().name;
    printSummary(global, summary, start);
  }
  return status;
}

}  // namespace lic3d::cli
