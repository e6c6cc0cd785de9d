// SPDX-License-Identifier: BSD-3-Clause
// Visible work in the renderer (docs/VISIBLE_WORK.md): pictures made from the visible bricks alone
// equal the pictures of the full pass with the same (visible bricks') statistics, and a view
// change makes only the bricks that became visible.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

#include "core/look.h"
#include "core/session.h"
#include "gpu_test_support.h"
#include "lic/noise.h"
#include "passes/visible_bricks_pass.h"
#include "render/lic_renderer.h"

namespace lic3d {
namespace {

using test::GpuTest;
using test::speedsOf;

constexpr Dims kGrid{40, 36, 44};

// A carotid-like vessel: a fast tube (|v| = 1, bending in x as it rises along z) through still
// fluid (|v| = 0.01), so that under the default look most bricks are transparent.
VectorField vesselField() {
  VectorField field;
  field.dims = kGrid;
  field.vectors.resize(voxelCount(kGrid));
  for (int k = 0; k < kGrid.z; ++k)
    for (int j = 0; j < kGrid.y; ++j)
      for (int i = 0; i < kGrid.x; ++i) {
        const float z = static_cast<float>(k);
        const float cx = 14.0f + 8.0f * std::sin(z / 14.0f), cy = 17.0f;
        const float dx = static_cast<float>(i) - cx, dy = static_cast<float>(j) - cy;
        const bool vessel = dx * dx + dy * dy < 4.5f * 4.5f;
        const glm::vec3 along(0.57f * std::cos(z / 14.0f), 0.1f, 1.0f);
        field.vectors[voxelIndex(kGrid, i, j, k)] =
            vessel ? glm::normalize(along) : glm::vec3(0.01f, 0.0f, 0.0f);
      }
  return field;
}

Session defaultSession() {
  Session session;
  applyLook(kDefaultLook, session);
  session.view.width = 192;
  session.view.height = 160;
  return session;
}

// Visible work over the listed bricks (never the full pass), or the full pass with the visible
// bricks' statistics: the reference pictures.
Result<LicRenderer> makeRenderer(const Context& context, bool bricks) {
  RendererOptions options;
  options.visibleWork = true;
  options.visibleFullPassShare = bricks ? 2.0 : 0.0;
  LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, options));
  LIC3D_TRY(renderer.setInputs(vesselField(), makeWhiteNoise(kGrid, 11)));
  return renderer;
}

int largestDifference(const RgbaImage& a, const RgbaImage& b) {
  EXPECT_EQ(a.pixels.size(), b.pixels.size());
  int largest = 0;
  for (std::size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i)
    largest = std::max(largest, std::abs(int(a.pixels[i]) - int(b.pixels[i])));
  return largest;
}

// A picture that shows something: not one colour everywhere.
bool showsSomething(const RgbaImage& image) {
  return std::any_of(image.pixels.begin(), image.pixels.end(),
                     [&](std::uint8_t p) { return p != image.pixels.front(); });
}

struct ViewCase {
  const char* name;
  void (*change)(ViewParams&);
};

class VisibleWorkPictureTest : public GpuTest, public ::testing::WithParamInterface<ViewCase> {};

TEST_P(VisibleWorkPictureTest, EqualsTheFullPassWithinOneGreyLevel) {
  Session session = defaultSession();
  GetParam().change(session.view);
  Result<LicRenderer> bricks = makeRenderer(context(), true);
  Result<LicRenderer> full = makeRenderer(context(), false);
  ASSERT_TRUE(bricks.ok() && full.ok());
  const Result<RgbaImage> fromBricks = bricks->render(session.lic, session.view);
  ASSERT_TRUE(fromBricks.ok()) << fromBricks.error().message;
  const VisibleWorkCounts counts = bricks->visibleWorkCounts();
  const Result<RgbaImage> fromFull = full->render(session.lic, session.view);
  ASSERT_TRUE(fromFull.ok()) << fromFull.error().message;
  EXPECT_TRUE(full->visibleWorkCounts().fullPass);

  EXPECT_FALSE(counts.fullPass);
  EXPECT_EQ(counts.made, counts.visible);
  // Some bricks are really left out.
  EXPECT_GT(counts.bricks, counts.made);
  EXPECT_GT(counts.made, 0u);
  const double skipped =
      1.0 - static_cast<double>(counts.made) / static_cast<double>(counts.bricks);
  RecordProperty("skipped_brick_fraction", std::to_string(skipped));
  EXPECT_TRUE(showsSomething(*fromBricks));
  EXPECT_LE(largestDifference(*fromBricks, *fromFull), 1);
  // The statistics are the visible bricks' in both.
  EXPECT_EQ(bricks->intensityStatistics().voxels, full->intensityStatistics().voxels);
}

INSTANTIATE_TEST_SUITE_P(
    Views, VisibleWorkPictureTest,
    ::testing::Values(
        ViewCase{"DefaultLook", [](ViewParams&) {}},
        ViewCase{"ClipPlane",
                 [](ViewParams& v) {
                   v.clipPlane = true;
                   v.clipPlanePoint = glm::vec3(0.45f, 0.5f, 0.5f);
                   v.clipPlaneNormal = glm::vec3(1.0f, 0.2f, 0.0f);
                 }},
        ViewCase{"RoiSphere",
                 [](ViewParams& v) {
                   v.roi = RoiShape::Sphere;
                   v.roiCenter = glm::vec3(0.4f, 0.5f, 0.6f);
                   v.roiSize = 0.45f;
                 }},
        ViewCase{"RoiCubeOutside",
                 [](ViewParams& v) {
                   v.roi = RoiShape::Cube;
                   v.roiOutside = true;
                   v.roiCenter = glm::vec3(0.4f, 0.5f, 0.3f);
                   v.roiSize = 0.4f;
                 }},
        ViewCase{"CubicFilter", [](ViewParams& v) { v.filter = VolumeFilter::Cubic; }},
        ViewCase{"GradientLighting", [](ViewParams& v) { v.lighting = Lighting::Gradient; }},
        ViewCase{"LinesLighting", [](ViewParams& v) { v.lighting = Lighting::Lines; }},
        ViewCase{"StrongHalos",
                 [](ViewParams& v) {
                   v.halo = 1.0f;
                   v.haloRadius = 3.0f;
                   v.clipPlane = true;
                   v.clipPlanePoint = glm::vec3(0.5f);
                   v.clipPlaneNormal = glm::vec3(0.0f, 0.0f, 1.0f);
                 }},
        ViewCase{"Stereo", [](ViewParams& v) { v.stereo = StereoMode::SideBySide; }},
        ViewCase{"OcclusionWithClipPlane",
                 [](ViewParams& v) {
                   v.occlusion = 0.8f;
                   v.clipPlane = true;
                   v.clipPlanePoint = glm::vec3(0.5f, 0.55f, 0.5f);
                   v.clipPlaneNormal = glm::vec3(0.0f, 1.0f, 0.3f);
                 }}),
    [](const ::testing::TestParamInfo<ViewCase>& param) { return std::string(param.param.name); });

// The bricks a view lists, by the CPU rule, and how many of them are not in `before`.
std::vector<std::uint32_t> visibleBricks(const LicRenderer& renderer, const ViewParams& view) {
  const Result<std::optional<VisibleBricksSetup>> setup = renderer.visibleBricksFor(view);
  EXPECT_TRUE(setup.ok() && setup->has_value());
  if (!setup.ok() || !setup->has_value()) return {};
  return classifyBricksOnCpu(**setup, kGrid, speedsOf(vesselField()));
}

std::uint64_t newlyVisible(const std::vector<std::uint32_t>& before,
                           const std::vector<std::uint32_t>& after) {
  std::uint64_t count = 0;
  for (std::size_t i = 0; i < after.size(); ++i) count += after[i] == 1 && before[i] == 0;
  return count;
}

// Moving the clip plane makes the bricks that became visible and no others; the picture still
// equals the full pass'. Moving it back makes nothing; a change of the LIC makes every visible
// brick again.
TEST_F(GpuTest, MovingTheClipPlaneMakesOnlyTheNewlyVisibleBricks) {
  Session session = defaultSession();
  session.view.clipPlane = true;
  session.view.clipPlaneNormal = glm::vec3(0.0f, 0.0f, 1.0f);
  session.view.clipPlanePoint = glm::vec3(0.5f, 0.5f, 0.3f);
  Result<LicRenderer> bricks = makeRenderer(context(), true);
  Result<LicRenderer> full = makeRenderer(context(), false);
  ASSERT_TRUE(bricks.ok() && full.ok());
  ASSERT_TRUE(bricks->render(session.lic, session.view).ok());
  const std::vector<std::uint32_t> low = visibleBricks(*bricks, session.view);
  EXPECT_EQ(bricks->visibleWorkCounts().made,
            newlyVisible(std::vector<std::uint32_t>(low.size()), low));

  ViewParams moved = session.view;
  moved.clipPlanePoint = glm::vec3(0.5f, 0.5f, 0.75f);
  const Result<RgbaImage> fromBricks = bricks->render(session.lic, moved);
  ASSERT_TRUE(fromBricks.ok());
  const std::vector<std::uint32_t> high = visibleBricks(*bricks, moved);
  const VisibleWorkCounts counts = bricks->visibleWorkCounts();
  EXPECT_EQ(counts.made, newlyVisible(low, high));
  EXPECT_GT(counts.made, 0u);
  EXPECT_LT(counts.made, counts.visible);
  const Result<RgbaImage> fromFull = full->render(session.lic, moved);
  ASSERT_TRUE(fromFull.ok());
  EXPECT_LE(largestDifference(*fromBricks, *fromFull), 1);

  // Back: every brick it shows is made; only the statistics are taken again.
  const Result<RgbaImage> back = bricks->render(session.lic, session.view);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(bricks->visibleWorkCounts().made, 0u);
  const Result<RgbaImage> backFull = full->render(session.lic, session.view);
  ASSERT_TRUE(backFull.ok());
  EXPECT_LE(largestDifference(*back, *backFull), 1);

  // The same view again: nothing at all.
  const std::uint64_t dispatches = bricks->licDispatchCount();
  ASSERT_TRUE(bricks->render(session.lic, session.view).ok());
  EXPECT_EQ(bricks->licDispatchCount(), dispatches);

  // Another LIC: the made bricks are forgotten.
  LicParams longer = session.lic;
  longer.length += 4;
  const Result<RgbaImage> again = bricks->render(longer, session.view);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(bricks->visibleWorkCounts().made,
            newlyVisible(std::vector<std::uint32_t>(low.size()), low));
  const Result<RgbaImage> againFull = full->render(longer, session.view);
  ASSERT_TRUE(againFull.ok());
  EXPECT_LE(largestDifference(*again, *againFull), 1);
}

// Without visible work (or with it, when updated without a view: what `compute` and the exports
// do) every voxel is made and the statistics are the whole grid's.
TEST_F(GpuTest, WithoutAViewEveryVoxelIsMade) {
  const Session session = defaultSession();
  Result<LicRenderer> bricks = makeRenderer(context(), true);
  ASSERT_TRUE(bricks.ok());
  ASSERT_TRUE(bricks->updateLic(session.lic).ok());
  Result<LicRenderer> plain = LicRenderer::create(context(), {});
  ASSERT_TRUE(plain.ok());
  ASSERT_TRUE(plain->setInputs(vesselField(), makeWhiteNoise(kGrid, 11)).ok());
  ASSERT_TRUE(plain->updateLic(session.lic).ok());
  const Result<ScalarVolume> a = bricks->readLicVolume(), b = plain->readLicVolume();
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_EQ(a->values, b->values);
  EXPECT_EQ(bricks->intensityStatistics().voxels, plain->intensityStatistics().voxels);
  // A picture then costs no LIC: every brick is made.
  ASSERT_TRUE(bricks->render(session.lic, session.view).ok());
  EXPECT_EQ(bricks->visibleWorkCounts().made, 0u);
  EXPECT_LE(bricks->intensityStatistics().voxels, plain->intensityStatistics().voxels);
}

}  // namespace
}  // namespace lic3d
