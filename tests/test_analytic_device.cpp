// SPDX-License-Identifier: BSD-3-Clause
// The analytic fields made on the device (passes/analytic_field_pass.h) against the CPU oracle
// in double precision (lic/analytic_fields.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/geometric.hpp>
#include <glm/gtc/packing.hpp>

#include "core/enum_names.h"
#include "core/volume_compare.h"
#include "gpu/submit.h"
#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "passes/analytic_field_pass.h"
#include "passes/analytic_vectors_pass.h"
#include "render/lic_renderer.h"

namespace lic3d {
namespace {

using test::GpuTest;

TEST_F(GpuTest, AnalyticFieldsOnTheDeviceMatchTheCpuOracle) {
  // An odd grid, several slabs' worth of layers, the tornado at a time off its start.
  const Dims dims{37, 29, 41};
  for (const auto& [field, name] : enumNames<AnalyticField>()) {
    const double time = field == AnalyticField::Tornado ? 123.4 : 0.0;
    const VectorField cpu = makeAnalyticField(field, dims, time);
    const Result<VectorField> gpu = makeAnalyticFieldOnDevice(context(), field, dims, time);
    ASSERT_TRUE(gpu) << gpu.error().message;
    ASSERT_EQ(gpu->dims, dims);
    EXPECT_EQ(gpu->geometry, cpu.geometry) << name;
    const double largest = maxMagnitude(cpu);
    // Float against double: the tornado's published formula jumps where |r - d| = r2, and a
    // voxel within rounding of that seam may land on the other side.
    std::size_t off = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < cpu.vectors.size(); ++i) {
      const double d = glm::length(glm::dvec3(gpu->vectors[i]) - glm::dvec3(cpu.vectors[i]));
      if (d > 1e-4 * largest)
        ++off;
      else
        worst = std::max(worst, d);
    }
    EXPECT_LE(off, cpu.vectors.size() / 10000) << name << ": voxels off the oracle";
    EXPECT_LT(worst, 1e-4 * largest) << name;
  }
}

// A texture's texels as floats, four per voxel (xyzw), decoded as the LIC pass samples them.
std::vector<float> texelsOf(const Context& context, const FieldTexture& texture) {
  const std::size_t bytes = fieldTexelBytes(texture.precision);
  const Result<std::vector<std::byte>> raw =
      readImage(context, texture.image, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, bytes);
  EXPECT_TRUE(raw) << raw.error().message;
  if (!raw) return {};
  std::vector<float> values(raw->size() / (bytes / 4));
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (texture.precision == FieldPrecision::Float) {
      std::memcpy(&values[i], raw->data() + 4 * i, 4);
    } else if (texture.precision == FieldPrecision::Byte) {
      // SNORM8: -128 and -127 both read as -1.
      values[i] = std::max(static_cast<float>(static_cast<std::int8_t>((*raw)[i])) / 127.0f, -1.0f);
    } else {
      std::uint16_t half = 0;
      std::memcpy(&half, raw->data() + 2 * i, 2);
      values[i] = glm::unpackHalf1x16(half);
    }
  }
  return values;
}

TEST_F(GpuTest, AnalyticFieldPassOnTheDeviceMatchTheHostPackedTexture) {
  // The field and its white noise made on the device straight into the texture (the front ends'
  // path for analytic fields) against the oracle's field and noise packed on the host.
  const Dims dims{37, 29, 41};  // odd sizes, three workgroups of z layers
  Result<AnalyticFieldPass> pass = AnalyticFieldPass::create(context());
  ASSERT_TRUE(pass) << pass.error().message;
  for (const AnalyticField field : {AnalyticField::Tornado, AnalyticField::Abc}) {
    const AnalyticInputs inputs{field, dims, field == AnalyticField::Tornado ? 123.4 : 0.0, 77};
    const VectorField cpuField = makeAnalyticField(field, dims, inputs.time);
    const NoiseVolume cpuNoise = makeWhiteNoise(dims, inputs.noiseSeed);
    for (const FieldPrecision precision :
         {FieldPrecision::Float, FieldPrecision::Half, FieldPrecision::Byte}) {
      const std::string what =
          std::string(enumName(field)) + " " + std::string(enumName(precision));
      const Result<FieldTexture> host = uploadLicInputs(context(), cpuField, cpuNoise, precision);
      ASSERT_TRUE(host) << host.error().message;
      Result<FieldTexture> device = pass->createTarget(inputs, precision);
      ASSERT_TRUE(device) << device.error().message;
      ASSERT_TRUE(pass->write(inputs, *device));
      EXPECT_EQ(device->geometry, host->geometry) << what;
      EXPECT_EQ(device->precision, host->precision) << what;
      EXPECT_NEAR(device->maxVoxelSpeed, host->maxVoxelSpeed, 1e-5 * host->maxVoxelSpeed) << what;
      EXPECT_NEAR(device->maxMagnitude, host->maxMagnitude, 1e-5 * host->maxMagnitude) << what;
      EXPECT_NEAR(device->minMagnitude, host->minMagnitude, 1e-4 * host->maxMagnitude) << what;
      for (int a = 0; a < 3; ++a)
        EXPECT_NEAR(device->texelToPhysical[a], host->texelToPhysical[a],
                    1e-5 * host->texelToPhysical[a])
            << what;
      ASSERT_TRUE(device->speeds);
      EXPECT_EQ(device->speeds->total(), voxelCount(dims)) << what;
      const double range = host->maxMagnitude - host->minMagnitude;
      for (const double q : {0.02, 0.5, 0.98})
        EXPECT_NEAR(device->speeds->percentile(q), host->speeds->percentile(q), 1e-3 * range)
            << what << " percentile " << q;

      const std::vector<float> a = texelsOf(context(), *host);
      const std::vector<float> b = texelsOf(context(), *device);
      ASSERT_EQ(a.size(), 4 * voxelCount(dims));
      ASSERT_EQ(b.size(), a.size());
      // The noise is the same bytes (up to the format's rounding); the vectors differ by float
      // against double arithmetic and one rounding of the texture format (a byte texel's step is
      // 1/127), except at the tornado's seam (see above).
      const double tolerance = precision == FieldPrecision::Byte   ? 1.01 / 127.0
                               : precision == FieldPrecision::Half ? 2e-3
                                                                   : 1e-4;
      // Half floats may be rounded either way on a store (Vulkan leaves it to the device): one
      // half-float step (2^-11 at most, for values in [0.5, 1]).
      const float noiseTolerance = precision == FieldPrecision::Half ? 4.9e-4f : 1e-6f;
      std::size_t noiseOff = 0, vectorsOff = 0;
      for (std::size_t i = 0; i < voxelCount(dims); ++i) {
        if (std::abs(a[4 * i + 3] - b[4 * i + 3]) > noiseTolerance) ++noiseOff;
        for (int c = 0; c < 3; ++c)
          if (std::abs(a[4 * i + c] - b[4 * i + c]) > tolerance) {
            ++vectorsOff;
            break;
          }
      }
      EXPECT_EQ(noiseOff, 0u) << what;
      EXPECT_LE(vectorsOff, voxelCount(dims) / 10000) << what;
    }
  }
}

TEST_F(GpuTest, TheLicOfAnAnalyticFieldMadeOnTheDeviceIsTheLicOfTheHostField) {
  const Dims dims{24, 24, 24};
  const AnalyticInputs inputs{AnalyticField::Tornado, dims, 40.0, 5};
  LicParams params;
  params.length = 8;
  ScalarVolume volumes[2];
  for (int onDevice = 0; onDevice < 2; ++onDevice) {
    Result<LicRenderer> renderer = LicRenderer::create(context());
    ASSERT_TRUE(renderer) << renderer.error().message;
    const Result<void> set =
        onDevice ? renderer->setAnalyticInputs(inputs)
                 : renderer->setInputs(makeAnalyticField(inputs.field, dims, inputs.time),
                                       makeWhiteNoise(dims, inputs.noiseSeed));
    ASSERT_TRUE(set) << set.error().message;
    ASSERT_TRUE(renderer->updateLic(params));
    Result<ScalarVolume> volume = renderer->readLicVolume();
    ASSERT_TRUE(volume) << volume.error().message;
    volumes[onDevice] = std::move(*volume);
    if (onDevice) {
      // A second time on the same grid rewrites the texture in place.
      ASSERT_TRUE(renderer->setAnalyticInputs(inputs));
      ASSERT_TRUE(renderer->updateLic(params));
      Result<ScalarVolume> again = renderer->readLicVolume();
      ASSERT_TRUE(again);
      EXPECT_EQ(again->values, volumes[1].values);
    }
  }
  const test::VolumeDifference difference = test::compareVolumes(volumes[0], volumes[1]);
  EXPECT_LT(difference.mean, 2e-3);
  EXPECT_GT(correlation(volumes[0], volumes[1]), 0.999);
}

}  // namespace
}  // namespace lic3d
