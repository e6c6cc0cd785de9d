// SPDX-License-Identifier: BSD-3-Clause
// Colour conventions and plane orientation on the CPU (docs/LOOKS.md): the diverging map of
// signed scalars and its symmetric range, the opacity of a signed scalar by its size, and the
// picture axes of planes as a continuous function of the normal, with square pixels on
// anisotropic grids.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>
#include <memory>
#include <vector>

#include "core/colormap.h"
#include "core/view_params.h"
#include "lic/field_plane.h"

namespace lic3d {
namespace {

// CIE L* of a display colour (sRGB, D65).
double lightness(glm::vec3 rgb) {
  const auto linear = [](double c) {
    return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
  };
  const double y = 0.2126 * linear(rgb.r) + 0.7152 * linear(rgb.g) + 0.0722 * linear(rgb.b);
  return y > 0.008856 ? 116.0 * std::cbrt(y) - 16.0 : 903.3 * y;
}

TEST(DivergingMap, MirrorsItsLightnessAboutANeutralCentre) {
  const glm::vec3 centre = sampleColormap(Colormap::CoolWarm, 0.5f);
  // Neutral: no channel more than 2 % away from the others, and light.
  EXPECT_LT(std::max({centre.r, centre.g, centre.b}) - std::min({centre.r, centre.g, centre.b}),
            0.02f);
  EXPECT_GT(lightness(centre), 80.0);
  for (int k = 1; k <= 20; ++k) {
    const float t = 0.5f * static_cast<float>(k) / 20.0f;
    const glm::vec3 low = sampleColormap(Colormap::CoolWarm, 0.5f - t);
    const glm::vec3 high = sampleColormap(Colormap::CoolWarm, 0.5f + t);
    EXPECT_NEAR(lightness(low), lightness(high), 2.0) << "at +-" << t;
    // Darker away from the centre on both sides, blue below and red above.
    EXPECT_LT(lightness(high), lightness(centre) + 0.5);
    EXPECT_GT(low.b, low.r) << t;
    EXPECT_GT(high.r, high.b) << t;
  }
}

TransferFacts factsOf(const std::vector<float>& values) {
  TransferFacts facts;
  facts.colorValues = std::make_shared<const ValueHistogram>(histogramOf(values));
  facts.minMagnitude = static_cast<float>(facts.colorValues->min);
  facts.maxMagnitude = static_cast<float>(facts.colorValues->max);
  return facts;
}

TEST(DivergingMap, SignedScalarsTakeItOverARangeSymmetricAboutZero) {
  ViewParams view;
  view.color = ColorMode::Magnitude;
  view.colormap = Colormap::Viridis;
  view.colorBy = view.opacityBy = "helicity";
  std::vector<float> values;
  for (int i = 0; i <= 100; ++i)
    values.push_back(-1.0f + 4.0f * static_cast<float>(i) / 100.0f);  // [-1, 3]
  const TransferFacts facts = factsOf(values);
  ASSERT_TRUE(divergingColor(view, facts));
  const ColorRange range = colorRange(view, facts);
  EXPECT_FLOAT_EQ(range.low, -range.high);
  EXPECT_FLOAT_EQ(range.high, 3.0f);
  EXPECT_EQ(shownView(view, facts).colormap, Colormap::CoolWarm);
  // Zero is the centre of the map.
  const glm::vec2 t = magnitudeTransfer(range);
  EXPECT_NEAR((0.0f - t.x) * t.y, 0.5f, 1e-6f);

  // With the look's percentiles the range is symmetric too.
  view.rangeTail = 0.05f;
  const ColorRange tail = colorRange(view, facts);
  EXPECT_FLOAT_EQ(tail.low, -tail.high);

  // A scalar of one sign keeps the view's map and its own range.
  const TransferFacts positive = factsOf({0.5f, 1.0f, 2.0f});
  EXPECT_FALSE(divergingColor(view, positive));
  EXPECT_EQ(shownView(view, positive).colormap, Colormap::Viridis);

  // A map or range chosen is kept.
  ViewParams chosen = view;
  chosen.divergingWhenSigned = false;
  EXPECT_EQ(shownView(chosen, facts).colormap, Colormap::Viridis);
  chosen = view;
  chosen.autoColorRange = false;
  chosen.colorLow = -1.0f;
  chosen.colorHigh = 3.0f;
  EXPECT_FALSE(divergingColor(chosen, facts));
}

TEST(DivergingMap, ASignedOpacityScalarWeighsByItsSize) {
  ViewParams view;
  view.color = ColorMode::Magnitude;
  view.colorBy = view.opacityBy = "helicity";
  view.magnitudeOpacity = 1.5f;
  view.magnitudeThreshold = 0.02f;
  const TransferFacts facts = factsOf({-2.0f, -1.0f, 0.0f, 1.0f, 2.0f});
  const ViewParams shown = shownView(view, facts);
  ASSERT_FALSE(shown.transfer.opacities.empty());
  for (int k = 0; k <= 10; ++k) {
    const float s = static_cast<float>(k) / 10.0f;
    EXPECT_NEAR(opacityWeight(shown, 0.5f - 0.5f * s), opacityWeight(shown, 0.5f + 0.5f * s), 1e-6)
        << s;
  }
  EXPECT_NEAR(opacityWeight(shown, 0.5f), 0.0, 1e-6) << "zero is clear";
  EXPECT_NEAR(opacityWeight(shown, 0.0f), 1.0, 1e-6) << "the largest negative value is opaque";
}

// ---- planes ------------------------------------------------------------------------------------

double angleDegrees(glm::dvec3 a, glm::dvec3 b) {
  return glm::degrees(
      std::acos(std::clamp(glm::dot(glm::normalize(a), glm::normalize(b)), -1.0, 1.0)));
}

TEST(PlaneAxes, TurnContinuouslyWithTheNormal) {
  const std::vector<glm::dvec3> normals = {{1, 0, 0},   {1, 0.2, 0},    {1, 1, 0}, {0, 1, 0},
                                           {1, 0, 0.3}, {0.3, -1, 0.5}, {0, 0, 1}};
  for (const glm::dvec3 n : normals) {
    const PlaneAxes axes = planePictureAxes(n);
    EXPECT_NEAR(glm::dot(axes.right, glm::normalize(n)), 0.0, 1e-9);
    EXPECT_NEAR(glm::dot(axes.up, glm::normalize(n)), 0.0, 1e-9);
    EXPECT_NEAR(glm::length(glm::cross(axes.right, axes.up) - glm::normalize(n)), 0.0, 1e-9)
        << "the normal points at the viewer";
    // A normal turned by about 1 degree turns the axes by about as much, not by 90.
    for (const glm::dvec3 nudge : {glm::dvec3(0.02, 0, 0), glm::dvec3(0, 0.02, 0),
                                   glm::dvec3(0, 0, 0.02), glm::dvec3(-0.02, 0.02, -0.02)}) {
      const glm::dvec3 m = glm::normalize(n) + nudge;
      const PlaneAxes near = planePictureAxes(m);
      const double turn = angleDegrees(glm::normalize(n), m);
      EXPECT_LT(angleDegrees(axes.up, near.up), 6.0 * turn + 0.1)
          << n.x << "," << n.y << "," << n.z;
      EXPECT_LT(angleDegrees(axes.right, near.right), 6.0 * turn + 0.1);
    }
  }
  // Along the horizontal arc from x to y, up stays z.
  for (int k = 0; k <= 90; k += 5) {
    const double a = glm::radians(static_cast<double>(k));
    EXPECT_LT(angleDegrees(planePictureAxes({std::cos(a), std::sin(a), 0}).up, {0, 0, 1}), 1e-6);
  }
  // The box axes give the slices' pictures.
  EXPECT_LT(angleDegrees(planePictureAxes({1, 0, 0}).right, {0, 1, 0}), 1e-6);
  EXPECT_LT(angleDegrees(planePictureAxes({0, -1, 0}).right, {1, 0, 0}), 1e-6);
  EXPECT_LT(angleDegrees(planePictureAxes({0, 0, 1}).right, {1, 0, 0}), 1e-6);
  EXPECT_LT(angleDegrees(planePictureAxes({0, 0, 1}).up, {0, 1, 0}), 1e-6);
}

TEST(PlaneAxes, ASliceOfAnAnisotropicGridHasSquarePixels) {
  VectorField plane;
  plane.dims = Dims(21, 21, 1);
  plane.geometry.spacing = glm::dvec3(0.05, 0.125, 0.05);
  plane.vectors.assign(voxelCount(plane.dims), glm::vec3(1.0f, 0.0f, 0.0f));
  const VectorField square = isotropicPlane(plane);
  const double width = (square.dims.x - 1) * square.geometry.spacing.x;
  const double height = (square.dims.y - 1) * square.geometry.spacing.y;
  EXPECT_NEAR(width, 20 * 0.05, 1e-9) << "the same extent";
  EXPECT_NEAR(height, 20 * 0.125, 1e-9);
  EXPECT_NEAR(square.geometry.spacing.x / square.geometry.spacing.y, 1.0, 1e-3);
  EXPECT_NEAR(static_cast<double>(square.dims.y - 1) / (square.dims.x - 1), height / width, 1e-3);
}

}  // namespace
}  // namespace lic3d
