// SPDX-License-Identifier: BSD-3-Clause
#include "jobs/bricks.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <mutex>
#include <string>
#include <thread>

#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "lic/field_piece.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"

namespace lic3d {

std::vector<Brick> planBricks(Dims whole, Dims core, int ghost) {
  std::vector<Brick> bricks;
  for (int z = 0; z < whole.z; z += core.z)
    for (int y = 0; y < whole.y; y += core.y)
      for (int x = 0; x < whole.x; x += core.x) {
        Brick brick;
        brick.ownOffset = {x, y, z};
        brick.ownDims = glm::min(core, whole - brick.ownOffset);
        const Dims low = glm::max(brick.ownOffset - Dims(ghost), Dims(0));
        const Dims high = glm::min(brick.ownOffset + brick.ownDims + Dims(ghost), whole);
        brick.offset = low;
        brick.dims = high - low;
        bricks.push_back(brick);
      }
  return bricks;
}

int axisToHalve(Dims core, int ghost) {
  if (core.z / 2 >= std::max(kMinSlabLayers, 4 * ghost)) return 2;
  int longest = 0;
  for (int a = 1; a < 3; ++a)
    if (core[a] > core[longest]) longest = a;
  return longest;
}

Dims splitCoreForDevices(Dims whole, Dims core, int count, int ghost) {
  const auto bricksOf = [&](Dims c) {
    const Dims n = (whole + c - Dims(1)) / c;
    return static_cast<std::int64_t>(n.x) * n.y * n.z;
  };
  while (bricksOf(core) < count && core != Dims(1)) {
    const int axis = axisToHalve(core, ghost);
    core[axis] = (core[axis] + 1) / 2;
  }
  return core;
}

std::optional<Dims> chooseBrickCore(Dims whole, int ghost,
                                    const std::function<bool(Dims brick)>& fits) {
  Dims core = whole;
  for (;;) {
    const Dims brick = glm::min(core + Dims(2 * ghost), whole);
    if (fits(brick)) return core;
    if (core == Dims(1)) return std::nullopt;
    const int axis = axisToHalve(core, ghost);
    core[axis] = (core[axis] + 1) / 2;
  }
}

void copyOwnVoxels(const Brick& brick, const ScalarVolume& lic, ScalarVolume& result) {
  if (!lic.drawn.empty() && result.drawn.empty()) result.drawn.assign(result.values.size(), 1);
  const Dims from = brick.ownOffset - brick.offset;
  // The brick's own rows into the result, the layers on the available threads.
  parallelFor(static_cast<std::size_t>(brick.ownDims.z), 0, [&](std::size_t layer) {
    const int k = static_cast<int>(layer);
    for (int j = 0; j < brick.ownDims.y; ++j) {
      const std::size_t at = voxelIndex(lic.dims, from.x, from.y + j, from.z + k);
      const std::size_t to =
          voxelIndex(result.dims, brick.ownOffset.x, brick.ownOffset.y + j, brick.ownOffset.z + k);
      std::copy_n(&lic.values[at], brick.ownDims.x, &result.values[to]);
      if (!lic.drawn.empty()) std::copy_n(&lic.drawn[at], brick.ownDims.x, &result.drawn[to]);
    }
  });
}

namespace {

ScalarVolume emptyResult(Dims dims, const GridGeometry& geometry) {
  ScalarVolume result;
  result.dims = dims;
  result.geometry = geometry;
  result.values.resize(voxelCount(dims));
  return result;
}

Result<void> checkWhiteNoise(const NoiseSource& noise) {
  if (!noise.file.empty() || noise.seedSpots > 0 || noise.seedFraction > 0.0f)
    return parameterError("noise.file",
                          "a LIC made in bricks takes the seeded white noise of the whole grid; "
                          "a noise file or seed noise must fit the device whole");
  return {};
}

}  // namespace

Result<ScalarVolume> computeBricked(const VectorField& whole, const NoiseSource& noise,
                                    const std::vector<Brick>& bricks, const PieceLic& licOf,
                                    const ProgressCallback& progress) {
  LIC3D_TRY(checkWhiteNoise(noise));
  const double maxSpeed = maxVoxelSpeedOverVoxels(whole);
  ScalarVolume result = emptyResult(whole.dims, whole.geometry);
  BrickJobs jobs;
  jobs.prepare = [&](const Brick& brick) -> Result<PieceInputs> {
    LIC3D_TRY_ASSIGN(VectorField piece, cutFieldPiece(whole, brick.offset, brick.dims, maxSpeed));
    return PieceInputs{std::move(piece),
                       makeWhiteNoisePiece(whole.dims, brick.offset, brick.dims, noise.seed)};
  };
  jobs.lic = [&](int, const Brick&, std::optional<PieceInputs> in) {
    return licOf(in->field, in->noise);
  };
  jobs.take = [&](const Brick& brick, const ScalarVolume& lic) -> Result<void> {
    copyOwnVoxels(brick, lic, result);
    return {};
  };
  LIC3D_TRY(runBricks(1, bricks, jobs, progress));
  return result;
}

Result<std::vector<int>> runBricks(int workers, const std::vector<Brick>& bricks,
                                   const BrickJobs& jobs, const ProgressCallback& progress) {
  std::vector<int> workerOf(bricks.size(), -1);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  std::mutex mutex;  // guards `take`, the progress and the first error
  std::optional<Error> failure;
  std::size_t done = 0;
  const auto fail = [&](Error error) {
    const std::lock_guard lock(mutex);
    if (!failure) failure = std::move(error);
    stop = true;
  };
  const auto claim = [&]() -> std::optional<std::size_t> {
    if (stop || progress.stopRequested()) return std::nullopt;
    const std::size_t b = next++;
    return b < bricks.size() ? std::optional(b) : std::nullopt;
  };
  using Prepared = Result<std::optional<PieceInputs>>;
  const auto prepare = [&](std::size_t b) {
    return std::async(std::launch::async, [&jobs, &brick = bricks[b]]() -> Prepared {
      if (!jobs.prepare) return std::optional<PieceInputs>();
      LIC3D_TRY_ASSIGN(PieceInputs in, jobs.prepare(brick));
      return std::optional<PieceInputs>(std::move(in));
    });
  };
  const auto work = [&](int worker) {
    std::optional<std::size_t> current = claim();
    if (!current) return;
    std::future<Prepared> prepared = prepare(*current);
    while (current) {
      Prepared inputs = prepared.get();
      if (progress.stopRequested()) return;  // not even the brick claimed before the stop
      // The next brick's inputs are made while this one is on the device.
      const std::optional<std::size_t> following = claim();
      if (following) prepared = prepare(*following);
      const Brick& brick = bricks[*current];
      Result<ScalarVolume> lic = inputs ? jobs.lic(worker, brick, std::move(*inputs))
                                        : Result<ScalarVolume>(inputs.error());
      if (!lic) return fail(lic.error());
      if (jobs.take && jobs.takeAtOnce)
        if (Result<void> taken = jobs.take(brick, *lic); !taken) return fail(taken.error());
      {
        const std::lock_guard lock(mutex);
        if (failure) return;
        if (jobs.take && !jobs.takeAtOnce)
          if (Result<void> taken = jobs.take(brick, *lic); !taken) {
            failure = taken.error();
            stop = true;
            return;
          }
        workerOf[*current] = worker;
        ++done;
        if (progress) progress(static_cast<double>(done) / static_cast<double>(bricks.size()));
      }
      current = following;
    }
  };
  if (workers <= 1) {
    work(0);
  } else {
    std::vector<std::thread> threads;
    for (int w = 0; w < workers; ++w) threads.emplace_back(work, w);
    for (std::thread& thread : threads) thread.join();
  }
  if (failure) return *failure;
  if (done < bricks.size()) return cancelledError();  // stopped before every brick was made
  return workerOf;
}

namespace {

// The host holds, besides what is loaded, the field where it is made here (an analytic one), the
// whole LIC volume (and its drawn mask with sparsity) unless a target takes the voxels, and per
// device two bricks at a time: at most while a brick's texels are packed into the staging buffer
// and the next brick's inputs are read: two bricks' field (12 bytes a voxel) and noise (1), and
// the staging texels (16 as RGBA32F, 8 as RGBA16F). A brick's read-back goes through the
// device's staging ring (3 x 128 MiB, gpu/readback.h) straight into the target: nothing a voxel.
// A brick made on the device holds nothing a voxel on the host.
constexpr std::uint64_t kBrickHostBytes = 2 * (12 + 1) + 16;

struct BrickedHost {
  bool fieldMadeHere = false;  // an analytic field sampled on the host, cut into bricks
  bool fieldOnHost = false;    // a field on the host at all (not made on the device)
  bool wholeResult = true;     // the LIC volume assembled on the host (no sink)
  int devices = 1;
};

// Host bytes a voxel of the whole grid and of a brick in flight take.
struct HostShare {
  std::uint64_t perVoxel = 0;
  std::uint64_t perBrickVoxel = 0;
};

HostShare hostShare(const Session& session, const BrickedHost& host) {
  const bool sparse = session.lic.sparsity.distribution != SparsityDistribution::None;
  return {(host.fieldMadeHere ? 12u : 0u) + (host.wholeResult ? 4u + (sparse ? 1u : 0u) : 0u),
          (host.fieldOnHost ? kBrickHostBytes : 0u) * static_cast<std::uint64_t>(host.devices)};
}

std::uint64_t hostBytes(const HostShare& share, Dims dims, Dims brick) {
  return voxelCount(dims) * share.perVoxel + voxelCount(brick) * share.perBrickVoxel;
}

Result<void> checkBrickedHostMemory(const Session& session, Dims dims,
                                    const std::vector<Brick>& bricks, const BrickedHost& host) {
  const HostShare share = hostShare(session, host);
  const std::uint64_t perVoxel = share.perVoxel;
  const std::uint64_t perBrick = share.perBrickVoxel;
  Dims largest{0};
  for (const Brick& brick : bricks)
    if (voxelCount(brick.dims) > voxelCount(largest)) largest = brick.dims;
  const std::uint64_t needed = hostBytes(share, dims, largest);
  const std::uint64_t available = hostAvailableBytes();
  if (needed <= available) return {};
  // About the same share of bricks for a cube: the whole grid's bytes dominate.
  const int cube = static_cast<int>(
      std::cbrt(static_cast<double>(available) / static_cast<double>(perVoxel + perBrick / 8)));
  return resourceLimitError(
      "the LIC of " + session.field.field + " (" + gridText(dims) + ") in " +
      std::to_string(bricks.size()) + " bricks needs " + std::to_string(needed >> 20) +
      " MiB of host memory (the field, the LIC volume and the bricks in flight); " +
      std::to_string(available >> 20) + " MiB are available; the largest cubic grid that fits is " +
      std::to_string(cube) + "^3");
}

using Clock = std::chrono::steady_clock;

// Layers per slab of a stream's scan: about 256 MiB of vectors each, read by all threads (the
// one slab buffer the scan holds).
int scanLayers(Dims dims) {
  const std::uint64_t layer =
      std::uint64_t{12} * static_cast<std::uint64_t>(dims.x) * static_cast<std::uint64_t>(dims.y);
  return static_cast<int>(
      std::clamp<std::uint64_t>((std::uint64_t{256} << 20) / layer, 1, std::max(dims.z, 1)));
}

// The progress of a bricked run from any worker, one call at a time: the bricks done and the part
// of each worker's brick under way; and the stages by name.
class BrickReport {
 public:
  BrickReport(std::size_t bricks, std::size_t workers, const ProgressCallback& progress,
              const std::function<void(const std::string&)>& stage)
      : bricks_(bricks), partial_(workers, 0.0), progress_(progress), stage_(stage) {}

  void stage(const std::string& text) {
    const std::lock_guard lock(mutex_);
    if (stage_) stage_(text);
  }
  void brickStage(std::size_t brick, const std::string& text) {
    stage("brick " + std::to_string(brick + 1) + " of " + std::to_string(bricks_) + ": " + text);
  }
  // The worker's brick is `fraction` done (0 again once its LIC is read back).
  void partial(int worker, double fraction) {
    const std::lock_guard lock(mutex_);
    partial_[static_cast<std::size_t>(worker)] = fraction;
    if (fraction > 0.0) report();
  }
  void brickDone() {
    const std::lock_guard lock(mutex_);
    ++done_;
    report();
  }

 private:
  void report() {
    if (!progress_) return;
    double under = 0.0;
    for (const double part : partial_) under += part;
    progress_(std::min(1.0, (static_cast<double>(done_) + under) / static_cast<double>(bricks_)));
  }

  std::mutex mutex_;
  std::size_t bricks_;
  std::size_t done_ = 0;
  std::vector<double> partial_;
  const ProgressCallback& progress_;
  const std::function<void(const std::string&)>& stage_;
};

// A LIC dispatch (timed with GPU timestamps when asked), its region [from, from + extent) read
// back into `target` at `at`; `progress` follows the dispatch (untimed only). Returns the
// region's drawn voxels.
Result<std::uint64_t> licOnDevice(const Context& context, LicRenderer& renderer,
                                  const LicParams& params, bool timed, DeviceShare& share,
                                  Dims from, Dims extent, const VoxelTarget& target, Dims at,
                                  const ProgressCallback& progress = {}) {
  if (timed) {
    GpuTimer timer;
    if (context.supportsTimestamps()) {
      LIC3D_TRY_ASSIGN(timer, GpuTimer::create(context, 1, "lic timestamps"));
    }
    LIC3D_TRY_ASSIGN(
        const double milliseconds,
        timeLicDispatch(context, renderer.licJob(), renderer.fieldTextures(), timer, params));
    share.licMilliseconds += milliseconds;
  } else {
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer.updateLic(params, progress));
  }
  const Clock::time_point start = Clock::now();
  const ReadbackRing& ring = renderer.licJob().readback();
  const double waited = ring.waitSeconds(), used = ring.useSeconds();
  LIC3D_TRY_ASSIGN(const std::uint64_t drawn, renderer.readLicInto(from, extent, target, at));
  share.readbackSeconds += secondsSince(start);
  share.readbackWaitSeconds += ring.waitSeconds() - waited;
  share.convertSeconds += ring.useSeconds() - used;
  share.readbackBytes += voxelCount(extent) * 4;
  return drawn;
}

}  // namespace

Result<StreamScan> scanFieldStream(const FieldStream& stream, const ProgressCallback& progress) {
  const StageTimer timer("field scan");
  const Dims dims = stream.dims();
  const int layers = scanLayers(dims);
  const int slabs = (dims.z + layers - 1) / layers;
  const glm::dvec3 scale = voxelUnitScale(stream.geometry());
  std::mutex mutex;  // guards `scan`
  StreamScan scan;
  // The slabs in turn, each read by all threads; each part measured by the thread that read it,
  // while it is in cache. The largest values are the same in any order.
  VectorField slab;
  const FieldStream::RunVisitor measure = [&](const glm::vec3* vectors, std::size_t count) {
    const double speed = maxVoxelSpeedOf(vectors, count, scale);
    double magnitude = 0.0;
    for (std::size_t i = 0; i < count; ++i)
      magnitude = std::max(magnitude, static_cast<double>(glm::length(vectors[i])));
    const std::lock_guard lock(mutex);
    scan.maxVoxelSpeed = std::max(scan.maxVoxelSpeed, speed);
    scan.maxMagnitude = std::max(scan.maxMagnitude, magnitude);
  };
  for (int s = 0; s < slabs; ++s) {
    const int z = s * layers;
    std::uint64_t nonFinite = 0;
    LIC3D_TRY(stream.readPieceInto({0, 0, z}, {dims.x, dims.y, std::min(layers, dims.z - z)}, slab,
                                   &nonFinite, measure));
    scan.nonFinite += nonFinite;
    if (progress) progress(static_cast<double>(s + 1) / static_cast<double>(slabs));
  }
  if (scan.maxMagnitude == 0.0)
    return inputError(stream.path().string() + ": every vector is zero; there is no flow to show");
  return scan;
}

SessionInputs streamedInputs(const FieldStream& stream, const Session& session,
                             const StreamScan& scan) {
  SessionInputs inputs;
  inputs.fromFile = true;
  inputs.field.dims = stream.dims();
  inputs.field.geometry = stream.geometry();
  inputs.field.unit = stream.unit();
  inputs.noise.dims = stream.dims();
  inputs.info.nonFiniteVectors = static_cast<std::size_t>(scan.nonFinite);
  inputs.info.arrayName = stream.arrayName();
  inputs.time = session.time;
  return inputs;
}

namespace {

// The LIC of the whole grid on the first device, in one piece, into `target`.
Result<void> computeWhole(const Context& context, const Session& session, SessionInputs& inputs,
                          const LicVolumeOptions& options, const VoxelTarget& target,
                          const ProgressCallback& progress, LicVolumeRun& run) {
  const Clock::time_point start = Clock::now();
  std::optional<LicRenderer> made;
  if (!options.renderer) {
    LIC3D_TRY_ASSIGN(made, LicRenderer::create(context, {session.precision}));
    LIC3D_TRY(moveToTime(inputs, session, session.time, *made, true));
  }
  LicRenderer& renderer = options.renderer ? *options.renderer : *made;
  DeviceShare& share = run.devices[0];
  const Dims dims = inputs.field.dims;
  LIC3D_TRY_ASSIGN(run.drawnVoxels, licOnDevice(context, renderer, session.lic, options.timeLic,
                                                share, Dims(0), dims, target, Dims(0), progress));
  share.bricks = 1;
  share.voxels = voxelCount(dims);
  share.seconds = secondsSince(start);
  share.peakDeviceBytes = context.allocatedBytes();
  run.brickCore = dims;
  run.devices.resize(1);
  return {};
}

// The largest brick core that every device and the host can hold beside the whole grid's
// arrays, or why none can (`whole`: whether the grid fit the first device whole).
Result<Dims> chooseCore(std::span<const Context* const> devices, const Session& session, Dims dims,
                        int ghost, const RequestShape& shape, const BrickedHost& host,
                        const Result<void>& whole) {
  const auto fitsEvery = [&](Dims brick) -> Result<void> {
    for (const Context* device : devices)
      LIC3D_TRY(checkRequestMemory(*device, session, brick, shape));
    return {};
  };
  const HostShare perVoxel = hostShare(session, host);
  const std::uint64_t hostAvailable = hostAvailableBytes();
  const std::optional<Dims> core = chooseBrickCore(dims, ghost, [&](Dims brick) {
    return fitsEvery(brick).ok() && hostBytes(perVoxel, dims, brick) <= hostAvailable;
  });
  if (core) return *core;
  const Dims smallest = glm::min(Dims(1 + 2 * ghost), dims);
  const Result<void> device = fitsEvery(smallest);
  if (device) {  // the host is what cannot hold even the smallest brick beside the grid's
    Brick brick;
    brick.dims = smallest;
    LIC3D_TRY(checkBrickedHostMemory(session, dims, {brick}, host));
    return resourceLimitError("no brick of " + gridText(dims) + " fits both the host and " +
                              "the device");
  }
  Error error = whole ? device.error() : whole.error();
  error.message += "; nor does a brick of one voxel and its " + std::to_string(ghost) +
                   " ghost layers on each side, so it cannot be made in bricks either";
  return error;
}

// How each brick's field and noise are made on the host: read from the stream, or cut from the
// field on the host (`made` holds it when it is sampled here). None when the device makes them.
Result<void> preparePieces(const Session& session, SessionInputs& inputs,
                           const LicVolumeOptions& options, std::optional<VectorField>& made,
                           BrickJobs& jobs) {
  const Dims dims = inputs.field.dims;
  const std::uint64_t seed = session.noise.seed;
  if (options.stream) {
    StreamScan scan;
    if (options.scan) {
      scan = *options.scan;
    } else {
      LIC3D_TRY_ASSIGN(scan, scanFieldStream(*options.stream));
    }
    jobs.prepare = [&options, dims, seed,
                    maxSpeed = scan.maxVoxelSpeed](const Brick& brick) -> Result<PieceInputs> {
      StageTimer reading("brick field read");
      LIC3D_TRY_ASSIGN(VectorField piece, options.stream->readPiece(brick.offset, brick.dims));
      reading.stop();
      piece.piece = FieldPiece{dims, brick.offset, maxSpeed};
      const StageTimer noise("brick noise");
      return PieceInputs{std::move(piece),
                         makeWhiteNoisePiece(dims, brick.offset, brick.dims, seed)};
    };
  } else if (!inputs.device) {
    if (inputs.sampled) {
      LIC3D_TRY_ASSIGN(made, hostFieldAt(inputs, session, session.time));
    }
    const VectorField* field = made ? &*made : &inputs.field;
    jobs.prepare = [field, dims, seed, maxSpeed = maxVoxelSpeedOverVoxels(*field)](
                       const Brick& brick) -> Result<PieceInputs> {
      LIC3D_TRY_ASSIGN(VectorField piece,
                       cutFieldPiece(*field, brick.offset, brick.dims, maxSpeed));
      return PieceInputs{std::move(piece),
                         makeWhiteNoisePiece(dims, brick.offset, brick.dims, seed)};
    };
  }
  return {};
}

}  // namespace

Result<LicVolumeRun> computeLicVolume(std::span<const Context* const> devices,
                                      const Session& session, SessionInputs& inputs,
                                      const LicVolumeOptions& options,
                                      const ProgressCallback& progress) {
  if (devices.empty()) return inputError("no device to compute the LIC on");
  const RequestShape shape{.volumeReadback = true,
                           .timeSeries = inputs.series.has_value(),
                           .deviceCap = options.deviceCap};
  const Dims dims = inputs.field.dims;
  const Result<void> whole = checkRequestMemory(*devices[0], session, dims, shape);
  const bool brickable = !inputs.series && isWhiteNoise(session.noise);
  LicVolumeRun run;
  run.devices.resize(devices.size());
  for (std::size_t d = 0; d < devices.size(); ++d)
    run.devices[d].device = devices[d]->deviceInfo().name;
  if (options.stream && !brickable)
    return parameterError("noise.file",
                          "a field read brick by brick takes the seeded white noise of the whole "
                          "grid, at one time");
  // Without a target, the voxels go into the run's volume on the host.
  const bool sparse = session.lic.sparsity.distribution != SparsityDistribution::None;
  VoxelTarget own;
  const auto targetOnHost = [&](const GridGeometry& geometry) {
    run.volume = emptyResult(dims, geometry);
    if (sparse) resizeLarge(run.volume.drawn, run.volume.values.size());
    own = memoryTarget(run.volume);
  };
  const VoxelTarget* target = options.target ? options.target : &own;
  // A grid that fits the first device whole is made there alone: more devices would add their
  // start-up and the ghost layers of a split to a LIC of a fraction of a second, and the
  // read-back and writing, which bound such a run, share the host (docs/SCALE.md, "Several
  // devices"). A streamed field is never whole on the host: always in bricks.
  if (!brickable || (whole && !options.stream)) {
    LIC3D_TRY(whole);
    if (!options.target) targetOnHost(inputs.field.geometry);
    LIC3D_TRY(computeWhole(*devices[0], session, inputs, options, *target, progress, run));
    return run;
  }
  const int ghost = licGhostLayers(session.lic);
  const bool onDevice = inputs.device.has_value();
  const BrickedHost host{
      .fieldMadeHere = !onDevice && !options.stream && inputs.sampled.has_value(),
      .fieldOnHost = !onDevice,
      .wholeResult = !options.target,
      .devices = static_cast<int>(devices.size())};
  // A brick fits every device, and the bricks in flight fit the host beside the whole grid's.
  LIC3D_TRY_ASSIGN(Dims core, chooseCore(devices, session, dims, ghost, shape, host, whole));
  core = splitCoreForDevices(dims, core, static_cast<int>(devices.size()), ghost);
  const std::vector<Brick> bricks = planBricks(dims, core, ghost);
  if (options.stream && inputs.field.dims != options.stream->dims())
    return inputError("the streamed field's grid is not the inputs' grid");
  LIC3D_TRY(checkBrickedHostMemory(session, dims, bricks, host));
  // Each brick takes long on a large grid (minutes on a CPU driver): its stages are named as they
  // start and its LIC reports its slabs, so that progress shows from the start.
  BrickReport report(bricks.size(), devices.size(), progress, options.stage);
  report.stage(std::to_string(bricks.size()) + " bricks of " + gridText(core) + " and " +
               std::to_string(ghost) + " ghost layers");
  std::vector<LicRenderer> renderers;
  for (const Context* device : devices) {
    LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(*device, {session.precision}));
    renderers.push_back(std::move(renderer));
  }
  BrickJobs jobs;
  std::atomic<std::uint64_t> drawnVoxels{0};
  // The field on the host, where the bricks are cut from, unless the device makes each brick's.
  std::optional<VectorField> made;
  LIC3D_TRY(preparePieces(session, inputs, options, made, jobs));
  jobs.lic = [&](int worker, const Brick& brick,
                 std::optional<PieceInputs> in) -> Result<ScalarVolume> {
    const Clock::time_point start = Clock::now();
    LicRenderer& renderer = renderers[static_cast<std::size_t>(worker)];
    DeviceShare& share = run.devices[static_cast<std::size_t>(worker)];
    const std::size_t index = static_cast<std::size_t>(&brick - bricks.data());
    // About a sixth of a brick's time goes to its field and noise, the rest to its LIC.
    constexpr double kInputsPart = 0.15;
    report.brickStage(index, in ? "field and noise upload" : "field and noise on the device");
    if (in) {
      LIC3D_TRY(renderer.setInputs(in->field, in->noise));
    } else {
      AnalyticInputs analytic = *inputs.device;
      if (inputs.sampled) analytic.time = session.time;
      analytic.brickOffset = brick.offset;
      analytic.brickDims = brick.dims;
      LIC3D_TRY(renderer.setAnalyticInputs(analytic));
    }
    report.brickStage(index, "LIC");
    report.partial(worker, kInputsPart);
    LIC3D_TRY_ASSIGN(
        const std::uint64_t drawn,
        licOnDevice(*devices[static_cast<std::size_t>(worker)], renderer, session.lic,
                    options.timeLic, share, brick.ownOffset - brick.offset, brick.ownDims, *target,
                    brick.ownOffset, progress.withReport([&](double f) {
                      report.partial(worker, kInputsPart + (1.0 - kInputsPart) * f);
                    })));
    drawnVoxels += drawn;
    report.partial(worker, 0.0);  // counted as done once taken
    share.peakDeviceBytes = std::max(share.peakDeviceBytes,
                                     devices[static_cast<std::size_t>(worker)]->allocatedBytes());
    share.bricks += 1;
    share.voxels += voxelCount(brick.ownDims);
    share.seconds += secondsSince(start);
    return ScalarVolume();  // its voxels are in the target already
  };
  if (!options.target) targetOnHost(inputs.field.geometry);
  LIC3D_TRY(runBricks(static_cast<int>(devices.size()), bricks, jobs,
                      progress.withReport([&](double) { report.brickDone(); })));
  run.bricks = static_cast<int>(bricks.size());
  run.drawnVoxels = drawnVoxels.load();
  run.brickCore = core;
  return run;
}

Result<LicVolumeRun> computeLicVolume(const Context& context, const Session& session,
                                      SessionInputs& inputs, std::uint64_t deviceCap,
                                      const ProgressCallback& progress) {
  const Context* devices[] = {&context};
  return computeLicVolume(devices, session, inputs, {.deviceCap = deviceCap}, progress);
}

}  // namespace lic3d
