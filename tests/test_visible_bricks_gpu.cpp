// SPDX-License-Identifier: BSD-3-Clause
// The classification of visible bricks (docs/VISIBLE_WORK.md) on the GPU against the same rule on
// the CPU, on small fields whose speeds and geometry lie far from every threshold.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>

#include "core/look.h"
#include "core/session.h"
#include "core/slice_geometry.h"
#include "gpu/submit.h"
#include "gpu_test_support.h"
#include "io/field_io.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "loading/session_inputs.h"
#include "passes/lic_histogram_pass.h"
#include "passes/lic_pass.h"
#include "passes/visible_bricks_pass.h"
#include "render/lic_renderer.h"
#include "test_support.h"

namespace lic3d {
namespace {

using test::GpuTest;
using test::speedsOf;

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

// Nothing removed: no clip, the whole box kept, opacity from the speed over [0, 1].
VisibleBricksSetup openSetup(const FieldTexture& texture, Dims dims = kGrid) {
  VisibleBricksSetup setup;
  gpu::VisibleBricksUniforms& u = setup.uniforms;
  const glm::vec3 h = boxHalfExtent(dims, texture.geometry);
  u.roiFromTexture = glm::mat4(1.0f);
  u.dims = glm::ivec4(dims, 1);
  u.bricks = glm::ivec4(brickCounts(dims), 0);
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

// The histogram of the visible bricks' voxels only: on a LIC volume of zeros every voxel is masked
// (counted apart), so the masked count is the number of voxels counted.
TEST_F(VisibleBricksTest, HistogramCountsTheVisibleBricksVoxelsOnly) {
  VisibleBricksSetup setup = openSetup(texture_);
  setup.specialization.opacityRule = 2;
  const std::vector<std::uint32_t> flags = expectSameBricks(setup);
  const glm::ivec3 counts = brickCounts(kGrid);
  std::uint32_t visibleVoxels = 0;
  for (int k = 0; k < kGrid.z; ++k)
    for (int j = 0; j < kGrid.y; ++j)
      for (int i = 0; i < kGrid.x; ++i)
        visibleVoxels += flags[i / 8 + counts.x * (j / 8 + counts.y * (k / 8))];
  ASSERT_GT(visibleVoxels, 0u);
  ASSERT_LT(visibleVoxels, voxelCount(kGrid));

  Result<LicHistogramPass> histogram = LicHistogramPass::create(context());
  ASSERT_TRUE(histogram.ok()) << histogram.error().message;
  ImageDesc desc;
  desc.format = kLicVolumeFormat;
  desc.extent = {static_cast<std::uint32_t>(kGrid.x), static_cast<std::uint32_t>(kGrid.y),
                 static_cast<std::uint32_t>(kGrid.z)};
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "zero lic volume";
  Result<Image> volume = Image::create(context(), desc);
  ASSERT_TRUE(volume.ok());
  const std::vector<std::uint32_t> zeros(voxelCount(kGrid), 0u);
  ASSERT_TRUE(uploadImage(context(), *volume, zeros.data(), zeros.size() * 4).ok());
  ASSERT_TRUE(submitAndWait(
                  context(),
                  [&](VkCommandBuffer cmd) {
                    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                  VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
                    histogram->record(cmd, *volume, texture_, 0.1, 0, &pass_->visible());
                    histogram->record(cmd, *volume, texture_, 0.1, 1);
                  },
                  "histogram of visible bricks")
                  .ok());
  const std::vector<std::uint32_t> visible = histogram->counts(0), whole = histogram->counts(1);
  EXPECT_EQ(visible.back(), visibleVoxels);
  EXPECT_EQ(whole.back(), voxelCount(kGrid));
  EXPECT_EQ(std::count(visible.begin(), visible.end() - 1, 0u), gpu::kHistogramBins);
}

// Grids smaller than a brick, one brick exactly, and thin ones: margins reach past the grid.
TEST_F(GpuTest, SmallGridsClassifyAsOnTheCpu) {
  Result<VisibleBricksPass> pass = VisibleBricksPass::create(context());
  ASSERT_TRUE(pass.ok());
  for (const Dims dims : {Dims{1, 1, 1}, Dims{9, 2, 17}, Dims{8, 8, 8}}) {
    VectorField field;
    field.dims = dims;
    field.vectors.resize(voxelCount(dims));
    for (int k = 0; k < dims.z; ++k)
      for (int j = 0; j < dims.y; ++j)
        for (int i = 0; i < dims.x; ++i)
          field.vectors[voxelIndex(dims, i, j, k)] =
              glm::vec3(0.0f, 0.0f, (i + 2 * j + 3 * k) % 11 == 0 ? 1.0f : 0.02f);
    Result<FieldTexture> texture =
        uploadLicInputs(context(), field, makeWhiteNoise(dims, 3), FieldPrecision::Float);
    ASSERT_TRUE(texture.ok()) << texture.error().message;
    ASSERT_TRUE(pass->reserve(dims).ok());
    VisibleBricksSetup threshold = openSetup(*texture, dims);
    threshold.specialization.opacityRule = 2;
    VisibleBricksSetup plane = openSetup(*texture, dims);
    plane.specialization.clipPlane = 1;
    plane.uniforms.clipPlane = glm::vec4(glm::normalize(glm::vec3(0.2f, 0.3f, -0.9f)), 0.37f);
    // Kept where x >= 1.3 half extents: only what a margin carries past the grid's last voxel.
    VisibleBricksSetup beyond = openSetup(*texture, dims);
    beyond.specialization.clipPlane = 1;
    beyond.uniforms.clipPlane = glm::vec4(-1.0f, 0.0f, 0.0f, -1.3f * beyond.uniforms.halfExtent.x);
    for (const VisibleBricksSetup& setup : {threshold, plane, beyond}) {
      ASSERT_TRUE(submitAndWait(
                      context(),
                      [&](VkCommandBuffer cmd) {
                        EXPECT_TRUE(pass->record(cmd, *texture, setup).ok());
                        pass->recordReadback(cmd);
                      },
                      "small grid")
                      .ok());
      EXPECT_EQ(pass->visibleFlags(), classifyBricksOnCpu(setup, dims, speedsOf(field)))
          << gridText(dims);
    }
  }
}

// The LIC pass over the listed bricks against the full pass: the listed bricks' voxels equal, bit
// for bit; the others untouched. Then the invalidation: bricks made are not listed again, and a
// looser rule lists only the bricks that became visible.
class BrickLicTest : public VisibleBricksTest {
 protected:
  void SetUp() override {
    VisibleBricksTest::SetUp();
    if (HasFatalFailure()) return;
    Result<LicPass> lic = LicPass::create(context());
    ASSERT_TRUE(lic.ok()) << lic.error().message;
    lic_.emplace(std::move(*lic));
    for (Image* image : {&full_, &bricks_}) {
      ImageDesc desc;
      desc.format = kLicVolumeFormat;
      desc.extent = {static_cast<std::uint32_t>(kGrid.x), static_cast<std::uint32_t>(kGrid.y),
                     static_cast<std::uint32_t>(kGrid.z)};
      desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
                   VK_IMAGE_USAGE_TRANSFER_DST_BIT;
      desc.name = "test lic volume";
      Result<Image> made = Image::create(context(), desc);
      ASSERT_TRUE(made.ok());
      *image = std::move(*made);
    }
    // Both cleared to 0 in GENERAL; the full one made whole.
    const Result<void> ran = submitAndWait(
        context(),
        [&](VkCommandBuffer cmd) {
          const VkClearColorValue zero{};
          const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
          for (const Image* image : {&full_, &bricks_}) {
            imageBarrier(cmd, image->handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                         VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                         VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
            vkCmdClearColorImage(cmd, image->handle(), VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
          }
          memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                        VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
          EXPECT_TRUE(lic_->record(cmd, texture_, nullptr, {}, full_, params_, 0, kGrid.z).ok());
        },
        "brick lic test setup");
    ASSERT_TRUE(ran.ok()) << ran.error().message;
  }
  void TearDown() override {
    lic_.reset();
    full_ = Image();
    bricks_ = Image();
    VisibleBricksTest::TearDown();
  }

  // Classifies, makes the listed bricks, reads the lists back: the bricks listed.
  std::vector<std::uint32_t> classifyAndMake(const VisibleBricksSetup& setup) {
    const Result<void> ran = submitAndWait(
        context(),
        [&](VkCommandBuffer cmd) {
          EXPECT_TRUE(pass_->record(cmd, texture_, setup).ok());
          pass_->recordReadback(cmd);
          EXPECT_TRUE(lic_->recordBricks(cmd, texture_, nullptr, {}, bricks_, params_, *pass_, 0,
                                         brickCounts(kGrid).z)
                          .ok());
        },
        "brick lic test");
    EXPECT_TRUE(ran.ok()) << ran.error().message;
    std::vector<std::uint32_t> listed;
    for (const std::vector<std::uint32_t>& layer : pass_->listedBricks())
      listed.insert(listed.end(), layer.begin(), layer.end());
    std::sort(listed.begin(), listed.end());
    return listed;
  }

  std::vector<std::uint32_t> texels(const Image& image) {
    Result<std::vector<std::byte>> bytes = readImage(context(), image, VK_IMAGE_LAYOUT_GENERAL, 4);
    EXPECT_TRUE(bytes.ok());
    std::vector<std::uint32_t> out(voxelCount(kGrid));
    if (bytes.ok()) std::memcpy(out.data(), bytes->data(), out.size() * 4);
    return out;
  }

  // Each voxel of a made brick equals the full pass'; every other voxel is 0.
  void expectMadeBricksEqual(const std::vector<std::uint32_t>& made) {
    const std::vector<std::uint32_t> full = texels(full_), bricks = texels(bricks_);
    const glm::ivec3 counts = brickCounts(kGrid);
    std::size_t equal = 0, differing = 0, untouched = 0;
    for (int k = 0; k < kGrid.z; ++k)
      for (int j = 0; j < kGrid.y; ++j)
        for (int i = 0; i < kGrid.x; ++i) {
          const std::size_t v = voxelIndex(kGrid, i, j, k);
          const std::uint32_t brick =
              static_cast<std::uint32_t>(i / 8 + counts.x * (j / 8 + counts.y * (k / 8)));
          const bool isMade = std::binary_search(made.begin(), made.end(), brick);
          if (isMade) {
            (bricks[v] == full[v] ? equal : differing) += 1;
          } else {
            EXPECT_EQ(bricks[v], 0u) << "voxel " << i << " " << j << " " << k;
            ++untouched;
          }
        }
    EXPECT_EQ(differing, 0u);
    EXPECT_GT(equal, 0u);
    RecordProperty("untouched", static_cast<int>(untouched));
  }

  std::optional<LicPass> lic_;
  LicParams params_;
  Image full_;
  Image bricks_;
};

TEST_F(BrickLicTest, ListedBricksEqualTheFullPassAndAreMadeOnce) {
  VisibleBricksSetup tube = openSetup(texture_);
  tube.specialization.opacityRule = 2;
  const std::vector<std::uint32_t> first = classifyAndMake(tube);
  const std::size_t all =
      static_cast<std::size_t>(brickCounts(kGrid).x) * brickCounts(kGrid).y * brickCounts(kGrid).z;
  ASSERT_GT(first.size(), 0u);
  ASSERT_LT(first.size(), all);
  expectMadeBricksEqual(first);

  // Made: the same view lists nothing.
  EXPECT_TRUE(classifyAndMake(tube).empty());

  // Every brick visible: only those not made before are listed, and then all equal.
  const std::vector<std::uint32_t> second = classifyAndMake(openSetup(texture_));
  EXPECT_EQ(first.size() + second.size(), all);
  for (std::uint32_t brick : second)
    EXPECT_FALSE(std::binary_search(first.begin(), first.end(), brick)) << brick;
  std::vector<std::uint32_t> every(all);
  for (std::size_t n = 0; n < all; ++n) every[n] = static_cast<std::uint32_t>(n);
  expectMadeBricksEqual(every);

  // Forgotten (new LIC values): every visible brick is listed again.
  ASSERT_TRUE(submitAndWait(
                  context(), [&](VkCommandBuffer cmd) { pass_->recordForget(cmd); }, "forget")
                  .ok());
  EXPECT_EQ(classifyAndMake(tube), first);
}

// The default look's visible bricks of `field` (the session's LIC parameters and view): the
// fraction of the grid's voxels they hold. (Their GPU time against the full pass is measured by
// `lic3d bench --visible`, not by tests.)
struct VisibleWork {
  double fraction = 0.0;  // of the grid's voxels, in visible bricks
};

void measureVisibleWork(const Context& context, const VectorField& field, const Session& session,
                        VisibleWork& work) {
  const Dims dims = field.dims;
  Result<LicRenderer> renderer = LicRenderer::create(context, {});
  ASSERT_TRUE(renderer.ok()) << renderer.error().message;
  ASSERT_TRUE(renderer->setInputs(field, makeWhiteNoise(dims, 7)).ok());
  ASSERT_TRUE(renderer->updateLic(session.lic).ok());
  const SliceFrame frame =
      makeSliceFrame(session.view, renderer->volumeFacts(), Eye::Mono, {1024, 1024});
  // A jitter margin of a whole slice spacing: more than half a spacing over the cosine of any
  // ray's angle in this view.
  const VisibleBricksSetup setup = visibleBricksSetup(frame.uniforms, frame.specialization, dims,
                                                      0.0f, frame.uniforms.eyePosition.w);
  const FieldTexture& texture = renderer->fieldTextures().field();

  Result<VisibleBricksPass> bricks = VisibleBricksPass::create(context);
  ASSERT_TRUE(bricks.ok());
  ASSERT_TRUE(bricks->reserve(dims).ok());
  const Result<void> ran = submitAndWait(
      context,
      [&](VkCommandBuffer cmd) {
        ASSERT_TRUE(bricks->record(cmd, texture, setup).ok());
        bricks->recordReadback(cmd);
      },
      "visible bricks");
  ASSERT_TRUE(ran.ok()) << ran.error().message;

  const std::vector<std::uint32_t> flags = bricks->visibleFlags();
  const glm::ivec3 counts = bricks->bricks();
  std::size_t visibleVoxels = 0;
  for (int bz = 0; bz < counts.z; ++bz)
    for (int by = 0; by < counts.y; ++by)
      for (int bx = 0; bx < counts.x; ++bx) {
        if (flags[(static_cast<std::size_t>(bz) * counts.y + by) * counts.x + bx] == 0) continue;
        const glm::ivec3 first = glm::ivec3(bx, by, bz) * 8;
        const glm::ivec3 size = glm::min(first + 8, glm::ivec3(dims)) - first;
        visibleVoxels += static_cast<std::size_t>(size.x) * size.y * size.z;
      }
  work.fraction = static_cast<double>(visibleVoxels) / static_cast<double>(voxelCount(dims));
  ::testing::Test::RecordProperty("grid", gridText(dims));
  ::testing::Test::RecordProperty("visible_voxel_fraction", std::to_string(work.fraction));
}

// The carotid at twice its resolution under the default look is mostly empty space: its visible
// bricks hold a small part of the grid.
TEST_F(GpuTest, CarotidAtTwiceItsResolutionMakesAFewOfItsBricks) {
  Result<VectorField> file = readVectorField(test::dataFolder() / "carotid.vtk");
  ASSERT_TRUE(file.ok()) << file.error().message;
  Session session;
  applyLook(kDefaultLook, session);
  session.field.resolution = "2x";
  Result<VectorField> field = atResolution(std::move(*file), session.field);
  ASSERT_TRUE(field.ok()) << field.error().message;
  VisibleWork work;
  measureVisibleWork(context(), *field, session, work);
  EXPECT_GT(work.fraction, 0.0);
  EXPECT_LT(work.fraction, 0.5);
}

// The tornado fills its box: every brick is visible, and the brick pass makes the whole grid.
TEST_F(GpuTest, TornadoMakesEveryBrick) {
  Session session;
  applyLook(kDefaultLook, session);
  const VectorField field = makeAnalyticField(AnalyticField::Tornado, Dims{110});
  VisibleWork work;
  measureVisibleWork(context(), field, session, work);
  EXPECT_EQ(work.fraction, 1.0);
}
}  // namespace
}  // namespace lic3d
