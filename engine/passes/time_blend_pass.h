// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Unsteady fields (docs/TIME.md): the field at a time between two time steps of a series, made on
// the GPU. Two steps are resident as textures; a compute pass (shaders/time_blend.comp) blends
// them per voxel and writes the LIC pass' field texture, with that texture's packing (xyz = u /
// max|u|, w = noise; volume_textures.h), so the LIC pass reads it like any field. Only the two
// steps in use are on the device: a series longer than device memory streams through it.

#include <cstdint>
#include <memory>

#include "core/error.h"
#include "core/value_histogram.h"
#include "core/volume.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/timer.h"
#include "gpu/vulkan_context.h"
#include "lic/time_series.h"
#include "passes/volume_textures.h"

namespace lic3d {

// One time step on the device: xyz = v / max|v| of the step (physical vectors, scaled so that
// half floats keep their precision whatever the field's units), RGBA32F for float precision and
// RGBA16F otherwise.
struct FieldStep {
  Image image;
  int index = -1;  // the step's number in its series
  Dims dims{0};
  GridGeometry geometry;
  double scale = 1.0;                            // max |v| of the step: texel xyz times this is v
  std::shared_ptr<const ValueHistogram> speeds;  // |v| over the step's voxels
};

Result<FieldStep> uploadFieldStep(const Context& context, const VectorField& field, int index,
                                  FieldPrecision precision);

class TimeBlendPass {
 public:
  // `context` must outlive the pass.
  static Result<TimeBlendPass> create(const Context& context);

  // A field texture that blend() can write (sampled like uploadLicInputs' texture, and a
  // storage image), for `dims` and `geometry` at `precision` (resolved as uploadLicInputs does).
  Result<FieldTexture> createTarget(Dims dims, const GridGeometry& geometry,
                                    FieldPrecision precision) const;
  // The noise that blend() writes into the texture's w (on the steps' grid).
  Result<void> setNoise(const NoiseVolume& noise);

  // target = (1 - w) a + w b in the texture's packing, with the target's magnitudes and scales
  // (maxVoxelSpeed, min and max |v|, texelToPhysical) from the GPU's measurement. Blocking: it
  // waits for the device's queue to be idle first, since frames may still read the texture.
  Result<void> blend(const FieldStep& a, const FieldStep& b, double weight, FieldTexture& target);

  // Bytes of device memory the noise volume holds.
  std::uint64_t noiseBytes() const { return noise_ ? noise_.memorySize() : 0; }
  // GPU milliseconds of the last blend()'s two passes (0 without timestamp queries).
  double lastMilliseconds() const { return lastMs_; }

 private:
  const Context* context_ = nullptr;
  PipelineLayout layout_;
  // Per field texture format: RGBA32F, RGBA16F, RGBA8 SNORM.
  ShaderModule shaders_[3];
  Pipeline measure_[3];
  Pipeline write_[3];
  Sampler nearest_;
  Image noise_;      // R32F on the steps' grid
  Buffer ranges_;    // device-local, kTimeBlendRangeCount uints
  Buffer readback_;  // the ranges for the CPU
  GpuTimer timer_;
  double lastMs_ = 0.0;
};

}  // namespace lic3d
