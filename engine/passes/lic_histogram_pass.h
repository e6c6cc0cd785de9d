// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A histogram of the drawn voxels of the LIC volume on the GPU. LIC values crowd around the
// noise mean (their spread shrinks like 1/sqrt(samples)), so the renderer stretches them to full
// grey (ViewParams::contrast); this pass supplies their mean and spread without reading the
// volume back.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/error.h"
#include "core/value_histogram.h"
#include "core/volume.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "passes/volume_textures.h"

namespace lic3d {

struct IntensityStatistics {
  float mean = 0.5f;
  float deviation = 0.0f;
  std::uint64_t voxels = 0;        // drawn voxels counted (outside empty space)
  std::uint64_t maskedVoxels = 0;  // voxels the sparsity mask hid
  // Their values over [0, 1] (the percentile window and the automatic alpha read it).
  std::shared_ptr<const ValueHistogram> histogram;
};

// Mean and standard deviation of a histogram over [0,1] (values at bin centres); `counts` is
// the pass' read-back: the bins, then the masked voxels.
IntensityStatistics intensityStatistics(const std::vector<std::uint32_t>& counts);

class LicHistogramPass {
 public:
  // Read-back slots: a histogram stays in its slot until the CPU has read it.
  static constexpr std::uint32_t kSlots = 4;

  // `context` must outlive the pass.
  static Result<LicHistogramPass> create(const Context& context);

  // Records the histogram of `volume` (SHADER_READ_ONLY_OPTIMAL, its writes already made
  // visible to compute shaders) on `field`'s grid, leaving out the voxels slower than
  // `emptySpeed` (physical |v|), and its copy to host-visible memory in `slot`. With
  // `visibleBricks` (VisibleBricksPass::visible(), written before and visible to compute
  // shaders), only the voxels of visible bricks count (docs/VISIBLE_WORK.md, "Statistics").
  // `stride` > 1: `volume` is a coarse LIC volume on coarseDims(field.dims, stride), voxel v of it
  // at field voxel v * stride; not with `visibleBricks`.
  void record(VkCommandBuffer cmd, const Image& volume, const FieldTexture& field,
              double emptySpeed, std::uint32_t slot, const Buffer* visibleBricks = nullptr,
              int stride = 1);
  // The counts recorded into `slot`, once that command buffer completed.
  // The bins, then the count of masked voxels.
  std::vector<std::uint32_t> counts(std::uint32_t slot) const;

 private:
  const Context* context_ = nullptr;
  PipelineLayout layout_;
  Pipeline pipeline_;
  Pipeline visiblePipeline_;  // the visible bricks' voxels only
  Sampler sampler_;
  Buffer noBricks_;  // bound to the bricks' binding of the whole-grid variant, which never reads it
  Buffer counts_;    // of the pass being recorded
  Buffer readback_;
};

}  // namespace lic3d
