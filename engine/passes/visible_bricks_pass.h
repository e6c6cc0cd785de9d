// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The bricks of the LIC volume the slice pass can show (docs/VISIBLE_WORK.md): a classification
// on the GPU, conservative with respect to slice.frag's opacity, clip box, clip plane and region
// of interest, widened by the slice filter's footprint; and the list of the visible bricks not
// made yet, with one VkDispatchIndirectCommand per layer of bricks along z.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <glm/vec3.hpp>
#include <span>
#include <vector>

#include "core/error.h"
#include "core/volume.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "passes/slice_pass.h"
#include "passes/volume_textures.h"
#include "shared_layout.h"

namespace lic3d {

// Field i is specialization constant i of visible_bricks.comp.
struct VisibleBricksSpecialization {
  std::uint32_t opacityRule = gpu::kVisibleDefaultOpacityRule;
  std::uint32_t packing = gpu::kVisibleDefaultPacking;
  std::uint32_t clipPlane = gpu::kVisibleDefaultClipPlane;
  std::uint32_t roiShape = gpu::kVisibleDefaultRoiShape;
  std::uint32_t roiOutside = gpu::kVisibleDefaultRoiOutside;

  bool operator==(const VisibleBricksSpecialization&) const = default;
};
static_assert(offsetof(VisibleBricksSpecialization, opacityRule) ==
              4 * gpu::kVisibleConstOpacityRule);
static_assert(offsetof(VisibleBricksSpecialization, packing) == 4 * gpu::kVisibleConstPacking);
static_assert(offsetof(VisibleBricksSpecialization, clipPlane) == 4 * gpu::kVisibleConstClipPlane);
static_assert(offsetof(VisibleBricksSpecialization, roiShape) == 4 * gpu::kVisibleConstRoiShape);
static_assert(offsetof(VisibleBricksSpecialization, roiOutside) ==
              4 * gpu::kVisibleConstRoiOutside);

// What the classification tests: its variant and its numbers.
struct VisibleBricksSetup {
  VisibleBricksSpecialization specialization;
  gpu::VisibleBricksUniforms uniforms{};
};

// Whether two classifications list the same bricks (their variant and numbers are equal).
bool sameClassification(const VisibleBricksSetup& a, const VisibleBricksSetup& b);

// Bricks per axis of a grid.
glm::ivec3 brickCounts(Dims dims);

// The margin in o kept below an opacity threshold, so that the rounding of trilinear weights never
// hides a fragment.
inline constexpr float kOpacityThresholdMargin = 1e-5f;

// The classification of one slice draw: its uniforms and specialization as the slice pass made
// them. `tableOpaqueFrom`: with the opacity table, the lowest o whose table opacity may be
// non-zero ((i0 - 1) / 255, i0 the first entry with alpha > 0; see opaqueFromTable).
// `jitterMargin`: how far (world units) a sample may lie from its slice point along its ray.
VisibleBricksSetup visibleBricksSetup(const gpu::SliceUniforms& uniforms,
                                      const SliceSpecialization& slice, Dims dims,
                                      float tableOpaqueFrom, float jitterMargin);
// The classification of the slice draw `frame` (makeSliceFrame), `table` the colour table it
// samples (colormapTable): the jitter margin is sampleReach(frame), and with halos the region
// test is widened by the ring's radius.
VisibleBricksSetup visibleBricksSetup(const SliceFrame& frame, Dims dims,
                                      std::span<const std::uint8_t> table);
// How far (world units) a sample slice.frag shades, or reads for a halo, may lie from the slice
// point its clip plane tests: half the slice spacing along the ray (jitter), over the smallest
// cosine between the view's rays and the slice normal, plus the halo ring's radius.
float sampleReach(const SliceFrame& frame);
// The classification that lists the bricks either lists (stereo: both eyes). The eyes of one view
// differ at most in the margin, the jitter margin and the ring radius, of which the larger is kept.
VisibleBricksSetup unionOf(const VisibleBricksSetup& a, const VisibleBricksSetup& b);
// The lowest o in [0, 1] at which a table of `alphas` (entries at i / (n - 1), read with linear
// filtering) may be non-zero; 2 when it is zero everywhere.
float opaqueFromTable(std::span<const float> alphas);

// The same rule on the CPU: the visible flag of each brick (x fastest) from the voxels' physical
// speeds (NaN where the field has no value), x fastest.
std::vector<std::uint32_t> classifyBricksOnCpu(const VisibleBricksSetup& setup, Dims dims,
                                               std::span<const float> speeds);

class VisibleBricksPass {
 public:
  // `context` must outlive the pass.
  static Result<VisibleBricksPass> create(const Context& context);

  // The per-brick buffers for `dims` (made again only when the brick counts change; then no
  // brick is made). Call before record, outside a command buffer.
  Result<void> reserve(Dims dims);
  // Marks every brick not made (the LIC values changed).
  void recordForget(VkCommandBuffer cmd);
  // Marks every brick made (the full pass wrote the whole grid).
  void recordAllMade(VkCommandBuffer cmd);
  // Classifies the bricks of `field` (SHADER_READ_ONLY_OPTIMAL) and lists the visible bricks not
  // made: after it, dispatch() holds per brick layer {listed, kVisibleBrickSize, 1} and lists()
  // the listed bricks' indices, layer z from z * bricksX * bricksY on.
  Result<void> record(VkCommandBuffer cmd, const FieldTexture& field,
                      const VisibleBricksSetup& setup);
  // Copies the flags, the dispatch commands and the lists to host memory (tests, statistics).
  void recordReadback(VkCommandBuffer cmd);
  // After that command buffer completed.
  std::vector<std::uint32_t> visibleFlags() const;
  // Per brick layer, the listed bricks' indices (in list order).
  std::vector<std::vector<std::uint32_t>> listedBricks() const;

  const Buffer& visible() const { return visible_; }
  const Buffer& made() const { return made_; }
  const Buffer& lists() const { return lists_; }
  const Buffer& dispatch() const { return dispatch_; }
  glm::ivec3 bricks() const { return bricks_; }

 private:
  const Context* context_ = nullptr;
  PipelineLayout layout_;
  ShaderModule shader_;
  PipelineCache<VisibleBricksSpecialization> pipelines_;
  Sampler sampler_;
  glm::ivec3 bricks_{0};
  Buffer uniforms_;
  Buffer visible_;
  Buffer made_;
  Buffer lists_;
  Buffer dispatch_;
  Buffer readback_;  // the flags, the dispatch commands, the lists

  void recordFillMade(VkCommandBuffer cmd, std::uint32_t value);
};

}  // namespace lic3d
