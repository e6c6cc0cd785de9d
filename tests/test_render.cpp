// SPDX-License-Identifier: BSD-3-Clause
// The slice pass, judged by measured image properties.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <glm/glm.hpp>

#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "render/lic_renderer.h"

namespace lic3d {
namespace {

using test::GpuTest;

using test::isBackground;
using test::kBackground;
using test::opaqueView;
using test::projectBox;
using test::ProjectedBox;
using test::rendererWithVolume;

TEST_F(GpuTest, OpaqueVolumeCoversExactlyItsProjectedBox) {
  const Dims dims{20, 24, 28};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int, int, int) { return 1.0f; });
  for (const bool ortho : {false, true}) {
    ViewParams view = opaqueView(160);
    view.height = 120;
    view.camera.azimuth = 30.0f;
    view.camera.elevation = 20.0f;
    view.camera.orthographic = ortho;
    const RgbaImage image = *renderer.render(LicParams{}, view);
    const ProjectedBox box = projectBox(view, dims);
    int inside = 0, insideCovered = 0, outside = 0, outsideBackground = 0;
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x) {
        const double d =
            box.signedDistance({static_cast<float>(x) + 0.5f, static_cast<float>(y) + 0.5f});
        // The outermost slices sit half a spacing inside the box: allow a 2-pixel band.
        if (d > 2.0) {
          ++inside;
          insideCovered += image.at(x, y) == glm::u8vec4(255, 255, 255, 255);
        } else if (d < -2.0) {
          ++outside;
          outsideBackground += isBackground(image.at(x, y));
        }
      }
    EXPECT_GT(inside, 2000) << "the box should fill a good part of the image";
    EXPECT_EQ(insideCovered, inside) << (ortho ? "orthographic" : "perspective");
    EXPECT_EQ(outsideBackground, outside) << (ortho ? "orthographic" : "perspective");
  }
}

TEST_F(GpuTest, FullyTransparentGivesTheBackground) {
  LicRenderer renderer =
      rendererWithVolume(context(), {16, 16, 16}, [](int, int, int) { return 1.0f; });
  ViewParams view = opaqueView(64);
  view.alpha = 0.0f;
  for (const OpacityMode mode : {OpacityMode::Constant, OpacityMode::Intensity}) {
    view.opacityMode = mode;
    const RgbaImage image = *renderer.render(LicParams{}, view);
    for (int y = 0; y < image.height; ++y)
      for (int x = 0; x < image.width; ++x)
        ASSERT_TRUE(isBackground(image.at(x, y))) << x << "," << y;
  }
}

// Slices must be composited back to front: an opaque volume shows its near half.
TEST_F(GpuTest, SlicesCompositeBackToFrontFromEitherSide) {
  const Dims dims{16, 16, 16};
  LicRenderer renderer = rendererWithVolume(context(), dims, [](int i, int, int) {
    return i < 8 ? 0.2f : 0.8f;  // dark at -x, bright at +x
  });
  for (const Slicing slicing : {Slicing::ViewAligned, Slicing::AxisAligned}) {
    for (const float azimuth : {0.0f, 180.0f}) {
      ViewParams view = opaqueView(64);
      view.slicing = slicing;
      view.camera.azimuth = azimuth;
      view.camera.elevation = 0.0f;
      const RgbaImage image = *renderer.render(LicParams{}, view);
      const int expected = azimuth == 0.0f ? 204 : 51;  // 0.8 or 0.2 in 8 bits
      EXPECT_NEAR(image.at(32, 32).r, expected, 2)
          << (slicing == Slicing::ViewAligned ? "view" : "axis") << " slicing, azimuth " << azimuth;
    }
  }
}

using test::meanAbsoluteDifference;

class LicPictureTest : public GpuTest {
 protected:
  LicRenderer renderer() {
    const VectorField field = makeAnalyticField(AnalyticField::Tornado, {32, 32, 32});
    Result<LicRenderer> r = LicRenderer::create(context());
    EXPECT_TRUE(r.ok());
    EXPECT_TRUE(r->setInputs(field, makeWhiteNoise(field.dims, 1)).ok());
    return std::move(r).value();
  }
};

TEST_F(LicPictureTest, ViewAndAxisAlignedSlicesAgreeHeadOn) {
  LicRenderer r = renderer();
  ViewParams view;
  view.width = view.height = 128;
  view.camera.azimuth = 0.0f;
  view.camera.elevation = 0.0f;
  view.slicing = Slicing::ViewAligned;
  const RgbaImage viewAligned = *r.render(LicParams{}, view);
  view.slicing = Slicing::AxisAligned;
  const RgbaImage axisAligned = *r.render(LicParams{}, view);
  // Head on, both cut the volume on the same planes: only rounding of the polygon corners
  // differs.
  EXPECT_LE(meanAbsoluteDifference(viewAligned, axisAligned), 0.5 / 255.0);

  // Slightly off-axis both slicings still see the x slabs; samples fall on different planes, so
  // the textures differ in detail, but the opacity correction keeps brightness and coverage the
  // same: we measure the mean grey of the two pictures.
  view.camera.azimuth = 15.0f;
  view.camera.elevation = 10.0f;
  view.slicing = Slicing::ViewAligned;
  const RgbaImage obliqueView = *r.render(LicParams{}, view);
  view.slicing = Slicing::AxisAligned;
  const RgbaImage obliqueAxis = *r.render(LicParams{}, view);
  auto meanGrey = [](const RgbaImage& image) {
    double sum = 0.0;
    for (std::size_t i = 0; i < image.pixels.size(); i += 4) sum += image.pixels[i];
    return sum / (static_cast<double>(image.pixels.size()) / 4.0) / 255.0;
  };
  EXPECT_NEAR(meanGrey(obliqueView), meanGrey(obliqueAxis), 0.02);
}

TEST_F(LicPictureTest, OpacityCorrectionMakesSliceCountIrrelevant) {
  LicRenderer r = renderer();
  ViewParams view;
  view.width = view.height = 96;
  view.alpha = 0.1f;
  view.slices = 32;
  const RgbaImage coarse = *r.render(LicParams{}, view);
  view.slices = 96;
  const RgbaImage fine = *r.render(LicParams{}, view);
  // Three times the slices at a third of the opacity each: the same picture but for sampling.
  EXPECT_LE(meanAbsoluteDifference(coarse, fine), 0.02);
  view.slices = 32;
  view.alpha = 0.3f;
  const RgbaImage denser = *r.render(LicParams{}, view);
  EXPECT_GE(meanAbsoluteDifference(coarse, denser), 0.03) << "alpha must matter";
}

TEST_F(LicPictureTest, DefaultViewShowsTextureNotAFlatBlock) {
  LicRenderer r = renderer();
  ViewParams view;
  view.width = view.height = 128;
  const RgbaImage image = *r.render(LicParams{}, view);
  // Inside the volume's footprint the grey values must vary (streaks), and the background
  // (black by default) must surround it.
  double sum = 0.0, sumSquares = 0.0;
  int covered = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const double g = image.at(x, y).r;
      if (g == 0.0) continue;
      ++covered;
      sum += g;
      sumSquares += g * g;
    }
  ASSERT_GT(covered, image.width * image.height / 4);
  const double mean = sum / covered;
  const double deviation = std::sqrt(sumSquares / covered - mean * mean);
  EXPECT_GT(deviation, 20.0) << "the LIC texture should have contrast";
  EXPECT_EQ(image.at(0, 0), glm::u8vec4(0, 0, 0, 255));
}

}  // namespace
}  // namespace lic3d

namespace lic3d {
namespace {

TEST_F(LicPictureTest, EightBitFrameBufferGivesNearlyTheSamePicture) {
  LicRenderer r = renderer();
  ViewParams view;
  view.width = view.height = 96;
  const RgbaImage wide = *r.render(LicParams{}, view);
  ASSERT_TRUE(r.setFramePrecision(FramePrecision::Unorm8).ok());
  const RgbaImage narrow = *r.render(LicParams{}, view);
  EXPECT_EQ(r.licDispatchCount(), 1u);
  // Each of ~50 blended slices rounds to 1/255 in the 8-bit buffer.
  EXPECT_LE(meanAbsoluteDifference(wide, narrow), 4.0 / 255.0);
  EXPECT_GT(meanAbsoluteDifference(wide, narrow), 0.0) << "the buffer format must have changed";
}

// 16-bit UNORM holds [0, 1] with more bits than half floats near 1: the picture of the float
// buffer up to one grey level per pixel, and visibly closer to it than the 8-bit buffer's.
TEST_F(LicPictureTest, UnormFrameBuffersGiveTheFloatBuffersPictureByTheirBits) {
  LicRenderer r = renderer();
  ViewParams view;
  view.width = view.height = 96;
  const RgbaImage half = *r.render(LicParams{}, view);
  ASSERT_TRUE(r.setFramePrecision(FramePrecision::Unorm16).ok());
  const RgbaImage unorm16 = *r.render(LicParams{}, view);
  ASSERT_TRUE(r.setFramePrecision(FramePrecision::Unorm10).ok());
  const RgbaImage unorm10 = *r.render(LicParams{}, view);
  ASSERT_TRUE(r.setFramePrecision(FramePrecision::Unorm8).ok());
  const RgbaImage unorm8 = *r.render(LicParams{}, view);
  EXPECT_EQ(r.licDispatchCount(), 1u);
  int largest = 0;
  for (std::size_t i = 0; i < half.pixels.size(); ++i)
    largest = std::max(largest, std::abs(int(half.pixels[i]) - int(unorm16.pixels[i])));
  EXPECT_LE(largest, 1);
  EXPECT_LT(2.0 * meanAbsoluteDifference(half, unorm16), meanAbsoluteDifference(half, unorm8));
  // 10-bit colour lies between: closer than 8 bits, and its alpha over the opaque background
  // reads back as 255 like the others'.
  EXPECT_LT(meanAbsoluteDifference(half, unorm10), meanAbsoluteDifference(half, unorm8));
  for (std::size_t i = 3; i < unorm10.pixels.size(); i += 4) ASSERT_EQ(unorm10.pixels[i], 255);
}

}  // namespace
}  // namespace lic3d
