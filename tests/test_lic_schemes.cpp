// SPDX-License-Identifier: BSD-3-Clause
// The one-fetch paths: the ab2 and fused schemes against the CPU reference and against the exact
// scheme, and the byte-packed field texture (docs/LIC_SEMANTICS.md, "Schemes" and "Field packing").
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/glm.hpp>
#include <optional>

#include "core/volume_compare.h"
#include "gpu_test_support.h"
#include "io/field_io.h"
#include "lic/analytic_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "render/lic_renderer.h"
#include "test_support.h"

namespace lic3d {
namespace {

using test::compareVolumes;
using test::GpuTest;

ScalarVolume gpuLic(const Context& context, const VectorField& field, const NoiseVolume& noise,
                    const LicParams& params, FieldPrecision precision) {
  Result<LicRenderer> renderer = LicRenderer::create(context, {precision});
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  EXPECT_TRUE(renderer->setInputs(field, noise).ok());
  EXPECT_TRUE(renderer->updateLic(params).ok());
  Result<ScalarVolume> volume = renderer->readLicVolume();
  EXPECT_TRUE(volume.ok());
  return std::move(*volume);
}

// The fused scheme's samples, on the CPU reference: the even ones are the exact scheme's RK2
// samples with steps of 2h, each odd one lies h from the sample before along the direction there.
TEST(LicSchemes, FusedSamplesAreRk2StepsOfTwiceHAndTheirMidpoints) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, Dims(24));
  const FieldSampler sampler(field);
  LicParams fused;
  fused.scheme = StepScheme::Fused;
  fused.length = 16;
  LicParams exact2h = fused;
  exact2h.scheme = StepScheme::Exact;
  exact2h.step = 2.0f * fused.step;
  exact2h.length = fused.length / 2;
  int compared = 0;
  for (const glm::dvec3 start : {glm::dvec3(12, 11, 12), glm::dvec3(11.3, 12.5, 10.2)}) {
    for (const int sign : {-1, 1}) {
      const std::vector<glm::dvec3> samples =
          traceStreamline(sampler, field.dims, fused, start, sign, fused.length);
      const std::vector<glm::dvec3> ends =
          traceStreamline(sampler, field.dims, exact2h, start, sign, exact2h.length);
      ASSERT_EQ(samples.size(), 2 * ends.size() - 1);
      for (std::size_t i = 0; i < samples.size(); ++i) {
        if (i % 2 == 0) {
          EXPECT_LT(glm::length(samples[i] - ends[i / 2]), 1e-12) << i;
          ++compared;
          continue;
        }
        const glm::dvec3 d = glm::normalize(sampler.at(samples[i - 1]));
        EXPECT_LT(glm::length(samples[i] - (samples[i - 1] + sign * 0.5 * d)), 1e-12) << i;
      }
    }
  }
  EXPECT_EQ(compared, 4 * 9);
}

// The converged reference the schemes are judged by: with no refinement it is the RK4 LIC itself;
// refined, it sits closer to exact RK2 than Euler's LIC does, and closer still to RK4's.
TEST(LicSchemes, ConvergedReferenceIsRefinedRk4) {
  const VectorField field = makeAnalyticField(AnalyticField::Vortex, Dims(20));
  const NoiseVolume noise = makeWhiteNoise(field.dims, 5);
  const FieldSampler sampler(field);
  LicParams rk4, rk2, euler;
  rk4.integrator = Integrator::Rk4;
  euler.integrator = Integrator::Euler;
  rk4.length = rk2.length = euler.length = 12;
  rk4.bias = rk2.bias = euler.bias = 2;
  rk4.step = rk2.step = euler.step = 0.7f;
  double offRk4 = 0.0, offRk2 = 0.0, offEuler = 0.0;
  for (int k = 2; k < 18; k += 3) {
    for (int j = 1; j < 19; j += 2) {
      for (int i = 0; i < 20; i += 2) {
        const glm::ivec3 v(i, j, k);
        EXPECT_NEAR(convergedLicAtVoxel(sampler, noise, rk2, v, 1),
                    licAtVoxel(sampler, noise, rk4, v), 1e-12);
        const double converged = convergedLicAtVoxel(sampler, noise, rk2, v);
        offRk4 += std::abs(licAtVoxel(sampler, noise, rk4, v) - converged);
        offRk2 += std::abs(licAtVoxel(sampler, noise, rk2, v) - converged);
        offEuler += std::abs(licAtVoxel(sampler, noise, euler, v) - converged);
      }
    }
  }
  std::printf("summed |LIC - converged|: rk4 %.3e, rk2 %.3e, euler %.3e\n", offRk4, offRk2,
              offEuler);
  EXPECT_LT(offRk4, offRk2);
  EXPECT_LT(offRk2, offEuler);
}

// The GPU integrates the same streamlines as the reference with each scheme: the tolerances
// of test_lic_gpu.cpp hold, for both texture precisions, with bias and both direction modes.
TEST_F(GpuTest, EveryRk2SchemeMatchesCpuReference) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {24, 32, 40});
  const NoiseVolume noise = makeWhiteNoise(field.dims, 7);
  for (const auto& [scheme, direction] :
       {std::pair{StepScheme::Ab2, DirectionMode::Normalized},
        std::pair{StepScheme::Ab2, DirectionMode::Magnitude},
        std::pair{StepScheme::Fused, DirectionMode::Normalized},
        std::pair{StepScheme::Fused, DirectionMode::Magnitude},
        std::pair{StepScheme::Exact, DirectionMode::Normalized}}) {
    LicParams params;
    params.scheme = scheme;
    params.length = 12;
    params.bias = 3;
    params.direction = direction;
    const ScalarVolume cpu = *computeLicReference(field, noise, params);
    LicParams other = params;
    other.scheme = scheme == StepScheme::Exact ? StepScheme::Ab2 : StepScheme::Exact;
    const ScalarVolume cpuOther = *computeLicReference(field, noise, other);
    for (const FieldPrecision precision : {FieldPrecision::Float, FieldPrecision::Half}) {
      const ScalarVolume gpu = gpuLic(context(), field, noise, params, precision);
      const test::VolumeDifference d = compareVolumes(gpu, cpu);
      const std::string what = std::string(enumName(scheme)) + ", " +
                               std::string(enumName(direction)) +
                               (precision == FieldPrecision::Half ? ", half" : ", float");
      EXPECT_LE(d.mean, 1e-3) << what;
      EXPECT_LE(d.quantile999, 2e-2) << what;
      // The GPU ran this scheme, not the other: it is much closer to this one's reference.
      const double otherMean = compareVolumes(gpu, cpuOther).mean;
      std::printf("%s: mean |GPU - CPU| %.2e, against the other scheme's CPU volume %.2e\n",
                  what.c_str(), d.mean, otherMean);
      if (precision == FieldPrecision::Float) {
        EXPECT_LT(3.0 * d.mean, otherMean) << what;
      }
    }
  }
}

// Workgroup shapes and walks change how the work is spread, not the volume: every launch gives
// the same one up to the order of the sums (one step of the 16-bit volume), also when the volume
// is computed in slabs that a workgroup's depth overhangs.
TEST_F(GpuTest, EveryLaunchGivesTheSameVolume) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {20, 12, 27});
  const NoiseVolume noise = makeWhiteNoise(field.dims, 4);
  for (const StepScheme scheme : {StepScheme::Exact, StepScheme::Fused}) {
    LicParams params;
    params.scheme = scheme;
    params.length = 9;
    params.sparsity.distribution = SparsityDistribution::Halton;
    std::optional<ScalarVolume> first;
    for (const LicSpecialization& launch : {licLaunch(8, 8, 1, true), licLaunch(4, 4, 4, false),
                                            licLaunch(16, 2, 2, true), licLaunch(8, 4, 2, false)}) {
      RendererOptions options;
      options.licLaunch = launch;
      Result<LicRenderer> renderer = LicRenderer::create(context(), options);
      ASSERT_TRUE(renderer.ok());
      ASSERT_TRUE(renderer->setInputs(field, noise).ok());
      // In one dispatch, then (with progress) in slabs of a few z slices.
      ASSERT_TRUE(renderer->updateLic(params).ok());
      const ScalarVolume whole = *renderer->readLicVolume();
      int slabs = 0;
      ASSERT_TRUE(renderer->setInputs(field, noise).ok());
      ASSERT_TRUE(renderer->updateLic(params, [&](double) { ++slabs; }).ok());
      EXPECT_GT(slabs, 2);
      ScalarVolume volume = *renderer->readLicVolume();
      EXPECT_EQ(volume.values, whole.values);
      if (!first) {
        first = std::move(volume);
        continue;
      }
      double largest = 0.0;
      for (std::size_t i = 0; i < volume.values.size(); ++i)
        largest = std::max(largest, std::abs(double(volume.values[i]) - first->values[i]));
      EXPECT_LE(largest, 1.5 / 65535.0)
          << launch.localSizeX << "x" << launch.localSizeY << "x" << launch.localSizeZ;
      EXPECT_EQ(volume.drawn, first->drawn);
    }
  }
}

// How close ab2's volumes come to the exact scheme's, on the analytic fields and the real ones
// (CPU reference, double precision, so the numbers are the schemes' own). Printed for
// docs/BENCHMARKS.md; the bounds are the measured values less a margin, so a change that makes
// ab2 drift further from exact fails here. Measured (L = 20, h = 0.5): see the printout.
TEST(LicSchemes, Ab2CorrelatesWithExactScheme) {
  struct Case {
    const char* name;
    VectorField field;
    double bound;
  };
  std::vector<Case> cases;
  for (const auto& [name, kind, bound] :
       {std::tuple{"tornado", AnalyticField::Tornado, 0.999},
        std::tuple{"corner", AnalyticField::Corner, 0.999},
        std::tuple{"abc", AnalyticField::Abc, 0.999},
        std::tuple{"vortex", AnalyticField::Vortex, 0.999},
        std::tuple{"solenoidal", AnalyticField::Solenoidal, 0.985}})
    cases.push_back({name, makeAnalyticField(kind, Dims(32)), bound});
  cases.push_back({"carotid", *readVectorField(test::dataFolder() / "carotid.vtk"), 0.85});
  cases.push_back({"femm", *readVectorField(test::dataFolder() / "example-femm-3d.vtk"), 0.999});
  for (const Case& c : cases) {
    const NoiseVolume noise = makeWhiteNoise(c.field.dims, 7);
    LicParams exact;
    exact.scheme = StepScheme::Exact;
    LicParams ab2 = exact;
    ab2.scheme = StepScheme::Ab2;
    LicParams rk4 = exact;
    rk4.integrator = Integrator::Rk4;
    const ScalarVolume reference = *computeLicReference(c.field, noise, exact);
    const ScalarVolume fast = *computeLicReference(c.field, noise, ab2);
    const double r = correlation(fast, reference);
    const double rRk4 = correlation(*computeLicReference(c.field, noise, rk4), reference);
    // Where the flow is (|v| at least 3 % of the largest, as the gallery shows the carotid):
    // elsewhere real data holds measurement noise, whose streamlines wander at random.
    const double top = maxMagnitude(c.field);
    const double rFlow = correlation(fast, reference, [&](std::size_t i) {
      return glm::length(c.field.vectors[i]) >= 0.03 * top;
    });
    std::printf(
        "%-10s %3dx%3dx%3d  r(ab2, exact) = %.5f (where |v| >= 3 %% of max: %.5f)  "
        "r(rk4, exact) = %.5f\n",
        c.name, c.field.dims.x, c.field.dims.y, c.field.dims.z, r, rFlow, rRk4);
    EXPECT_GE(r, c.bound) << c.name;
  }
}

// The byte texture: 8-bit directions and noise, so not the reference's numbers, but the same
// picture: the volume correlates with the float texture's, and colour by magnitude decodes the
// square-root packing (a texture read as u / max|u| would make the slow flow far too slow).
TEST_F(GpuTest, BytePackedFieldGivesTheSameVolumeAndColours) {
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, Dims(40));
  const NoiseVolume noise = makeWhiteNoise(field.dims, 3);
  LicParams params;
  params.length = 10;
  const ScalarVolume full = gpuLic(context(), field, noise, params, FieldPrecision::Float);
  const ScalarVolume packed = gpuLic(context(), field, noise, params, FieldPrecision::Byte);
  const double r = correlation(full, packed);
  std::printf("tornado 40^3: r(byte, float) = %.5f, mean |diff| = %.2e\n", r,
              compareVolumes(full, packed).mean);
  EXPECT_GE(r, 0.99);
  EXPECT_LE(compareVolumes(full, packed).mean, 1e-2);

  ViewParams view;
  view.width = view.height = 96;
  view.color = ColorMode::Magnitude;
  RgbaImage images[2];
  int i = 0;
  for (const FieldPrecision precision : {FieldPrecision::Float, FieldPrecision::Byte}) {
    Result<LicRenderer> renderer = LicRenderer::create(context(), {precision});
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->setInputs(field, noise).ok());
    Result<RgbaImage> image = renderer->render(params, view);
    ASSERT_TRUE(image.ok()) << image.error().message;
    images[i++] = std::move(*image);
  }
  double difference = 0.0;
  for (std::size_t p = 0; p < images[0].pixels.size(); ++p)
    difference +=
        std::abs(static_cast<int>(images[0].pixels[p]) - static_cast<int>(images[1].pixels[p]));
  difference /= static_cast<double>(images[0].pixels.size());
  std::printf("colour by magnitude, byte against float: mean |difference| %.2f of 255\n",
              difference);
  EXPECT_LE(difference, 3.0);
}

}  // namespace
}  // namespace lic3d
