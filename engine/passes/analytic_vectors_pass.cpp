// SPDX-License-Identifier: BSD-3-Clause
#include "passes/analytic_vectors_pass.h"

#include <algorithm>
#include <cstddef>
#include <string>

#include "core/parallel.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "passes/lic_push.h"
#include "shared_layout.h"

namespace lic3d {
namespace {

// constant_id i <-> field i (see shaders/analytic_fields.glsl), defaulting to the shader's
// default (shared_layout.h).
struct AnalyticVectorsSpecialization {
  std::uint32_t field = gpu::kAnalyticDefaultField;
};
static_assert(sizeof(AnalyticVectorsSpecialization) == 1 * 4);
static_assert(offsetof(AnalyticVectorsSpecialization, field) == 4 * gpu::kAnalyticConstField);

// The slab buffer: at most this many bytes (and the device's storage buffer range), so that
// memory stays bounded whatever the grid.
constexpr VkDeviceSize kSlabBytes = VkDeviceSize{256} << 20;

}  // namespace

Result<VectorField> makeAnalyticFieldOnDevice(const Context& context, AnalyticField field,
                                              Dims dims, double time) {
  VectorField result;
  result.dims = dims;
  result.geometry = analyticGeometry(field, dims);
  const VkDeviceSize layerBytes =
      VkDeviceSize{3} * sizeof(float) * std::size_t(dims.x) * std::size_t(dims.y);
  const VkDeviceSize limit =
      std::min<VkDeviceSize>(kSlabBytes, context.properties().limits.maxStorageBufferRange);
  if (layerBytes > limit)
    return unsupportedError("a z layer of " + gridText(dims) +
                            " does not fit one storage buffer of this device");
  const int slab = static_cast<int>(std::min<VkDeviceSize>(limit / layerBytes, dims.z));

  constexpr Binding bindings[] = {
      {gpu::kAnalyticBindingVectors, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER}};
  LIC3D_TRY_ASSIGN(const PipelineLayout layout,
                   PipelineLayout::create(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT,
                                          sizeof(gpu::AnalyticPushConstants), "analytic field"));
  LIC3D_TRY_ASSIGN(const ShaderModule shader, loadShader(context, ShaderId::AnalyticVectors));
  const Specialization<AnalyticVectorsSpecialization> constants(
      AnalyticVectorsSpecialization{static_cast<std::uint32_t>(field)});
  LIC3D_TRY_ASSIGN(const Pipeline pipeline,
                   createComputePipeline(context, shader, layout, constants.info(),
                                         "analytic field " + std::string(enumName(field))));
  LIC3D_TRY_ASSIGN(const Buffer vectors,
                   Buffer::create(context, layerBytes * static_cast<VkDeviceSize>(slab),
                                  VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Readback,
                                  "analytic field slab"));

  result.vectors.resize(voxelCount(dims));
  gpu::AnalyticPushConstants push{};
  push.unitScale = glm::vec4(1.0f);
  push.origin = glm::vec4(glm::vec3(result.geometry.origin), static_cast<float>(time));
  push.spacing = glm::vec4(glm::vec3(result.geometry.spacing), 0.0f);
  for (int z0 = 0; z0 < dims.z; z0 += slab) {
    const int layers = std::min(slab, dims.z - z0);
    push.dims = glm::ivec4(dims.x, dims.y, layers, z0);
    DescriptorWrites writes;
    writes.storageBuffer(gpu::kAnalyticBindingVectors, vectors);
    LIC3D_TRY(submitAndWait(
        context,
        [&](VkCommandBuffer cmd) {
          writes.push(context, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout);
          vkCmdPushConstants(cmd, layout.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push),
                             &push);
          vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline.get());
          vkCmdDispatch(cmd, groupCount(dims.x, gpu::kAnalyticLocalSizeX),
                        groupCount(dims.y, gpu::kAnalyticLocalSizeY),
                        static_cast<std::uint32_t>(layers));
          memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_HOST_BIT,
                        VK_ACCESS_2_HOST_READ_BIT);
        },
        "analytic field"));
    // Three floats per voxel, x fastest: the layout of glm::vec3.
    static_assert(sizeof(glm::vec3) == 3 * sizeof(float));
    const std::size_t first = voxelIndex(dims, 0, 0, z0);
    const std::size_t bytes =
        static_cast<std::size_t>(layerBytes) * static_cast<std::size_t>(layers);
    parallelCopy(result.vectors.data() + first, vectors.mapped(), bytes);
  }
  return result;
}

}  // namespace lic3d
