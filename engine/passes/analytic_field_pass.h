// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An analytic field (lic/analytic_fields.h) made on the device in float, with its white noise,
// straight into the LIC pass' field texture (shaders/analytic_field.comp), with the statistics
// uploadLicInputs measures on the host (min and max |v|, max |u|, the histogram of |v|): nothing
// of the field passes through the host, which is what the front ends use for an analytic field
// with white noise (docs/BENCHMARKS.md, "End to end"). The CPU versions in double stay the oracle
// (tests/test_analytic_device.cpp).
#include <cstdint>

#include "core/error.h"
#include "core/volume.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "lic/analytic_fields.h"
#include "passes/volume_textures.h"

namespace lic3d {

// An analytic field at a time on a grid, and the seed of its white noise (lic/noise.h): what
// AnalyticFieldPass makes the LIC inputs from.
// With `brickDims` set, only the brick of the grid at `brickOffset` is made (bricked LIC,
// jobs/bricks.h): its texels are the whole grid's there, normalised by the whole grid's max |u|.
struct AnalyticInputs {
  AnalyticField field = AnalyticField::Tornado;
  Dims dims{0};
  double time = 0.0;
  std::uint64_t noiseSeed = 1;
  Dims brickOffset{0};
  Dims brickDims{0};  // 0: the whole grid
  bool operator==(const AnalyticInputs&) const = default;

  bool isBrick() const { return brickDims != Dims(0); }
  Dims texelDims() const { return isBrick() ? brickDims : dims; }
  // analyticGeometry of the grid, moved to the brick's first voxel.
  GridGeometry texelGeometry() const;
};

class AnalyticFieldPass {
 public:
  // `context` must outlive the pass.
  static Result<AnalyticFieldPass> create(const Context& context);

  // A texture write() can fill: the texels' grid and geometry (texelGeometry), `precision`
  // resolved as uploadLicInputs does. Checks the device's limits and memory first.
  Result<FieldTexture> createTarget(const AnalyticInputs& inputs, FieldPrecision precision) const;

  // Fills `target` (from createTarget, on the inputs' grid) with the inputs' texels and sets its
  // statistics. Blocking; the caller makes sure no work in flight reads the texture.
  Result<void> write(const AnalyticInputs& inputs, FieldTexture& target);

 private:
  struct Key {
    std::uint32_t field = 0;
    std::uint32_t phase = 0;
    int variant = 0;  // the texture format: RGBA32F, RGBA16F, RGBA8 SNORM
    bool operator==(const Key&) const = default;
  };
  Result<VkPipeline> pipeline(Key key);
  void recordClearStatistics(VkCommandBuffer cmd) const;
  void recordStatisticsReadback(VkCommandBuffer cmd) const;
  void readStatistics(const glm::dvec3& unit, FieldTexture& target) const;

  const Context* context_ = nullptr;
  PipelineLayout layout_;
  ShaderModule shaders_[3];
  PipelineCache<Key> pipelines_;
  Buffer statistics_;  // device-local: kAnalyticStatisticsWords uints
  Buffer readback_;    // its copy for the host
};

}  // namespace lic3d
