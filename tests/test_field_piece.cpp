// SPDX-License-Identifier: BSD-3-Clause
// Pieces of a field (engine/field_piece.h): LIC computed piece by piece with ghost layers, as the
// ParaView plugin does under MPI, against LIC of the whole field, with the CPU reference.
#include <gtest/gtest.h>

#include <functional>

#include "lic/analytic_fields.h"
#include "lic/field_piece.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "lic/sparsity.h"
#include "piece_support.h"

namespace lic3d {
namespace {

using test::PieceRun;

TEST(FieldPiece, GhostLayersCoverTheLongerSideOfTheStreamline) {
  LicParams params;  // L = 20, h = 0.5: 10 voxels, and one for interpolation
  EXPECT_EQ(licGhostLayers(params), 11);
  params.bias = 5;  // 15 back, 25 forward: 12.5 voxels, rounded up
  EXPECT_EQ(licGhostLayers(params), 14);
  params.bias = -5;
  EXPECT_EQ(licGhostLayers(params), 14);
  params = {};
  params.length = 0;
  EXPECT_EQ(licGhostLayers(params), 1);
  params.length = 10;
  params.step = 0.25f;
  EXPECT_EQ(licGhostLayers(params), 4);
}

TEST(FieldPiece, CutKeepsGeometryAndTheWholeMaximum) {
  VectorField whole = makeAnalyticField(AnalyticField::Tornado, {12, 10, 8});
  whole.geometry = {{0.5, 1.0, 2.0}, {10.0, 20.0, 30.0}};
  const Result<VectorField> piece = cutFieldPiece(whole, {2, 3, 4}, {5, 4, 3});
  ASSERT_TRUE(piece.ok()) << piece.error().message;
  EXPECT_EQ(piece->dims, Dims(5, 4, 3));
  EXPECT_EQ(piece->geometry.origin, glm::dvec3(11.0, 23.0, 38.0));
  EXPECT_EQ(piece->at(0, 0, 0), whole.at(2, 3, 4));
  EXPECT_EQ(piece->at(4, 3, 2), whole.at(6, 6, 6));
  ASSERT_TRUE(piece->piece.has_value());
  EXPECT_EQ(piece->piece->wholeDims, whole.dims);
  EXPECT_EQ(piece->piece->offset, Dims(2, 3, 4));
  EXPECT_EQ(maxVoxelSpeed(*piece), maxVoxelSpeed(whole));
  EXPECT_LT(maxVoxelSpeedOverVoxels(*piece), maxVoxelSpeed(whole));
  EXPECT_FALSE(cutFieldPiece(whole, {8, 0, 0}, {5, 1, 1}).ok());
  EXPECT_FALSE(cutFieldPiece(whole, {-1, 0, 0}, {1, 1, 1}).ok());
}

TEST(FieldPiece, NoiseOfAPieceIsTheWholeNoiseThere) {
  const Dims whole{9, 7, 5}, offset{2, 1, 3}, dims{4, 5, 2};
  const NoiseVolume all = makeWhiteNoise(whole, 42);
  const NoiseVolume piece = makeWhiteNoisePiece(whole, offset, dims, 42);
  ASSERT_EQ(piece.dims, dims);
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        EXPECT_EQ(piece.bytes[voxelIndex(dims, i, j, k)],
                  all.bytes[voxelIndex(whole, offset.x + i, offset.y + j, offset.z + k)]);
}

TEST(FieldPiece, SparsityMaskOfAPieceIsTheWholeMaskThere) {
  const Dims whole{20, 16, 12}, offset{3, 5, 2}, dims{10, 8, 9};
  for (const SparsityDistribution d :
       {SparsityDistribution::Checkerboard, SparsityDistribution::Poisson,
        SparsityDistribution::Halton}) {
    SparsityParams params;
    params.distribution = d;
    const Result<SparsityMask> all = makeSparsityMask(params, whole);
    const Result<SparsityMask> piece =
        makeSparsityMaskPiece(params, FieldPiece{whole, offset, 1.0}, dims);
    ASSERT_TRUE(all.ok() && piece.ok());
    std::size_t black = 0;
    for (int k = 0; k < dims.z; ++k)
      for (int j = 0; j < dims.y; ++j)
        for (int i = 0; i < dims.x; ++i) {
          const std::uint8_t b = piece->black[voxelIndex(dims, i, j, k)];
          EXPECT_EQ(b, all->black[voxelIndex(whole, offset.x + i, offset.y + j, offset.z + k)]);
          black += b;
        }
    EXPECT_EQ(piece->blackCount, black);
  }
  EXPECT_FALSE(makeSparsityMaskPiece({SparsityDistribution::Halton}, FieldPiece{whole, offset, 1.0},
                                     {18, 1, 1})
                   .ok());
}

// The tornado, faster along +x: its largest |v| lies in the last pieces along x only.
VectorField rampedTornado(Dims dims) {
  VectorField field = makeAnalyticField(AnalyticField::Tornado, dims);
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        field.vectors[voxelIndex(dims, i, j, k)] *=
            1.0f + 2.0f * static_cast<float>(i) / static_cast<float>(dims.x);
  return field;
}

// Each configuration: the whole field's LIC against the pieces' (2 x 2 x 2 pieces with
// licGhostLayers ghost layers), on the CPU reference in double precision.
using Compute = test::PieceCompute;

Compute cpuReference() {
  return [](const VectorField& field, const NoiseVolume& noise, const LicParams& params) {
    return computeLicReference(field, noise, params);
  };
}

void expectPiecesMatchWhole(const VectorField& field, const LicParams& params) {
  const PieceRun run =
      test::runInPieces(field, params, {2, 2, 2}, licGhostLayers(params), cpuReference());
  ASSERT_TRUE(run.ok) << run.error;
  EXPECT_EQ(run.hiddenMismatches, 0u);
  EXPECT_LE(run.difference.max, 1e-6) << "worst voxel index " << run.difference.argMax;
}

TEST(FieldPiece, CpuPiecesMatchTheWholeField) {
  const VectorField tornado = makeAnalyticField(AnalyticField::Tornado, {20, 16, 12});
  LicParams params;
  params.length = 8;
  expectPiecesMatchWhole(tornado, params);
  params.bias = 4;  // the forward side reaches further
  params.integrator = Integrator::Rk4;
  params.kernel = Kernel::Hann;
  expectPiecesMatchWhole(tornado, params);
}

// Magnitude steps scale by the whole field's max|u|, which the pieces take from FieldPiece; the
// sparsity mask is cut from the whole grid's.
TEST(FieldPiece, CpuPiecesMatchWithMagnitudeStepsAndSparsity) {
  VectorField field = rampedTornado({20, 16, 12});
  field.geometry.spacing = {1.0, 1.5, 0.75};  // anisotropic: u differs from v
  LicParams params;
  params.length = 8;
  params.direction = DirectionMode::Magnitude;
  params.noiseFilter = NoiseFilter::Nearest;
  params.sparsity.distribution = SparsityDistribution::Poisson;
  expectPiecesMatchWhole(field, params);
}

// The comparison is sharp: one ghost layer too few, or each piece's own max|u|, changes voxels.
TEST(FieldPiece, FewerGhostLayersOrALocalMaximumChangeTheResult) {
  const VectorField tornado = makeAnalyticField(AnalyticField::Tornado, {20, 16, 12});
  LicParams params;
  params.length = 8;
  const PieceRun thin =
      test::runInPieces(tornado, params, {2, 2, 2}, licGhostLayers(params) - 2, cpuReference());
  ASSERT_TRUE(thin.ok) << thin.error;
  EXPECT_GT(thin.difference.max, 1e-3);

  params.direction = DirectionMode::Magnitude;
  const Compute ownMaximum = [](const VectorField& field, const NoiseVolume& noise,
                                const LicParams& p) {
    VectorField alone = field;
    alone.piece.reset();
    return computeLicReference(alone, noise, p);
  };
  const PieceRun local = test::runInPieces(rampedTornado({20, 16, 12}), params, {2, 2, 2},
                                           licGhostLayers(params), ownMaximum);
  ASSERT_TRUE(local.ok) << local.error;
  EXPECT_GT(local.difference.max, 1e-2);
}

}  // namespace
}  // namespace lic3d
