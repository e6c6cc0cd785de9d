// SPDX-License-Identifier: BSD-3-Clause
// Pictures that show the inside without hand-tuning (docs/LOOKS.md), measured on rendered
// images: how much of the volume's silhouette lets the background through (rendered on black and
// on white), how much stays solid, and what colour follows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "core/colormap.h"
#include "core/resolution.h"
#include "io/nrrd.h"
#include "io/vti.h"
#include "lic/analytic_fields.h"
#include "lic/derived_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "lic/resample.h"
#include "png_read.h"
#include "test_support.h"

namespace lic3d {
namespace {

using test::CliTest;
using test::CommandRun;

// Per pixel, the transmittance T of a picture rendered on black and on white: the white
// background shows through by T (C_white - C_black = T x 255 in every channel).
std::vector<double> transmittance(const test::RgbaPixels& black, const test::RgbaPixels& white) {
  std::vector<double> t(black.rgba.size() / 4);
  for (std::size_t i = 0; i < t.size(); ++i) {
    double sum = 0.0;
    for (int c = 0; c < 3; ++c) sum += white.rgba[4 * i + c] - black.rgba[4 * i + c];
    t[i] = sum / (3.0 * 255.0);
  }
  return t;
}

struct SeeThrough {
  double seeThrough = 0.0;  // of the silhouette: T > 0.1, the background shows
  double solid = 0.0;       // T < 0.5: the structure
  double clear = 0.0;       // T > 0.9: empty
  double lit = 0.0;         // brighter than 0.1 on black
};

class LookTest : public CliTest {
 protected:
  // Renders `flags` on black and on white at 128 x 128, and the silhouette of the box: the
  // dense look with opacity 1 lets nothing through.
  SeeThrough measure(const std::string& field, const std::string& flags) {
    const std::string common = "render -q --field " + field + " --width 128 --height 128 ";
    const auto render = [&](const std::string& extra, const std::string& name) {
      const CommandRun r = run(common + extra + " -o " + name);
      EXPECT_EQ(r.status, 0) << r.output;
      return test::readRgbaPng(path(name));
    };
    const std::vector<double> box = transmittance(
        render("--look dense --opacity constant --alpha 1 --background 0,0,0", "sb.png"),
        render("--look dense --opacity constant --alpha 1 --background 1,1,1", "sw.png"));
    const test::RgbaPixels black = render(flags + " --background 0,0,0", "b.png");
    const std::vector<double> t =
        transmittance(black, render(flags + " --background 1,1,1", "w.png"));
    SeeThrough m;
    int silhouette = 0;
    for (std::size_t i = 0; i < t.size(); ++i) {
      if (box[i] > 0.5) continue;
      ++silhouette;
      m.seeThrough += t[i] > 0.1 ? 1 : 0;
      m.solid += t[i] < 0.5 ? 1 : 0;
      m.clear += t[i] > 0.9 ? 1 : 0;
      const int sum = black.rgba[4 * i] + black.rgba[4 * i + 1] + black.rgba[4 * i + 2];
      m.lit += sum > 3 * 0.1 * 255 ? 1 : 0;
    }
    EXPECT_GT(silhouette, 2000) << "the box should fill much of the picture";
    const double n = std::max(silhouette, 1);
    return {m.seeThrough / n, m.solid / n, m.clear / n, m.lit / n};
  }
};

TEST_F(LookTest, TheDefaultShowsTheTornadosInsideAndTheCarotidsVesselsAlone) {
  // The tornado: the funnel and core show through the volume, and the structure is still solid.
  const SeeThrough tornado = measure("tornado --grid 48", "");
  EXPECT_GE(tornado.seeThrough, 0.5);
  EXPECT_GE(tornado.solid, 0.1);
  // The thesis' dense look, one flag away, is the opaque block the default replaced.
  const SeeThrough dense = measure("tornado --grid 48", "--look dense");
  EXPECT_LT(dense.seeThrough, 0.3);
  EXPECT_GT(dense.solid, 0.8);

  // The carotid: the still tissue around the vessels is clear, the vessels solid.
  const std::string carotid = "'" + (test::dataFolder() / "carotid.vtk").string() + "'";
  const SeeThrough vessels = measure(carotid, "");
  EXPECT_GE(vessels.clear, 0.5) << "empty space should be transparent";
  EXPECT_GT(vessels.solid, 0.03) << "the vessels should stand out";
  EXPECT_LT(vessels.solid, 0.4);
  EXPECT_LT(measure(carotid, "--look dense").clear, 0.2);
}

TEST_F(LookTest, SparseAndSeedNoiseVolumesAreNeitherBlackNorOpaque) {
  // Before: the dense look's contrast stretch made seed noise an opaque block (72 % of the
  // silhouette with T < 0.1), and the automatic Poisson mask left 1 % of it lit.
  for (const char* flags : {"--look dense --seed-noise 500", "--look dense --seed-noise 4000",
                            "--look dense --sparsity poisson", "--look dense --sparsity halton",
                            "--look streamlines", "--look sparse"}) {
    const SeeThrough m = measure("tornado --grid 48", flags);
    EXPECT_GT(m.lit, 0.2) << flags << ": nearly black";
    EXPECT_GT(m.seeThrough, 0.3) << flags << ": opaque";
    EXPECT_LT(m.clear, 0.6) << flags << ": nearly empty";
  }
}

// `render` classifies the bricks its picture can show (docs/VISIBLE_WORK.md) unless
// --visible-work off; `compute` makes every voxel without classifying.
TEST_F(CliTest, RenderClassifiesVisibleBricksUnlessTurnedOff) {
  const std::string carotid = "'" + (test::dataFolder() / "carotid.vtk").string() + "'";
  const auto classified = [&](const std::string& command) {
    const CommandRun made = run(command + " --field " + carotid);
    EXPECT_EQ(made.status, 0) << made.output;
    return made.output.find("\"visible bricks\":") != std::string::npos;
  };
  EXPECT_TRUE(classified("render --width 32 --height 32 -o on.png"));
  EXPECT_FALSE(classified("render --width 32 --height 32 --visible-work off -o off.png"));
  EXPECT_FALSE(classified("compute -o c.nrrd"));
  EXPECT_NE(run("render --visible-work maybe -o x.png").status, 0);
}

// The hidden fraction `render` reports (the GPU's count of masked voxels) is the one `compute`
// counts in the volume it writes, on a field with empty space too.
TEST_F(CliTest, RenderAndComputeReportTheSameHiddenFraction) {
  const std::string carotid = "'" + (test::dataFolder() / "carotid.vtk").string() + "'";
  const std::string flags = " --field " + carotid + " --sparsity halton --sparsity-amount 0.5 ";
  const CommandRun render = run("render" + flags + "--width 32 --height 32 -o r.png");
  const CommandRun compute = run("compute" + flags + "-o c.nrrd");
  ASSERT_EQ(render.status, 0) << render.output;
  ASSERT_EQ(compute.status, 0) << compute.output;
  const auto hidden = [](const std::string& output) {
    const std::size_t at = output.find("\"hidden_fraction\":");
    return at == std::string::npos ? -1.0 : std::stod(output.substr(at + 18));
  };
  EXPECT_GT(hidden(compute.output), 0.3);
  EXPECT_NEAR(hidden(render.output), hidden(compute.output), 1e-4) << render.output;
}

// Colour by a scalar file: through the GPU's scalar texture the same picture as the speed the
// slices take from the field itself, and on the CPU (the RGBA volume) the colour map at the
// scalar's value times the LIC grey.
TEST_F(CliTest, ColourByAScalarFollowsItOnTheGpuAndTheCpu) {
  const VectorField field = makeAnalyticField(AnalyticField::Abc, Dims(12));
  ASSERT_TRUE(writeVectorFieldNrrd(path("abc.nrrd"), field));
  ScalarVolume speed;
  speed.dims = field.dims;
  speed.geometry = field.geometry;
  for (const glm::vec3& v : field.vectors) speed.values.push_back(glm::length(v));
  ASSERT_TRUE(writeScalarNrrd(path("speed.nrrd"), speed));
  const std::string common =
      "render -q --look dense --field abc.nrrd --length 4 --width 64 --height 64 --color "
      "magnitude ";
  ASSERT_EQ(run(common + "-o by_field.png").status, 0);
  const CommandRun byFile = run(common + "--color-by speed.nrrd -o by_file.png");
  ASSERT_EQ(byFile.status, 0) << byFile.output;
  const test::RgbaPixels a = test::readRgbaPng(path("by_field.png"));
  const test::RgbaPixels b = test::readRgbaPng(path("by_file.png"));
  ASSERT_EQ(a.rgba.size(), b.rgba.size());
  double difference = 0.0;
  for (std::size_t i = 0; i < a.rgba.size(); ++i) difference += std::abs(a.rgba[i] - b.rgba[i]);
  EXPECT_LT(difference / static_cast<double>(a.rgba.size()), 1.0)
      << "speed from a file and from the field should colour alike";

  // Another scalar: x across the box. On the CPU, voxel by voxel.
  ScalarVolume ramp = speed;
  for (std::size_t i = 0; i < ramp.values.size(); ++i)
    ramp.values[i] = static_cast<float>(i % 12) * 2.0f - 5.0f;
  ASSERT_TRUE(writeScalarNrrd(path("ramp.nrrd"), ramp));
  const CommandRun cpu = run(common +
                             "--cpu --window 0,1 --alpha 0.5 --color-by ramp.nrrd "
                             "--rgba-volume rgba.vti -o cpu.png");
  ASSERT_EQ(cpu.status, 0) << cpu.output;
  const Result<RgbaVolume> rgba = readRgbaVti(path("rgba.vti"));
  ASSERT_TRUE(rgba) << rgba.error().message;
  LicParams params;
  params.length = 4;
  const ScalarVolume lic = *computeLicReference(field, makeWhiteNoise(field.dims, 1), params);
  int worst = 0;
  for (std::size_t i = 0; i < lic.values.size(); ++i) {
    const float grey = std::clamp(lic.values[i], 0.0f, 1.0f);
    // The ramp is signed: the diverging map over [-17, 17] (docs/LOOKS.md).
    const float t = (ramp.values[i] + 17.0f) / 34.0f;
    const glm::vec3 rgb = sampleColormap(Colormap::CoolWarm, t) * grey;
    for (int c = 0; c < 3; ++c)
      worst = std::max(
          worst, std::abs(rgba->rgba[4 * i + c] - static_cast<int>(std::lround(rgb[c] * 255.0f))));
  }
  EXPECT_LE(worst, 2);
  // A scalar on another grid, or a name the file lacks, is refused naming it.
  const CommandRun wrong = run(common + "--color-by nothing -o x.png");
  EXPECT_EQ(wrong.status, 2);
  EXPECT_NE(wrong.output.find("nothing"), std::string::npos) << wrong.output;
}

// The default look of a field is the same picture whatever its unit: the same tornado times 1e-20
// or 1e25 (speeds whose squares leave the float range) coloured every voxel by one end of the
// colour map and made it black or empty (hardening, class 7). Also through the RGBA volume.
TEST_F(CliTest, AFieldScaledByAnyFactorGivesTheSamePicture) {
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, Dims(16));
  std::vector<test::RgbaPixels> pictures;
  std::vector<RgbaVolume> volumes;
  for (const double scale : {1.0, 1e-20, 1e25}) {
    VectorField scaled = field;
    for (glm::vec3& v : scaled.vectors) v = glm::vec3(glm::dvec3(v) * scale);
    ASSERT_TRUE(writeVectorFieldNrrd(path("f.nrrd"), scaled));
    const CommandRun r = run(
        "render -q --field f.nrrd --length 4 --width 64 --height 64 --rgba-volume v.vti -o f.png");
    ASSERT_EQ(r.status, 0) << r.output;
    pictures.push_back(test::readRgbaPng(path("f.png")));
    Result<RgbaVolume> volume = readRgbaVti(path("v.vti"));
    ASSERT_TRUE(volume) << volume.error().message;
    volumes.push_back(std::move(*volume));
  }
  for (std::size_t k = 1; k < pictures.size(); ++k) {
    ASSERT_EQ(pictures[k].rgba.size(), pictures[0].rgba.size());
    int worst = 0;
    for (std::size_t i = 0; i < pictures[0].rgba.size(); ++i)
      worst = std::max(worst, std::abs(pictures[k].rgba[i] - pictures[0].rgba[i]));
    EXPECT_LE(worst, 2) << "scale " << k;
    ASSERT_EQ(volumes[k].rgba.size(), volumes[0].rgba.size());
    worst = 0;
    for (std::size_t i = 0; i < volumes[0].rgba.size(); ++i)
      worst = std::max(worst, std::abs(volumes[k].rgba[i] - volumes[0].rgba[i]));
    EXPECT_LE(worst, 2) << "scale " << k;
  }
}

// --resolution: the field sampled trilinearly on the finer grid, the noise made there, the LIC
// the reference's on that grid.
TEST_F(CliTest, LicAtAFinerResolutionIsTheReferenceOnTheResampledField) {
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, Dims(10, 9, 8));
  ASSERT_TRUE(writeVectorFieldNrrd(path("coarse.nrrd"), field));
  const CommandRun r = run("compute -q --field coarse.nrrd --resolution 2x --length 8 -o up.nrrd");
  ASSERT_EQ(r.status, 0) << r.output;
  const Result<ScalarVolume> gpu = readScalarNrrd(path("up.nrrd"));
  ASSERT_TRUE(gpu) << gpu.error().message;
  const Dims fine = resolvedGrid(*parseResolution("2x"), field.dims);
  ASSERT_EQ(gpu->dims, fine);
  LicParams params;
  params.length = 8;
  const ScalarVolume cpu =
      *computeLicReference(resampleField(field, fine), makeWhiteNoise(fine, 1), params);
  double mean = 0.0;
  for (std::size_t i = 0; i < cpu.values.size(); ++i)
    mean += std::abs(gpu->values[i] - cpu.values[i]);
  EXPECT_LT(mean / static_cast<double>(cpu.values.size()), 2e-3);
  // Analytic fields take --grid instead.
  const CommandRun analytic = run("compute --field abc --resolution 2x -o a.nrrd");
  EXPECT_EQ(analytic.status, 2);
  EXPECT_NE(analytic.output.find("--grid"), std::string::npos) << analytic.output;
}

// A ParaView preset colours the picture; the picture's session keeps it.
TEST_F(CliTest, ATransferFunctionFileColoursThePictureAndTravelsInItsSession) {
  writeBytes("red.json", R"([{"Name": "reds", "RGBPoints": [0, 1, 0, 0, 1, 1, 0.2, 0.2]}])");
  const CommandRun r =
      run("render -q --look dense --field abc --grid 12 --width 48 --height 48 --color magnitude "
          "--tf red.json -o red.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const test::RgbaPixels image = test::readRgbaPng(path("red.png"));
  int lit = 0, red = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    if (image.rgba[i] + image.rgba[i + 1] + image.rgba[i + 2] < 30) continue;
    ++lit;
    red += image.rgba[i] > 2 * image.rgba[i + 1] && image.rgba[i] > 2 * image.rgba[i + 2];
  }
  ASSERT_GT(lit, 500);
  EXPECT_GT(static_cast<double>(red) / lit, 0.95);
  const Result<Session> stored = test::sessionInPng(path("red.png"));
  ASSERT_TRUE(stored) << stored.error().message;
  EXPECT_EQ(stored->view.transfer.name, "reds");
  EXPECT_EQ(stored->view.transfer.colors.size(), 2u);
  const CommandRun bad = run("render --tf missing.json -o x.png");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.output.find("missing.json"), std::string::npos) << bad.output;
}

// A 2D LIC plane at any orientation: what lies outside the box is background.
TEST_F(CliTest, AnObliquePlaneIsDrawnWithTheBoxOutsideAsBackground) {
  const CommandRun r =
      run("render2d -q --field tornado --grid 24 --plane 0.8,0.8,0.8,1,1,1 --width 96 "
          "--background 0,0,1 -o plane.png");
  ASSERT_EQ(r.status, 0) << r.output;
  const test::RgbaPixels image = test::readRgbaPng(path("plane.png"));
  int background = 0, texture = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4) {
    const bool blue = image.rgba[i] == 0 && image.rgba[i + 1] == 0 && image.rgba[i + 2] == 255;
    background += blue;
    texture += !blue;
  }
  // A plane across a corner cuts a triangle out of the box: much of its rectangle is outside.
  EXPECT_GT(background, static_cast<int>(image.rgba.size() / 4) / 5);
  EXPECT_GT(texture, static_cast<int>(image.rgba.size() / 4) / 5);
  const CommandRun misses = run("render2d --field tornado --plane 2,2,2,1,0,0 -o x.png");
  EXPECT_EQ(misses.status, 2) << misses.output;
}

}  // namespace
}  // namespace lic3d
