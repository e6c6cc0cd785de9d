// SPDX-License-Identifier: BSD-3-Clause
// Depth that reads (docs/LOOKS.md, "Depth cues"), measured on rendered pictures: two layers of
// flow one behind the other, seen face on, each streaked at right angles to the other; and the
// slices' facets and bands when a voxel covers many pixels.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "png_read.h"

namespace lic3d {
namespace {

using test::CliTest;
using test::CommandRun;

constexpr int kGrid = 64;

// A 64^3 NRRD field: flow along y in the layer 0.6 < x < 0.8, along z in 0.2 < x < 0.4, still
// elsewhere. The camera at azimuth 0 looks from +x, so the first layer is the near one; with
// `swapped` the near layer flows along z and the far one along y.
void writeTwoLayers(const std::filesystem::path& file, bool swapped) {
  std::vector<float> v(3 * kGrid * kGrid * kGrid, 0.0f);
  const int nearAxis = swapped ? 2 : 1;
  const int farAxis = swapped ? 1 : 2;
  for (int z = 0; z < kGrid; ++z)
    for (int y = 0; y < kGrid; ++y)
      for (int x = 0; x < kGrid; ++x) {
        const double fx = (x + 0.5) / kGrid;
        const std::size_t i = 3 * ((static_cast<std::size_t>(z) * kGrid + y) * kGrid + x);
        if (fx > 0.6 && fx < 0.8) v[i + nearAxis] = 1.0f;
        if (fx > 0.2 && fx < 0.4) v[i + farAxis] = 1.0f;
      }
  std::ofstream out(file, std::ios::binary);
  out << "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 " << kGrid << " " << kGrid << " " << kGrid
      << "\nkinds: vector domain domain domain\nencoding: raw\nendian: little\n"
         "spacings: nan 1 1 1\n\n";
  out.write(reinterpret_cast<const char*>(v.data()),
            static_cast<std::streamsize>(v.size() * sizeof(float)));
}

double grey(const test::RgbaPixels& image, int x, int y) {
  const std::uint8_t* p = &image.rgba[4 * (static_cast<std::size_t>(y) * image.width + x)];
  return (p[0] + p[1] + p[2]) / 3.0;
}

// The share of the picture's streak contrast that runs horizontally: the variance left after
// smoothing each row along x over `kAlong` pixels (which keeps horizontal streaks and averages
// vertical ones away), over that plus the variance left after smoothing along y. In the middle
// 40 % of the picture, inside both layers' footprint. 1: only horizontal streaks show.
double horizontalShare(const test::RgbaPixels& image) {
  constexpr int kAlong = 12;
  const int x0 = image.width * 3 / 10, x1 = image.width * 7 / 10;
  const int y0 = image.height * 3 / 10, y1 = image.height * 7 / 10;
  std::vector<double> alongX, alongY;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      double sx = 0.0, sy = 0.0;
      for (int k = -kAlong / 2; k < kAlong / 2; ++k) {
        sx += grey(image, x + k, y);
        sy += grey(image, x, y + k);
      }
      alongX.push_back(sx / kAlong);
      alongY.push_back(sy / kAlong);
    }
  const auto variance = [](const std::vector<double>& values) {
    double mean = 0.0, squares = 0.0;
    for (const double v : values) mean += v;
    mean /= static_cast<double>(values.size());
    for (const double v : values) squares += (v - mean) * (v - mean);
    return squares / static_cast<double>(values.size());
  };
  const double h = variance(alongX), v = variance(alongY);
  return h / std::max(h + v, 1e-12);
}

// The depth criterion: seen face on, each layer keeps a clear share of the streak contrast (the
// far one at least kFarShare: it is legible) and the near one the larger part (at least
// kNearShare: it reads as in front), whichever layer is in front.
constexpr double kNearShare = 0.6;
constexpr double kFarShare = 0.25;

struct LayerShares {
  double nearFirst = 0.0;   // the near layer's share, near layer streaked horizontally
  double nearSecond = 0.0;  // the same with the layers swapped (near layer vertical)
  bool meets() const {
    return std::min(nearFirst, nearSecond) >= kNearShare &&
           1.0 - std::max(nearFirst, nearSecond) >= kFarShare;
  }
};

class DepthTest : public CliTest {
 protected:
  LayerShares layerShares(const std::string& flags) {
    LayerShares shares;
    for (const bool swapped : {false, true}) {
      const std::string field = swapped ? "swapped.nrrd" : "layers.nrrd";
      if (!std::filesystem::exists(path(field))) writeTwoLayers(path(field), swapped);
      const CommandRun r =
          run("render -q --field " + field +
              " --azimuth 0 --elevation 0 --width 256 --height 256 " + flags + " -o layers.png");
      EXPECT_EQ(r.status, 0) << r.output;
      const double horizontal = horizontalShare(test::readRgbaPng(path("layers.png")));
      (swapped ? shares.nearSecond : shares.nearFirst) = swapped ? 1.0 - horizontal : horizontal;
    }
    return shares;
  }
};

std::string describe(const LayerShares& s) {
  return "near layer's share " + std::to_string(s.nearFirst) + " (near streaks horizontal), " +
         std::to_string(s.nearSecond) + " (swapped)";
}

TEST_F(DepthTest, TheDefaultShowsBothLayersAndTheNearOneInFront) {
  const LayerShares shares = layerShares("");
  EXPECT_TRUE(shares.meets()) << describe(shares);
}

TEST_F(DepthTest, TheCriterionTellsPicturesThatHideOrFlattenALayer) {
  // The see-through look as it was before depth cues (linear sampling, optical depth 1.1, no
  // halos): the near layer hides the far one (its share falls under kFarShare).
  const LayerShares hidden = layerShares("--filter linear --optical-depth 1.1 --halo 0");
  EXPECT_FALSE(hidden.meets()) << describe(hidden);
  EXPECT_LT(1.0 - std::max(hidden.nearFirst, hidden.nearSecond), kFarShare) << describe(hidden);
  // Streamlines without halos: both layers show, and nothing says which is in front (in one
  // order the far layer has the larger share).
  const LayerShares unordered = layerShares("--look streamlines --halo 0");
  EXPECT_FALSE(unordered.meets()) << describe(unordered);
  EXPECT_LT(std::min(unordered.nearFirst, unordered.nearSecond), kNearShare) << describe(unordered);
  // The thesis' dense look: an opaque block whose noise on the box's face says nothing of either
  // layer.
  const LayerShares flat = layerShares("--look dense");
  EXPECT_FALSE(flat.meets()) << describe(flat);
}

TEST_F(DepthTest, HalosAndOcclusionPutTheNearLayerInFront) {
  const std::string base = "--optical-depth 0.5 --halo 0 ";
  const LayerShares none = layerShares(base);
  const LayerShares halos = layerShares("--optical-depth 0.5 --halo 0.6");
  const LayerShares occluded = layerShares(base + "--occlusion 0.8");
  for (const LayerShares* cue : {&halos, &occluded}) {
    EXPECT_GT(cue->nearFirst, none.nearFirst + 0.02)
        << describe(*cue) << " against " << describe(none);
    EXPECT_GT(cue->nearSecond, none.nearSecond + 0.02)
        << describe(*cue) << " against " << describe(none);
  }
}

// The mean of |a - b| over the pixels, in grey levels.
double meanDifference(const test::RgbaPixels& a, const test::RgbaPixels& b) {
  double sum = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) sum += std::abs(grey(a, x, y) - grey(b, x, y));
  return sum / (static_cast<double>(a.width) * a.height);
}

TEST_F(DepthTest, LightingFromTheLicGradientIsVisible) {
  // On the dense look's block, where every pixel is lit.
  const std::string common =
      "render -q --field tornado --grid 32 --look dense --width 96 --height 96 ";
  ASSERT_EQ(run(common + "-o unlit.png").status, 0);
  const CommandRun lit = run(common + "--lighting gradient -o lit.png");
  ASSERT_EQ(lit.status, 0) << lit.output;
  EXPECT_GT(
      meanDifference(test::readRgbaPng(path("unlit.png")), test::readRgbaPng(path("lit.png"))),
      2.0);
}

TEST_F(DepthTest, ZoomedSlicesShowNeitherFacetsNorBands) {
  // The dense look from close by, where a voxel covers about 8 pixels, against the same with 16
  // times the slices and no jitter (the picture the slices converge to). Plain slicing (linear
  // sampling, no jitter) shows the voxels' facets and bands along the slices' edges; the default
  // comes within half of its distance.
  const std::string common =
      "render -q --field tornado --grid 24 --look dense --distance 1.0 --width 128 --height 128 ";
  ASSERT_EQ(run(common + "--slices 384 --jitter off --filter cubic -o converged.png").status, 0);
  ASSERT_EQ(run(common + "--filter linear --jitter off -o plain.png").status, 0);
  ASSERT_EQ(run(common + "-o default.png").status, 0);
  const test::RgbaPixels converged = test::readRgbaPng(path("converged.png"));
  const double plain = meanDifference(test::readRgbaPng(path("plain.png")), converged);
  const double now = meanDifference(test::readRgbaPng(path("default.png")), converged);
  EXPECT_LT(now, 0.5 * plain) << "default " << now << " grey levels from the converged picture, "
                              << "plain slicing " << plain;
}

}  // namespace
}  // namespace lic3d
