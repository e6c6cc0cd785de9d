// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The LIC compute pass: one invocation per voxel writes the LIC volume (a 3D storage image).
// Each (integrator, kernel, noise filter, direction, scheme, packing, sparsity) variant is its own
// pipeline, specialized at creation and cached: the thesis' #ifdef variants without copied shaders.

#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/lic_params.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "lic/sparsity.h"
#include "passes/volume_textures.h"

namespace lic3d {

// constant_id i <-> field i (see shaders/lic.comp).
struct LicSpecialization {
  std::uint32_t integrator = 1;
  std::uint32_t kernel = 0;
  std::uint32_t noiseFilter = 1;
  std::uint32_t direction = 0;
  std::uint32_t localSizeX = 8;  // LicLaunch
  std::uint32_t localSizeY = 8;
  std::uint32_t localSizeZ = 1;
  std::uint32_t sparsity = 0;
  std::uint32_t scheme = 0;
  std::uint32_t packing = 0;     // 1 for FieldPrecision::Byte
  std::uint32_t interleave = 1;  // LicLaunch

  bool operator==(const LicSpecialization&) const = default;
};
static_assert(sizeof(LicSpecialization) == 11 * 4);

LicSpecialization licSpecialization(const LicParams& params, FieldPrecision precision);

// How the LIC pass is launched, whatever the parameters: the workgroup shape and whether an
// invocation walks the two directions of its streamline in one loop (shaders/lic.comp,
// INTERLEAVE). Both are specialization constants chosen per device type (licLaunchFor), from
// `lic3d bench --kernels`, which also times the others (docs/BENCHMARKS.md).
struct LicLaunch {
  std::uint32_t localSizeX = 8;
  std::uint32_t localSizeY = 8;
  std::uint32_t localSizeZ = 1;
  bool interleave = true;
  bool operator==(const LicLaunch&) const = default;
};
LicLaunch licLaunchFor(VkPhysicalDeviceType type);

// The format of LIC volumes: 16-bit UNORM, enough for contrast stretching without banding; the
// second channel is 1 where the voxel is drawn and 0 where sparsity masks it.
inline constexpr VkFormat kLicVolumeFormat = VK_FORMAT_R16G16_UNORM;
// The sparsity mask: one byte per voxel, 1 = black.
inline constexpr VkFormat kSparsityMaskFormat = VK_FORMAT_R8_UINT;

class LicPass {
 public:
  // `context` must outlive the pass. With `separateNoise` (benchmark builds only) the pass runs
  // the naive reference kernel, which reads the noise from an R8 texture of its own.
  // `launch` replaces the device type's LicLaunch (the benchmark's comparisons).
  static Result<LicPass> create(const Context& context, bool separateNoise = false,
                                std::optional<LicLaunch> launch = std::nullopt);

  // Records the dispatch for z slices [zBegin, zEnd). `field`, `mask` and `noise` must be in
  // SHADER_READ_ONLY_OPTIMAL and `output` in GENERAL layout; barriers are the caller's. `mask`
  // is read only when params.sparsity has a distribution (any image will do otherwise); `noise`
  // only by a separate-noise pass.
  Result<void> record(VkCommandBuffer cmd, const FieldTexture& field, const Image& mask,
                      const MaskBeyondGrid& beyond, const Image& output, const LicParams& params,
                      int zBegin, int zEnd, const Image* noise = nullptr);

  // The driver's statistics of the pipeline already made for these parameters and texture with
  // the current launch (pipelineStatistics); empty if none was made or none are captured.
  std::vector<std::pair<std::string, std::string>> statistics(const LicParams& params,
                                                              FieldPrecision precision) const;
  // The launch of the next records (pipelines of every launch stay cached).
  void setLaunch(const LicLaunch& launch) { launch_ = launch; }
  // z slices one workgroup spans: slabs of a multiple of it keep every invocation busy.
  int launchDepth() const { return static_cast<int>(launch_.localSizeZ); }
  std::size_t variantCount() const { return pipelines_.size(); }
  bool separateNoise() const { return separateNoise_; }

 private:
  LicSpecialization specializationFor(const LicParams& params, FieldPrecision precision) const;

  const Context* context_ = nullptr;
  PipelineLayout layout_;
  ShaderModule shader_;
  Sampler sampler_;
  Sampler maskSampler_;
  bool separateNoise_ = false;
  LicLaunch launch_;
  PipelineCache<LicSpecialization> pipelines_;
};

}  // namespace lic3d
