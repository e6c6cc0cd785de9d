// SPDX-License-Identifier: BSD-3-Clause
// K slices composited per fragment (slice.frag, slice.vert): the same picture as one slice per
// fragment, but for the rounding of the blend, for every slice feature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/look.h"
#include "core/session.h"
#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "render/lic_renderer.h"

namespace lic3d {
namespace {

using test::GpuTest;

struct Difference {
  double max = 0.0;    // the largest |a - b| of any channel, in 1/255
  double mean = 0.0;   // over all channels of all pixels, in 1/255
  double above = 0.0;  // the share of channels that differ by more than 2/255
};

Difference difference(const RgbaImage& a, const RgbaImage& b) {
  Difference d;
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  if (a.pixels.size() != b.pixels.size() || a.pixels.empty()) return d;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) {
    const double e = std::abs(static_cast<int>(a.pixels[i]) - static_cast<int>(b.pixels[i]));
    d.max = std::max(d.max, e);
    sum += e;
    if (e > 2.0) d.above += 1.0;
  }
  d.mean = sum / static_cast<double>(a.pixels.size());
  d.above /= static_cast<double>(a.pixels.size());
  return d;
}

// The share of pixels that differ from the background: that a picture shows something.
double drawnShare(const RgbaImage& image, glm::vec3 background) {
  std::size_t drawn = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const glm::u8vec4 p = image.at(x, y);
      const glm::vec3 c = glm::vec3(p.r, p.g, p.b) / 255.0f;
      if (glm::length(c - background) > 0.02f) ++drawn;
    }
  return static_cast<double>(drawn) / (image.width * image.height);
}

struct Case {
  std::string name;
  ViewParams view;
};

// The default look and its variations, each a feature that slices must keep with K > 1.
std::vector<Case> cases(const Session& look) {
  std::vector<Case> all;
  ViewParams base = look.view;
  base.width = base.height = 160;
  all.push_back({"default look (halos)", base});
  ViewParams plain = base;
  plain.halo = 0.0f;
  all.push_back({"no halos", plain});
  ViewParams plane = base;
  plane.clipPlane = true;
  plane.clipPlanePoint = glm::vec3(0.5f, 0.45f, 0.5f);
  plane.clipPlaneNormal = glm::vec3(0.3f, 1.0f, 0.2f);
  all.push_back({"clip plane", plane});
  ViewParams box = base;
  box.clipMin = glm::vec3(0.1f, 0.2f, 0.0f);
  box.clipMax = glm::vec3(0.8f, 1.0f, 0.7f);
  all.push_back({"clip box", box});
  ViewParams occlusion = base;
  occlusion.occlusion = 0.6f;
  all.push_back({"occlusion", occlusion});
  ViewParams anaglyph = base;
  anaglyph.stereo = StereoMode::Anaglyph;
  all.push_back({"anaglyph stereo", anaglyph});
  ViewParams sideBySide = base;
  sideBySide.stereo = StereoMode::SideBySide;
  sideBySide.width = 96;
  all.push_back({"side-by-side stereo", sideBySide});
  ViewParams cues = base;
  cues.fog = true;
  cues.lighting = Lighting::Phong;
  cues.roi = RoiShape::Sphere;
  cues.roiSize = 0.8f;
  cues.camera.orthographic = true;
  cues.camera.elevation = 55.0f;
  all.push_back({"fog, lighting, region, orthographic", cues});
  ViewParams axis = base;
  axis.slicing = Slicing::AxisAligned;
  axis.camera.azimuth = 20.0f;
  axis.slices = 37;  // not a multiple of 2 or 4: the last group is short
  all.push_back({"axis-aligned, 37 slices", axis});
  return all;
}

TEST_F(GpuTest, SlicesPerFragmentDrawTheSamePictureAsOneSliceEach) {
  Session look;
  applyLook(kDefaultLook, look);
  ASSERT_GT(look.view.halo, 0.0f) << "the default look has halos";
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, {40, 40, 40});
  for (const FramePrecision precision : {FramePrecision::Float16, FramePrecision::Unorm8}) {
    RendererOptions options;
    options.framePrecision = precision;
    Result<LicRenderer> renderer = LicRenderer::create(context(), options);
    ASSERT_TRUE(renderer.ok());
    ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(field.dims, 3)).ok());
    const std::vector<Case> all = cases(look);
    for (const Case& c : all) {
      renderer->setSlicesPerFragment(1);
      const Result<RgbaImage> one = renderer->render(look.lic, c.view);
      ASSERT_TRUE(one.ok()) << c.name;
      const std::size_t before = renderer->drawVariantCount();
      EXPECT_GT(drawnShare(*one, c.view.background), 0.05) << c.name;
      for (const int k : {2, 4}) {
        renderer->setSlicesPerFragment(k);
        const Result<RgbaImage> grouped = renderer->render(look.lic, c.view);
        ASSERT_TRUE(grouped.ok()) << c.name;
        const Difference d = difference(*one, *grouped);
        std::printf("%-36s %7s K=%d: max %2.0f, mean %.4f, over 2: %.4f %%\n", c.name.c_str(),
                    precision == FramePrecision::Float16 ? "rgba16f" : "rgba8", k, d.max, d.mean,
                    100.0 * d.above);
        // Float rounding of the blend only: an RGBA16F target rounds little, an 8-bit one rounds
        // every slice's blend where K > 1 rounds once per group. Where a slice's edge passes
        // through a pixel centre, rasterization (K = 1) and the box test (K > 1) may decide
        // differently: a few pixels at the box's silhouette differ more.
        const bool eightBit = precision == FramePrecision::Unorm8;
        EXPECT_LE(d.mean, eightBit ? 1.0 : 0.05) << c.name << " K=" << k;
        EXPECT_LE(d.above, eightBit ? 0.15 : 0.002) << c.name << " K=" << k;
        EXPECT_LE(d.max, 20.0) << c.name << " K=" << k;
      }
      // With occlusion each slice reads the buffer the one in front wrote: K stays 1, no new
      // pipeline.
      if (c.view.occlusion > 0.0f) {
        EXPECT_EQ(renderer->drawVariantCount(), before) << c.name;
      } else if (&c == &all.front()) {
        EXPECT_EQ(renderer->drawVariantCount(), before + 2) << "a pipeline for each K";
      }
    }
  }
}

// Slices that alternate black and white along every ray, half opaque: the order in which a
// fragment composites its K samples shows at once.
TEST_F(GpuTest, SlicesPerFragmentCompositeBackToFrontAsTheBlendDoes) {
  const Dims dims{16, 16, 16};
  LicRenderer renderer = test::rendererWithVolume(
      context(), dims, [](int i, int j, int k) { return (i + j + k) % 2 == 0 ? 1.0f : 0.0f; });
  ViewParams view = test::opaqueView(96);
  view.alpha = 0.5f;
  view.filter = VolumeFilter::Nearest;
  view.slices = 64;
  renderer.setSlicesPerFragment(1);
  const Result<RgbaImage> one = renderer.render(LicParams{}, view);
  ASSERT_TRUE(one.ok());
  for (const int k : {2, 4}) {
    renderer.setSlicesPerFragment(k);
    const Result<RgbaImage> grouped = renderer.render(LicParams{}, view);
    ASSERT_TRUE(grouped.ok());
    const Difference d = difference(*one, *grouped);
    std::printf("alternating slices K=%d: max %.0f, mean %.4f, over 2: %.4f %%\n", k, d.max, d.mean,
                100.0 * d.above);
    EXPECT_LE(d.mean, 0.05) << "K=" << k;
    EXPECT_LE(d.above, 0.002) << "K=" << k;
  }
}

}  // namespace
}  // namespace lic3d
