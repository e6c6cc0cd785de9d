// SPDX-License-Identifier: BSD-3-Clause
// Pieces of a field on the GPU (lavapipe): LIC computed piece by piece with ghost layers, as the
// ParaView plugin does under MPI, against the GPU's LIC of the whole field.
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "lic/field_piece.h"
#include "passes/lic_renderer.h"
#include "piece_support.h"

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

}  // namespace
}  // namespace lic3d
