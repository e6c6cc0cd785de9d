// SPDX-License-Identifier: BSD-3-Clause
// The GPU LIC pass against the CPU reference, and the recompute-only-on-change contract.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <glm/gtc/packing.hpp>
#include <stop_token>
#include <tuple>

#include "gpu/submit.h"
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
using test::VolumeDifference;

// A non-cubic grid: a swapped axis anywhere shows up as a large difference.
constexpr Dims kGrid{24, 32, 40};

struct Comparison {
  VolumeDifference difference;
  ScalarVolume gpu;
};

Comparison compareWithReference(const Context& context, const VectorField& field,
                                const LicParams& params,
                                FieldPrecision precision = FieldPrecision::Float) {
  const NoiseVolume noise = makeWhiteNoise(field.dims, 7);
  Result<LicRenderer> renderer = LicRenderer::create(context, {precision});
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  EXPECT_TRUE(renderer->setInputs(field, noise).ok());
  Result<bool> ran = renderer->updateLic(params);
  EXPECT_TRUE(ran.ok()) << ran.error().message;
  Result<ScalarVolume> gpu = renderer->readLicVolume();
  EXPECT_TRUE(gpu.ok()) << gpu.error().message;
  Result<ScalarVolume> cpu = computeLicReference(field, noise, params);
  EXPECT_TRUE(cpu.ok());
  return {compareVolumes(*gpu, *cpu), std::move(*gpu)};
}

// Tolerances, and why:
// - Trilinear noise: streamline positions differ between the GPU (float32 arithmetic, hardware
//   filtering with fixed-point weights) and the double-precision reference by about 1e-3 voxel
//   after L steps; the noise is continuous in position, so each sample differs by a few 1e-3 at
//   most, and the 16-bit output adds 1e-5. Hence mean 1e-3 and max 2e-2 as the issue asks.
// - Nearest noise: the lookup is discontinuous. A sample position within ~1e-3 voxel of a voxel
//   boundary may round the other way on the GPU, swapping one noise value (a change of up to 1)
//   in a sum of 2L+1 weighted samples. Such voxels are rare (the mean and the 99.9th percentile
//   still meet 1e-3 and 2e-2), and in each one the error is bounded by the swapped samples'
//   weight: we allow two swaps, 2 * w_max / sum(w).
struct Tolerance {
  double mean = 1e-3;
  double quantile999 = 2e-2;
  double max = 2e-2;
};

Tolerance toleranceFor(const LicParams& params) {
  Tolerance t;
  if (params.noiseFilter == NoiseFilter::Nearest) {
    double sum = 0.0, largest = 0.0;
    for (int i = -(params.length - params.bias); i <= params.length + params.bias; ++i) {
      const double w = kernelWeight(params.kernel, i, params.length, params.bias);
      sum += w;
      largest = std::max(largest, w);
    }
    t.max = 2.0 * largest / sum;
  }
  return t;
}

void expectWithin(const VolumeDifference& d, const Tolerance& t, const std::string& what) {
  EXPECT_LE(d.mean, t.mean) << what;
  EXPECT_LE(d.quantile999, t.quantile999) << what;
  EXPECT_LE(d.max, t.max) << what << " (worst voxel index " << d.argMax << ")";
}

using Variant = std::tuple<Integrator, Kernel, NoiseFilter>;

class LicVariantTest : public GpuTest, public ::testing::WithParamInterface<Variant> {};

// Every variant with both texture precisions: float (lavapipe's default) and half (GPUs').
TEST_P(LicVariantTest, GpuMatchesCpuReferenceOnVortex) {
  LicParams params;
  std::tie(params.integrator, params.kernel, params.noiseFilter) = GetParam();
  params.length = 10;
  const VectorField field = makeAnalyticField(AnalyticField::Vortex, kGrid);
  for (const FieldPrecision precision : {FieldPrecision::Float, FieldPrecision::Half}) {
    const Comparison c = compareWithReference(context(), field, params, precision);
    expectWithin(c.difference, toleranceFor(params),
                 precision == FieldPrecision::Half ? "vortex, half" : "vortex, float");
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllVariants, LicVariantTest,
    ::testing::Combine(::testing::Values(Integrator::Euler, Integrator::Rk2, Integrator::Rk4),
                       ::testing::Values(Kernel::Box, Kernel::Hann, Kernel::Gauss),
                       ::testing::Values(NoiseFilter::Nearest, NoiseFilter::Linear)),
    [](const ::testing::TestParamInfo<Variant>& variant) {
      return std::string(enumName(std::get<0>(variant.param))) + "_" +
             std::string(enumName(std::get<1>(variant.param))) + "_" +
             std::string(enumName(std::get<2>(variant.param)));
    });

// With half precision the GPU stores v / max|v| and the noise as half floats. Away from the
// vortex' uniform speed, that rounding alone moves a few streamlines enough to change single
// voxels by more than 2e-2 (we measured 2 of 30720 voxels at 0.026 for ABC below). So the half
// texture is held to the reference in two ways: against the exact inputs with the mean
// and a 99.9th percentile, and against the reference run on the half-rounded inputs (what the
// GPU actually integrates) with the max too.
float roundedToHalf(float value) { return glm::unpackHalf1x16(glm::packHalf1x16(value)); }

VectorField roundedToHalfPrecision(const VectorField& field) {
  VectorField rounded = field;
  const double scale = maxMagnitude(field);
  for (glm::vec3& v : rounded.vectors)
    for (int a = 0; a < 3; ++a)
      v[a] = static_cast<float>(roundedToHalf(static_cast<float>(v[a] / scale)) * scale);
  return rounded;
}

NoiseVolume roundedToHalfPrecision(const NoiseVolume& noise) {
  NoiseVolume rounded;
  rounded.dims = noise.dims;
  rounded.type = NoiseType::Float32;
  rounded.bytes.resize(4 * voxelCount(noise.dims));
  for (std::size_t i = 0; i < voxelCount(noise.dims); ++i) {
    const float v = roundedToHalf(noise.value(i));
    std::memcpy(rounded.bytes.data() + 4 * i, &v, 4);
  }
  return rounded;
}

TEST_F(GpuTest, GpuMatchesCpuReferenceOnAbcWithBiasAndMagnitudeSteps) {
  LicParams params;
  params.length = 12;
  params.bias = 5;
  params.direction = DirectionMode::Magnitude;
  params.step = 0.7f;
  const VectorField field = makeAnalyticField(AnalyticField::Abc, kGrid);
  expectWithin(compareWithReference(context(), field, params, FieldPrecision::Float).difference,
               toleranceFor(params), "abc, float");
  const Comparison half = compareWithReference(context(), field, params, FieldPrecision::Half);
  EXPECT_LE(half.difference.mean, 1e-3);
  EXPECT_LE(half.difference.quantile999, 2e-2);
  const ScalarVolume rounded = *computeLicReference(
      roundedToHalfPrecision(field), roundedToHalfPrecision(makeWhiteNoise(field.dims, 7)), params);
  expectWithin(compareVolumes(half.gpu, rounded), toleranceFor(params), "abc, half-rounded inputs");
}

// The solenoidal field vanishes on the three coordinate axes through the grid centre: critical
// lines around which the direction turns within a voxel, so streamlines started half a voxel away
// are sensitive to the hardware's 8-bit interpolation weights. The mean and 99 % of the voxels
// still meet the tolerances (we measured 0.6 % of the voxels above 2e-2, all near those lines).
TEST_F(GpuTest, GpuMatchesCpuReferenceOnSolenoidalWithRk4Gauss) {
  LicParams params;
  params.length = 15;
  params.integrator = Integrator::Rk4;
  params.kernel = Kernel::Gauss;
  const VectorField field = makeAnalyticField(AnalyticField::Solenoidal, kGrid);
  const Comparison c = compareWithReference(context(), field, params);
  EXPECT_LE(c.difference.mean, 1e-3);
  const ScalarVolume cpu = *computeLicReference(field, makeWhiteNoise(field.dims, 7), params);
  std::size_t close = 0;
  for (std::size_t i = 0; i < cpu.values.size(); ++i)
    close += std::abs(cpu.values[i] - c.gpu.values[i]) <= 2e-2f;
  EXPECT_GE(static_cast<double>(close) / static_cast<double>(cpu.values.size()), 0.99);
}

// The real fields have regions of near-zero, noisy vectors (outside the carotid artery) where
// a half-float field and hardware interpolation send streamlines elsewhere than the reference:
// the mean stays small, single voxels may differ a lot. We hold the mean to 5e-3 and 99 % of the
// voxels to 2e-2.
void expectCloseOnRealField(const Context& context, const char* file) {
  Result<VectorField> field = readVectorField(test::dataFolder() / file);
  ASSERT_TRUE(field.ok()) << field.error().message;
  LicParams params;
  const Comparison c = compareWithReference(context, *field, params);
  EXPECT_LE(c.difference.mean, 5e-3) << file;
  const ScalarVolume cpu = *computeLicReference(*field, makeWhiteNoise(field->dims, 7), params);
  std::size_t close = 0;
  for (std::size_t i = 0; i < cpu.values.size(); ++i)
    close += std::abs(cpu.values[i] - c.gpu.values[i]) <= 2e-2f;
  EXPECT_GE(static_cast<double>(close) / static_cast<double>(cpu.values.size()), 0.99) << file;
}

TEST_F(GpuTest, GpuMatchesCpuReferenceOnCarotidFlow) {
  expectCloseOnRealField(context(), "carotid.vtk");
}

TEST_F(GpuTest, GpuMatchesCpuReferenceOnMagneticMirror) {
  expectCloseOnRealField(context(), "example-femm-3d.vtk");
}

// ---- Anisotropic grids (docs/LIC_SEMANTICS.md) -------------------------------------------------

// A different spacing on each axis: the upload must convert each component with its own axis'
// spacing as the reference does. The result must also differ clearly from the same vectors on a
// cubic grid, so a GPU path that skipped the conversion could not pass. Measured on lavapipe:
// mean 3.8e-6 and max 8.9e-6 from the reference, mean 5.1e-2 and 5.3e-2 from the cubic grid's.
TEST_F(GpuTest, GpuMatchesCpuReferenceOnAnisotropicGrid) {
  VectorField field = makeAnalyticField(AnalyticField::Abc, kGrid);
  VectorField cubic = field;
  cubic.geometry.spacing = glm::dvec3(1.0);
  field.geometry.spacing = {0.5, 1.0, 2.0};
  LicParams normalized;
  normalized.length = 10;
  LicParams magnitude;
  magnitude.length = 12;
  magnitude.bias = 3;
  magnitude.integrator = Integrator::Rk4;
  magnitude.direction = DirectionMode::Magnitude;
  magnitude.step = 0.7f;
  for (const LicParams& params : {normalized, magnitude}) {
    const std::string what =
        "abc on a 0.5 x 1 x 2 grid, " + std::string(enumName(params.direction));
    const Comparison c = compareWithReference(context(), field, params);
    expectWithin(c.difference, toleranceFor(params), what);
    const ScalarVolume onCubicGrid =
        *computeLicReference(cubic, makeWhiteNoise(field.dims, 7), params);
    const VolumeDifference d = compareVolumes(c.gpu, onCubicGrid);
    EXPECT_GT(d.mean, 10 * Tolerance{}.mean) << what << ": as if the grid were cubic";
  }
  // Half precision stores the converted vectors as half floats: held to the mean and 99.9 %.
  const Comparison half = compareWithReference(context(), field, normalized, FieldPrecision::Half);
  EXPECT_LE(half.difference.mean, 1e-3);
  EXPECT_LE(half.difference.quantile999, 2e-2);
}

// The conversion's factor is exactly 1 on isotropic grids: an analytic field on its own cubic
// spacing gives the very same LIC volume as on spacing 1.
TEST_F(GpuTest, IsotropicSpacingDoesNotChangeTheGpuResult) {
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, {16, 12, 20});
  ASSERT_NE(field.geometry.spacing, glm::dvec3(1.0));
  VectorField unit = field;
  unit.geometry.spacing = glm::dvec3(1.0);
  const NoiseVolume noise = makeWhiteNoise(field.dims, 5);
  LicParams params;
  params.direction = DirectionMode::Magnitude;
  std::vector<ScalarVolume> volumes;
  for (const VectorField* f : {&field, static_cast<const VectorField*>(&unit)}) {
    Result<LicRenderer> renderer = LicRenderer::create(context(), {FieldPrecision::Half});
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->setInputs(*f, noise).ok());
    ASSERT_TRUE(renderer->updateLic(params).ok());
    volumes.push_back(*renderer->readLicVolume());
  }
  EXPECT_EQ(volumes[0].values, volumes[1].values);
}

TEST_F(GpuTest, ZeroFieldGivesTheNoiseItself) {
  VectorField field;
  field.dims = {9, 10, 11};
  field.vectors.assign(voxelCount(field.dims), glm::vec3(0.0f));
  const NoiseVolume noise = makeWhiteNoise(field.dims, 3);
  Result<LicRenderer> renderer = LicRenderer::create(context(), {FieldPrecision::Float});
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, noise).ok());
  ASSERT_TRUE(renderer->updateLic(LicParams{}).ok());
  const ScalarVolume gpu = *renderer->readLicVolume();
  for (std::size_t i = 0; i < gpu.values.size(); ++i)
    ASSERT_NEAR(gpu.values[i], noise.value(i), 1.0 / 65535.0) << i;
}

TEST_F(GpuTest, RecomputesOnlyWhenLicInputsChange) {
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, {16, 16, 16});
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  LicParams lic;
  ViewParams view;
  view.width = view.height = 48;

  ASSERT_TRUE(renderer->render(lic, view).ok());
  ASSERT_TRUE(renderer->render(lic, view).ok());
  EXPECT_EQ(renderer->licDispatchCount(), 1u) << "same LicParams twice";

  view.camera.azimuth += 40.0f;
  view.alpha = 0.5f;
  view.slicing = Slicing::AxisAligned;
  ASSERT_TRUE(renderer->render(lic, view).ok());
  EXPECT_EQ(renderer->licDispatchCount(), 1u) << "view changes redraw only";

  lic.length += 1;
  ASSERT_TRUE(renderer->render(lic, view).ok());
  EXPECT_EQ(renderer->licDispatchCount(), 2u) << "a LIC parameter changed";

  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 2)).ok());
  ASSERT_TRUE(renderer->render(lic, view).ok());
  EXPECT_EQ(renderer->licDispatchCount(), 3u) << "the noise changed";

  ASSERT_TRUE(renderer
                  ->setInputs(makeAnalyticField(AnalyticField::Vortex, {16, 16, 16}),
                              makeWhiteNoise(field.dims, 2))
                  .ok());
  ASSERT_TRUE(renderer->render(lic, view).ok());
  ASSERT_TRUE(renderer->render(lic, view).ok());
  EXPECT_EQ(renderer->licDispatchCount(), 4u) << "the field changed";
}

TEST_F(GpuTest, PipelineVariantsAreCreatedOnceAndCached) {
  const VectorField field = makeAnalyticField(AnalyticField::Vortex, {8, 8, 8});
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  LicParams a, b;
  b.integrator = Integrator::Rk4;
  b.kernel = Kernel::Hann;
  for (const LicParams& p : {a, b, a, b}) {
    LicParams changed = p;
    changed.length = p.length + static_cast<int>(renderer->licDispatchCount());  // force a dispatch
    ASSERT_TRUE(renderer->updateLic(changed).ok());
  }
  EXPECT_EQ(renderer->licDispatchCount(), 4u);
  EXPECT_EQ(renderer->licJob().variantCount(), 2u);
}

TEST_F(GpuTest, ProgressSplitsTheWorkAndReachesOne) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {16, 16, 40});
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  LicParams params;
  std::vector<double> reports;
  ASSERT_TRUE(renderer->updateLic(params, [&](double f) { reports.push_back(f); }).ok());
  ASSERT_GE(reports.size(), 10u);
  EXPECT_TRUE(std::is_sorted(reports.begin(), reports.end()));
  EXPECT_DOUBLE_EQ(reports.back(), 1.0);
  // The slabs together equal one whole dispatch.
  const ScalarVolume slabbed = *renderer->readLicVolume();
  params.length += 1;
  ASSERT_TRUE(renderer->updateLic(params).ok());
  params.length -= 1;
  ASSERT_TRUE(renderer->updateLic(params).ok());
  const ScalarVolume whole = *renderer->readLicVolume();
  EXPECT_EQ(compareVolumes(slabbed, whole).max, 0.0);
}

TEST_F(GpuTest, AStopRequestEndsTheJobAfterTheSlabInFlightAndItResumes) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {16, 16, 40});
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  LicParams params;
  std::stop_source stop;
  std::vector<double> reports;
  const Result<bool> stopped = renderer->updateLic(params, ProgressCallback(
                                                               [&](double f) {
                                                                 reports.push_back(f);
                                                                 stop.request_stop();
                                                               },
                                                               stop.get_token()));
  ASSERT_FALSE(stopped.ok());
  EXPECT_EQ(stopped.error().kind, ErrorKind::Cancelled);
  ASSERT_EQ(reports.size(), 1u) << "no slab after the stop";
  EXPECT_LT(reports[0], 1.0);
  EXPECT_TRUE(renderer->licStatus().pending);
  // The job goes on where it stopped, to the volume of one whole run.
  ASSERT_TRUE(renderer->updateLic(params).ok());
  const ScalarVolume resumed = *renderer->readLicVolume();
  params.length += 1;
  ASSERT_TRUE(renderer->updateLic(params).ok());
  params.length -= 1;
  ASSERT_TRUE(renderer->updateLic(params).ok());
  EXPECT_EQ(compareVolumes(resumed, *renderer->readLicVolume()).max, 0.0);
}

TEST_F(GpuTest, MismatchedNoiseGridIsAnInputError) {
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  const Result<void> set = renderer->setInputs(makeAnalyticField(AnalyticField::Vortex, {8, 8, 8}),
                                               makeWhiteNoise({8, 8, 9}, 1));
  ASSERT_FALSE(set.ok());
  EXPECT_EQ(set.error().kind, ErrorKind::InvalidInput);
  EXPECT_FALSE(renderer->updateLic(LicParams{}).ok()) << "nothing to compute from";
}

TEST_F(GpuTest, GridWithoutPositiveSpacingIsAnInputError) {
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  VectorField field = makeAnalyticField(AnalyticField::Vortex, {8, 8, 8});
  field.geometry.spacing.y = 0.0;
  const Result<void> set = renderer->setInputs(field, makeWhiteNoise({8, 8, 8}, 1));
  ASSERT_FALSE(set.ok());
  EXPECT_EQ(set.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(set.error().message.find("spacing"), std::string::npos) << set.error().message;
}

}  // namespace
}  // namespace lic3d

namespace lic3d {
namespace {

// The desktop app spreads a recompute over frames: the shown volume stays the previous one until
// the job's last slab, a new request replaces the pending job, and the result equals the blocking
// computation.
TEST_F(GpuTest, FramePacedRecomputeShowsOnlyFinishedVolumes) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {16, 16, 24});
  const NoiseVolume noise = makeWhiteNoise(field.dims, 5);
  RendererOptions options;
  options.doubleBuffered = true;
  Result<LicRenderer> renderer = LicRenderer::create(context(), options);
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, noise).ok());

  LicParams first;
  first.length = 6;
  ASSERT_TRUE(renderer->updateLic(first).ok());
  const ScalarVolume firstVolume = *renderer->readLicVolume();

  LicParams second = first;
  second.length = 9;
  LicParams third = first;
  third.kernel = Kernel::Hann;
  ASSERT_TRUE(renderer->requestLic(second).ok());
  int frames = 0;
  auto frame = [&](int slices) {
    Result<LicWork> work = LicWork{};
    EXPECT_TRUE(submitAndWait(
                    context(),
                    [&](VkCommandBuffer cmd) {
                      work = renderer->recordLicWork(cmd, slices,
                                                     static_cast<std::uint32_t>(frames % 2));
                    },
                    "test frame")
                    .ok());
    EXPECT_TRUE(work.ok());
    if (work->finished) renderer->collectStatistics(static_cast<std::uint32_t>(frames % 2));
    ++frames;
    return *work;
  };
  EXPECT_FALSE(frame(5).finished);
  EXPECT_EQ(renderer->shownParams(), first) << "a half-computed volume is never shown";
  EXPECT_NEAR(renderer->licStatus().fraction, 5.0 / 24.0, 1e-12);
  EXPECT_EQ(compareVolumes(*renderer->readLicVolume(), firstVolume).max, 0.0);

  // A new request drops the pending job and starts over.
  ASSERT_TRUE(renderer->requestLic(third).ok());
  EXPECT_EQ(renderer->licStatus().fraction, 0.0);
  while (!frame(5).finished) {
  }
  EXPECT_EQ(frames, 1 + 5);  // 24 slices in slabs of 5
  EXPECT_EQ(renderer->shownParams(), third);
  EXPECT_FALSE(renderer->licStatus().pending);
  const ScalarVolume paced = *renderer->readLicVolume();

  // The same volume as a blocking computation.
  Result<LicRenderer> blocking = LicRenderer::create(context());
  ASSERT_TRUE(blocking.ok());
  ASSERT_TRUE(blocking->setInputs(field, noise).ok());
  ASSERT_TRUE(blocking->updateLic(third).ok());
  EXPECT_EQ(compareVolumes(paced, *blocking->readLicVolume()).max, 0.0);
  EXPECT_NEAR(renderer->intensityStatistics().mean, blocking->intensityStatistics().mean, 1e-6);
}

// While a LIC parameter is dragged the app shows a coarse volume: every stride-th voxel along each
// axis, each the full LIC at that voxel, so the same picture, blurrier. Its voxels must equal the
// full volume's at the same positions (the same streamlines, bit for bit), the sparsity mask's
// hidden voxels included, on a grid that no stride divides; its histogram counts its own voxels,
// empty space judged by the field at the same positions.
TEST_F(GpuTest, CoarseVolumeHoldsTheFullVolumesVoxelsAtItsPositions) {
  VectorField field = makeAnalyticField(AnalyticField::Abc, {33, 30, 29});
  // Empty space (a zero field) for x < 12: the histogram leaves it out.
  for (int k = 0; k < field.dims.z; ++k)
    for (int j = 0; j < field.dims.y; ++j)
      for (int i = 0; i < 12; ++i) field.vectors[voxelIndex(field.dims, i, j, k)] = glm::vec3(0.0f);
  RendererOptions options;
  options.doubleBuffered = true;
  Result<LicRenderer> renderer = LicRenderer::create(context(), options);
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 3)).ok());
  LicParams params;
  params.length = 7;
  params.sparsity.distribution = SparsityDistribution::Checkerboard;
  params.sparsity.ratio = 0.002f;
  ASSERT_TRUE(renderer->updateLic(params).ok());
  const ScalarVolume full = *renderer->readLicVolume();
  const IntensityStatistics fullStatistics = renderer->intensityStatistics();
  ASSERT_EQ(renderer->licJob().shownStride(), 1);

  for (const int stride : {2, 4}) {
    SCOPED_TRACE("stride " + std::to_string(stride));
    Result<bool> ran =
        renderer->licJob().update(params, renderer->fieldTextures(), {}, nullptr, stride);
    ASSERT_TRUE(ran.ok()) << ran.error().message;
    EXPECT_TRUE(*ran);
    EXPECT_EQ(renderer->licJob().shownStride(), stride);
    EXPECT_TRUE(renderer->needsLic(params)) << "a coarse volume is not the full one";
    const ScalarVolume coarse = *renderer->readLicVolume();
    ASSERT_EQ(coarse.dims, coarseDims(field.dims, stride));
    EXPECT_EQ(coarse.geometry.spacing, field.geometry.spacing * static_cast<double>(stride));
    const double emptySpeed = renderer->fieldTextures().emptySpeed();
    int differing = 0, hidden = 0, drawnDiffering = 0;
    std::uint64_t counted = 0;  // drawn, outside empty space
    for (int k = 0; k < coarse.dims.z; ++k)
      for (int j = 0; j < coarse.dims.y; ++j)
        for (int i = 0; i < coarse.dims.x; ++i) {
          const std::size_t c = voxelIndex(coarse.dims, i, j, k);
          const std::size_t f = voxelIndex(full.dims, i * stride, j * stride, k * stride);
          if (coarse.values[c] != full.values[f]) ++differing;
          if (coarse.drawn[c] != full.drawn[f]) ++drawnDiffering;
          if (!coarse.drawn[c]) ++hidden;
          if (coarse.drawn[c] && glm::length(field.vectors[f]) >= emptySpeed) ++counted;
        }
    EXPECT_EQ(differing, 0);
    EXPECT_EQ(drawnDiffering, 0);
    ASSERT_GT(hidden, 0) << "the mask should hide some of the coarse voxels";
    // The histogram is the coarse grid's: its masked count, and the hidden fraction of it.
    const IntensityStatistics& statistics = renderer->intensityStatistics();
    EXPECT_EQ(statistics.maskedVoxels, static_cast<std::uint64_t>(hidden));
    EXPECT_EQ(statistics.voxels, counted);
    EXPECT_NEAR(*renderer->hiddenFraction(),
                static_cast<double>(hidden) / static_cast<double>(voxelCount(coarse.dims)), 1e-12);
    // A sample of the full volume's voxels: its mean is the full volume's, within a few %.
    EXPECT_NEAR(statistics.mean, fullStatistics.mean, 0.03);
  }

  // The full volume replaces the coarse one.
  ASSERT_TRUE(renderer->updateLic(params).ok());
  EXPECT_EQ(renderer->licJob().shownStride(), 1);
  EXPECT_FALSE(renderer->needsLic(params));
  EXPECT_EQ(compareVolumes(*renderer->readLicVolume(), full).max, 0.0);
}

TEST(CoarseLicStride, TheCoarseJobFitsTheDragBudget) {
  EXPECT_EQ(coarseLicStride(0.0), 1) << "no full LIC timed yet";
  EXPECT_EQ(coarseLicStride(3.0), 1);  // 256^3 on the H100: a full LIC per frame
  EXPECT_EQ(coarseLicStride(8.0), 1);
  EXPECT_EQ(coarseLicStride(23.0), 2);  // 512^3: 2.9 ms
  EXPECT_EQ(coarseLicStride(64.0), 2);
  EXPECT_EQ(coarseLicStride(190.0), 4);  // 1024^3: 3.0 ms
  EXPECT_EQ(coarseLicStride(1e6), 8);
  for (const double ms : {1.0, 9.0, 100.0, 600.0}) {
    const int stride = coarseLicStride(ms);
    EXPECT_TRUE(ms / (stride * stride * stride) <= kDragLicBudgetMs || stride == 8) << ms;
    EXPECT_TRUE(stride == 1 || ms / ((stride / 2) * (stride / 2) * (stride / 2)) > kDragLicBudgetMs)
        << ms << ": a smaller stride would fit";
  }
}

}  // namespace
}  // namespace lic3d
