// SPDX-License-Identifier: BSD-3-Clause
#include "passes/lic2d_pass.h"

#include <array>
#include <cstdlib>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "lic/lic2d_reference.h"
#include "lic/lic_reference.h"
#include "passes/lic_push.h"
#include "shared_layout.h"

namespace lic3d {
namespace {

Result<Image> uploadImage2D(const Context& context, VkFormat format, Dims size, const void* data,
                            std::size_t bytes, const char* name) {
  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.format = format;
  desc.extent = extentOf(size);
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = name;
  LIC3D_TRY_ASSIGN(Image image, Image::create(context, desc));
  LIC3D_TRY(uploadImage(context, image, data, bytes));
  return image;
}

}  // namespace

Lic2DSpecialization lic2DSpecialization(const LicParams& params) {
  Lic2DSpecialization s;
  s.integrator = static_cast<std::uint32_t>(params.integrator);
  s.kernel = static_cast<std::uint32_t>(params.kernel);
  s.noiseFilter = static_cast<std::uint32_t>(params.noiseFilter);
  s.direction = static_cast<std::uint32_t>(params.direction);
  s.scheme = static_cast<std::uint32_t>(params.scheme);
  return s;
}

Result<Lic2DInputs> uploadLic2DInputs(const Context& context, const VectorField& field,
                                      const NoiseVolume& noise, FieldPrecision precision) {
  LIC3D_TRY(checkLic2DInputs(field, noise));
  const std::uint32_t limit = context.properties().limits.maxImageDimension2D;
  for (const Dims d : {field.dims, noise.dims})
    if (static_cast<std::uint32_t>(std::max(d.x, d.y)) > limit)
      return inputError("2D LIC: " + sizeText(d) + " exceeds what " + context.deviceInfo().name +
                        " allows per side (" + std::to_string(limit) + ")");
  Lic2DInputs inputs;
  inputs.fieldDims = field.dims;
  inputs.imageDims = noise.dims;
  inputs.precision = resolvePrecision(context, precision);
  // The reference's own scale and normalisation (output pixel units), so both integrate the same
  // field.
  const FieldSampler sampler(field, noise.dims);
  inputs.maxSpeed = sampler.maxSpeed();
  const double speed = inputs.maxSpeed > 0.0 ? inputs.maxSpeed : 1.0;
  const glm::dvec3 scale = sampler.unitScale() / speed;

  const std::size_t pixels = field.vectors.size();
  if (inputs.precision == FieldPrecision::Half) {
    std::vector<std::uint16_t> texels(2 * pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      const glm::dvec3 v = glm::dvec3(field.vectors[i]) * scale;
      texels[2 * i] = glm::packHalf1x16(static_cast<float>(v.x));
      texels[2 * i + 1] = glm::packHalf1x16(static_cast<float>(v.y));
    }
    LIC3D_TRY_ASSIGN(inputs.field,
                     uploadImage2D(context, VK_FORMAT_R16G16_SFLOAT, field.dims, texels.data(),
                                   texels.size() * sizeof(texels[0]), "2d field texture"));
  } else {
    if (!supportsFormat(context, VK_FORMAT_R32G32_SFLOAT,
                        VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
      return unsupportedError(context.deviceInfo().name +
                              " cannot filter RG32F textures; use half precision");
    std::vector<float> texels(2 * pixels);
    for (std::size_t i = 0; i < pixels; ++i) {
      const glm::dvec3 v = glm::dvec3(field.vectors[i]) * scale;
      texels[2 * i] = static_cast<float>(v.x);
      texels[2 * i + 1] = static_cast<float>(v.y);
    }
    LIC3D_TRY_ASSIGN(inputs.field,
                     uploadImage2D(context, VK_FORMAT_R32G32_SFLOAT, field.dims, texels.data(),
                                   texels.size() * sizeof(texels[0]), "2d field texture"));
  }

  if (noise.type == NoiseType::UInt8) {
    // Byte noise reads as value / 255 on both sides: UNORM is exact.
    LIC3D_TRY_ASSIGN(inputs.noise,
                     uploadImage2D(context, VK_FORMAT_R8_UNORM, noise.dims, noise.bytes.data(),
                                   noise.bytes.size(), "2d noise texture"));
  } else {
    if (!supportsFormat(context, VK_FORMAT_R32_SFLOAT,
                        VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
      return unsupportedError(context.deviceInfo().name + " cannot filter R32F textures");
    std::vector<float> values(voxelCount(noise.dims));
    for (std::size_t i = 0; i < values.size(); ++i) values[i] = noise.value(i);
    LIC3D_TRY_ASSIGN(inputs.noise,
                     uploadImage2D(context, VK_FORMAT_R32_SFLOAT, noise.dims, values.data(),
                                   values.size() * sizeof(float), "2d noise texture"));
  }
  return inputs;
}

Result<Lic2DPass> Lic2DPass::create(const Context& context) {
  Lic2DPass pass;
  pass.context_ = &context;
  constexpr Binding bindings[] = {
      {gpu::kLic2DBindingField},
      {gpu::kLic2DBindingNoise},
      {gpu::kLic2DBindingOutput, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
  };
  LIC3D_TRY_ASSIGN(pass.layout_,
                   PipelineLayout::create(context, bindings, VK_SHADER_STAGE_COMPUTE_BIT,
                                          sizeof(gpu::Lic2DPushConstants), "lic 2d"));
  LIC3D_TRY_ASSIGN(pass.shader_, loadShader(context, ShaderId::Lic2DCompute));
  LIC3D_TRY_ASSIGN(pass.linear_,
                   Sampler::create(context, VK_FILTER_LINEAR, "lic 2d bilinear sampler"));
  if (context.supportsTimestamps()) {
    LIC3D_TRY_ASSIGN(pass.timer_, GpuTimer::create(context, 1, "lic 2d timestamps"));
  }
  return pass;
}

Result<void> Lic2DPass::record(VkCommandBuffer cmd, const Lic2DInputs& inputs, const Image& output,
                               const LicParams& params) {
  LIC3D_TRY(checkLic2DParams(params));
  const Lic2DSpecialization specialization = lic2DSpecialization(params);
  LIC3D_TRY_ASSIGN(VkPipeline pipeline,
                   pipelines_.get(specialization, [&](const Lic2DSpecialization& key) {
                     const Specialization<Lic2DSpecialization> constants(key);
                     return createComputePipeline(*context_, shader_, layout_, constants.info(),
                                                  licPipelineName("lic 2d ", key));
                   }));
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);

  DescriptorWrites()
      .sampledImage(gpu::kLic2DBindingField, linear_, inputs.field.view())
      .sampledImage(gpu::kLic2DBindingNoise, linear_, inputs.noise.view())
      .storageImage(gpu::kLic2DBindingOutput, output.view())
      .push(*context_, cmd, VK_PIPELINE_BIND_POINT_COMPUTE, layout_);

  const Dims size = inputs.imageDims;
  gpu::Lic2DPushConstants push{};
  push.size = glm::ivec4(size.x, size.y, 0, 0);
  push.invSize =
      glm::vec4(1.0f / static_cast<float>(size.x), 1.0f / static_cast<float>(size.y), 0.0f, 0.0f);
  setLicPushParams(push, params);
  vkCmdPushConstants(cmd, layout_.get(), VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);

  vkCmdDispatch(cmd, groupCount(size.x, specialization.localSizeX),
                groupCount(size.y, specialization.localSizeY), 1);
  return {};
}

Result<ScalarVolume> Lic2DPass::compute(const Lic2DInputs& inputs, const LicParams& params) {
  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.format = kLic2DImageFormat;
  desc.extent = extentOf(inputs.imageDims);
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.name = "2d lic image";
  LIC3D_TRY_ASSIGN(const Image output, Image::create(*context_, desc));
  Result<void> recorded;
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, output.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                     VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        if (timer_.valid()) {
          timer_.reset(cmd, 0);
          timer_.begin(cmd, 0);
        }
        recorded = record(cmd, inputs, output, params);
        if (timer_.valid()) timer_.end(cmd, 0);
      },
      "lic 2d compute"));
  LIC3D_TRY(std::move(recorded));
  if (timer_.valid()) {
    LIC3D_TRY_ASSIGN(lastMs_, timer_.milliseconds(0));
  }
  LIC3D_TRY_ASSIGN(const std::vector<std::byte> bytes,
                   readImage(*context_, output, VK_IMAGE_LAYOUT_GENERAL, sizeof(float)));
  ScalarVolume image;
  image.dims = inputs.imageDims;
  image.values.resize(voxelCount(image.dims));
  std::memcpy(image.values.data(), bytes.data(), image.values.size() * sizeof(float));
  return image;
}

}  // namespace lic3d
