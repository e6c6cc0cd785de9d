// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The LIC compute pass: one invocation per voxel writes the LIC volume (a 3D storage image).
// Each (integrator, kernel, noise filter, direction, scheme, packing, sparsity) variant is its own
// pipeline, specialized at creation and cached: the thesis' #ifdef variants without copied shaders.

#include <vulkan/vulkan.h>

#include <cstddef>
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
#include "passes/visible_bricks_pass.h"
#include "passes/volume_textures.h"
#include "shared_layout.h"

namespace lic3d {

// constant_id i <-> field i (see shaders/lic.comp), each defaulting to the shader's default
// (shared_layout.h). Two kinds of fields: those LicParams and the field texture decide
// (licSpecialization), and the launch (local size, interleave): how the pass is launched whatever
// the parameters, chosen per device type (licLaunchFor) from `lic3d bench --kernels`, which also
// times the others (docs/BENCHMARKS.md).
struct LicSpecialization {
  std::uint32_t integrator = gpu::kLicDefaultIntegrator;
  std::uint32_t kernel = gpu::kLicDefaultKernel;
  std::uint32_t noiseFilter = gpu::kLicDefaultNoiseFilter;
  std::uint32_t direction = gpu::kLicDefaultDirection;
  std::uint32_t localSizeX = gpu::kLicDefaultLocalSizeX;  // launch
  std::uint32_t localSizeY = gpu::kLicDefaultLocalSizeY;  // launch
  std::uint32_t localSizeZ = gpu::kLicDefaultLocalSizeZ;  // launch
  std::uint32_t sparsity = gpu::kLicDefaultSparsity;
  std::uint32_t scheme = gpu::kLicDefaultScheme;
  std::uint32_t packing = gpu::kLicDefaultPacking;        // 1 for FieldPrecision::Byte
  std::uint32_t interleave = gpu::kLicDefaultInterleave;  // launch
  std::uint32_t brickList = gpu::kLicDefaultBrickList;    // set by recordBricks

  bool operator==(const LicSpecialization&) const = default;
};
static_assert(sizeof(LicSpecialization) == 12 * 4);
static_assert(offsetof(LicSpecialization, integrator) == 4 * gpu::kLicConstIntegrator);
static_assert(offsetof(LicSpecialization, kernel) == 4 * gpu::kLicConstKernel);
static_assert(offsetof(LicSpecialization, noiseFilter) == 4 * gpu::kLicConstNoiseFilter);
static_assert(offsetof(LicSpecialization, direction) == 4 * gpu::kLicConstDirection);
static_assert(offsetof(LicSpecialization, localSizeX) == 4 * gpu::kLicConstLocalSizeX);
static_assert(offsetof(LicSpecialization, localSizeY) == 4 * gpu::kLicConstLocalSizeY);
static_assert(offsetof(LicSpecialization, localSizeZ) == 4 * gpu::kLicConstLocalSizeZ);
static_assert(offsetof(LicSpecialization, sparsity) == 4 * gpu::kLicConstSparsity);
static_assert(offsetof(LicSpecialization, scheme) == 4 * gpu::kLicConstScheme);
static_assert(offsetof(LicSpecialization, packing) == 4 * gpu::kLicConstPacking);
static_assert(offsetof(LicSpecialization, interleave) == 4 * gpu::kLicConstInterleave);
static_assert(offsetof(LicSpecialization, brickList) == 4 * gpu::kLicConstBrickList);

// The fields of `params` and the texture's packing; the launch fields are `launch`'s.
LicSpecialization licSpecialization(const LicParams& params, FieldPrecision precision,
                                    const LicSpecialization& launch = {});

// A specialization whose launch fields are a workgroup of x * y * z and the walk (interleave: both
// directions in one loop); its other fields are the defaults.
LicSpecialization licLaunch(std::uint32_t x, std::uint32_t y, std::uint32_t z, bool interleave);
// The launch fields chosen for a device type.
LicSpecialization licLaunchFor(VkPhysicalDeviceType type);

// The format of LIC volumes: 16-bit UNORM, enough for contrast stretching without banding; the
// second channel is 1 where the voxel is drawn and 0 where sparsity masks it.
inline constexpr VkFormat kLicVolumeFormat = VK_FORMAT_R16G16_UNORM;

class LicPass {
 public:
  // `context` must outlive the pass. With `separateNoise` (benchmark builds only) the pass runs
  // the naive reference kernel, which reads the noise from an R8 texture of its own.
  // The launch fields of `launch` replace the device type's (the benchmark's comparisons).
  static Result<LicPass> create(const Context& context, bool separateNoise = false,
                                std::optional<LicSpecialization> launch = std::nullopt);

  // Records the dispatch for z slices [zBegin, zEnd) of `output`. `field` and `noise` must be in
  // SHADER_READ_ONLY_OPTIMAL and `output` in GENERAL layout; barriers are the caller's. `mask`,
  // the bit-packed sparsity mask of the field's grid (packSparsityMask, SparsityMaskPass), is
  // read only when params.sparsity has a distribution (may be null otherwise); `noise` only by a
  // separate-noise pass. With `stride` > 1, `output` is a coarse volume on
  // coarseDims(field.dims, stride): its voxel v is the LIC of field voxel v * stride, the full
  // volume's value there, for 1 / stride^3 of the work.
  Result<void> record(VkCommandBuffer cmd, const FieldTexture& field, const Buffer* mask,
                      const MaskBeyondGrid& beyond, const Image& output, const LicParams& params,
                      int zBegin, int zEnd, const Image* noise = nullptr, int stride = 1);
  // The same for the bricks `bricks` listed in brick layers [layerBegin, layerEnd) (its record
  // done, its writes visible to indirect dispatches and compute shaders): one indirect dispatch
  // per layer, workgroups of 8 x 8 x 1 whatever the launch; each brick made is marked in
  // bricks.made(). Voxels of unlisted bricks are not written. Not with separate noise.
  Result<void> recordBricks(VkCommandBuffer cmd, const FieldTexture& field, const Buffer* mask,
                            const MaskBeyondGrid& beyond, const Image& output,
                            const LicParams& params, const VisibleBricksPass& bricks,
                            int layerBegin, int layerEnd);

  // The driver's statistics of the pipeline already made for these parameters and texture with
  // the current launch (pipelineStatistics); empty if none was made or none are captured.
  std::vector<std::pair<std::string, std::string>> statistics(const LicParams& params,
                                                              FieldPrecision precision) const;
  // The launch fields of the next records (pipelines of every launch stay cached).
  void setLaunch(const LicSpecialization& launch) { launch_ = launch; }
  // z slices one workgroup spans: slabs of a multiple of it keep every invocation busy.
  int launchDepth() const { return static_cast<int>(launch_.localSizeZ); }
  std::size_t variantCount() const { return pipelines_.size(); }
  bool separateNoise() const { return separateNoise_; }

 private:
  const Context* context_ = nullptr;
  PipelineLayout layout_;
  ShaderModule shader_;
  Sampler sampler_;
  bool separateNoise_ = false;
  LicSpecialization launch_;  // only its launch fields are used
  PipelineCache<LicSpecialization> pipelines_;
  Buffer noBricks_;  // bound to the brick bindings of the slab variant, which never reads it
  Buffer noMask_;    // bound to the mask binding of unmasked variants, which never read it

  Result<VkPipeline> pipelineFor(const LicSpecialization& specialization);
  void pushDescriptors(VkCommandBuffer cmd, const FieldTexture& field, const Buffer* mask,
                       const Image& output, const Image* noise, const Buffer& lists,
                       const Buffer& made);
  gpu::LicPushConstants pushConstants(Dims dims, const MaskBeyondGrid& beyond,
                                      const LicParams& params, int zBegin, int zEnd,
                                      int stride = 1) const;
};

}  // namespace lic3d
