// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Sparsity masks made on the GPU (sparsity_mask.comp) for the distributions whose black voxels are
// each a function of their own index: the checkerboard, Halton and Hammersley. They are bit for bit
// makeSparsityMask's (lic/sparsity.h), packed as packSparsityMask packs it. The others, Poisson
// disk, best candidate and jittering, decide each point from the points before it and stay on
// the CPU (docs/LIC_SEMANTICS.md, "Where masks are made").

#include <vulkan/vulkan.h>

#include <cstdint>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/volume.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "shared_layout.h"

namespace lic3d {

// Field i is specialization constant i of sparsity_mask.comp.
struct SparsityMaskSpecialization {
  std::uint32_t distribution = gpu::kMaskDefaultDistribution;
  bool operator==(const SparsityMaskSpecialization&) const = default;
};
static_assert(offsetof(SparsityMaskSpecialization, distribution) ==
              4 * gpu::kMaskConstDistribution);
static_assert(gpu::kMaskCheckerboard ==
                  static_cast<std::uint32_t>(SparsityDistribution::Checkerboard) &&
              gpu::kMaskHalton == static_cast<std::uint32_t>(SparsityDistribution::Halton) &&
              gpu::kMaskHammersley == static_cast<std::uint32_t>(SparsityDistribution::Hammersley));

// Whether SparsityMaskPass makes this distribution's mask.
bool madeOnGpu(SparsityDistribution distribution);

class SparsityMaskPass {
 public:
  // `context` must outlive the pass.
  static Result<SparsityMaskPass> create(const Context& context);

  // Records the mask of `params` (validated, madeOnGpu) on the whole grid `dims` into the start of
  // `bits` (sparsityMaskWords(dims) words, storage and transfer-dst usage), and its black voxel
  // count into `count` (one uint, the same usages). Afterwards both are visible to compute
  // shaders and transfers; earlier compute and transfer work with them is waited for.
  Result<void> record(VkCommandBuffer cmd, const SparsityParams& params, Dims dims,
                      const Buffer& bits, const Buffer& count);

 private:
  const Context* context_ = nullptr;
  PipelineLayout layout_;
  ShaderModule shader_;
  PipelineCache<SparsityMaskSpecialization> pipelines_;
};

}  // namespace lic3d
