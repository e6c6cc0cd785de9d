// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Bricked LIC (docs/SCALE.md): a grid whose LIC does not fit the device's memory (or the budget
// --memory-budget sets) is computed brick by brick. Each brick is a piece of the field widened by
// the ghost layers of the streamline's reach (licGhostLayers), with the whole grid's largest |u|,
// white noise and sparsity mask cut to it (FieldPiece), so its own voxels get the whole grid's
// LIC; they are copied into the result.

#include <cstdint>
#include <functional>
#include <vector>

#include "core/error.h"
#include "core/session.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"
#include "inputs/session_inputs.h"
#include "lic/lic_reference.h"

namespace lic3d {

struct Brick {
  Dims offset{0};  // of the brick, ghost layers included, in the whole grid
  Dims dims{0};
  Dims ownOffset{0};  // the voxels it writes into the result
  Dims ownDims{0};
};

// Bricks whose own parts tile `whole` in blocks of at most `core` voxels per axis (the last of
// each row shorter), each widened by `ghost` layers where the grid goes on.
std::vector<Brick> planBricks(Dims whole, Dims core, int ghost);

// The largest brick core for which `fits` accepts the brick (core plus the ghost layers): the
// whole grid when it fits; else cores halved along the longest axis until one fits. Nothing when
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

struct LicVolumeRun {
  ScalarVolume volume;
  int bricks = 1;  // 1: the grid in one piece
  Dims brickCore{0};
};

// The LIC volume of the session's inputs at session.time on `context`, read back: in one piece
// when it fits the device (at most `deviceCap` bytes when > 0), else in bricks of the largest
// core that fits. A time series, or noise other than the seeded white noise, must fit whole
// (ResourceLimit otherwise, as without bricks).
Result<LicVolumeRun> computeLicVolume(const Context& context, const Session& session,
                                      SessionInputs& inputs, std::uint64_t deviceCap,
                                      const ProgressCallback& progress = {});

}  // namespace lic3d
