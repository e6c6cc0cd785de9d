// SPDX-License-Identifier: BSD-3-Clause
#include "inputs/bricks.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/memory_budget.h"
#include "core/parallel.h"
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

std::optional<Dims> chooseBrickCore(Dims whole, int ghost,
                                    const std::function<bool(Dims brick)>& fits) {
  Dims core = whole;
  for (;;) {
    const Dims brick = glm::min(core + Dims(2 * ghost), whole);
    if (fits(brick)) return core;
    if (core == Dims(1)) return std::nullopt;
    // Halve the longest axis (the one a slab would cut), so bricks stay close to cubes.
    int longest = 0;
    for (int a = 1; a < 3; ++a)
      if (core[a] > core[longest]) longest = a;
    core[longest] = (core[longest] + 1) / 2;
  }
}

Result<ScalarVolume> computeBricked(const VectorField& whole, const NoiseSource& noise,
                                    const std::vector<Brick>& bricks, const PieceLic& licOf,
                                    const ProgressCallback& progress) {
  if (!noise.file.empty() || noise.seedSpots > 0 || noise.seedFraction > 0.0f)
    return parameterError("noise.file",
                          "a LIC made in bricks takes the seeded white noise of the whole grid; "
                          "a noise file or seed noise must fit the device whole");
  const double maxSpeed = maxVoxelSpeedOverVoxels(whole);
  ScalarVolume result;
  result.dims = whole.dims;
  result.geometry = whole.geometry;
  result.values.resize(voxelCount(whole.dims));
  for (std::size_t b = 0; b < bricks.size(); ++b) {
    const Brick& brick = bricks[b];
    LIC3D_TRY_ASSIGN(VectorField piece, cutFieldPiece(whole, brick.offset, brick.dims, maxSpeed));
    const NoiseVolume pieceNoise =
        makeWhiteNoisePiece(whole.dims, brick.offset, brick.dims, noise.seed);
    LIC3D_TRY_ASSIGN(const ScalarVolume lic, licOf(piece, pieceNoise));
    if (!lic.drawn.empty() && result.drawn.empty()) result.drawn.assign(result.values.size(), 1);
    const Dims from = brick.ownOffset - brick.offset;
    // The brick's own rows into the result, the layers on the available threads.
    parallelFor(static_cast<std::size_t>(brick.ownDims.z), 0, [&](std::size_t layer) {
      const int k = static_cast<int>(layer);
      for (int j = 0; j < brick.ownDims.y; ++j) {
        const std::size_t at = voxelIndex(lic.dims, from.x, from.y + j, from.z + k);
        const std::size_t to =
            voxelIndex(whole.dims, brick.ownOffset.x, brick.ownOffset.y + j, brick.ownOffset.z + k);
        std::copy_n(&lic.values[at], brick.ownDims.x, &result.values[to]);
        if (!lic.drawn.empty()) std::copy_n(&lic.drawn[at], brick.ownDims.x, &result.drawn[to]);
      }
    });
    if (progress) progress(static_cast<double>(b + 1) / static_cast<double>(bricks.size()));
  }
  return result;
}

namespace {

// The host holds, besides what is loaded, the field where it is made here (an analytic one), the
// whole LIC volume (and its drawn mask with sparsity), and one brick at a time: its field copy,
// noise, packed texels, staging and read-back, about kBrickHostBytes a voxel.
constexpr std::uint64_t kBrickHostBytes = 40;

Result<void> checkBrickedHostMemory(const Session& session, Dims dims,
                                    const std::vector<Brick>& bricks, bool fieldMadeHere) {
  const bool sparse = session.lic.sparsity.distribution != SparsityDistribution::None;
  const std::uint64_t perVoxel = (fieldMadeHere ? 12 : 0) + 4 + (sparse ? 1 : 0);
  std::uint64_t largest = 0;
  for (const Brick& brick : bricks)
    largest = std::max<std::uint64_t>(largest, voxelCount(brick.dims));
  const std::uint64_t needed = voxelCount(dims) * perVoxel + largest * kBrickHostBytes;
  const std::uint64_t available = hostAvailableBytes();
  if (needed <= available) return {};
  // About the same share of bricks for a cube: the whole grid's bytes dominate.
  const int cube = static_cast<int>(std::cbrt(static_cast<double>(available) /
                                              static_cast<double>(perVoxel + kBrickHostBytes / 8)));
  return resourceLimitError(
      "the LIC of " + session.field.field + " (" + gridText(dims) + ") in " +
      std::to_string(bricks.size()) + " bricks needs " + std::to_string(needed >> 20) +
      " MiB of host memory (the field, the LIC volume and one brick); " +
      std::to_string(available >> 20) + " MiB are available; the largest cubic grid that fits is " +
      std::to_string(cube) + "^3");
}

}  // namespace

Result<LicVolumeRun> computeLicVolume(const Context& context, const Session& session,
                                      SessionInputs& inputs, std::uint64_t deviceCap,
                                      const ProgressCallback& progress) {
  const RequestShape shape{
      .volumeReadback = true, .timeSeries = inputs.series.has_value(), .deviceCap = deviceCap};
  const Dims dims = inputs.field.dims;
  const Result<void> whole = checkRequestMemory(context, session, dims, shape);
  LicVolumeRun run;
  LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, {session.precision}));
  if (whole || inputs.series || !isWhiteNoise(session.noise)) {
    LIC3D_TRY(whole);
    LIC3D_TRY(moveToTime(inputs, session, session.time, renderer, true));
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer.updateLic(session.lic, progress));
    LIC3D_TRY_ASSIGN(run.volume, renderer.readLicVolume());
    run.brickCore = dims;
    return run;
  }
  const int ghost = licGhostLayers(session.lic);
  const std::optional<Dims> core = chooseBrickCore(dims, ghost, [&](Dims brick) {
    return checkRequestMemory(context, session, brick, shape).ok();
  });
  if (!core) {
    Error error = whole.error();
    error.message += "; nor does a brick of one voxel and its " + std::to_string(ghost) +
                     " ghost layers on each side, so it cannot be made in bricks either";
    return error;
  }
  const std::vector<Brick> bricks = planBricks(dims, *core, ghost);
  LIC3D_TRY(checkBrickedHostMemory(session, dims, bricks, inputs.device || inputs.sampled));
  // The field on the host, where the bricks are cut from.
  std::optional<VectorField> made;
  if (inputs.device || inputs.sampled) {
    LIC3D_TRY_ASSIGN(made, hostFieldAt(inputs, session, session.time));
  }
  const VectorField& field = made ? *made : inputs.field;
  const PieceLic licOf = [&](const VectorField& piece,
                             const NoiseVolume& noise) -> Result<ScalarVolume> {
    LIC3D_TRY(renderer.setInputs(piece, noise));
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer.updateLic(session.lic));
    return renderer.readLicVolume();
  };
  LIC3D_TRY_ASSIGN(run.volume, computeBricked(field, session.noise, bricks, licOf, progress));
  run.bricks = static_cast<int>(bricks.size());
  run.brickCore = *core;
  return run;
}

}  // namespace lic3d
