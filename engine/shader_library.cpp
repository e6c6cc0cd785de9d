#include "shader_library.h"

#include <cstdint>

#include "vk_check.h"

// Generated at build time by glslangValidator --vn (see cmake/Lic3dShaders.cmake).
#include "lic_comp_spv.h"
#include "lic_histogram_comp_spv.h"
#include "slice_frag_spv.h"
#include "slice_vert_spv.h"

namespace lic3d {

std::span<const std::uint32_t> spirv(ShaderId id) {
  switch (id) {
    case ShaderId::LicCompute: return lic_comp_spv;
    case ShaderId::LicHistogram: return lic_histogram_comp_spv;
    case ShaderId::SliceVertex: return slice_vert_spv;
    case ShaderId::SliceFragment: return slice_frag_spv;
  }
  return {};
}

const char* shaderName(ShaderId id) {
  switch (id) {
    case ShaderId::LicCompute: return "lic.comp";
    case ShaderId::LicHistogram: return "lic_histogram.comp";
    case ShaderId::SliceVertex: return "slice.vert";
    case ShaderId::SliceFragment: return "slice.frag";
  }
  return "?";
}

Result<VkShaderModule> createShaderModule(const Context& context, ShaderId id) {
  const std::span<const std::uint32_t> code = spirv(id);
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
