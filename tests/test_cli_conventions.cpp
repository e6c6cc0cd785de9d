// SPDX-License-Identifier: BSD-3-Clause
// Honest settings on the command line (docs/LOOKS.md): signed scalars drawn with the diverging
// map, colour by a quantity carrying the opacity, flags given winning over the look, flags that
// need another refused before any work, names checked before the LIC, and --slice pictures with
// the physical aspect. Tiny renders: 64 x 64 pixels of 24^3 grids.
#include <gtest/gtest.h>

#include <string>

#include "cli_test_support.h"
#include "png_read.h"

namespace lic3d {
namespace {

using test::CliTest;
using test::CommandRun;

const std::string kTiny = "render -q --field tornado --grid 24 --width 64 --height 64 ";

struct Hues {
  int coloured = 0;  // pixels brighter than 0.1
  int green = 0;     // of them, green the strongest channel
  int blue = 0;      // blue the strongest
  int red = 0;       // red the strongest
};

Hues huesOf(const test::RgbaPixels& png) {
  Hues h;
  for (std::size_t i = 0; i + 3 < png.rgba.size(); i += 4) {
    const int r = png.rgba[i], g = png.rgba[i + 1], b = png.rgba[i + 2];
    if (std::max({r, g, b}) < 26) continue;
    ++h.coloured;
    if (g > r + 4 && g > b + 4) ++h.green;
    if (b > r + 4 && b > g + 4) ++h.blue;
    if (r > g + 4 && r > b + 4) ++h.red;
  }
  return h;
}

TEST_F(CliTest, HelicityIsDrawnWithTheDivergingMap) {
  // The tornado's helicity has both signs. Cool-warm never has green as its strongest channel;
  // viridis, over the same values, often does.
  ASSERT_EQ(run(kTiny + "--color-by helicity -o default.png").status, 0);
  ASSERT_EQ(run(kTiny + "--color-by helicity --colormap viridis -o viridis.png").status, 0);
  const Hues diverging = huesOf(test::readRgbaPng(path("default.png")));
  const Hues viridis = huesOf(test::readRgbaPng(path("viridis.png")));
  ASSERT_GT(diverging.coloured, 50);
  EXPECT_LT(diverging.green, diverging.coloured / 50);
  EXPECT_GT(diverging.blue, diverging.coloured / 5) << "the negative helicity of the core";
  EXPECT_GT(viridis.green, viridis.coloured / 10);
  // Speed keeps viridis: one sign.
  ASSERT_EQ(run(kTiny + "-o speed.png").status, 0);
  EXPECT_GT(huesOf(test::readRgbaPng(path("speed.png"))).green, 0);
}

TEST_F(CliTest, ColourByAQuantityCarriesTheOpacity) {
  ASSERT_EQ(run(kTiny + "--color-by vorticity -o vorticity.png").status, 0);
  ASSERT_EQ(run(kTiny + "--color-by vorticity --opacity-by speed -o speed.png").status, 0);
  const Result<Session> session = test::sessionInPng(path("vorticity.png"));
  ASSERT_TRUE(session) << session.error().message;
  EXPECT_EQ(session->view.opacityBy, "vorticity");
  EXPECT_NE(test::readRgbaPng(path("vorticity.png")).rgba,
            test::readRgbaPng(path("speed.png")).rgba);
  // The session remakes the picture.
  ASSERT_EQ(run("render -q --session vorticity.png -o again.png").status, 0);
  EXPECT_EQ(test::readRgbaPng(path("vorticity.png")).rgba,
            test::readRgbaPng(path("again.png")).rgba);
}

TEST_F(CliTest, FlagsGivenWinOverTheLook) {
  const auto pixels = [&](const std::string& flags, const std::string& name) {
    const CommandRun r = run(kTiny + flags + " -o " + name);
    EXPECT_EQ(r.status, 0) << r.output;
    return test::readRgbaPng(path(name)).rgba;
  };
  EXPECT_NE(pixels("", "default.png"), pixels("--alpha 0.9", "alpha.png"));
  EXPECT_NE(pixels("--look streamlines", "lines.png"),
            pixels("--look streamlines --contrast off", "contrast.png"));
  EXPECT_NE(pixels("--look streamlines", "lines2.png"),
            pixels("--look streamlines --seed-noise 0", "white.png"));
}

TEST_F(CliTest, FlagsThatNeedAnotherAreRefusedNamingIt) {
  const struct {
    const char* flags;
    const char* needs;
  } cases[] = {
      {"--sparsity-amount 0.5", "--sparsity"},
      {"--sparsity halton --sparsity-radius 2", "--sparsity poisson or jitter"},
      {"--sparsity halton --sparsity-amount 0.5 --sparsity-points 40", "give one"},
      {"--fog-color 1,0,0", "--fog"},
      {"--eye-separation 0.1", "--stereo"},
      {"--zero-parallax 2", "--stereo"},
      {"--roi-size 0.3", "--roi"},
      {"--alpha 0.5 --optical-depth 1", "give one"},
      {"--window 0.2,0.8 --window-percentiles 0.1,0.9", "give one"},
      {"--color none --color-by vorticity", "--color none"},
      {"--look dense --halo-radius 2", "--halo"},
      {"--look dense --opacity-floor 0.2", "--magnitude-opacity"},
  };
  for (const auto& c : cases) {
    const CommandRun r = run(kTiny + c.flags + " -o x.png");
    EXPECT_EQ(r.status, 2) << c.flags << ": " << r.output;
    EXPECT_NE(r.output.find(c.needs), std::string::npos) << c.flags << ": " << r.output;
    EXPECT_FALSE(std::filesystem::exists(path("x.png")));
  }
  // With what they need, they act.
  EXPECT_EQ(run(kTiny + "--sparsity halton --sparsity-amount 0.5 -o x.png").status, 0);
  EXPECT_EQ(run(kTiny + "--halo 0.5 --halo-radius 2 --opacity-floor 0.2 -o x.png").status, 0);
}

TEST_F(CliTest, ABadScalarNameIsRefusedBeforeTheLic) {
  const CommandRun analytic = run(kTiny + "--color-by vortcity -o x.png");
  EXPECT_EQ(analytic.status, 2);
  EXPECT_NE(analytic.output.find("--color-by"), std::string::npos) << analytic.output;
  EXPECT_NE(analytic.output.find("vorticity, helicity"), std::string::npos) << analytic.output;
  // A file's arrays are listed, and the refusal comes before the LIC: no progress of it is
  // printed (the progress lines are on without -q).
  const CommandRun file =
      run("render --field " + ("'" + (test::dataFolder() / "carotid.vtk").string() + "'") +
          " --resolution 4x --opacity-by nope -o x.png");
  EXPECT_EQ(file.status, 2) << file.output;
  EXPECT_NE(file.output.find("--opacity-by 'nope'"), std::string::npos) << file.output;
  EXPECT_NE(file.output.find("scalars"), std::string::npos) << "the file's array";
  EXPECT_EQ(file.output.find("lic3d: LIC"), std::string::npos) << file.output;
}

TEST_F(CliTest, ASliceHasThePhysicalAspect) {
  // The magnetic mirror: spacing 0.05 along x and y, 0.125 along z, 47 points each.
  const std::string field = ("'" + (test::dataFolder() / "example-femm-3d.vtk").string() + "'");
  ASSERT_EQ(run("render2d -q --cpu --field " + field + " --slice y -o y.png").status, 0);
  ASSERT_EQ(
      run("render2d -q --cpu --field " + field + " --plane 0.5,0.5,0.5,0,-1,0 -o p.png").status, 0);
  const auto [w, h] = test::pngSize(path("y.png"));
  const double physical = (46 * 0.125) / (46 * 0.05);
  EXPECT_NEAR(static_cast<double>(h - 1) / (w - 1), physical, 0.03);
  EXPECT_EQ(test::pngSize(path("p.png")), test::pngSize(path("y.png")));
}

}  // namespace
}  // namespace lic3d
