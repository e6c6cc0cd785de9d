// SPDX-License-Identifier: BSD-3-Clause
// The classification of visible bricks (docs/VISIBLE_WORK.md) on the GPU against the same rule on
// the CPU, on small fields whose speeds and geometry lie far from every threshold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "core/slice_geometry.h"
#include "gpu/submit.h"
#include "gpu_test_support.h"
#include "lic/noise.h"
#include "passes/visible_bricks_pass.h"

namespace lic3d {
namespace {

using test::GpuTest;

// Not a multiple of the brick size on any axis: 3 x 3 x 4 bricks, the last of each cut short.
constexpr Dims kGrid{21, 18, 27};

// Still fluid (|v| = 0.02) with a fast tube (|v| = 1) along z through (6.3, 11.2), and NaN
// vectors (no value) in a block when `holes`.
VectorField tubeField(bool holes) {
  VectorField field;
  field.dims = kGrid;
  field.vectors.resize(voxelCount(kGrid));
  for (int k = 0; k < kGrid.z; ++k)
    for (int j = 0; j < kGrid.y; ++j)
      for (int i = 0; i < kGrid.x; ++i) {
        const float dx = static_cast<float>(i) - 6.3f, dy = static_cast<float>(j) - 11.2f;
        const bool tube = dx * dx + dy * dy < 2.5f * 2.5f && k > 4;
        glm::vec3 v(0.0f, 0.0f, tube ? 1.0f : 0.02f);
        if (holes && i >= 16 && j < 8 && k >= 8 && k < 16)
          v = glm::vec3(std::numeric_limits<float>::quiet_NaN());
        field.vectors[voxelIndex(kGrid, i, j, k)] = v;
      }
  return field;
}

std::vector<float> speedsOf(const VectorField& field) {
  std::vector<float> speeds(field.vectors.size());
  std::transform(field.vectors.begin(), field.vectors.end(), speeds.begin(),
                 [](glm::vec3 v) { return glm::length(v); });
  return speeds;
}

// Nothing removed: no clip, the whole box kept, opacity from the speed over [0, 1].
VisibleBricksSetup openSetup(const FieldTexture& texture) {
  VisibleBricksSetup setup;
  gpu::VisibleBricksUniforms& u = setup.uniforms;
  const glm::vec3 h = boxHalfExtent(kGrid, texture.geometry);
  u.roiFromTexture = glm::mat4(1.0f);
  u.dims = glm::ivec4(kGrid, 1);
  u.bricks = glm::ivec4(brickCounts(kGrid), 0);
  u.halfExtent = glm::vec4(h, 0.0f);
  u.clipMin = glm::vec4(-h, 0.0f);
  u.clipMax = glm::vec4(h, 0.0f);
  u.texelToPhysical = texelToPhysicalForShader(texture.texelToPhysical);
  u.opacity = glm::vec4(0.0f, 1.0f, 0.5f - kOpacityThresholdMargin, 0.0f);
  setup.specialization.packing = texture.precision == FieldPrecision::Byte ? 1u : 0u;
  return setup;
}

// A region of `size` (box fractions) centred at `centre`, turned by `angle` about `axis`, as the
// slice pass makes roiFromTexture.
glm::mat4 region(glm::vec3 h, glm::vec3 centre, float size, float angle, glm::vec3 axis) {
  const glm::mat4 toWorld =
      glm::scale(glm::mat4(1.0f), 2.0f * h) * glm::translate(glm::mat4(1.0f), -centre);
  return glm::scale(glm::mat4(1.0f), glm::vec3(1.0f / size)) *
         glm::transpose(glm::rotate(glm::mat4(1.0f), angle, axis)) * toWorld;
}

class VisibleBricksTest : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    field_ = tubeField(true);
    Result<FieldTexture> texture =
        uploadLicInputs(context(), field_, makeWhiteNoise(kGrid, 3), FieldPrecision::Float);
    ASSERT_TRUE(texture.ok()) << texture.error().message;
    texture_ = std::move(*texture);
    Result<VisibleBricksPass> pass = VisibleBricksPass::create(context());
    ASSERT_TRUE(pass.ok()) << pass.error().message;
    pass_.emplace(std::move(*pass));
    ASSERT_TRUE(pass_->reserve(kGrid).ok());
  }
  void TearDown() override {
    pass_.reset();
    texture_ = FieldTexture();
    GpuTest::TearDown();
  }

  // Classifies on both sides; the flags must agree, and every visible brick must be listed once,
  // in its layer (none is made).
  std::vector<std::uint32_t> expectSameBricks(const VisibleBricksSetup& setup) {
    const Result<void> ran = submitAndWait(
        context(),
        [&](VkCommandBuffer cmd) {
          EXPECT_TRUE(pass_->record(cmd, texture_, setup).ok());
          pass_->recordReadback(cmd);
        },
        "visible bricks test");
    EXPECT_TRUE(ran.ok()) << ran.error().message;
    const std::vector<std::uint32_t> gpu = pass_->visibleFlags();
    const std::vector<std::uint32_t> cpu = classifyBricksOnCpu(setup, kGrid, speedsOf(field_));
    EXPECT_EQ(gpu, cpu);
    const glm::ivec3 bricks = brickCounts(kGrid);
    const std::vector<std::vector<std::uint32_t>> lists = pass_->listedBricks();
    for (int layer = 0; layer < bricks.z; ++layer) {
      std::vector<std::uint32_t> expected;
      for (int n = 0; n < bricks.x * bricks.y; ++n) {
        const std::uint32_t index = static_cast<std::uint32_t>(layer * bricks.x * bricks.y + n);
        if (cpu[index] != 0) expected.push_back(index);
      }
      std::vector<std::uint32_t> listed = lists[layer];
      std::sort(listed.begin(), listed.end());
      EXPECT_EQ(listed, expected) << "layer " << layer;
    }
    return gpu;
  }

  static std::size_t countVisible(const std::vector<std::uint32_t>& flags) {
    return static_cast<std::size_t>(std::count(flags.begin(), flags.end(), 1u));
  }

  VectorField field_;
  FieldTexture texture_;
  std::optional<VisibleBricksPass> pass_;
};

TEST_F(VisibleBricksTest, EveryBrickWithoutOpacityRuleOrGeometry) {
  const std::vector<std::uint32_t> flags = expectSameBricks(openSetup(texture_));
  EXPECT_EQ(countVisible(flags), flags.size());
}

TEST_F(VisibleBricksTest, SpeedThresholdKeepsTheTubeWidenedByTheMargin) {
  VisibleBricksSetup setup = openSetup(texture_);
  setup.specialization.opacityRule = 2;
  std::size_t last = 0;
  for (int margin = 1; margin <= 3; ++margin) {
    setup.uniforms.dims.w = margin;
    const std::size_t shown = countVisible(expectSameBricks(setup));
    EXPECT_GT(shown, 0u);
    EXPECT_LT(shown, brickCounts(kGrid).x * brickCounts(kGrid).y * brickCounts(kGrid).z);
    EXPECT_GE(shown, last) << "a wider margin keeps at least as many bricks";
    last = shown;
  }
  // Above every speed: nothing.
  setup.uniforms.opacity.z = 1.5f;
  EXPECT_EQ(countVisible(expectSameBricks(setup)), 0u);
}

TEST_F(VisibleBricksTest, NanVoxelsAreEmptyWhereSpeedShades) {
  VisibleBricksSetup setup = openSetup(texture_);
  setup.specialization.opacityRule = 1;
  setup.uniforms.dims.w = 0;  // the NaN block is brick (2, 0, 1): empty without a margin
  const std::vector<std::uint32_t> flags = expectSameBricks(setup);
  EXPECT_EQ(countVisible(flags), flags.size() - 1);
}

TEST_F(VisibleBricksTest, ClipBoxAndClipPlane) {
  VisibleBricksSetup setup = openSetup(texture_);
  const glm::vec3 h(setup.uniforms.halfExtent);
  setup.uniforms.clipMin = glm::vec4(-0.37f * h.x, -h.y, -0.81f * h.z, 0.0f);
  setup.uniforms.clipMax = glm::vec4(h.x, 0.13f * h.y, h.z, 0.0f);
  const std::size_t boxed = countVisible(expectSameBricks(setup));
  EXPECT_GT(boxed, 0u);
  setup.specialization.clipPlane = 1;
  const glm::vec3 normal = glm::normalize(glm::vec3(0.31f, -0.52f, 0.79f));
  setup.uniforms.clipPlane = glm::vec4(normal, 0.071f);
  const std::size_t planed = countVisible(expectSameBricks(setup));
  EXPECT_LT(planed, boxed);
  // The jitter margin keeps more.
  setup.uniforms.halfExtent.w = 2.3f;
  EXPECT_GE(countVisible(expectSameBricks(setup)), planed);
}

TEST_F(VisibleBricksTest, RegionsOfInterestInsideAndOutside) {
  VisibleBricksSetup setup = openSetup(texture_);
  const glm::vec3 h(setup.uniforms.halfExtent);
  setup.uniforms.roiFromTexture =
      region(h, glm::vec3(0.43f, 0.57f, 0.38f), 0.47f, 0.61f, glm::vec3(0.2f, 0.9f, 0.4f));
  const std::size_t all = countVisible(expectSameBricks(setup));
  for (std::uint32_t shape = 1; shape <= 3; ++shape) {
    setup.specialization.roiShape = shape;
    setup.specialization.roiOutside = 0;
    const std::size_t inside = countVisible(expectSameBricks(setup));
    EXPECT_GT(inside, 0u) << "shape " << shape;
    EXPECT_LT(inside, all) << "shape " << shape;
    setup.specialization.roiOutside = 1;
    const std::size_t outside = countVisible(expectSameBricks(setup));
    EXPECT_GT(outside, 0u) << "shape " << shape;
  }
  // A region with the speed threshold: both tests at once.
  setup.specialization.roiShape = 1;
  setup.specialization.roiOutside = 0;
  setup.specialization.opacityRule = 2;
  expectSameBricks(setup);
}

TEST_F(VisibleBricksTest, SetupFollowsTheSliceShader) {
  gpu::SliceUniforms u{};
  u.magnitudeOpacity = glm::vec4(2.0f, 0.25f, 0.1f, 4.0f);
  SliceSpecialization slice;
  slice.filter = 2;
  slice.lighting = 3;
  slice.magnitudeOpacity = 1;
  VisibleBricksSetup setup = visibleBricksSetup(u, slice, kGrid, 0.0f, 0.5f);
  EXPECT_EQ(setup.specialization.opacityRule, 2u);
  EXPECT_EQ(setup.uniforms.dims.w, 3);  // cubic 2, tube lighting 1
  EXPECT_FLOAT_EQ(setup.uniforms.opacity.z, 0.25f - kOpacityThresholdMargin);
  EXPECT_FLOAT_EQ(setup.uniforms.halfExtent.w, 0.5f);
  // Opacity by another scalar: the speed only colours, NaN still empties.
  slice.opacitySource = 1;
  slice.colorMode = 1;
  EXPECT_EQ(visibleBricksSetup(u, slice, kGrid, 0.0f, 0.0f).specialization.opacityRule, 1u);
  slice.colorSource = 1;
  EXPECT_EQ(visibleBricksSetup(u, slice, kGrid, 0.0f, 0.0f).specialization.opacityRule, 0u);
  // The table: linear filtering reaches one entry before the first opaque one.
  const std::vector<float> table = {0.0f, 0.0f, 0.0f, 0.4f, 1.0f};
  EXPECT_FLOAT_EQ(opaqueFromTable(table), 0.5f);
  EXPECT_FLOAT_EQ(opaqueFromTable(std::vector<float>{0.3f, 0.0f}), 0.0f);
  EXPECT_GT(opaqueFromTable(std::vector<float>{0.0f, 0.0f}), 1.0f);
}

}  // namespace
}  // namespace lic3d
