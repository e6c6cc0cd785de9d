// SPDX-License-Identifier: BSD-3-Clause
// The de-cluttering techniques of thesis chapter 5, each judged by a measured property of the
// picture or against the CPU reference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "gpu/shader_library.h"
#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "render/lic_renderer.h"

namespace lic3d {
namespace {

using test::GpuTest;
using test::isBackground;
using test::kBackground;
using test::meanAbsoluteDifference;
using test::opaqueView;
using test::projectBox;
using test::rendererWithVolume;

float luminance(glm::u8vec4 p) { return 0.299f * p.r + 0.587f * p.g + 0.114f * p.b; }

// ---- Sparsity ---------------------------------------------------------------------------------

// The GPU's mask channel against the CPU reference of the mask rule: a voxel is hidden when a
// sample of its streamline lies in a black voxel. Sample positions near a voxel boundary can round
// the other way on the GPU (as for nearest noise), so a few voxels may disagree: we allow 0.5 %.
void expectMaskMatchesReference(const Context& context, SparsityDistribution distribution,
                                StepScheme scheme = StepScheme::Exact) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, {24, 32, 40});
  const NoiseVolume noise = makeWhiteNoise(field.dims, 2);
  LicParams params;
  params.length = 8;
  params.scheme = scheme;
  params.sparsity.distribution = distribution;
  Result<LicRenderer> renderer = LicRenderer::create(context, {FieldPrecision::Float});
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, noise).ok());
  ASSERT_TRUE(renderer->updateLic(params).ok());
  const ScalarVolume gpu = *renderer->readLicVolume();
  const ScalarVolume cpu = *computeLicReference(field, noise, params);
  ASSERT_EQ(gpu.drawn.size(), cpu.drawn.size());
  double agree = 0, drawnCpu = 0, drawnGpu = 0;
  for (std::size_t i = 0; i < cpu.drawn.size(); ++i) {
    agree += gpu.drawn[i] == cpu.drawn[i];
    drawnCpu += cpu.drawn[i];
    drawnGpu += gpu.drawn[i];
  }
  const double n = static_cast<double>(cpu.drawn.size());
  EXPECT_GE(agree / n, 0.995) << enumName(distribution);
  // The expected fraction is removed, and it is a real fraction: not nothing, not everything.
  EXPECT_NEAR(drawnGpu / n, drawnCpu / n, 0.005) << enumName(distribution);
  EXPECT_GT(drawnCpu / n, 0.05) << enumName(distribution);
  EXPECT_LT(drawnCpu / n, 0.95) << enumName(distribution);
}

TEST_F(GpuTest, SparsityMaskMatchesTheReferenceForEveryDistribution) {
  for (const SparsityDistribution d :
       {SparsityDistribution::Checkerboard, SparsityDistribution::Poisson,
        SparsityDistribution::PoissonApprox, SparsityDistribution::Jitter,
        SparsityDistribution::Halton, SparsityDistribution::Hammersley})
    expectMaskMatchesReference(context(), d);
  // The one-fetch walks stop and leave the grid at their own samples.
  expectMaskMatchesReference(context(), SparsityDistribution::Halton, StepScheme::Fused);
  expectMaskMatchesReference(context(), SparsityDistribution::Halton, StepScheme::Ab2);
}

TEST_F(GpuTest, SparsityHidesMaskedVoxelsAndOnlyRebuildsTheMaskWhenItChanges) {
  const VectorField field = makeAnalyticField(AnalyticField::Vortex, {32, 32, 32});
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  LicParams lic;
  ViewParams view;
  view.width = view.height = 96;
  view.alpha = 0.6f;
  const RgbaImage dense = *renderer->render(lic, view);
  lic.sparsity.distribution = SparsityDistribution::Poisson;
  lic.sparsity.radius = 1.8f;
  const RgbaImage sparse = *renderer->render(lic, view);
  lic.length += 2;  // a LIC change recomputes, but the mask stays
  ASSERT_TRUE(renderer->render(lic, view).ok());
  EXPECT_EQ(renderer->maskBuildCount(), 1u);
  EXPECT_EQ(renderer->licDispatchCount(), 3u);
  // Fewer voxels drawn: the picture lets more background through.
  auto covered = [](const RgbaImage& image) {
    int n = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) n += luminance(image.at(x, y)) > 40.0f;
    return n;
  };
  EXPECT_LT(covered(sparse), 0.9 * covered(dense));
}

TEST(SeedNoise, HasTheRequestedSpotsOnBlack) {
  const NoiseVolume noise = makeSeedNoise({40, 40, 40}, 500, 3);
  std::size_t spots = 0, other = 0;
  for (std::uint8_t b : noise.bytes) {
    spots += b == 255;
    other += b != 0 && b != 255;
  }
  EXPECT_EQ(other, 0u);
  EXPECT_GE(spots, 450u);
  EXPECT_LE(spots, 500u);
}

// ---- Colour and magnitude ----------------------------------------------------------------------

// A field whose speed grows along x: slow at -x, fast at +x.
VectorField speedRamp(Dims dims) {
  VectorField field;
  field.dims = dims;
  field.vectors.resize(voxelCount(dims));
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        field.vectors[voxelIndex(dims, i, j, k)] =
            glm::vec3(0.0f, 0.0f, 0.1f + static_cast<float>(i) / static_cast<float>(dims.x - 1));
  return field;
}

ViewParams frontView(int size) {
  ViewParams view = opaqueView(size);
  view.camera.azimuth = -90.0f;  // look from -y: +x is to the right
  view.camera.elevation = 0.0f;
  view.camera.orthographic = true;
  return view;
}

TEST_F(GpuTest, ColourByMagnitudeFollowsTheThesisRampWithALegendBesideTheVolume) {
  const Dims dims{16, 16, 16};
  const VectorField field = speedRamp(dims);
  LicRenderer renderer = rendererWithVolume(
      context(), dims, [](int, int, int) { return 1.0f; }, &field);
  ViewParams view = frontView(128);
  view.width = 256;
  view.color = ColorMode::Magnitude;
  view.legend = true;
  view.title = "ramp";
  const RgbaImage image = *renderer.render(LicParams{}, view);
  const PictureLayout layout = renderer.pictureLayoutFor(view);
  // The legend has a column of its own right of the volume, the title a band above it.
  ASSERT_GT(layout.legend.z, 0);
  ASSERT_GT(layout.title.w, 0);
  EXPECT_EQ(layout.picture.x + layout.picture.z, layout.legend.x);
  int left = image.width, right = -1, top = image.height, bottom = -1;
  for (int y = layout.picture.y; y < image.height; ++y)
    for (int x = 0; x < layout.legend.x; ++x)
      if (!isBackground(image.at(x, y))) {
        left = std::min(left, x);
        right = std::max(right, x);
        top = std::min(top, y);
        bottom = std::max(bottom, y);
      }
  ASSERT_LT(left + 20, right);
  // Nothing of the volume under the title band: only the background and anti-aliased text, the
  // background blended towards white or black by one coverage in every channel.
  const auto textOrBackground = [](glm::u8vec4 p) {
    for (const float ink : {255.0f, 0.0f}) {
      float low = 1.0f, high = 0.0f;
      for (int c = 0; c < 3; ++c) {
        const float bg = static_cast<float>(test::kBackground8[c]);
        const float coverage = std::abs(ink - bg) < 1.0f ? 0.0f : (p[c] - bg) / (ink - bg);
        low = std::min(low, coverage);
        high = std::max(high, coverage);
      }
      if (high - low < 0.04f) return true;
    }
    return false;
  };
  for (int y = 0; y < layout.title.w; ++y)
    for (int x = left; x <= right; ++x)
      EXPECT_TRUE(textOrBackground(image.at(x, y)))
          << "a coloured pixel in the title band at " << x << "," << y;
  const int row = (top + bottom) / 2;
  const glm::u8vec4 slow = image.at(left + 4, row), fast = image.at(right - 4, row);
  EXPECT_GT(slow.b, 150) << "slow flow is blue";
  EXPECT_LT(slow.r, 100);
  EXPECT_GT(fast.r, 150) << "fast flow is red";
  EXPECT_LT(fast.b, 100);
  // In the legend column: a bar red at its top and blue at its bottom, and white label text
  // that stays inside the image.
  int barTop = image.height, barBottom = -1, inkRight = -1;
  for (int y = layout.legend.y; y < image.height; ++y)
    for (int x = layout.legend.x; x < image.width; ++x) {
      const glm::u8vec4 p = image.at(x, y);
      if (p.r == 255 && p.g == 255 && p.b == 255) inkRight = std::max(inkRight, x);
      if (std::max({p.r, p.g, p.b}) - std::min({p.r, p.g, p.b}) > 120) {
        barTop = std::min(barTop, y);
        barBottom = std::max(barBottom, y);
      }
    }
  ASSERT_LT(barTop + 20, barBottom);
  bool redTop = false, blueBottom = false;
  for (int x = layout.legend.x; x < image.width; ++x) {
    const glm::u8vec4 t = image.at(x, barTop + 1), b = image.at(x, barBottom - 1);
    redTop = redTop || (t.r > 200 && t.b < 60);
    blueBottom = blueBottom || (b.b > 200 && b.r < 60);
  }
  EXPECT_TRUE(redTop);
  EXPECT_TRUE(blueBottom);
  EXPECT_GT(inkRight, layout.legend.x) << "no label text";
  EXPECT_LT(inkRight, image.width - 2) << "a label reaches the image's edge";
}

TEST_F(GpuTest, MagnitudeOpacityFadesSlowRegions) {
  const Dims dims{16, 16, 16};
  const VectorField field = speedRamp(dims);
  LicRenderer renderer = rendererWithVolume(
      context(), dims, [](int, int, int) { return 1.0f; }, &field);
  ViewParams view = frontView(128);
  view.alpha = 0.2f;
  view.magnitudeOpacity = 1.0f;
  view.magnitudeThreshold = 0.3f;
  const RgbaImage image = *renderer.render(LicParams{}, view);
  // Below the threshold (the slowest 30 %) nothing is drawn; fast flow is drawn.
  EXPECT_TRUE(isBackground(image.at(35, 64)));
  EXPECT_FALSE(isBackground(image.at(90, 64)));
  // Opacity grows with speed between the two.
  EXPECT_LT(
      std::abs(luminance(image.at(60, 64)) - luminance(glm::u8vec4(kBackground * 255.0f, 255))),
      std::abs(luminance(image.at(90, 64)) - luminance(glm::u8vec4(kBackground * 255.0f, 255))));
}

// ---- Anisotropic grids --------------------------------------------------------------------------

// z voxels 2.5 times as long as x and y voxels.
constexpr glm::dvec3 kTallVoxels{1.0, 1.0, 2.5};

// Physical speed 1 everywhere, pointing along x in the left half and along z in the right half:
// in voxel units the right half is 2.5 times slower, which magnitude colouring must not show.
VectorField equalSpeedTwoDirections(Dims dims) {
  VectorField field;
  field.dims = dims;
  field.geometry.spacing = kTallVoxels;
  field.vectors.resize(voxelCount(dims));
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i)
        field.vectors[voxelIndex(dims, i, j, k)] =
            i < dims.x / 2 ? glm::vec3(1.0f, 0.0f, 0.0f) : glm::vec3(0.0f, 0.0f, 1.0f);
  return field;
}

// The colour range, the legend and the shader's speeds are physical |v| on anisotropic grids.
TEST_F(GpuTest, MagnitudeColourShowsPhysicalSpeedOnAnisotropicGrids) {
  const Dims dims{16, 16, 16};
  const VectorField field = equalSpeedTwoDirections(dims);
  LicRenderer renderer = rendererWithVolume(
      context(), dims, [](int, int, int) { return 1.0f; }, &field);
  const VolumeFacts facts = renderer.volumeFacts();
  EXPECT_FLOAT_EQ(facts.minMagnitude, 1.0f);
  EXPECT_FLOAT_EQ(facts.maxMagnitude, 1.0f);
  // Texels hold u / max|u| with u = (v_x, v_y, v_z / 2.5) and max|u| = 1.
  EXPECT_EQ(facts.texelToPhysical, glm::vec3(1.0f, 1.0f, 2.5f));

  ViewParams view = frontView(128);
  view.color = ColorMode::Magnitude;
  view.autoColorRange = false;
  view.colorLow = 0.0f;  // speed 1 is the middle of the map; 0.4 would be far from it
  view.colorHigh = 2.0f;
  const RgbaImage image = *renderer.render(LicParams{}, view);
  int left = image.width, right = -1;
  for (int x = 0; x < image.width; ++x)
    if (!isBackground(image.at(x, 64))) {
      left = std::min(left, x);
      right = std::max(right, x);
    }
  ASSERT_LT(left + 20, right);
  const int quarter = (right - left) / 4;
  const glm::u8vec4 alongX = image.at(left + quarter, 64), alongZ = image.at(right - quarter, 64);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(alongX[c], alongZ[c], 3)
        << "channel " << c << ": equal physical speeds, one colour";

  // A legend over the same range as the automatic one: physical min and max |v|.
  VectorField ramp = speedRamp(dims);  // along z, 0.1 .. 1.1
  ramp.geometry.spacing = kTallVoxels;
  LicRenderer rampRenderer = rendererWithVolume(
      context(), dims, [](int, int, int) { return 1.0f; }, &ramp);
  EXPECT_FLOAT_EQ(rampRenderer.volumeFacts().minMagnitude, 0.1f);
  EXPECT_FLOAT_EQ(rampRenderer.volumeFacts().maxMagnitude, 1.1f);
}

// Illuminated lines shade by the world-space tangent alone. A constant field along the physical
// direction (1, 0, 1) must be lit the same on tall voxels as on cubic ones; the texels hold
// (1, 0, 0.4) in voxel units, which the voxel's world size turns back into (1, 0, 1). Scaling a
// physical vector by the voxel size instead would light the direction (1, 0, 2.5), which the third
// picture shows to shade visibly differently.
TEST_F(GpuTest, LightingUsesThePhysicalTangentOnAnisotropicGrids) {
  const Dims dims{16, 16, 16};
  auto centreColour = [&](glm::vec3 v, glm::dvec3 spacing) {
    VectorField field;
    field.dims = dims;
    field.geometry.spacing = spacing;
    field.vectors.assign(voxelCount(dims), v);
    LicRenderer renderer = rendererWithVolume(
        context(), dims, [](int, int, int) { return 0.4f; }, &field);
    ViewParams view = frontView(128);
    view.lighting = Lighting::Lines;
    return glm::vec3(renderer.render(LicParams{}, view)->at(64, 64));
  };
  const glm::vec3 tall = centreColour({1.0f, 0.0f, 1.0f}, kTallVoxels);
  const glm::vec3 cubic = centreColour({1.0f, 0.0f, 1.0f}, glm::dvec3(1.0));
  const glm::vec3 steeper = centreColour({1.0f, 0.0f, 2.5f}, glm::dvec3(1.0));
  // Measured: grey 193 on tall and on cubic voxels, 141 for (1, 0, 2.5).
  EXPECT_LE(glm::length(tall - cubic), 3.0f) << "tall " << tall.r << " cubic " << cubic.r;
  EXPECT_GE(glm::length(steeper - cubic), 30.0f) << "steeper " << steeper.r << " cubic " << cubic.r;
}

// The box has physical proportions: its sides are N * spacing, the longest 1.
TEST_F(GpuTest, AnisotropicBoxIsDrawnWithPhysicalProportions) {
  const glm::vec3 mirror = boxHalfExtent({47, 47, 47}, GridGeometry{{0.05, 0.05, 0.125}});
  EXPECT_NEAR(mirror.x, 0.2f, 1e-6f);
  EXPECT_NEAR(mirror.y, 0.2f, 1e-6f);
  EXPECT_NEAR(mirror.z, 0.5f, 1e-6f);

  const Dims dims{16, 16, 16};
  const VectorField field = equalSpeedTwoDirections(dims);
  LicRenderer renderer = rendererWithVolume(
      context(), dims, [](int, int, int) { return 1.0f; }, &field);
  const RgbaImage image = *renderer.render(LicParams{}, frontView(128));
  int width = 0, height = 0;
  for (int x = 0; x < image.width; ++x) width += !isBackground(image.at(x, 64));
  for (int y = 0; y < image.height; ++y) height += !isBackground(image.at(64, y));
  ASSERT_GT(height, 20);
  EXPECT_NEAR(static_cast<double>(width) / height, 1.0 / 2.5, 0.05) << width << " x " << height;
}

// ---- Clip planes and regions of interest -------------------------------------------------------

TEST_F(GpuTest, ClipPlanesLeaveTheClippedRegionAtBackground) {
  const Dims dims{20, 20, 20};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 1.0f; });
  ViewParams view = opaqueView(128);
  view.clipMin = {0.0f, 0.25f, 0.0f};
  view.clipMax = {0.5f, 1.0f, 0.8f};
  const RgbaImage image = *renderer.render(LicParams{}, view);
  const test::ProjectedBox kept = projectBox(view, dims, view.clipMin, view.clipMax);
  int inside = 0, insideDrawn = 0, outside = 0, outsideBackground = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double d =
          kept.signedDistance({static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f});
      if (d > 2.0) {
        ++inside;
        insideDrawn += !isBackground(image.at(x, y));
      } else if (d < -2.0) {
        ++outside;
        outsideBackground += isBackground(image.at(x, y));
      }
    }
  EXPECT_GT(inside, 500);
  EXPECT_EQ(insideDrawn, inside);
  EXPECT_EQ(outsideBackground, outside);
}

struct Coverage {
  int pixels = 0;
  glm::vec2 centre{0.0f};
  float maxRadius = 0.0f;
  int minX = 1 << 30, maxX = -1;
};

Coverage coverage(const RgbaImage& image) {
  Coverage c;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!isBackground(image.at(x, y))) {
        ++c.pixels;
        c.centre += glm::vec2(static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f);
        c.minX = std::min(c.minX, x);
        c.maxX = std::max(c.maxX, x);
      }
  if (c.pixels) c.centre /= static_cast<float>(c.pixels);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      if (!isBackground(image.at(x, y)))
        c.maxRadius =
            std::max(c.maxRadius, glm::distance(c.centre, glm::vec2(static_cast<float>(x) + 0.5f,
                                                                    static_cast<float>(y) + 0.5f)));
  return c;
}

TEST_F(GpuTest, SphereRegionLeavesOnlyADisc) {
  const Dims dims{32, 32, 32};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 1.0f; });
  ViewParams view = opaqueView(128);
  view.camera.orthographic = true;
  view.roi = RoiShape::Sphere;
  view.roiSize = 0.5f;
  const RgbaImage image = *renderer.render(LicParams{}, view);
  const Coverage c = coverage(image);
  // Orthographic: the disc's radius in pixels is the sphere's radius over the half height shown.
  const SliceFrame frame = makeSliceFrame(view, renderer.volumeFacts(), Eye::Mono, {128, 128});
  const float halfHeight = 1.0f / frame.camera.projection[1][1];  // ortho: |P11| = 1 / half height
  const float radius = 0.25f / std::abs(halfHeight) * 64.0f;
  EXPECT_NEAR(c.centre.x, 64.0f, 1.0f);
  EXPECT_NEAR(c.centre.y, 64.0f, 1.0f);
  EXPECT_LE(c.maxRadius, radius + 1.5f);
  EXPECT_NEAR(c.pixels, 3.14159f * radius * radius, 0.06f * 3.14159f * radius * radius);

  view.roiOutside = true;
  const RgbaImage outside = *renderer.render(LicParams{}, view);
  EXPECT_FALSE(isBackground(outside.at(64, 64))) << "the front of the box stays";
  EXPECT_GT(coverage(outside).pixels, c.pixels);
}

TEST_F(GpuTest, RotatedCubeRegionTurnsWithItsTextureCoordinates) {
  const Dims dims{32, 32, 32};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 1.0f; });
  ViewParams view = opaqueView(128);
  view.camera.orthographic = true;
  view.camera.azimuth = 0.0f;
  view.camera.elevation = 90.0f;  // from above, screen axes along y and x
  view.roi = RoiShape::Cube;
  view.roiSize = 0.4f;
  const Coverage square = coverage(*renderer.render(LicParams{}, view));
  view.roiRotation = {0.0f, 0.0f, 45.0f};
  const Coverage diamond = coverage(*renderer.render(LicParams{}, view));
  const float side = static_cast<float>(square.maxX - square.minX + 1);
  EXPECT_NEAR(static_cast<float>(diamond.maxX - diamond.minX + 1), side * std::sqrt(2.0f), 3.0f);
  EXPECT_NEAR(diamond.pixels, square.pixels, 0.05 * square.pixels) << "same area, turned";
}

// ---- Depth: fog, stereo, lighting ---------------------------------------------------------------

TEST_F(GpuTest, FogDarkensFarPixelsMonotonically) {
  const Dims dims{24, 24, 24};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 1.0f; });
  ViewParams view = opaqueView(128);
  view.background = glm::vec3(0.0f);
  view.camera.azimuth = 45.0f;  // the nearest vertical edge of the box is in the middle
  view.camera.elevation = 0.0f;
  view.fog = true;
  view.fogStart = 0.0f;
  view.fogEnd = 1.0f;
  view.jitter = false;  // its grain would break the run of darkening by a level here and there
  const RgbaImage image = *renderer.render(LicParams{}, view);
  // Along the middle row, away from the near edge in either direction, pixels only get darker.
  for (const int direction : {-1, 1}) {
    float previous = 256.0f;
    int drawn = 0;
    for (int x = 64; x >= 0 && x < 128; x += direction) {
      const float l = luminance(image.at(x, 64));
      if (l == 0.0f) break;  // past the silhouette
      EXPECT_LE(l, previous + 1.0f) << "x = " << x;
      previous = l;
      ++drawn;
    }
    EXPECT_GT(drawn, 20);
    EXPECT_LT(previous, luminance(image.at(64, 64)) - 10.0f) << "the far end is darker";
  }
}

float channelCentroidX(const RgbaImage& image, int channel) {
  double sum = 0.0, weight = 0.0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float v = image.at(x, y)[channel];
      sum += v * (x + 0.5);
      weight += v;
    }
  return static_cast<float>(sum / weight);
}

TEST_F(GpuTest, AnaglyphDisparityHasTheExpectedSign) {
  const Dims dims{24, 24, 24};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 1.0f; });
  ViewParams view = opaqueView(128);
  view.background = glm::vec3(0.0f);
  view.roi = RoiShape::Sphere;
  view.roiSize = 0.5f;
  view.stereo = StereoMode::Anaglyph;
  view.eyeSeparation = 0.15f;
  const SliceFrame frame = makeSliceFrame(view, renderer.volumeFacts(), Eye::Mono, {128, 128});
  // Zero parallax in front of the volume: it lies behind the screen, uncrossed disparity, so the
  // left (red) image sits left of the right (cyan) one. Behind the volume: the other way.
  view.zeroParallax = 0.6f * frame.camera.distance;
  const RgbaImage behind = *renderer.render(LicParams{}, view);
  EXPECT_LT(channelCentroidX(behind, 0) + 1.0f, channelCentroidX(behind, 1));
  view.zeroParallax = 1.6f * frame.camera.distance;
  const RgbaImage front = *renderer.render(LicParams{}, view);
  EXPECT_GT(channelCentroidX(front, 0), channelCentroidX(front, 1) + 1.0f);
  // Zero parallax at the sphere's centre: the two images nearly coincide.
  view.zeroParallax = 0.0f;
  const RgbaImage centred = *renderer.render(LicParams{}, view);
  EXPECT_NEAR(channelCentroidX(centred, 0), channelCentroidX(centred, 1), 0.5f);
}

TEST_F(GpuTest, SideBySideStereoDoublesTheWidth) {
  const Dims dims{16, 16, 16};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 1.0f; });
  ViewParams view = opaqueView(64);
  view.stereo = StereoMode::SideBySide;
  const RgbaImage image = *renderer.render(LicParams{}, view);
  ASSERT_EQ(image.width, 128);
  ASSERT_EQ(image.height, 64);
  EXPECT_FALSE(isBackground(image.at(32, 32))) << "left eye sees the volume";
  EXPECT_FALSE(isBackground(image.at(96, 32))) << "right eye sees the volume";
}

TEST_F(GpuTest, LightingChangesTheShadingAndTheTwoModelsDiffer) {
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, {32, 32, 32});
  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer.ok());
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  ViewParams view;
  view.width = view.height = 96;
  const RgbaImage unlit = *renderer->render(LicParams{}, view);
  view.lighting = Lighting::Phong;
  const RgbaImage phong = *renderer->render(LicParams{}, view);
  view.lighting = Lighting::Lines;
  const RgbaImage lines = *renderer->render(LicParams{}, view);
  EXPECT_GT(meanAbsoluteDifference(unlit, phong), 0.01);
  EXPECT_GT(meanAbsoluteDifference(unlit, lines), 0.01);
  EXPECT_GT(meanAbsoluteDifference(phong, lines), 0.005);
}

// ---- Filtering, contrast, variants -------------------------------------------------------------

TEST_F(GpuTest, NearestFilteringKeepsVoxelValues) {
  const Dims dims{8, 8, 8};
  LicRenderer renderer = rendererWithVolume(
      context(), dims, [](int i, int j, int k) { return (i + j + k) % 2 ? 1.0f : 0.0f; });
  ViewParams view = frontView(128);
  view.filter = VolumeFilter::Nearest;
  const RgbaImage nearest = *renderer.render(LicParams{}, view);
  view.filter = VolumeFilter::Linear;
  const RgbaImage linear = *renderer.render(LicParams{}, view);
  auto intermediate = [](const RgbaImage& image) {
    int n = 0;
    for (int y = 32; y < 96; ++y)
      for (int x = 32; x < 96; ++x) n += image.at(x, y).r > 20 && image.at(x, y).r < 235;
    return n;
  };
  EXPECT_LT(intermediate(nearest), 64) << "only voxel edges may fall between black and white";
  EXPECT_GT(intermediate(linear), 1000) << "linear filtering blends neighbouring voxels";
}

TEST(ContrastStretch, MapsMeanAndDeviationToTheirTargets) {
  VolumeFacts facts;
  facts.dims = {8, 8, 8};
  facts.intensityMean = 0.47f;
  facts.intensityDeviation = 0.04f;
  ViewParams view;
  const glm::vec4 on = makeSliceFrame(view, facts, Eye::Mono, {128, 128}).uniforms.transfer;
  EXPECT_NEAR(on.x * 0.47f + on.y, 0.5f, 1e-5f);
  EXPECT_NEAR(on.x * (0.47f + 0.04f) + on.y, 0.5f + kContrastTargetDeviation, 1e-5f);
  view.contrast = false;
  const glm::vec4 off = makeSliceFrame(view, facts, Eye::Mono, {128, 128}).uniforms.transfer;
  EXPECT_FLOAT_EQ(off.x, 1.0f);
  EXPECT_FLOAT_EQ(off.y, 0.0f);
  view.manualWindow = true;
  view.windowLow = 0.4f;
  view.windowHigh = 0.6f;
  view.gain = 2.0f;
  view.brightness = 0.1f;
  const glm::vec4 window = makeSliceFrame(view, facts, Eye::Mono, {128, 128}).uniforms.transfer;
  EXPECT_NEAR(window.x * 0.5f + window.y, 0.6f, 1e-5f) << "window centre, then brightness";
  EXPECT_NEAR(window.x * 0.6f + window.y, 0.5f + 2.0f * 0.5f + 0.1f, 1e-5f);
}

TEST_F(GpuTest, EachDisplayVariantIsItsOwnCachedPipeline) {
  const Dims dims{8, 8, 8};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 0.5f; });
  ViewParams view = opaqueView(32);
  const std::size_t before = renderer.drawVariantCount();
  ASSERT_TRUE(renderer.render(LicParams{}, view).ok());
  view.fog = true;
  ASSERT_TRUE(renderer.render(LicParams{}, view).ok());
  view.color = ColorMode::Magnitude;
  ASSERT_TRUE(renderer.render(LicParams{}, view).ok());
  view.fog = false;
  view.color = ColorMode::None;
  ASSERT_TRUE(renderer.render(LicParams{}, view).ok());
  EXPECT_EQ(renderer.drawVariantCount(), before + 3);
}

// Halos are drawn by every other slice. A CPU driver runs both sides of the shader's branch, so
// there the slices without halos take the pipeline without them: two variants for one frame.
TEST_F(GpuTest, HalosOnACpuDriverDrawEveryOtherSliceWithoutTheRing) {
  const Dims dims{8, 8, 8};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 0.5f; });
  renderer.setSlicesPerFragment(1);  // K > 1 draws each group's halo slice in its one draw
  ViewParams view = opaqueView(32);
  view.halo = 0.6f;
  const std::size_t before = renderer.drawVariantCount();
  ASSERT_TRUE(renderer.render(LicParams{}, view).ok());
  const bool cpu = context().deviceInfo().type == VK_PHYSICAL_DEVICE_TYPE_CPU;
  EXPECT_EQ(renderer.drawVariantCount(), before + (cpu ? 2 : 1));
  // The same with occlusion, whose slices are drawn front to back one at a time.
  view.occlusion = 0.5f;
  ASSERT_TRUE(renderer.render(LicParams{}, view).ok());
  EXPECT_EQ(renderer.drawVariantCount(), before + (cpu ? 4 : 2));
}

}  // namespace
}  // namespace lic3d

namespace lic3d {
namespace {

// The benchmark compares specialized pipelines with one shader that decides its modes at run
// time; both must draw the same picture or the comparison means nothing.
TEST_F(GpuTest, RuntimeModeShaderDrawsWhatTheSpecializedVariantsDraw) {
  if (!hasRuntimeModeShaders()) GTEST_SKIP() << "built without LIC3D_BENCH_RUNTIME_MODES";
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, {24, 24, 24});
  LicParams lic;
  lic.sparsity.distribution = SparsityDistribution::Halton;
  ViewParams base;
  base.width = base.height = 64;
  std::vector<ViewParams> views(5, base);
  views[1].color = ColorMode::Magnitude;
  views[1].magnitudeOpacity = 1.0f;
  views[2].fog = true;
  views[2].roi = RoiShape::Sphere;
  views[2].filter = VolumeFilter::Nearest;
  views[3].lighting = Lighting::Phong;
  views[3].stereo = StereoMode::Anaglyph;
  views[3].colormap = Colormap::Viridis;
  views[3].color = ColorMode::Magnitude;
  // On a CPU driver the specialized halos take one draw per slice, the runtime-mode shader one
  // draw whose slices decide by their index.
  views[4].color = ColorMode::Magnitude;
  views[4].magnitudeOpacity = 1.0f;
  views[4].halo = 0.6f;
  Result<LicRenderer> specialized = LicRenderer::create(context());
  RendererOptions runtimeOptions;
  runtimeOptions.runtimeModes = true;
  Result<LicRenderer> runtime = LicRenderer::create(context(), runtimeOptions);
  ASSERT_TRUE(specialized.ok() && runtime.ok());
  ASSERT_TRUE(specialized->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  ASSERT_TRUE(runtime->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
  for (const ViewParams& view : views) {
    const RgbaImage a = *specialized->render(lic, view);
    const RgbaImage b = *runtime->render(lic, view);
    EXPECT_LE(meanAbsoluteDifference(a, b), 1.0 / 255.0);
  }
}

}  // namespace
}  // namespace lic3d
