// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// SPIR-V compiled from shaders/ at build time and embedded in the binary; pipelines are made
// from it with typed specialization constants.

#include <vulkan/vulkan.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <type_traits>

#include "core/error.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

enum class ShaderId {
  LicCompute,
  LicHistogram,
  VisibleBricks,  // the bricks of the LIC volume the slice pass can show
  SparsityMask,   // the sparsity masks of the distributions the GPU makes
  SliceVertex,
  SliceFragment,
  SliceFragmentRuntimeModes,  // only in builds with LIC3D_BENCH_RUNTIME_MODES
  FullscreenVertex,           // one triangle over the viewport
  OcclusionComposite,         // the occlusion-shaded image over the frame
  LicComputeSeparateNoise,    // the benchmark's naive kernel, same builds only
  Lic2DCompute,
  TimeBlend,          // time interpolation into an RGBA32F field texture
  TimeBlendHalf,      // the same into RGBA16F
  TimeBlendByte,      // the same into RGBA8 SNORM with its packing (FieldPrecision::Byte)
  AnalyticVectors,    // the analytic fields' plain vectors evaluated on the device
  AnalyticField,      // an analytic field and its noise into an RGBA32F field texture
  AnalyticFieldHalf,  // the same into RGBA16F
  AnalyticFieldByte,  // the same into RGBA8 SNORM
};

// Whether this build embeds the slice shader with runtime mode switches.
bool hasRuntimeModeShaders();

std::span<const std::uint32_t> spirv(ShaderId id);
const char* shaderName(ShaderId id);

Result<VkShaderModule> createShaderModule(const Context& context, ShaderId id);

// A specialization struct whose field i is constant_id i: only 32-bit fields, no padding.
// The pipeline variant cache is keyed by the struct itself.
template <class T>
class Specialization {
  static_assert(std::is_trivially_copyable_v<T>);
  static_assert(sizeof(T) % 4 == 0, "specialization constants are 32-bit fields");

 public:
  explicit Specialization(const T& values) : values_(values) {
    for (std::uint32_t i = 0; i < kCount; ++i) entries_[i] = {i, 4 * i, 4};
    info_.mapEntryCount = kCount;
    info_.pMapEntries = entries_.data();
    info_.dataSize = sizeof(T);
    info_.pData = &values_;
  }
  Specialization(const Specialization&) = delete;
  Specialization& operator=(const Specialization&) = delete;

  const VkSpecializationInfo* info() const { return &info_; }

 private:
  static constexpr std::uint32_t kCount = sizeof(T) / 4;
  T values_;
  std::array<VkSpecializationMapEntry, kCount> entries_{};
  VkSpecializationInfo info_{};
};

}  // namespace lic3d
