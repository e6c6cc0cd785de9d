// SPDX-License-Identifier: BSD-3-Clause
// The CPU reference against properties that follow from the LIC semantics.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>

#include "lic/analytic_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"

namespace lic3d {
namespace {

VectorField constantField(Dims dims, glm::vec3 v) {
  VectorField f;
  f.dims = dims;
  f.vectors.assign(voxelCount(dims), v);
  return f;
}

double noiseAt(const NoiseVolume& n, int i, int j, int k) {
  return n.value(voxelIndex(n.dims, i, j, k));
}

TEST(LicReference, ConstantFieldAveragesTheNoiseOnItsLine) {
  const Dims dims{40, 6, 5};
  const VectorField field = constantField(dims, {2.5f, 0.0f, 0.0f});  // magnitude irrelevant
  const NoiseVolume noise = makeWhiteNoise(dims, 11);
  const FieldSampler sampler(field);
  LicParams params;
  params.length = 7;
  params.step = 1.0f;  // samples land on voxel centres: both noise filters see voxel values
  for (const NoiseFilter filter : {NoiseFilter::Nearest, NoiseFilter::Linear}) {
    params.noiseFilter = filter;
    double expected = 0.0;
    for (int i = 20 - 7; i <= 20 + 7; ++i) expected += noiseAt(noise, i, 3, 2);
    expected /= 15.0;
    EXPECT_NEAR(licAtVoxel(sampler, noise, params, {20, 3, 2}), expected, 1e-12);
  }
}

TEST(LicReference, BoundaryVoxelsAverageFewerSamples) {
  const Dims dims{20, 3, 3};
  const VectorField field = constantField(dims, {1.0f, 0.0f, 0.0f});
  const NoiseVolume noise = makeWhiteNoise(dims, 5);
  const FieldSampler sampler(field);
  LicParams params;
  params.length = 6;
  params.step = 1.0f;
  // At i = 2 the backward streamline reaches x = 1 and 0 and stops before leaving the grid.
  double expected = 0.0;
  for (int i = 0; i <= 2 + 6; ++i) expected += noiseAt(noise, i, 1, 1);
  expected /= 9.0;
  EXPECT_NEAR(licAtVoxel(sampler, noise, params, {2, 1, 1}), expected, 1e-12);
  // The last voxel: only backward samples. The face x = NX - 1 counts as inside.
  expected = 0.0;
  for (int i = 19 - 6; i <= 19; ++i) expected += noiseAt(noise, i, 1, 1);
  EXPECT_NEAR(licAtVoxel(sampler, noise, params, {19, 1, 1}), expected / 7.0, 1e-12);
}

TEST(LicReference, ZeroFieldGivesTheNoiseItself) {
  const Dims dims{7, 8, 9};
  const VectorField field = constantField(dims, glm::vec3(0.0f));
  const NoiseVolume noise = makeWhiteNoise(dims, 2);
  for (const Integrator integrator : {Integrator::Euler, Integrator::Rk2, Integrator::Rk4}) {
    LicParams params;
    params.integrator = integrator;
    params.kernel = Kernel::Gauss;
    const ScalarVolume out = *computeLicReference(field, noise, params);
    for (std::size_t i = 0; i < out.values.size(); ++i)
      ASSERT_FLOAT_EQ(out.values[i], noise.value(i));
  }
}

TEST(LicReference, BiasEqualToLengthLooksForwardOnly) {
  const Dims dims{50, 4, 4};
  const VectorField forward = constantField(dims, {1.0f, 0.0f, 0.0f});
  const NoiseVolume noise = makeWhiteNoise(dims, 8);
  const FieldSampler sampler(forward);
  LicParams params;
  params.length = 5;
  params.bias = 5;  // Lb = 0, Lf = 10
  params.step = 1.0f;
  double expected = 0.0;
  for (int i = 10; i <= 20; ++i) expected += noiseAt(noise, i, 2, 2);
  EXPECT_NEAR(licAtVoxel(sampler, noise, params, {10, 2, 2}), expected / 11.0, 1e-12);
  params.bias = -5;  // backward only
  expected = 0.0;
  for (int i = 0; i <= 10; ++i) expected += noiseAt(noise, i, 2, 2);
  EXPECT_NEAR(licAtVoxel(sampler, noise, params, {10, 2, 2}), expected / 11.0, 1e-12);
}

TEST(LicReference, StreamlinesStopAtCriticalPointsAndNeverLeaveTheGrid) {
  // +x flow in the left half, zero in the right half from voxel 10 on.
  const Dims dims{20, 3, 3};
  VectorField field = constantField(dims, {1.0f, 0.0f, 0.0f});
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < 3; ++j)
      for (int i = 10; i < 20; ++i) field.vectors[voxelIndex(dims, i, j, k)] = glm::vec3(0.0f);
  const FieldSampler sampler(field);
  LicParams params;
  params.step = 1.0f;
  // From x = 7 the samples are 8, 9 and 10; v(10) = 0 exactly: x = 10 is reached (a sample) and
  // the streamline ends there.
  const std::vector<glm::dvec3> line = traceStreamline(sampler, dims, params, {7, 1, 1}, +1, 10);
  ASSERT_EQ(line.size(), 4u);
  EXPECT_DOUBLE_EQ(line.back().x, 10.0);

  const VectorField outward = constantField(dims, {1.0f, 0.3f, 0.0f});
  const FieldSampler outwardSampler(outward);
  params.step = 0.5f;
  const std::vector<glm::dvec3> clipped =
      traceStreamline(outwardSampler, dims, params, {5, 1, 1}, +1, 100);
  for (const glm::dvec3& x : clipped) {
    EXPECT_GE(x.y, 0.0);
    EXPECT_LE(x.y, 2.0);
  }
  EXPECT_LT(clipped.size(), 10u) << "leaves through y = 2 after about 3 voxels";
}

// Radial drift of a streamline around the vortex axis after many steps.
double radialDrift(Integrator integrator) {
  const VectorField field = makeAnalyticField(AnalyticField::Vortex, {65, 65, 65});
  const FieldSampler sampler(field);
  LicParams params;
  params.integrator = integrator;
  params.step = 1.0f;
  const glm::dvec3 centre(32.0, 32.0, 0.0);
  const glm::dvec3 start = centre + glm::dvec3(16.0, 0.0, 1.0);
  // 100 unit steps on a circle of radius 16 voxels: about one full turn.
  const std::vector<glm::dvec3> line = traceStreamline(sampler, field.dims, params, start, +1, 100);
  EXPECT_EQ(line.size(), 101u);
  const glm::dvec2 end(line.back().x - centre.x, line.back().y - centre.y);
  return std::abs(glm::length(end) - 16.0);
}

TEST(LicReference, RungeKuttaKeepsCirclesFarBetterThanEuler) {
  const double euler = radialDrift(Integrator::Euler);
  const double rk2 = radialDrift(Integrator::Rk2);
  const double rk4 = radialDrift(Integrator::Rk4);
  // Euler spirals outwards by r (sqrt(1 + (h/r)^2)^n - 1), about 3 voxels here.
  EXPECT_GT(euler, 1.0);
  EXPECT_LT(rk2, euler / 20.0);
  EXPECT_LT(rk4, rk2 + 1e-3);
}

TEST(LicReference, KernelWeights) {
  EXPECT_EQ(kernelWeight(Kernel::Box, 7, 10, 0), 1.0);
  EXPECT_DOUBLE_EQ(kernelWeight(Kernel::Hann, 0, 10, 0), 1.0);
  EXPECT_NEAR(kernelWeight(Kernel::Hann, 11, 10, 0), 0.0, 1e-15);  // reaches zero just past L
  EXPECT_NEAR(kernelWeight(Kernel::Hann, 5, 10, 3), 0.5 * (1 + std::cos(M_PI * 5 / 14)), 1e-15);
  EXPECT_DOUBLE_EQ(kernelWeight(Kernel::Gauss, 0, 10, 0), 1.0);
  EXPECT_NEAR(kernelWeight(Kernel::Gauss, 5, 10, 0), std::exp(-0.5), 1e-15);  // one sigma = L/2
  EXPECT_DOUBLE_EQ(kernelWeight(Kernel::Gauss, 0, 0, 0), 1.0);
}

TEST(LicReference, ThreadCountDoesNotChangeTheResult) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {12, 10, 14});
  const NoiseVolume noise = makeWhiteNoise(field.dims, 4);
  LicParams params;
  params.integrator = Integrator::Rk4;
  const ScalarVolume one = *computeLicReference(field, noise, params, 1);
  const ScalarVolume many = *computeLicReference(field, noise, params, 5);
  EXPECT_EQ(one.values, many.values);
}

// ---- Anisotropic grids (docs/LIC_SEMANTICS.md) -------------------------------------------------

// The magnetic mirror's grid (assets/data/example-femm-3d.vtk): z voxels are 2.5 times as long.
constexpr glm::dvec3 kMirrorSpacing{0.05, 0.05, 0.125};

VectorField onGrid(VectorField field, glm::dvec3 spacing) {
  field.geometry.spacing = spacing;
  return field;
}

TEST(LicReference, VoxelUnitScaleIsExactlyOneOnIsotropicGrids) {
  EXPECT_EQ(voxelUnitScale(GridGeometry{glm::dvec3(0.37)}), glm::dvec3(1.0));
  EXPECT_EQ(voxelUnitScale(GridGeometry{kMirrorSpacing}), glm::dvec3(1.0, 1.0, 0.4));
  const VectorField field = onGrid(constantField({3, 3, 3}, {1.0f, 1.0f, 1.0f}), kMirrorSpacing);
  EXPECT_DOUBLE_EQ(maxVoxelSpeed(field), std::sqrt(2.16));
}

// The physical diagonal (1,1,1) on the mirror's grid is (20, 20, 8) per unit time in voxels
// (component / spacing), the direction (5, 5, 2): a streamline that ignored the spacing would run
// along the voxel diagonal (1, 1, 1) instead, 19.5 degrees away.
TEST(LicReference, StreamlinesOnAnisotropicGridsFollowThePhysicalDirection) {
  const Dims dims{30, 30, 30};
  const VectorField field = onGrid(constantField(dims, {1.0f, 1.0f, 1.0f}), kMirrorSpacing);
  const FieldSampler sampler(field);
  const glm::dvec3 expected = glm::normalize(glm::dvec3(5.0, 5.0, 2.0));
  for (const Integrator integrator : {Integrator::Euler, Integrator::Rk2, Integrator::Rk4}) {
    LicParams params;
    params.integrator = integrator;
    const std::vector<glm::dvec3> line =
        traceStreamline(sampler, dims, params, {5.0, 5.0, 5.0}, +1, 20);
    ASSERT_EQ(line.size(), 21u);
    for (std::size_t i = 1; i < line.size(); ++i) {
      const glm::dvec3 step = line[i] - line[i - 1];
      EXPECT_NEAR(glm::length(step - 0.5 * expected), 0.0, 1e-12) << enumName(integrator) << i;
      // Back in physical units the step points along the field.
      const glm::dvec3 physical = glm::normalize(step * kMirrorSpacing);
      EXPECT_NEAR(glm::length(physical - glm::normalize(glm::dvec3(1.0))), 0.0, 1e-12);
    }
  }
}

// Pearson correlation of a volume with itself shifted by whole voxels, over the voxels where both
// lie in the grid.
double shiftedCorrelation(const ScalarVolume& v, glm::ivec3 shift) {
  double n = 0, sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (int k = 0; k + shift.z < v.dims.z; ++k)
    for (int j = 0; j + shift.y < v.dims.y; ++j)
      for (int i = 0; i + shift.x < v.dims.x; ++i) {
        const double a = v.at(i, j, k), b = v.at(i + shift.x, j + shift.y, k + shift.z);
        n += 1;
        sa += a;
        sb += b;
        saa += a * a;
        sbb += b * b;
        sab += a * b;
      }
  const double cov = sab / n - (sa / n) * (sb / n);
  return cov / std::sqrt((saa / n - (sa / n) * (sa / n)) * (sbb / n - (sb / n) * (sb / n)));
}

// White-noise LIC of a constant field smears the noise along straight lines: the volume is nearly
// unchanged by a shift along them and uncorrelated with a shift across them. On the mirror's grid
// the lines of the physical diagonal run along (5, 5, 2) voxels, not along the voxel diagonal;
// on an isotropic grid the same field gives the opposite picture, so the measure tells the two
// apart.
TEST(LicReference, AnisotropicLicIsSmearedAlongTheVoxelSpaceLine) {
  const Dims dims{32, 32, 32};
  const NoiseVolume noise = makeWhiteNoise(dims, 3);
  LicParams params;
  params.length = 30;  // 15 voxels each way, twice the shift below
  const glm::ivec3 alongLine{5, 5, 2}, alongVoxelDiagonal{4, 4, 4};  // 7.3 and 6.9 voxels

  const VectorField mirror = onGrid(constantField(dims, {1.0f, 1.0f, 1.0f}), kMirrorSpacing);
  const ScalarVolume anisotropic = *computeLicReference(mirror, noise, params);
  // Measured: 0.90 along the line and -0.04 along the voxel diagonal, and the other way round
  // (0.00 and 0.90) on the cubic grid.
  EXPECT_GT(shiftedCorrelation(anisotropic, alongLine), 0.7);
  EXPECT_LT(std::abs(shiftedCorrelation(anisotropic, alongVoxelDiagonal)), 0.15);

  const VectorField cubic = onGrid(mirror, glm::dvec3(0.05));
  const ScalarVolume isotropic = *computeLicReference(cubic, noise, params);
  EXPECT_LT(std::abs(shiftedCorrelation(isotropic, alongLine)), 0.15);
  EXPECT_GT(shiftedCorrelation(isotropic, alongVoxelDiagonal), 0.7);
}

// Magnitude mode scales steps by the voxel-unit speed |u| / max|u|: equally fast physical flow
// along x (fine) and along z (2.5 times coarser) takes equally long physical steps, and the
// fastest voxel-unit flow exactly h voxels.
TEST(LicReference, MagnitudeStepsOnAnisotropicGridsAreProportionalToPhysicalSpeed) {
  const Dims dims{40, 8, 40};
  VectorField field = onGrid(constantField(dims, {1.0f, 0.0f, 0.0f}), kMirrorSpacing);
  for (int k = 0; k < dims.z; ++k)
    for (int j = 4; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        field.vectors[voxelIndex(dims, i, j, k)] = {0.0f, 0.0f, 1.0f};
  const FieldSampler sampler(field);
  LicParams params;
  params.direction = DirectionMode::Magnitude;
  const std::vector<glm::dvec3> alongX = traceStreamline(sampler, dims, params, {10, 1, 10}, +1, 5);
  const std::vector<glm::dvec3> alongZ = traceStreamline(sampler, dims, params, {10, 6, 10}, +1, 5);
  ASSERT_EQ(alongX.size(), 6u);
  ASSERT_EQ(alongZ.size(), 6u);
  EXPECT_NEAR(alongX[1].x - alongX[0].x, 0.5, 1e-12) << "the fastest flow steps h voxels";
  EXPECT_NEAR(alongZ[1].z - alongZ[0].z, 0.5 * 0.4, 1e-12) << "z voxels are 2.5 times as long";
  for (std::size_t i = 1; i < alongX.size(); ++i)
    EXPECT_NEAR(glm::length((alongZ[i] - alongZ[i - 1]) * kMirrorSpacing),
                glm::length((alongX[i] - alongX[i - 1]) * kMirrorSpacing), 1e-12);
}

// Isotropic grids keep the numbers they had before the conversion: the analytic fields come with
// their own (cubic) spacing, which must not change a single bit against spacing 1.
TEST(LicReference, IsotropicSpacingDoesNotChangeTheResult) {
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, {12, 10, 14});
  ASSERT_NE(field.geometry.spacing, glm::dvec3(1.0));
  const NoiseVolume noise = makeWhiteNoise(field.dims, 4);
  for (const DirectionMode direction : {DirectionMode::Normalized, DirectionMode::Magnitude}) {
    LicParams params;
    params.direction = direction;
    const ScalarVolume own = *computeLicReference(field, noise, params);
    const ScalarVolume unit = *computeLicReference(onGrid(field, glm::dvec3(1.0)), noise, params);
    EXPECT_EQ(own.values, unit.values);
  }
}

TEST(LicReference, RejectsGridsWithoutPositiveSpacing) {
  const NoiseVolume noise = makeWhiteNoise({4, 4, 4}, 1);
  for (const glm::dvec3 spacing : {glm::dvec3(1.0, 0.0, 1.0), glm::dvec3(-1.0, 1.0, 1.0),
                                   glm::dvec3(1.0, 1.0, std::nan(""))}) {
    const Result<ScalarVolume> out = computeLicReference(
        onGrid(constantField({4, 4, 4}, {1, 0, 0}), spacing), noise, LicParams{});
    ASSERT_FALSE(out.ok());
    EXPECT_EQ(out.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(out.error().message.find("spacing"), std::string::npos);
  }
}

TEST(LicReference, RejectsBadParameters) {
  const VectorField field = constantField({4, 4, 4}, {1, 0, 0});
  const NoiseVolume noise = makeWhiteNoise({4, 4, 4}, 1);
  LicParams params;
  params.bias = params.length + 1;
  EXPECT_FALSE(computeLicReference(field, noise, params).ok());
  params = {};
  params.step = 0.0f;
  EXPECT_FALSE(computeLicReference(field, noise, params).ok());
  params = {};
  params.length = -1;
  EXPECT_FALSE(computeLicReference(field, noise, params).ok());
  EXPECT_FALSE(computeLicReference(field, makeWhiteNoise({4, 4, 5}, 1), LicParams{}).ok());
}

}  // namespace
}  // namespace lic3d
