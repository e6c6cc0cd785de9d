// SPDX-License-Identifier: BSD-3-Clause
// 2D LIC on the GPU against the CPU reference, and unsteady 3D fields: the time interpolation on
// the GPU against the CPU's blend of the same steps, and the LIC of the blended field.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <glm/glm.hpp>
#include <glm/gtc/packing.hpp>
#include <tuple>

#include "gpu/submit.h"
#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "lic/lic2d_reference.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "lic/time_series.h"
#include "passes/lic2d_pass.h"
#include "passes/time_blend_pass.h"
#include "render/lic_renderer.h"

namespace lic3d {
namespace {

using test::compareVolumes;
using test::GpuTest;
using test::VolumeDifference;

// The 3D tolerances (tests/test_lic_gpu.cpp says why): float positions against double ones move
// trilinear (here bilinear) noise samples by a few 1e-3 at most.
void expectClose(const VolumeDifference& d, const std::string& what) {
  EXPECT_LE(d.mean, 1e-3) << what;
  EXPECT_LE(d.quantile999, 2e-2) << what;
  EXPECT_LE(d.max, 2e-2) << what << " (worst pixel " << d.argMax << ")";
}

VolumeDifference compare2D(const Context& context, const VectorField& field, Dims image,
                           const LicParams& params, FieldPrecision precision) {
  const NoiseVolume noise = makeWhiteNoise(image, 13);
  Result<Lic2DPass> pass = Lic2DPass::create(context);
  EXPECT_TRUE(pass.ok()) << pass.error().message;
  Result<Lic2DInputs> inputs = uploadLic2DInputs(context, field, noise, precision);
  EXPECT_TRUE(inputs.ok()) << inputs.error().message;
  Result<ScalarVolume> gpu = pass->compute(*inputs, params);
  EXPECT_TRUE(gpu.ok()) << gpu.error().message;
  Result<ScalarVolume> cpu = computeLic2DReference(field, noise, params);
  EXPECT_TRUE(cpu.ok()) << cpu.error().message;
  return compareVolumes(*gpu, *cpu);
}

using Variant = std::tuple<Integrator, Kernel>;
class Lic2DVariantTest : public GpuTest, public ::testing::WithParamInterface<Variant> {};

// Every integrator and kernel, at the field's resolution and on an image 2.5 times finer.
TEST_P(Lic2DVariantTest, GpuMatchesCpuReference) {
  LicParams params;
  std::tie(params.integrator, params.kernel) = GetParam();
  params.length = 10;
  params.bias = 3;
  const VectorField circle = makeAnalyticField2D(AnalyticField2D::Circle, {40, 32});
  expectClose(compare2D(context(), circle, circle.dims, params, FieldPrecision::Float),
              "circle at the field's size");
  const VectorField saddle = makeAnalyticField2D(AnalyticField2D::Saddle, {24, 20});
  expectClose(compare2D(context(), saddle, {60, 50, 1}, params, FieldPrecision::Float),
              "saddle upsampled");
}

INSTANTIATE_TEST_SUITE_P(
    AllVariants, Lic2DVariantTest,
    ::testing::Combine(::testing::Values(Integrator::Euler, Integrator::Rk2, Integrator::Rk4),
                       ::testing::Values(Kernel::Box, Kernel::Hann, Kernel::Gauss)),
    [](const ::testing::TestParamInfo<Variant>& variant) {
      return std::string(enumName(std::get<0>(variant.param))) + "_" +
             std::string(enumName(std::get<1>(variant.param)));
    });

TEST_F(GpuTest, Lic2DNearestNoiseMagnitudeStepsExactAndFusedSchemesAndHalfTextures) {
  // A plane of the tornado: speeds vary, so magnitude steps matter.
  const VectorField plane = makeAnalyticFieldPlane(AnalyticField::Tornado, {36, 36, 36}, 2, 20);
  LicParams params;
  params.length = 8;
  params.direction = DirectionMode::Magnitude;
  params.scheme = StepScheme::Exact;
  expectClose(compare2D(context(), plane, {72, 72, 1}, params, FieldPrecision::Float),
              "magnitude steps, exact RK2");
  params.scheme = StepScheme::Fused;
  expectClose(compare2D(context(), plane, {72, 72, 1}, params, FieldPrecision::Float),
              "magnitude steps, fused RK2");
  params.direction = DirectionMode::Normalized;
  params.scheme = LicParams{}.scheme;
  params.noiseFilter = NoiseFilter::Nearest;
  // Nearest noise may swap one sample near a pixel boundary (test_lic_gpu.cpp): two samples'
  // weight at most, the mean stays small.
  const VolumeDifference nearest =
      compare2D(context(), plane, {72, 72, 1}, params, FieldPrecision::Float);
  EXPECT_LE(nearest.mean, 1e-3);
  EXPECT_LE(nearest.max, 2.0 / 17.0);
  // Half textures round the field to 11 bits: the mean still holds.
  params.noiseFilter = NoiseFilter::Linear;
  EXPECT_LE(compare2D(context(), plane, plane.dims, params, FieldPrecision::Half).mean, 2e-3);
}

// The field texture the LIC pass would read for `field` and `noise`: xyz = u / max|u|, w = noise.
std::vector<glm::vec4> packedTexels(const VectorField& field, const NoiseVolume& noise) {
  const glm::dvec3 scale = voxelUnitScale(field.geometry) / maxVoxelSpeed(field);
  std::vector<glm::vec4> texels(field.vectors.size());
  for (std::size_t i = 0; i < texels.size(); ++i)
    texels[i] = glm::vec4(glm::vec3(glm::dvec3(field.vectors[i]) * scale), noise.value(i));
  return texels;
}

TEST_F(GpuTest, TimeInterpolationOnTheGpuMatchesTheCpuBlend) {
  // An anisotropic grid, so the voxel-unit conversion is part of what is checked.
  VectorField a = makeAnalyticField(AnalyticField::Tornado, {20, 18, 16}, 0.0);
  VectorField b = makeAnalyticField(AnalyticField::Tornado, {20, 18, 16}, 150.0);
  a.geometry.spacing = b.geometry.spacing = {0.05, 0.05, 0.08};
  for (glm::vec3& v : b.vectors) v *= 3.0f;  // steps of different scales
  const NoiseVolume noise = makeWhiteNoise(a.dims, 4);
  const double weight = 0.3;
  const VectorField blend = *interpolateFields(a, b, weight);
  const std::vector<glm::vec4> expected = packedTexels(blend, noise);

  Result<TimeBlendPass> pass = TimeBlendPass::create(context());
  ASSERT_TRUE(pass.ok()) << pass.error().message;
  ASSERT_TRUE(pass->setNoise(noise).ok());
  for (const FieldPrecision precision : {FieldPrecision::Float, FieldPrecision::Half}) {
    const bool half = precision == FieldPrecision::Half;
    Result<FieldStep> stepA = uploadFieldStep(context(), a, 0, precision);
    Result<FieldStep> stepB = uploadFieldStep(context(), b, 1, precision);
    ASSERT_TRUE(stepA.ok() && stepB.ok());
    Result<FieldTexture> target = pass->createTarget(a.dims, a.geometry, precision);
    ASSERT_TRUE(target.ok()) << target.error().message;
    ASSERT_TRUE(pass->blend(*stepA, *stepB, weight, *target).ok());
    // The measured scales are the blend's (half steps hold 11 significant bits).
    const double relative = half ? 1e-3 : 1e-5;
    EXPECT_NEAR(target->maxVoxelSpeed, maxVoxelSpeed(blend), relative * maxVoxelSpeed(blend));
    EXPECT_NEAR(target->maxMagnitude, maxMagnitude(blend), relative * maxMagnitude(blend));
    EXPECT_NEAR(target->minMagnitude, minMagnitude(blend), relative * maxMagnitude(blend));

    Result<std::vector<std::byte>> bytes = readImage(
        context(), target->image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, half ? 8 : 16);
    ASSERT_TRUE(bytes.ok());
    double worst = 0.0;
    for (std::size_t i = 0; i < expected.size(); ++i) {
      glm::vec4 texel;
      if (half) {
        std::uint16_t h[4];
        std::memcpy(h, bytes->data() + 8 * i, 8);
        for (int c = 0; c < 4; ++c) texel[c] = glm::unpackHalf1x16(h[c]);
      } else {
        std::memcpy(&texel, bytes->data() + 16 * i, 16);
      }
      worst = std::max(worst, static_cast<double>(glm::length(texel - expected[i])));
    }
    // Float: rounding only. Half: the steps and the texture each round to 11 bits.
    EXPECT_LT(worst, half ? 3e-3 : 1e-5) << (half ? "half" : "float");
  }
}

TEST_F(GpuTest, LicOfATimeSeriesIsTheLicOfTheBlendedField) {
  const Dims dims{24, 20, 16};
  const Result<TimeSeries> series = analyticSeries(AnalyticField::Tornado, dims, 6);
  ASSERT_TRUE(series.ok());
  const NoiseVolume noise = makeWhiteNoise(dims, 8);
  Result<LicRenderer> renderer = LicRenderer::create(context(), {FieldPrecision::Float});
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setTimeNoise(noise).ok());
  LicParams params;
  params.length = 8;
  std::uint64_t bytesWithTwoSteps = 0;
  // Times in three intervals: steps stream through the two resident slots.
  for (const double t : {0.4, 1.7, 2.25}) {
    const TimeBracket b = series->bracket(t * series->period / 6);
    for (const int k : {b.first, b.second}) {
      if (renderer->hasTimeStep(k)) continue;
      const int keep = k == b.first ? b.second : b.first;
      ASSERT_TRUE(renderer->setTimeStep(k, *series->loadStep(k), keep).ok());
    }
    ASSERT_TRUE(renderer->blendTime(b.first, b.second, b.weight).ok());
    EXPECT_TRUE(renderer->needsLic(params));
    ASSERT_TRUE(renderer->updateLic(params).ok());
    EXPECT_FALSE(renderer->needsLic(params));
    const Result<ScalarVolume> gpu = renderer->readLicVolume();
    ASSERT_TRUE(gpu.ok());
    const VectorField blend =
        *interpolateFields(*series->loadStep(b.first), *series->loadStep(b.second), b.weight);
    const Result<ScalarVolume> cpu = computeLicReference(blend, noise, params);
    expectClose(compareVolumes(*gpu, *cpu), "time " + std::to_string(t));
    // Only the two steps in use are on the device.
    EXPECT_EQ(renderer->hasTimeStep(b.first) + renderer->hasTimeStep(b.second), 2);
    if (bytesWithTwoSteps == 0) bytesWithTwoSteps = renderer->volumeBytes();
    EXPECT_EQ(renderer->volumeBytes(), bytesWithTwoSteps);
  }
  EXPECT_FALSE(renderer->hasTimeStep(0));
}

// Setting a series' noise starts a new series: steps of the last one with the same numbers are
// not taken for the new one's (the app loading another series, or the tornado with another step
// count).
TEST_F(GpuTest, ANewSeriesDoesNotReuseTheLastSeriesSteps) {
  const Dims dims{16, 16, 12};
  // Step 1 of 4 over the period is another time than step 1 of 3.
  const Result<TimeSeries> four = analyticSeries(AnalyticField::Tornado, dims, 4);
  const Result<TimeSeries> three = analyticSeries(AnalyticField::Tornado, dims, 3);
  ASSERT_TRUE(four.ok() && three.ok());
  const NoiseVolume noise = makeWhiteNoise(dims, 3);
  Result<LicRenderer> renderer = LicRenderer::create(context(), {FieldPrecision::Float});
  ASSERT_TRUE(renderer.ok());
  LicParams params;
  params.length = 6;
  for (const TimeSeries* series : {&*four, &*three}) {
    ASSERT_TRUE(renderer->setTimeNoise(noise).ok());
    EXPECT_FALSE(renderer->hasTimeStep(0));
    ASSERT_TRUE(renderer->setTimeStep(0, *series->loadStep(0), 1).ok());
    ASSERT_TRUE(renderer->setTimeStep(1, *series->loadStep(1), 0).ok());
    ASSERT_TRUE(renderer->blendTime(0, 1, 0.5).ok());
    ASSERT_TRUE(renderer->updateLic(params).ok());
    const Result<ScalarVolume> gpu = renderer->readLicVolume();
    ASSERT_TRUE(gpu.ok());
    const VectorField blend = *interpolateFields(*series->loadStep(0), *series->loadStep(1), 0.5);
    expectClose(compareVolumes(*gpu, *computeLicReference(blend, noise, params)),
                series->describe());
  }
}

}  // namespace
}  // namespace lic3d
