// SPDX-License-Identifier: BSD-3-Clause
#include <gtest/gtest.h>

#include <cmath>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/slice_geometry.h"
#include "lic/legend.h"

namespace lic3d {
namespace {

TEST(SliceGeometry, BoxKeepsPhysicalProportions) {
  GridGeometry geometry;
  geometry.spacing = {0.05, 0.05, 0.125};
  const glm::vec3 half = boxHalfExtent({47, 47, 47}, geometry);
  EXPECT_FLOAT_EQ(half.z, 0.5f);
  EXPECT_NEAR(half.x, 0.5 * 0.05 / 0.125, 1e-6);
}

TEST(SliceGeometry, ViewAlignedSlicesCoverTheBoxBackToFront) {
  const glm::vec3 half{0.5f, 0.25f, 0.375f};
  const glm::vec3 toViewer = glm::normalize(glm::vec3(1.0f, 2.0f, -0.5f));
  const SlicePlan plan = planSlices(Slicing::ViewAligned, {64, 32, 48}, half, toViewer, 0);
  const float reach = glm::dot(glm::abs(toViewer), half);
  EXPECT_NEAR(glm::length(plan.normal - toViewer), 0.0f, 1e-6f);
  EXPECT_NEAR(plan.firstOffset, -reach + 0.5f * plan.spacing, 1e-6f);  // farthest first
  EXPECT_NEAR(plan.firstOffset + static_cast<float>(plan.count - 1) * plan.spacing,
              reach - 0.5f * plan.spacing, 1e-5f);
  EXPECT_LE(plan.spacing, plan.voxelSize * 1.0001f) << "at least one slice per voxel";
  EXPECT_FLOAT_EQ(plan.voxelSize, 1.0f / 64.0f);
}

TEST(SliceGeometry, AxisAlignedPicksTheAxisClosestToTheViewer) {
  const glm::vec3 half{0.5f, 0.5f, 0.5f};
  const SlicePlan fromMinusY = planSlices(Slicing::AxisAligned, {10, 20, 30}, half,
                                          glm::normalize(glm::vec3(0.3f, -0.9f, 0.2f)), 0);
  EXPECT_EQ(fromMinusY.axis, 1);
  EXPECT_EQ(fromMinusY.normal, glm::vec3(0.0f, -1.0f, 0.0f)) << "normal points to the viewer";
  EXPECT_EQ(fromMinusY.count, 20) << "one slice per voxel layer";
  EXPECT_NEAR(fromMinusY.firstOffset, -0.5f + 0.5f / 20.0f, 1e-6f);
  const SlicePlan fromAbove = planSlices(Slicing::AxisAligned, {10, 20, 30}, half,
                                         glm::normalize(glm::vec3(0.1f, 0.2f, 0.9f)), 7);
  EXPECT_EQ(fromAbove.axis, 2);
  EXPECT_EQ(fromAbove.count, 7);
}

TEST(Camera, DefaultViewFitsTheWholeBox) {
  const glm::vec3 half{0.5f, 0.3f, 0.4f};
  for (const float aspect : {0.5f, 1.0f, 2.0f}) {
    CameraParams params;
    const CameraMatrices m = computeCamera(params, half, aspect);
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 corner = half * glm::vec3(c & 1 ? 1 : -1, c & 2 ? 1 : -1, c & 4 ? 1 : -1);
      const glm::vec4 clip = m.viewProjection * glm::vec4(corner, 1.0f);
      const glm::vec3 ndc = glm::vec3(clip) / clip.w;
      EXPECT_LT(std::abs(ndc.x), 1.0f) << aspect;
      EXPECT_LT(std::abs(ndc.y), 1.0f) << aspect;
      EXPECT_GT(ndc.z, 0.0f);
      EXPECT_LT(ndc.z, 1.0f);
    }
  }
}

TEST(Camera, ZUpAndVulkanClipSpace) {
  CameraParams params;
  params.azimuth = 0.0f;
  params.elevation = 0.0f;
  const CameraMatrices m = computeCamera(params, glm::vec3(0.5f), 1.0f);
  EXPECT_NEAR(glm::length(m.toViewer - glm::vec3(1, 0, 0)), 0.0f, 1e-6f);
  // +z is up on screen, which in Vulkan's clip space is negative y.
  const glm::vec4 top = m.viewProjection * glm::vec4(0, 0, 0.4f, 1);
  EXPECT_LT(top.y / top.w, 0.0f);
  // Looking from +x with z up, +y is to the right.
  const glm::vec4 right = m.viewProjection * glm::vec4(0, 0.4f, 0, 1);
  EXPECT_GT(right.x / right.w, 0.0f);
}

// --axes: the box's edges on screen but those behind the volume, each axis with ticks at round
// values of its physical coordinate.
TEST(BoxAxes, FrontEdgesInsideTheFittedViewAndTicksInThePhysicalRanges) {
  const Dims dims{47, 47, 47};
  GridGeometry geometry;
  geometry.spacing = {0.05, 0.05, 0.125};
  geometry.origin = {-1.15, -1.15, -0.375};
  const glm::vec3 half = boxHalfExtent(dims, geometry);
  const CameraMatrices camera = computeCamera(CameraParams{}, half, 1.0f);
  const BoxAxes axes = projectBoxAxes(camera, false, half, dims, geometry, {0, 0, 400, 400});
  // Seen from above a corner, three faces face the camera: the three edges that meet at the far
  // corner lie behind the volume.
  ASSERT_EQ(axes.edges.size(), 9u);
  for (const auto& [a, b] : axes.edges)
    for (glm::vec2 p : {a, b}) {
      EXPECT_GE(p.x, 0.0f);
      EXPECT_LE(p.x, 400.0f);
      EXPECT_GE(p.y, 0.0f);
      EXPECT_LE(p.y, 400.0f);
    }
  ASSERT_EQ(axes.labels.size(), 3u);
  EXPECT_EQ(axes.labels[0].text, "x");
  EXPECT_EQ(axes.labels[2].text, "z");
  const double first[3] = {-1.15, -1.15, -0.375}, last[3] = {1.15, 1.15, 5.375};
  int perAxis[3] = {0, 0, 0};
  for (const AxisTick& tick : axes.ticks) {
    const double value = std::stod(tick.text);
    ++perAxis[tick.axis];
    EXPECT_GE(value, first[tick.axis] - 1e-9) << tick.text;
    EXPECT_LE(value, last[tick.axis] + 1e-9) << tick.text;
  }
  for (const int n : perAxis) EXPECT_GE(n, 2);
  EXPECT_GE(axes.ticks.size(), 6u);  // at least two per axis
}

TEST(BoxAxes, NiceTicksAreRoundValuesInTheRange) {
  EXPECT_EQ(niceTicks(0.0, 1.0, 6), (std::vector<double>{0.0, 0.2, 0.4, 0.6, 0.8, 1.0}));
  EXPECT_EQ(niceTicks(-1.15, 1.15, 5), (std::vector<double>{-1.0, -0.5, 0.0, 0.5, 1.0}));
  EXPECT_EQ(niceTicks(-1.15, 1.15, 2), (std::vector<double>{-1.0, 0.0, 1.0}));
  EXPECT_EQ(niceTicks(0.0092, 0.0092, 5), (std::vector<double>{0.0092}));
  for (const double v : niceTicks(3.7e-4, 9.1e-3, 6)) {
    EXPECT_GE(v, 3.7e-4);
    EXPECT_LE(v, 9.1e-3);
  }
}

}  // namespace
}  // namespace lic3d
