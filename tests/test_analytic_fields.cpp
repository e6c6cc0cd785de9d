// SPDX-License-Identifier: BSD-3-Clause
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <numbers>

#include "lic/analytic_fields.h"

namespace lic3d {
namespace {

TEST(AnalyticFields, NamesRoundTrip) {
  for (const auto& [value, name] : enumNames<AnalyticField>()) {
    const auto field = parseEnum<AnalyticField>(name);
    ASSERT_TRUE(field.has_value()) << name;
    EXPECT_EQ(enumName(*field), name);
  }
  EXPECT_FALSE(parseEnum<AnalyticField>("Tornado").has_value());
  EXPECT_FALSE(parseEnum<AnalyticField>("").has_value());
}

TEST(AnalyticFields, CubicGridSpansTheDomain) {
  const VectorField v = makeAnalyticField(AnalyticField::Vortex, {5, 5, 5});
  EXPECT_DOUBLE_EQ(v.geometry.spacing.x, 0.5);
  EXPECT_DOUBLE_EQ(v.geometry.origin.x, -1.0);
  // Vortex (-y, x, 0.2) at the corner voxel (-1,-1,-1).
  EXPECT_FLOAT_EQ(v.at(0, 0, 0).x, 1.0f);
  EXPECT_FLOAT_EQ(v.at(0, 0, 0).y, -1.0f);
  EXPECT_FLOAT_EQ(v.at(0, 0, 0).z, 0.2f);
}

TEST(AnalyticFields, NonCubicGridsKeepCubicVoxels) {
  const VectorField v = makeAnalyticField(AnalyticField::Solenoidal, {24, 32, 40});
  EXPECT_EQ(v.geometry.spacing.x, v.geometry.spacing.y);
  EXPECT_EQ(v.geometry.spacing.y, v.geometry.spacing.z);
  EXPECT_NEAR(v.geometry.origin.z, -1.0, 1e-12);
  EXPECT_NEAR(v.geometry.origin.z + 39 * v.geometry.spacing.z, 1.0, 1e-12);
  EXPECT_NEAR(v.geometry.origin.x + 23 * v.geometry.spacing.x, -v.geometry.origin.x, 1e-12)
      << "shorter axes are centred in the domain";
  // Axis order: value at voxel (i,j,k) uses x from i, y from j, z from k.
  const glm::dvec3 p = v.geometry.origin + glm::dvec3(3, 5, 7) * v.geometry.spacing;
  const glm::vec3 at = v.at(3, 5, 7);
  EXPECT_NEAR(at.x, p.y * p.z * (p.y * p.y + p.z * p.z), 1e-6);
  EXPECT_NEAR(at.y, p.x * p.z * (p.x * p.x + p.z * p.z), 1e-6);
  EXPECT_NEAR(at.z, p.x * p.y * (p.x * p.x + p.y * p.y), 1e-6);
}

TEST(AnalyticFields, SolenoidalAndAbcAreDivergenceFree) {
  for (const AnalyticField kind : {AnalyticField::Solenoidal, AnalyticField::Abc}) {
    const VectorField f = makeAnalyticField(kind, {33, 33, 33});
    const double h = f.geometry.spacing.x;
    double worst = 0.0, scale = 0.0;
    for (int k = 1; k < 32; ++k)
      for (int j = 1; j < 32; ++j)
        for (int i = 1; i < 32; ++i) {
          const double div = (f.at(i + 1, j, k).x - f.at(i - 1, j, k).x + f.at(i, j + 1, k).y -
                              f.at(i, j - 1, k).y + f.at(i, j, k + 1).z - f.at(i, j, k - 1).z) /
                             (2 * h);
          worst = std::max(worst, std::abs(div));
          scale = std::max(scale, static_cast<double>(glm::length(f.at(i, j, k))) / h);
        }
    EXPECT_LT(worst, 1e-4 * scale) << enumName(kind);
  }
}

TEST(AnalyticFields, AbcAndCornerMatchTheirFormulas) {
  const VectorField abc = makeAnalyticField(AnalyticField::Abc, {5, 5, 5});
  // Voxel (1,2,3) of a 5^3 grid on [0,2pi]^3 sits at (pi/2, pi, 3pi/2).
  const double x = std::numbers::pi / 2, y = std::numbers::pi, z = 1.5 * std::numbers::pi;
  EXPECT_NEAR(abc.at(1, 2, 3).x, std::sqrt(3.0) * std::sin(z) + std::cos(y), 1e-6);
  EXPECT_NEAR(abc.at(1, 2, 3).y, std::sqrt(2.0) * std::sin(x) + std::sqrt(3.0) * std::cos(z), 1e-6);
  EXPECT_NEAR(abc.at(1, 2, 3).z, std::sin(y) + std::sqrt(2.0) * std::cos(x), 1e-6);

  const VectorField corner = makeAnalyticField(AnalyticField::Corner, {3, 3, 3});
  // Voxel (2,1,0) sits at (1, 0.5, 0) on [0,1]^3 (thesis 4.5).
  EXPECT_NEAR(corner.at(2, 1, 0).x, -3 + 6 - 4 * 1.5, 1e-6);
  EXPECT_NEAR(corner.at(2, 1, 0).y, 12 - 4, 1e-6);
  EXPECT_NEAR(corner.at(2, 1, 0).z, 3 + 4 - 4 * 1.5, 1e-6);
}

TEST(AnalyticFields, TornadoSwirlsAroundAVerticalFunnel) {
  const VectorField t = makeAnalyticField(AnalyticField::Tornado, {64, 64, 64});
  // Crawfis: magnitudes from 0 to about 0.4 near the funnel, rotation about z (clockwise seen
  // from +z: v ~ scale * (y - yc, -(x - xc))), with an upward component inside the funnel.
  double largest = 0.0;
  for (const glm::vec3& v : t.vectors)
    largest = std::max(largest, static_cast<double>(glm::length(v)));
  EXPECT_GT(largest, 0.2);
  EXPECT_LT(largest, 2.0);
  // At the bottom slice, the centre is (0.5, 0.6): a point at +x of it moves towards -y.
  const glm::vec3 east = t.at(45, 38, 0);
  EXPECT_LT(east.y, 0.0f);
  EXPECT_GE(t.at(32, 38, 0).z, 0.0f);
}

}  // namespace
}  // namespace lic3d
