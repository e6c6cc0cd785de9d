// SPDX-License-Identifier: BSD-3-Clause
#include "passes/analytic_field_pass.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <memory>

#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "gpu/pipelines.h"
#include "gpu/resources.h"
#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "lic/lic_reference.h"
#include "passes/lic_push.h"
#include "shared_layout.h"

namespace lic3d {
namespace {

// constant_id i <-> field i (see shaders/analytic_field.comp), each defaulting to the shader's
// default (shared_layout.h).
struct AnalyticFieldSpecialization {
  std::uint32_t field = gpu::kAnalyticDefaultField;
  std::uint32_t phase = gpu::kAnalyticDefaultPhase;
};
static_assert(sizeof(AnalyticFieldSpecialization) == 2 * 4);
static_assert(offsetof(AnalyticFieldSpecialization, field) == 4 * gpu::kAnalyticConstField);
static_assert(offsetof(AnalyticFieldSpecialization, phase) == 4 * gpu::kAnalyticConstPhase);

}  // namespace

Result<AnalyticFieldPass> AnalyticFieldPass::create(const Context& context) {
  AnalyticFieldPass pass;
  pass.context_ = &context;
  constexpr Binding bindings[] = {
      {gpu::kAnalyticBindingTexels, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
      {gpu::kAnalyticBindingStatistics, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
  };
  LIC3D_TRY_ASSIGN(pass.layout_,
                   PipelineLayout::create(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT,
                                          sizeof(gpu::AnalyticPushConstants), "analytic field"));
  const ShaderId ids[3] = {ShaderId::AnalyticField, ShaderId::AnalyticFieldHalf,
                           ShaderId::AnalyticFieldByte};
  for (int variant = 0; variant < 3; ++variant) {
    LIC3D_TRY_ASSIGN(pass.shaders_[variant], loadShader(context, ids[variant]));
  }
  LIC3D_TRY_ASSIGN(
      pass.statistics_,
      Buffer::create(context, VkDeviceSize{gpu::kAnalyticStatisticsWords} * sizeof(std::uint32_t),
                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                         VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                     MemoryUse::DeviceLocal, "analytic field statistics"));
  LIC3D_TRY_ASSIGN(
      pass.readback_,
      Buffer::create(context, pass.statistics_.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                     MemoryUse::Readback, "analytic field statistics readback"));
  return pass;
}

Result<VkPipeline> AnalyticFieldPass::pipeline(Key key) {
  return pipelines_.get(key, [&](const Key& k) {
    const Specialization<AnalyticFieldSpecialization> constants(
        AnalyticFieldSpecialization{k.field, k.phase});
    return createComputePipeline(*context_, shaders_[k.variant], layout_, constants.info(),
                                 std::string("analytic field ") +
                                     (k.phase == 0 ? "measure " : "write ") +
                                     std::string(enumName(static_cast<AnalyticField>(k.field))) +
                                     " " + kFieldTexelVariantNames[k.variant]);
  });
}

GridGeometry AnalyticInputs::texelGeometry() const {
  GridGeometry geometry = analyticGeometry(field, dims);
  geometry.origin += glm::dvec3(brickOffset) * geometry.spacing;
  return geometry;
}

Result<FieldTexture> AnalyticFieldPass::createTarget(const AnalyticInputs& inputs,
                                                     FieldPrecision precision) const {
  const Dims dims = inputs.texelDims();
  LIC3D_TRY(checkVolumeDims(*context_, dims, "field"));
  // The texture and the LIC volume must fit (a CPU driver would otherwise accept the allocation
  // and fail when the memory is first touched), as uploadLicInputs checks.
  MemoryRequest request;
  request.dims = dims;
  request.precision = resolvePrecision(*context_, precision);
  LIC3D_TRY(checkMemoryBudget(request, queryMemoryBudget(*context_), "the field"));
  return createWritableFieldTexture(*context_, dims, inputs.texelGeometry(), precision,
                                    "analytic field and noise texture");
}

namespace {

Result<void> checkTarget(const AnalyticInputs& inputs, const FieldTexture& target) {
  const Dims dims = inputs.texelDims();
  if (target.dims != dims || !target.image)
    return inputError("the analytic field's texture must be made for its grid " + gridText(dims));
  if (inputs.isBrick() && (glm::any(glm::lessThan(inputs.brickOffset, Dims(0))) ||
                           glm::any(glm::greaterThan(inputs.brickOffset + dims, inputs.dims))))
    return inputError("the brick " + gridText(dims) + " at " + gridText(inputs.brickOffset) +
                      " is not inside the grid " + gridText(inputs.dims));
  return {};
}

// Positions from the whole grid's origin, so that a brick's are the whole grid's there.
gpu::AnalyticPushConstants measurePush(const AnalyticInputs& inputs, const glm::dvec3& unit) {
  const GridGeometry geometry = analyticGeometry(inputs.field, inputs.dims);
  gpu::AnalyticPushConstants push{};
  push.dims = glm::ivec4(inputs.dims, 0);
  push.whole = glm::ivec4(inputs.dims, 0);
  push.origin = glm::vec4(glm::vec3(geometry.origin), static_cast<float>(inputs.time));
  push.spacing = glm::vec4(glm::vec3(geometry.spacing), 0.0f);
  push.unitScale = glm::vec4(glm::vec3(unit), 0.0f);
  push.seed = glm::uvec4(static_cast<std::uint32_t>(inputs.noiseSeed),
                         static_cast<std::uint32_t>(inputs.noiseSeed >> 32), 0u, 0u);
  return push;
}

glm::uvec3 groupsOf(Dims d) {
  return glm::uvec3(groupCount(d.x, gpu::kAnalyticLocalSizeX),
                    groupCount(d.y, gpu::kAnalyticLocalSizeY),
                    groupCount(d.z, gpu::kAnalyticLayersPerGroup));
}

constexpr VkPipelineStageFlags2 kTextureReaders =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

}  // namespace

void AnalyticFieldPass::recordClearStatistics(VkCommandBuffer cmd) const {
  // max |u|, max |v| and the counts start at 0, min |v| at the largest float.
  constexpr VkDeviceSize word = sizeof(std::uint32_t);
  constexpr VkDeviceSize minimum = gpu::kAnalyticMinMagnitude * word;
  vkCmdFillBuffer(cmd, statistics_.handle(), 0, minimum, 0u);
  vkCmdFillBuffer(cmd, statistics_.handle(), minimum, word, 0x7F7FFFFFu);
  vkCmdFillBuffer(cmd, statistics_.handle(), minimum + word, VK_WHOLE_SIZE, 0u);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
}

void AnalyticFieldPass::recordStatisticsReadback(VkCommandBuffer cmd) const {
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  const VkBufferCopy copy{0, 0, statistics_.size()};
  vkCmdCopyBuffer(cmd, statistics_.handle(), readback_.handle(), 1, &copy);
  memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
}

void AnalyticFieldPass::readStatistics(const glm::dvec3& unit, FieldTexture& target) const {
  std::array<std::uint32_t, gpu::kAnalyticStatisticsWords> words{};
  std::memcpy(words.data(), readback_.mapped(), sizeof(words));
  const auto asFloat = [&](std::uint32_t index) {
    float value = 0.0f;
    std::memcpy(&value, &words[index], sizeof(value));
    return static_cast<double>(value);
  };
  target.maxVoxelSpeed = asFloat(gpu::kAnalyticMaxSpeed);
  target.maxMagnitude = asFloat(gpu::kAnalyticMaxMagnitude);
  target.minMagnitude = std::min(asFloat(gpu::kAnalyticMinMagnitude), target.maxMagnitude);
  // As uploadLicInputs: a texel's xyz times this is the physical vector.
  const double speed = target.maxVoxelSpeed > 0.0 ? target.maxVoxelSpeed : 1.0;
  target.texelToPhysical = speed / unit;
  target.speeds = std::make_shared<const ValueHistogram>(
      histogramOfCounts(std::span<const std::uint32_t>(words).subspan(gpu::kAnalyticFirstBin),
                        target.minMagnitude, target.maxMagnitude));
  target.unit.clear();
}

Result<void> AnalyticFieldPass::write(const AnalyticInputs& inputs, FieldTexture& target) {
  LIC3D_TRY(checkTarget(inputs, target));
  const Dims dims = inputs.texelDims();
  const StageTimer timer("field and noise (on the device)");
  const auto field = static_cast<std::uint32_t>(inputs.field);
  const int variant = fieldTexelVariant(target.precision);
  LIC3D_TRY_ASSIGN(const VkPipeline measure, pipeline({field, 0, variant}));
  LIC3D_TRY_ASSIGN(const VkPipeline write, pipeline({field, 1, variant}));

  const glm::dvec3 unit = voxelUnitScale(analyticGeometry(inputs.field, inputs.dims));
  const gpu::AnalyticPushConstants push = measurePush(inputs, unit);
  DescriptorWrites writes;
  writes.storageImage(gpu::kAnalyticBindingTexels, target.image.view())
      .storageBuffer(gpu::kAnalyticBindingStatistics, statistics_);
  // Phase 0 measures the whole grid; phase 1 writes the texels' part of it.
  gpu::AnalyticPushConstants texels = push;
  texels.dims = glm::ivec4(dims, 0);
  texels.offset = glm::ivec4(inputs.brickOffset, 0);
  const glm::uvec3 measureGroups = groupsOf(inputs.dims);
  const glm::uvec3 writeGroups = groupsOf(dims);
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        recordClearStatistics(cmd);
        // The old contents are replaced whole: earlier readers must be done.
        imageBarrier(cmd, target.image.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                     kTextureReaders | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        writes.push(*context_, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_);
        vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, measure);
        vkCmdDispatch(cmd, measureGroups.x, measureGroups.y, measureGroups.z);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(texels),
                           &texels);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, write);
        vkCmdDispatch(cmd, writeGroups.x, writeGroups.y, writeGroups.z);
        recordStatisticsReadback(cmd);
        imageBarrier(cmd, target.image.handle(), VK_IMAGE_LAYOUT_GENERAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     kTextureReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
      },
      "analytic field"));
  readStatistics(unit, target);
  return {};
}

}  // namespace lic3d
