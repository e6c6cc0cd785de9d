// SPDX-License-Identifier: BSD-3-Clause
// Sparsity in the LIC volume (CPU reference): the amount control, and the mask beyond the grid
// that keeps boundary streamlines from being drawn more often than interior ones.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "lic/analytic_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "lic/sparsity.h"

namespace lic3d {
namespace {

// Drawn fractions of the voxels inside, on the faces (one coordinate at the grid's edge) and on
// the edges and corners (two or three).
struct DrawnByPlace {
  double inside = 0, faces = 0, edges = 0;
};

DrawnByPlace drawnByPlace(const ScalarVolume& volume) {
  const Dims d = volume.dims;
  double drawn[3] = {0, 0, 0}, count[3] = {0, 0, 0};
  for (int k = 0; k < d.z; ++k)
    for (int j = 0; j < d.y; ++j)
      for (int i = 0; i < d.x; ++i) {
        const int atEdge =
            (i == 0 || i == d.x - 1) + (j == 0 || j == d.y - 1) + (k == 0 || k == d.z - 1);
        const int place = atEdge > 2 ? 2 : atEdge;
        drawn[place] += volume.drawn[voxelIndex(d, i, j, k)];
        count[place] += 1;
      }
  return {drawn[0] / count[0], drawn[1] / count[1], drawn[2] / count[2]};
}

double hiddenFraction(const ScalarVolume& volume) {
  double drawn = 0;
  for (const std::uint8_t d : volume.drawn) drawn += d;
  return 1.0 - drawn / static_cast<double>(volume.drawn.size());
}

TEST(SparsityLic, BoundaryStreamlinesAreHiddenAsOftenAsInteriorOnes) {
  // Before the mask went on beyond the grid, this tornado drew 55 % of the voxels inside, 70 %
  // on faces and 73 % on edges with halton, and 11 %, 23 %, 30 % with poisson.
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, {40, 40, 40});
  const NoiseVolume noise = makeWhiteNoise(field.dims, 3);
  for (const SparsityDistribution d : {SparsityDistribution::Halton, SparsityDistribution::Poisson,
                                       SparsityDistribution::Checkerboard}) {
    LicParams params;
    params.sparsity.distribution = d;
    params.sparsity.amount = 0.6f;
    const Result<ScalarVolume> volume = computeLicReference(field, noise, params);
    ASSERT_TRUE(volume.ok()) << volume.error().message;
    const DrawnByPlace drawn = drawnByPlace(*volume);
    const std::string name(enumName(d));
    EXPECT_NEAR(drawn.faces, drawn.inside, 0.05) << name;
    EXPECT_NEAR(drawn.edges, drawn.inside, 0.08) << name;
  }
}

TEST(SparsityLic, AmountIsTheFractionOfVoxelsHidden) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {32, 32, 32});
  const NoiseVolume noise = makeWhiteNoise(field.dims, 4);
  for (const SparsityDistribution d :
       {SparsityDistribution::Checkerboard, SparsityDistribution::Poisson,
        SparsityDistribution::PoissonApprox, SparsityDistribution::Jitter,
        SparsityDistribution::Halton, SparsityDistribution::Hammersley})
    for (const float amount : {0.3f, 0.8f}) {
      LicParams params;
      params.sparsity.distribution = d;
      params.sparsity.amount = amount;
      const Result<ScalarVolume> volume = computeLicReference(field, noise, params);
      ASSERT_TRUE(volume.ok()) << volume.error().message;
      EXPECT_NEAR(hiddenFraction(*volume), amount, 0.07) << enumName(d) << " " << amount;
    }
}

TEST(SparsityLic, AmountSetsTheBlackFractionFromTheStreamlineLength) {
  LicParams params;
  // No amount: automatic values hide half of the voxels; the checkerboard's ratio is as given,
  // and given points or radii leave the black fraction alone (a length change keeps the mask).
  params.sparsity.distribution = SparsityDistribution::Halton;
  const double automatic = maskParams(params).blackFraction;
  EXPECT_NEAR(std::pow(1.0 - automatic, 23.0), 1.0 - kDefaultSparsityAmount, 1e-6);
  params.sparsity.points = 1000;
  EXPECT_DOUBLE_EQ(maskParams(params).blackFraction, kDefaultBlackFraction);
  params.sparsity.points = 0;
  params.sparsity.distribution = SparsityDistribution::Checkerboard;
  EXPECT_FLOAT_EQ(maskParams(params).ratio, 0.05f);

  params.sparsity.amount = 0.5f;  // L = 20, h = 0.5: 23 voxels, (1 - f)^23 = 0.5
  EXPECT_DOUBLE_EQ(streamlineVoxels(params), 23.0);
  const double f = maskParams(params).blackFraction;
  EXPECT_NEAR(std::pow(1.0 - f, 23.0), 0.5, 1e-9);
  EXPECT_FLOAT_EQ(maskParams(params).ratio, static_cast<float>(f));

  params.length = 40;  // longer streamlines touch more voxels: fewer black ones hide as many
  EXPECT_LT(maskParams(params).blackFraction, f);
}

TEST(SparsityLic, TheMaskBeyondTheGridHasTheMasksBlackFraction) {
  SparsityParams params;
  params.distribution = SparsityDistribution::Halton;
  const Result<SparsityMask> mask = makeSparsityMask(params, {20, 20, 20});
  ASSERT_TRUE(mask.ok());
  double black = 0, count = 0;
  for (int k = -30; k < 50; ++k)
    for (int j = -30; j < 50; ++j)
      for (int i = 20; i < 60; ++i, ++count) black += isBlack(*mask, {i, j, k});
  EXPECT_NEAR(black / count, static_cast<double>(mask->blackCount) / 8000.0, 0.005);
  // Inside, the mask itself.
  EXPECT_EQ(isBlack(*mask, {3, 4, 5}), mask->black[voxelIndex(mask->dims, 3, 4, 5)] != 0);
}

}  // namespace
}  // namespace lic3d
