// SPDX-License-Identifier: BSD-3-Clause
#include "passes/time_blend_pass.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "lic/lic_reference.h"
#include "passes/lic_push.h"
#include "shared_layout.h"

namespace lic3d {
namespace {

// constant_id i <-> field i (see shaders/time_blend.comp), defaulting to the shader's default
// (shared_layout.h).
struct TimeBlendSpecialization {
  std::uint32_t phase = gpu::kTimeBlendDefaultPhase;
};
static_assert(sizeof(TimeBlendSpecialization) == 1 * 4);
static_assert(offsetof(TimeBlendSpecialization, phase) == 4 * gpu::kTimeBlendConstPhase);

// Steps keep 16 bits at least: they are blended before the texture's own rounding.
VkFormat stepFormat(FieldPrecision precision) {
  return precision == FieldPrecision::Float ? VK_FORMAT_R32G32B32A32_SFLOAT
                                            : VK_FORMAT_R16G16B16A16_SFLOAT;
}

}  // namespace

Result<FieldStep> uploadFieldStep(const Context& context, const VectorField& field, int index,
                                  FieldPrecision precision) {
  LIC3D_TRY(checkVolumeDims(context, field.dims, "time step"));
  LIC3D_TRY(checkSpacing(field.geometry));
  LIC3D_TRY_ASSIGN(const FieldPrecision resolved, checkFieldPrecision(context, precision));
  FieldStep step;
  step.index = index;
  step.dims = field.dims;
  step.geometry = field.geometry;
  const double largest = maxMagnitude(field);
  step.scale = largest > 0.0 ? largest : 1.0;
  step.speeds = std::make_shared<const ValueHistogram>(speedHistogram(field));

  ImageDesc desc;
  desc.format = stepFormat(resolved);
  desc.extent = extentOf(field.dims);
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "time step " + std::to_string(index);
  LIC3D_TRY_ASSIGN(step.image, Image::create(context, desc));
  const std::size_t voxels = field.vectors.size();
  if (resolved != FieldPrecision::Float) {
    std::vector<std::uint16_t> texels(4 * voxels, 0);
    for (std::size_t i = 0; i < voxels; ++i)
      for (int c = 0; c < 3; ++c)
        texels[4 * i + c] = glm::packHalf1x16(static_cast<float>(field.vectors[i][c] / step.scale));
    LIC3D_TRY(uploadImage(context, step.image, texels.data(), texels.size() * sizeof(texels[0])));
  } else {
    std::vector<float> texels(4 * voxels, 0.0f);
    for (std::size_t i = 0; i < voxels; ++i)
      for (int c = 0; c < 3; ++c)
        texels[4 * i + c] = static_cast<float>(field.vectors[i][c] / step.scale);
    LIC3D_TRY(uploadImage(context, step.image, texels.data(), texels.size() * sizeof(texels[0])));
  }
  return step;
}

Result<TimeBlendPass> TimeBlendPass::create(const Context& context) {
  TimeBlendPass pass;
  pass.context_ = &context;
  constexpr Binding bindings[] = {
      {gpu::kTimeBlendBindingStepA},
      {gpu::kTimeBlendBindingStepB},
      {gpu::kTimeBlendBindingNoise},
      {gpu::kTimeBlendBindingTarget, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
      {gpu::kTimeBlendBindingRanges, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
  };
  LIC3D_TRY_ASSIGN(pass.layout_,
                   PipelineLayout::create(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT,
                                          sizeof(gpu::TimeBlendPushConstants), "time blend"));
  const ShaderId ids[3] = {ShaderId::TimeBlend, ShaderId::TimeBlendHalf, ShaderId::TimeBlendByte};
  for (int variant = 0; variant < 3; ++variant) {
    LIC3D_TRY_ASSIGN(pass.shaders_[variant], loadShader(context, ids[variant]));
    for (std::uint32_t phase : {0u, 1u}) {
      const Specialization<TimeBlendSpecialization> constants(TimeBlendSpecialization{phase});
      const std::string name = std::string("time blend ") + (phase == 0 ? "measure " : "write ") +
                               kFieldTexelVariantNames[variant];
      LIC3D_TRY_ASSIGN(Pipeline pipeline,
                       createComputePipeline(context, pass.shaders_[variant], pass.layout_,
                                             constants.info(), name));
      (phase == 0 ? pass.measure_ : pass.write_)[variant] = std::move(pipeline);
    }
  }
  LIC3D_TRY_ASSIGN(pass.nearest_,
                   Sampler::create(context, VK_FILTER_NEAREST, "time blend sampler"));
  const VkDeviceSize rangeBytes = gpu::kTimeBlendRangeCount * sizeof(std::uint32_t);
  LIC3D_TRY_ASSIGN(pass.ranges_, Buffer::create(context, rangeBytes,
                                                VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                                    VK_BUFFER_USAGE_TRANSFER_DST_BIT |
                                                    VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                                                MemoryUse::DeviceLocal, "time blend ranges"));
  LIC3D_TRY_ASSIGN(pass.readback_,
                   Buffer::create(context, rangeBytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                  MemoryUse::Readback, "time blend ranges readback"));
  if (context.supportsTimestamps()) {
    LIC3D_TRY_ASSIGN(pass.timer_, GpuTimer::create(context, 1, "time blend timestamps"));
  }
  return pass;
}

Result<FieldTexture> TimeBlendPass::createTarget(Dims dims, const GridGeometry& geometry,
                                                 FieldPrecision precision) const {
  return createWritableFieldTexture(*context_, dims, geometry, precision,
                                    "blended field and noise texture");
}

Result<void> TimeBlendPass::setNoise(const NoiseVolume& noise) {
  LIC3D_TRY(checkVolumeDims(*context_, noise.dims, "noise"));
  std::vector<float> values(voxelCount(noise.dims));
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = noise.value(i);
  noise_ = Image();
  ImageDesc desc;
  desc.format = VK_FORMAT_R32_SFLOAT;
  desc.extent = extentOf(noise.dims);
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "time series noise";
  LIC3D_TRY_ASSIGN(noise_, Image::create(*context_, desc));
  return uploadImage(*context_, noise_, values.data(), values.size() * sizeof(float));
}

Result<void> TimeBlendPass::blend(const FieldStep& a, const FieldStep& b, double weight,
                                  FieldTexture& target) {
  if (a.dims != target.dims || b.dims != target.dims || !(a.geometry == b.geometry))
    return inputError("time steps " + std::to_string(a.index) + " and " + std::to_string(b.index) +
                      " must share the field's grid (" + gridText(target.dims) +
                      "), spacing and origin");
  if (!noise_ || noise_.extent().width != extentOf(target.dims).width ||
      noise_.extent().height != extentOf(target.dims).height ||
      noise_.extent().depth != extentOf(target.dims).depth)
    return inputError("the noise must be set on the time steps' grid");
  const VkFormat steps = stepFormat(target.precision);
  if (a.image.format() != steps || b.image.format() != steps)
    return inputError("time steps and the field texture must have the same precision");
  const int variant = fieldTexelVariant(target.precision);
  const VkPipeline measure = measure_[variant].get();
  const VkPipeline write = write_[variant].get();

  const glm::dvec3 unit = voxelUnitScale(target.geometry);
  gpu::TimeBlendPushConstants push{};
  push.dims = glm::ivec4(target.dims, 0);
  push.unitScale = glm::vec4(glm::vec3(unit), static_cast<float>(std::clamp(weight, 0.0, 1.0)));
  push.stepScales = glm::vec4(static_cast<float>(a.scale), static_cast<float>(b.scale), 0.0f, 0.0f);

  DescriptorWrites writes;
  writes.sampledImage(gpu::kTimeBlendBindingStepA, nearest_, a.image.view())
      .sampledImage(gpu::kTimeBlendBindingStepB, nearest_, b.image.view())
      .sampledImage(gpu::kTimeBlendBindingNoise, nearest_, noise_.view())
      .storageImage(gpu::kTimeBlendBindingTarget, target.image.view())
      .storageBuffer(gpu::kTimeBlendBindingRanges, ranges_);
  const std::uint32_t groupsX = groupCount(target.dims.x, gpu::kTimeBlendLocalSizeX);
  const std::uint32_t groupsY = groupCount(target.dims.y, gpu::kTimeBlendLocalSizeY);
  const std::uint32_t groupsZ = static_cast<std::uint32_t>(target.dims.z);

  // Frames and LIC slabs still in flight may read the texture that is about to be rewritten.
  vkQueueWaitIdle(context_->queue());
  constexpr VkPipelineStageFlags2 kReaders =
      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        // max |u| and max |v| start at 0, min |v| at the largest float.
        vkCmdFillBuffer(cmd, ranges_.handle(), 0, 2 * sizeof(std::uint32_t), 0u);
        vkCmdFillBuffer(cmd, ranges_.handle(), 2 * sizeof(std::uint32_t), sizeof(std::uint32_t),
                        0x7F7FFFFFu);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        // The old contents are replaced whole: earlier readers must be done.
        imageBarrier(cmd, target.image.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                     kReaders | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        writes.push(*context_, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_);
        vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
        if (timer_.valid()) {
          timer_.reset(cmd, 0);
          timer_.begin(cmd, 0);
        }
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, measure);
        vkCmdDispatch(cmd, groupsX, groupsY, groupsZ);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
                      VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, write);
        vkCmdDispatch(cmd, groupsX, groupsY, groupsZ);
        if (timer_.valid()) timer_.end(cmd, 0);
        const VkBufferCopy copy{0, 0, ranges_.size()};
        vkCmdCopyBuffer(cmd, ranges_.handle(), readback_.handle(), 1, &copy);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
        imageBarrier(cmd, target.image.handle(), VK_IMAGE_LAYOUT_GENERAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     kReaders, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
      },
      "field time interpolation"));

  if (timer_.valid()) {
    LIC3D_TRY_ASSIGN(lastMs_, timer_.milliseconds(0));
  }
  std::array<float, gpu::kTimeBlendRangeCount> ranges{};
  std::memcpy(ranges.data(), readback_.mapped(), sizeof(ranges));
  target.maxVoxelSpeed = ranges[gpu::kTimeBlendRangeMaxSpeed];
  target.maxMagnitude = ranges[gpu::kTimeBlendRangeMaxMagnitude];
  target.minMagnitude =
      std::min(ranges[gpu::kTimeBlendRangeMinMagnitude], ranges[gpu::kTimeBlendRangeMaxMagnitude]);
  // As uploadLicInputs: a texel's xyz times this is the physical vector.
  const double speed = target.maxVoxelSpeed > 0.0 ? target.maxVoxelSpeed : 1.0;
  target.texelToPhysical = speed / unit;
  // The blend's spread of speeds, from the steps' (measured on the host when they were read).
  if (a.speeds && b.speeds)
    target.speeds = std::make_shared<const ValueHistogram>(
        ValueHistogram::blend(*a.speeds, *b.speeds, std::clamp(weight, 0.0, 1.0)));
  return {};
}

}  // namespace lic3d
