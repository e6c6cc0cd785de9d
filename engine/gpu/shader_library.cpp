// SPDX-License-Identifier: BSD-3-Clause
#include "gpu/shader_library.h"

#include <cstdint>

#include "gpu/vk_check.h"

// Generated at build time by glslangValidator --vn (see cmake/Lic3dShaders.cmake).
#include "analytic_field_byte_comp_spv.h"
#include "analytic_field_comp_spv.h"
#include "analytic_field_half_comp_spv.h"
#include "analytic_vectors_comp_spv.h"
#include "fullscreen_vert_spv.h"
#include "lic2d_comp_spv.h"
#include "lic_comp_spv.h"
#include "lic_histogram_comp_spv.h"
#include "occlusion_composite_frag_spv.h"
#include "slice_frag_spv.h"
#include "slice_vert_spv.h"
#include "sparsity_mask_comp_spv.h"
#include "time_blend_byte_comp_spv.h"
#include "time_blend_comp_spv.h"
#include "time_blend_half_comp_spv.h"
#include "visible_bricks_comp_spv.h"
#ifdef LIC3D_BENCH_RUNTIME_MODES
#include "lic_naive_comp_spv.h"
#include "slice_runtime_frag_spv.h"
#endif

namespace lic3d {

std::span<const std::uint32_t> spirv(ShaderId id) {
  switch (id) {
    case ShaderId::LicCompute: return lic_comp_spv;
    case ShaderId::LicHistogram: return lic_histogram_comp_spv;
    case ShaderId::VisibleBricks: return visible_bricks_comp_spv;
    case ShaderId::SparsityMask: return sparsity_mask_comp_spv;
    case ShaderId::SliceVertex: return slice_vert_spv;
    case ShaderId::SliceFragment: return slice_frag_spv;
    case ShaderId::SliceFragmentRuntimeModes:
#ifdef LIC3D_BENCH_RUNTIME_MODES
      return slice_runtime_frag_spv;
#else
      return {};
#endif
    case ShaderId::FullscreenVertex: return fullscreen_vert_spv;
    case ShaderId::OcclusionComposite: return occlusion_composite_frag_spv;
    case ShaderId::LicComputeSeparateNoise:
#ifdef LIC3D_BENCH_RUNTIME_MODES
      return lic_naive_comp_spv;
#else
      return {};
#endif
    case ShaderId::Lic2DCompute: return lic2d_comp_spv;
    case ShaderId::TimeBlend: return time_blend_comp_spv;
    case ShaderId::TimeBlendHalf: return time_blend_half_comp_spv;
    case ShaderId::TimeBlendByte: return time_blend_byte_comp_spv;
    case ShaderId::AnalyticVectors: return analytic_vectors_comp_spv;
    case ShaderId::AnalyticField: return analytic_field_comp_spv;
    case ShaderId::AnalyticFieldHalf: return analytic_field_half_comp_spv;
    case ShaderId::AnalyticFieldByte: return analytic_field_byte_comp_spv;
  }
  return {};
}

bool hasRuntimeModeShaders() {
#ifdef LIC3D_BENCH_RUNTIME_MODES
  return true;
#else
  return false;
#endif
}

const char* shaderName(ShaderId id) {
  switch (id) {
    case ShaderId::LicCompute: return "lic.comp";
    case ShaderId::LicHistogram: return "lic_histogram.comp";
    case ShaderId::VisibleBricks: return "visible_bricks.comp";
    case ShaderId::SparsityMask: return "sparsity_mask.comp";
    case ShaderId::SliceVertex: return "slice.vert";
    case ShaderId::SliceFragment: return "slice.frag";
    case ShaderId::SliceFragmentRuntimeModes: return "slice.frag (runtime modes)";
    case ShaderId::FullscreenVertex: return "fullscreen.vert";
    case ShaderId::OcclusionComposite: return "occlusion_composite.frag";
    case ShaderId::LicComputeSeparateNoise: return "lic.comp (naive, separate noise)";
    case ShaderId::Lic2DCompute: return "lic2d.comp";
    case ShaderId::TimeBlend: return "time_blend.comp";
    case ShaderId::TimeBlendHalf: return "time_blend.comp (rgba16f)";
    case ShaderId::TimeBlendByte: return "time_blend.comp (rgba8 snorm)";
    case ShaderId::AnalyticVectors: return "analytic_vectors.comp";
    case ShaderId::AnalyticField: return "analytic_field.comp";
    case ShaderId::AnalyticFieldHalf: return "analytic_field.comp (rgba16f)";
    case ShaderId::AnalyticFieldByte: return "analytic_field.comp (rgba8 snorm)";
  }
  return "?";
}

Result<VkShaderModule> createShaderModule(const Context& context, ShaderId id) {
  const std::span<const std::uint32_t> code = spirv(id);
  if (code.empty())
    return unsupportedError(
        std::string(shaderName(id)) +
        " is not in this build (configure with -DLIC3D_BENCH_RUNTIME_MODES=ON)");
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = code.size_bytes();
  info.pCode = code.data();
  VkShaderModule module = VK_NULL_HANDLE;
  LIC3D_TRY(checkVk(vkCreateShaderModule(context.device(), &info, nullptr, &module),
                    "vkCreateShaderModule"));
  context.setDebugName(module, VK_OBJECT_TYPE_SHADER_MODULE, shaderName(id));
  return module;
}

}  // namespace lic3d
