// SPDX-License-Identifier: BSD-3-Clause
// Pieces of a field on the GPU (lavapipe): LIC computed piece by piece with ghost layers, as the
// ParaView plugin does under MPI, against the GPU's LIC of the whole field.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "gpu_test_support.h"
#include "jobs/bricks.h"
#include "lic/analytic_fields.h"
#include "lic/field_piece.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "piece_support.h"
#include "render/lic_renderer.h"

namespace lic3d {
namespace {

using test::GpuTest;

test::PieceCompute onGpu(const Context& context) {
  return [&context](const VectorField& field, const NoiseVolume& noise,
                    const LicParams& params) -> Result<ScalarVolume> {
    LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, {FieldPrecision::Float}));
    LIC3D_TRY(renderer.setInputs(field, noise));
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer.updateLic(params));
    return renderer.readLicVolume();
  };
}

// A piece's positions are its own voxel coordinates, and its texture coordinates are divided by
// its own size: float32 rounds them differently than on the whole grid, and the 8-bit weights of
// hardware trilinear filtering turn the difference into another weight now and then. Streamlines
// near critical points or across strong turns then drift apart. So, as for the GPU against the
// CPU reference (test_lic_gpu.cpp): the mean, and 99.9 % of the voxels within 2e-2; the CPU
// reference gives the pieces the whole field's values to 1e-6 (test_field_piece.cpp).
void expectClose(const test::PieceRun& run, const char* what) {
  ASSERT_TRUE(run.ok) << run.error;
  EXPECT_LE(run.difference.mean, 1e-3) << what;
  EXPECT_LE(run.difference.quantile999, 2e-2) << what;
}

TEST_F(GpuTest, GpuPiecesMatchTheWholeField) {
  const VectorField tornado = makeAnalyticField(AnalyticField::Tornado, {40, 32, 24});
  LicParams params;
  params.length = 12;
  params.bias = 3;
  const test::PieceRun run =
      test::runInPieces(tornado, params, {2, 2, 1}, licGhostLayers(params), onGpu(context()));
  expectClose(run, "tornado");
  EXPECT_EQ(run.pieces, 4u);
}

TEST_F(GpuTest, GpuPiecesMatchWithMagnitudeStepsAndSparsity) {
  const VectorField tornado = makeAnalyticField(AnalyticField::Tornado, {40, 32, 24});
  LicParams params;
  params.length = 12;
  params.direction = DirectionMode::Magnitude;
  params.sparsity.distribution = SparsityDistribution::Jitter;
  const test::PieceRun run =
      test::runInPieces(tornado, params, {1, 2, 2}, licGhostLayers(params), onGpu(context()));
  expectClose(run, "tornado, magnitude, jitter");
  // A drifted streamline may touch a black voxel that the other misses.
  EXPECT_LE(run.hiddenMismatches, voxelCount(tornado.dims) / 1000);
}

// Bricks (jobs/bricks.h) are pieces that tile the grid: the plan covers every voxel once, the
// CPU reference in bricks gives the whole field's LIC, and on the device the bricked LIC that a
// budget forces stays as close to the whole one as the pieces above.
TEST(Bricks, ThePlanCoversEveryVoxelOnceWithGhostLayersInsideTheGrid) {
  const Dims whole(37, 20, 9);
  const std::vector<Brick> bricks = planBricks(whole, {16, 16, 4}, 3);
  EXPECT_EQ(bricks.size(), 3u * 2u * 3u);
  std::vector<int> owners(voxelCount(whole), 0);
  for (const Brick& b : bricks) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_GE(b.offset[a], 0);
      EXPECT_LE(b.offset[a] + b.dims[a], whole[a]);
      EXPECT_EQ(b.ownOffset[a] - b.offset[a], std::min(3, b.ownOffset[a]));
    }
    for (int k = 0; k < b.ownDims.z; ++k)
      for (int j = 0; j < b.ownDims.y; ++j)
        for (int i = 0; i < b.ownDims.x; ++i)
          ++owners[voxelIndex(whole, b.ownOffset.x + i, b.ownOffset.y + j, b.ownOffset.z + k)];
  }
  EXPECT_EQ(std::count(owners.begin(), owners.end(), 1), static_cast<long>(owners.size()));
  // The core shrinks until a brick fits, and nothing fits when a single voxel does not.
  const auto fitsVoxels = [](std::size_t most) {
    return [most](Dims brick) { return voxelCount(brick) <= most; };
  };
  EXPECT_EQ(chooseBrickCore(whole, 3, fitsVoxels(1u << 20)), std::optional<Dims>(whole));
  const std::optional<Dims> core = chooseBrickCore(whole, 3, fitsVoxels(2000));
  ASSERT_TRUE(core);
  EXPECT_LE(voxelCount(glm::min(*core + Dims(6), whole)), 2000u);
  EXPECT_FALSE(chooseBrickCore(whole, 3, fitsVoxels(100)));
}

TEST(Bricks, CpuBricksGiveTheWholeFieldsLic) {
  const VectorField tornado = makeAnalyticField(AnalyticField::Tornado, {36, 28, 20});
  LicParams params;
  params.length = 10;
  params.bias = 2;
  params.direction = DirectionMode::Magnitude;
  params.sparsity.distribution = SparsityDistribution::Jitter;
  NoiseSource noise;
  noise.seed = 5;
  const Result<ScalarVolume> whole =
      computeLicReference(tornado, makeWhiteNoise(tornado.dims, 5), params);
  const std::vector<Brick> bricks = planBricks(tornado.dims, {16, 16, 8}, licGhostLayers(params));
  const Result<ScalarVolume> bricked = computeBricked(
      tornado, noise, bricks, [&](const VectorField& piece, const NoiseVolume& pieceNoise) {
        return computeLicReference(piece, pieceNoise, params);
      });
  ASSERT_TRUE(whole && bricked);
  ASSERT_EQ(bricked->values.size(), whole->values.size());
  EXPECT_EQ(bricked->drawn, whole->drawn);
  double worst = 0.0;
  for (std::size_t i = 0; i < whole->values.size(); ++i)
    worst = std::max(worst, std::abs(static_cast<double>(whole->values[i]) - bricked->values[i]));
  EXPECT_LE(worst, 1e-6);
  // Another noise than the whole grid's white noise cannot be cut into bricks.
  noise.seedSpots = 10;
  EXPECT_FALSE(computeBricked(tornado, noise, bricks, {}));
}

TEST_F(GpuTest, ABudgetMakesTheDeviceComputeInBricks) {
  Session session;
  session.field.grid = {40, 32, 24};
  session.lic.length = 12;
  session.precision = FieldPrecision::Float;
  Result<SessionInputs> inputs = loadSessionInputs(session);
  ASSERT_TRUE(inputs);
  const Result<LicVolumeRun> whole = computeLicVolume(context(), session, *inputs, 0);
  const Result<LicVolumeRun> bricked = computeLicVolume(context(), session, *inputs, 400000);
  ASSERT_TRUE(whole) << whole.error().message;
  ASSERT_TRUE(bricked) << bricked.error().message;
  EXPECT_EQ(whole->bricks, 1);
  EXPECT_GT(bricked->bricks, 1);
  std::vector<double> differences;
  for (std::size_t i = 0; i < whole->volume.values.size(); ++i)
    differences.push_back(
        std::abs(static_cast<double>(whole->volume.values[i]) - bricked->volume.values[i]));
  std::sort(differences.begin(), differences.end());
  double sum = 0.0;
  for (const double d : differences) sum += d;
  EXPECT_LE(sum / static_cast<double>(differences.size()), 1e-3);
  EXPECT_LE(differences[differences.size() * 999 / 1000], 2e-2);
  // Below what one voxel and its ghost layers need: refused as a whole grid would be.
  const Result<LicVolumeRun> refused = computeLicVolume(context(), session, *inputs, 1000);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().kind, ErrorKind::ResourceLimit);
}

}  // namespace
}  // namespace lic3d
