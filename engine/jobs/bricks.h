// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Bricked LIC (docs/SCALE.md): a grid whose LIC does not fit the device's memory (or the budget
// --memory-budget sets) is computed brick by brick. Each brick is a piece of the field widened by
// the ghost layers of the streamline's reach (licGhostLayers), with the whole grid's largest |u|,
// white noise and sparsity mask cut to it (FieldPiece), so its own voxels get the whole grid's
// LIC; they are copied into the result (or handed to a sink: a file written brick by brick).
// Bricks are spread over one or more devices, each on a thread of its own taking the next brick
// not yet taken; a brick's host inputs are made while its device works on the one before.

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/session.h"
#include "core/volume.h"
#include "core/voxel_target.h"
#include "gpu/vulkan_context.h"
#include "io/field_stream.h"
#include "lic/lic_reference.h"
#include "loading/session_inputs.h"

namespace lic3d {

struct Brick {
  Dims offset{0};  // of the brick, ghost layers included, in the whole grid
  Dims dims{0};
  Dims ownOffset{0};  // the voxels it writes into the result
  Dims ownDims{0};
};

// Bricks are slabs of whole x-y layers while they can be: a slab's own voxels are one run of a
// file or a volume (read, converted and written as one piece, docs/SCALE.md), and its ghost layers
// cost no more than a cube's while it is at least kMinSlabLayers and 4 ghost layers thick on
// each side. Past that, bricks are halved along their longest axis, staying close to cubes.
inline constexpr int kMinSlabLayers = 32;
// The axis a brick core of `ghost` ghost layers is halved along next: z while the halves stay
// such slabs, else its longest.
int axisToHalve(Dims core, int ghost);

// Splits `core` further (axisToHalve) until `whole` has at least `count` bricks, so that each of
// `count` devices gets one.
Dims splitCoreForDevices(Dims whole, Dims core, int count, int ghost = 0);

// Bricks whose own parts tile `whole` in blocks of at most `core` voxels per axis (the last of
// each row shorter), each widened by `ghost` layers where the grid goes on.
std::vector<Brick> planBricks(Dims whole, Dims core, int ghost);

// The largest brick core for which `fits` accepts the brick (core plus the ghost layers): the
// whole grid when it fits; else cores halved (axisToHalve) until one fits. Nothing when
// not even a core of one voxel fits.
std::optional<Dims> chooseBrickCore(Dims whole, int ghost,
                                    const std::function<bool(Dims brick)>& fits);

// A piece's LIC (the device or the CPU reference), of a field with VectorField::piece set.
using PieceLic =
    std::function<Result<ScalarVolume>(const VectorField& piece, const NoiseVolume& noise)>;

// The LIC of `whole` made brick by brick by `licOf`; the noise of each brick is the whole grid's
// seeded white noise cut to it (other noise needs the whole grid: InvalidInput naming it).
Result<ScalarVolume> computeBricked(const VectorField& whole, const NoiseSource& noise,
                                    const std::vector<Brick>& bricks, const PieceLic& licOf,
                                    const ProgressCallback& progress = {});

// Copies the brick's own voxels of its LIC (and drawn mask) into `result`, on the whole grid.
void copyOwnVoxels(const Brick& brick, const ScalarVolume& lic, ScalarVolume& result);

// A brick's inputs made on the host: its field (VectorField::piece set) and noise.
struct PieceInputs {
  VectorField field;
  NoiseVolume noise;
};

// The work of a bricked run. `prepare` (optional) makes a brick's host inputs; `lic` makes its
// LIC on worker `worker` (a device); `take` (optional: `lic` may deliver the voxels itself) gets
// each brick's LIC, one call at a time.
struct BrickJobs {
  std::function<Result<PieceInputs>(const Brick&)> prepare;
  std::function<Result<ScalarVolume>(int worker, const Brick&, std::optional<PieceInputs>)> lic;
  std::function<Result<void>(const Brick&, const ScalarVolume&)> take;
  bool takeAtOnce = false;  // `take` may run on several workers at once (disjoint parts of a file)
};

// Runs `bricks` on `workers` threads, each taking the next brick not yet taken and preparing the
// one after it on a thread of its own while its `lic` runs. The first error stops every worker
// and is returned, as is Cancelled when the progress' stop is requested (no brick starts after
// it). Returns the worker of each brick. `take` runs one call at a time unless
// jobs.takeAtOnce.
Result<std::vector<int>> runBricks(int workers, const std::vector<Brick>& bricks,
                                   const BrickJobs& jobs, const ProgressCallback& progress = {});

// One device's share of a LIC volume's work.
struct DeviceShare {
  std::string device;
  int bricks = 0;
  std::uint64_t voxels = 0;          // its bricks' own voxels
  double seconds = 0.0;              // busy: its bricks' inputs, LIC and read-back
  double licMilliseconds = 0.0;      // its LIC dispatches on the device (LicVolumeOptions::timeLic)
  double readbackSeconds = 0.0;      // reading its bricks back and converting them into the target
  std::uint64_t readbackBytes = 0;   // of LIC texels read back (4 a voxel)
  double readbackWaitSeconds = 0.0;  // of those, waiting for slabs to come over the link
  double convertSeconds = 0.0;  // of those, converting slabs into the target (and writing them)
  std::uint64_t peakDeviceBytes = 0;  // lic3d's own device allocations at their highest
};

struct LicVolumeRun {
  ScalarVolume volume;  // empty when a target took the voxels
  int bricks = 1;       // 1: the grid in one piece
  Dims brickCore{0};
  std::vector<DeviceShare> devices;
  std::uint64_t drawnVoxels = 0;  // of the grid: all of them without a sparsity mask
};

// What a field streamed from its file needs before its bricks: the whole field's max |u|
// (maxVoxelSpeedOverVoxels), its largest |v| and its non-finite vectors, from one pass over the
// file in slabs of a few layers.
struct StreamScan {
  double maxVoxelSpeed = 0.0;
  double maxMagnitude = 0.0;
  std::uint64_t nonFinite = 0;
};
struct LicVolumeOptions {
  std::uint64_t deviceCap = 0;  // > 0: at most this many bytes of each device (--memory-budget)
  // Where the voxels go as each brick (or the one piece) is read back, from every device at once
  // (a file written in place, a reduced copy); LicVolumeRun::volume then stays empty. Null: into
  // LicVolumeRun::volume.
  const VoxelTarget* target = nullptr;
  bool timeLic = false;  // time each LIC dispatch with GPU timestamps (lic3d bench)
  // A renderer on the first device that holds the inputs at session.time already (moveToTime):
  // a grid made whole is made with it, keeping its pipelines, field textures and LIC volume
  // between runs (the Python module's lic3d.Renderer). Null: one is made for the run.
  LicRenderer* renderer = nullptr;
  // The field read brick by brick from this file (SessionInputs::field then holds only its grid
  // and geometry: streamedInputs), never whole.
  const FieldStream* stream = nullptr;
  const StreamScan* scan = nullptr;  // the stream's scan, where made already (else made here)
  // What a bricked run does, named as it starts, from any worker but one call at a time: the plan
  // ("8 bricks of 350x350x350 and 8 ghost layers"), then each brick's inputs and LIC ("brick 2 of
  // 8: LIC"). The progress meanwhile counts the part of each brick under way.
  std::function<void(const std::string& stage)> stage;
};

Result<StreamScan> scanFieldStream(const FieldStream& stream,
                                   const ProgressCallback& progress = {});

// SessionInputs for a field read brick by brick from `stream`: its grid and geometry, no vectors,
// and the seeded white noise's grid (the noise of each brick is made with it).
SessionInputs streamedInputs(const FieldStream& stream, const Session& session,
                             const StreamScan& scan);

// The LIC volume of the session's inputs at session.time, read back: in one piece on the first
// device when it fits it (at most `deviceCap` bytes when > 0) and one device is given, else in
// bricks of the largest core that fits every device, at least one a device, spread over them. A
// time series, or noise other than the seeded white noise, must fit whole (ResourceLimit
// otherwise).
Result<LicVolumeRun> computeLicVolume(std::span<const Context* const> devices,
                                      const Session& session, SessionInputs& inputs,
                                      const LicVolumeOptions& options,
                                      const ProgressCallback& progress = {});
Result<LicVolumeRun> computeLicVolume(const Context& context, const Session& session,
                                      SessionInputs& inputs, std::uint64_t deviceCap,
                                      const ProgressCallback& progress = {});

}  // namespace lic3d
