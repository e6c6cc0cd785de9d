// The CPU reference against properties that follow from the LIC semantics.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/glm.hpp>

#include "analytic_fields.h"
#include "lic_reference.h"
#include "noise.h"

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
