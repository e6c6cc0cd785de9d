#include "lic_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <glm/gtc/packing.hpp>

#include "gpu_submit.h"
#include "legend.h"
#include "vk_check.h"

namespace lic3d {
namespace {

// With progress reporting the pass is split into this many slabs along z (at most).
constexpr int kProgressSlabs = 16;

constexpr VkPipelineStageFlags2 kVolumeReaders =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

}  // namespace

Result<LicRenderer> LicRenderer::create(const Context& context, const RendererOptions& options) {
  LicRenderer renderer;
  renderer.context_ = &context;
  renderer.precision_ = resolvePrecision(context, options.fieldPrecision);
  LIC3D_TRY(renderer.setFramePrecision(options.framePrecision));
  LIC3D_TRY_ASSIGN(renderer.licPass_, LicPass::create(context));
  LIC3D_TRY_ASSIGN(renderer.histogramPass_, LicHistogramPass::create(context));
  LIC3D_TRY_ASSIGN(renderer.slicePass_, SlicePass::create(context, options.runtimeModes));
  if (context.supportsTimestamps()) {
    LIC3D_TRY_ASSIGN(renderer.timer_, GpuTimer::create(context, 2, "renderer timestamps"));
  }
  ImageDesc maskDesc;
  maskDesc.format = kSparsityMaskFormat;
  maskDesc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  maskDesc.name = "empty sparsity mask";
  LIC3D_TRY_ASSIGN(renderer.emptyMask_, Image::create(context, maskDesc));
  const std::uint8_t white = 0;
  LIC3D_TRY(uploadImage(context, renderer.emptyMask_, &white, 1));
  if (!supportsFormat(context, kLicVolumeFormat,
                      VK_FORMAT_FEATURE_2_STORAGE_IMAGE_BIT |
                          VK_FORMAT_FEATURE_2_SAMPLED_IMAGE_FILTER_LINEAR_BIT))
    return unsupportedError(context.deviceInfo().name +
                            " cannot use R16_UNORM as a filtered storage image");
  return renderer;
}

Result<void> LicRenderer::setFramePrecision(FramePrecision precision) {
  const VkFormat format = precision == FramePrecision::Float16 ? VK_FORMAT_R16G16B16A16_SFLOAT
                                                               : VK_FORMAT_R8G8B8A8_UNORM;
  if (!supportsFormat(*context_, format, VK_FORMAT_FEATURE_2_COLOR_ATTACHMENT_BLEND_BIT))
    return unsupportedError(context_->deviceInfo().name + " cannot blend into the frame format");
  frameFormat_ = format;
  return {};
}

LicRenderer::~LicRenderer() {
  // Resources may still be in use by the last submission only if it failed; be safe.
  if (context_) vkDeviceWaitIdle(context_->device());
}

Result<void> LicRenderer::setInputs(const VectorField& field, const NoiseVolume& noise) {
  licParams_.reset();
  if (field.dims != field_.dims) maskParams_.reset();  // the mask lives on the field's grid
  field_ = FieldTexture();  // free the old texture before allocating the new one
  LIC3D_TRY_ASSIGN(field_, uploadLicInputs(*context_, field, noise, precision_));
  return {};
}

Result<void> LicRenderer::ensureLicVolume() {
  if (!field_.image) return inputError("no vector field and noise were set");
  if (licVolume_) {
    const VkExtent3D e = licVolume_.extent();
    if (Dims(e.width, e.height, e.depth) == field_.dims) return {};
  }
  ImageDesc desc;
  desc.format = kLicVolumeFormat;
  desc.extent = {static_cast<std::uint32_t>(field_.dims.x), static_cast<std::uint32_t>(field_.dims.y),
                 static_cast<std::uint32_t>(field_.dims.z)};
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
               VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "lic volume";
  licVolume_ = Image();  // free the old volume before allocating the new one
  LIC3D_TRY_ASSIGN(licVolume_, Image::create(*context_, desc));
  return {};
}

Result<void> LicRenderer::setLicVolume(const ScalarVolume& volume, const LicParams& params) {
  if (!field_.image || volume.dims != field_.dims)
    return inputError("the LIC volume's grid does not match the field's");
  LIC3D_TRY(ensureLicVolume());
  // RG16: the value, and whether the voxel is drawn.
  std::vector<std::uint16_t> texels(2 * volume.values.size());
  for (std::size_t i = 0; i < volume.values.size(); ++i) {
    texels[2 * i] = static_cast<std::uint16_t>(
        std::lround(std::clamp(volume.values[i], 0.0f, 1.0f) * 65535.0f));
    texels[2 * i + 1] = volume.drawn.empty() || volume.drawn[i] ? 65535 : 0;
  }
  LIC3D_TRY(uploadImage(*context_, licVolume_, texels.data(), texels.size() * sizeof(std::uint16_t)));
  LIC3D_TRY(submitAndWait(
      *context_, [&](VkCommandBuffer cmd) { histogramPass_.record(cmd, licVolume_, field_.dims); },
      "lic histogram"));
  statistics_ = lic3d::intensityStatistics(histogramPass_.counts());
  licParams_ = params;
  return {};
}

Result<void> LicRenderer::ensureMask(const SparsityParams& sparsity) {
  if (sparsity.distribution == SparsityDistribution::None) return {};
  if (maskParams_ && *maskParams_ == sparsity) return {};
  LIC3D_TRY_ASSIGN(const SparsityMask mask, makeSparsityMask(sparsity, field_.dims));
  ImageDesc desc;
  desc.format = kSparsityMaskFormat;
  desc.extent = licVolume_.extent();
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "sparsity mask";
  maskParams_.reset();
  mask_ = Image();
  LIC3D_TRY_ASSIGN(mask_, Image::create(*context_, desc));
  LIC3D_TRY(uploadImage(*context_, mask_, mask.black.data(), mask.black.size()));
  maskParams_ = sparsity;
  ++maskBuilds_;
  return {};
}

const Image& LicRenderer::maskFor(const LicParams& params) const {
  return params.sparsity.distribution == SparsityDistribution::None ? emptyMask_ : mask_;
}

VolumeFacts LicRenderer::volumeFacts() const {
  VolumeFacts facts;
  facts.dims = field_.dims;
  facts.geometry = field_.geometry;
  facts.minMagnitude = static_cast<float>(field_.minMagnitude);
  facts.maxMagnitude = static_cast<float>(field_.maxMagnitude);
  facts.intensityMean = statistics_.mean;
  facts.intensityDeviation = statistics_.deviation;
  facts.sparsity =
      licParams_ && licParams_->sparsity.distribution != SparsityDistribution::None;
  return facts;
}

void LicRenderer::recordLicSlab(VkCommandBuffer cmd, const LicParams& params, int zBegin, int zEnd,
                                bool first, bool last, Result<void>& status) {
  if (first) {
    // The old contents are discarded; earlier frames and histograms must be done reading.
    imageBarrier(cmd, licVolume_.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                 kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  } else {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  status = licPass_.record(cmd, field_, maskFor(params), licVolume_, params, zBegin, zEnd);
  if (!status) return;
  if (last) {
    imageBarrier(cmd, licVolume_.handle(), VK_IMAGE_LAYOUT_GENERAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                 VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
    histogramPass_.record(cmd, licVolume_, field_.dims);
  }
}

Result<bool> LicRenderer::updateLic(const LicParams& params, const ProgressCallback& progress) {
  LIC3D_TRY(validate(params));
  if (licParams_ && *licParams_ == params) return false;
  LIC3D_TRY(ensureLicVolume());
  licParams_.reset();
  LIC3D_TRY(ensureMask(params.sparsity));

  const Dims dims = field_.dims;
  const int slab = progress ? (dims.z + kProgressSlabs - 1) / kProgressSlabs : dims.z;
  for (int z = 0; z < dims.z; z += slab) {
    const int zEnd = std::min(dims.z, z + slab);
    Result<void> status;
    LIC3D_TRY(submitAndWait(
        *context_,
        [&](VkCommandBuffer cmd) {
          recordLicSlab(cmd, params, z, zEnd, z == 0, zEnd == dims.z, status);
        },
        "lic compute"));
    LIC3D_TRY(std::move(status));
    if (progress) progress(static_cast<double>(zEnd) / dims.z);
  }
  ++licDispatches_;
  statistics_ = lic3d::intensityStatistics(histogramPass_.counts());
  licParams_ = params;
  return true;
}

Result<void> LicRenderer::ensureTarget(int width, int height) {
  if (width < 1 || height < 1 || width > 16384 || height > 16384)
    return inputError("image size must be 1..16384 pixels per side, got " + std::to_string(width) +
                      "x" + std::to_string(height));
  const std::uint32_t limit = context_->properties().limits.maxImageDimension2D;
  if (static_cast<std::uint32_t>(std::max(width, height)) > limit)
    return inputError("image size " + std::to_string(width) + "x" + std::to_string(height) +
                      " exceeds the device's limit of " + std::to_string(limit));
  if (target_ && target_.format() == frameFormat_ &&
      target_.extent().width == static_cast<std::uint32_t>(width) &&
      target_.extent().height == static_cast<std::uint32_t>(height))
    return {};
  target_ = Image();
  targetReadback_ = Buffer();
  ImageDesc desc;
  desc.type = VK_IMAGE_TYPE_2D;
  desc.format = frameFormat_;
  desc.extent = {static_cast<std::uint32_t>(width), static_cast<std::uint32_t>(height), 1};
  desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.name = "offscreen colour";
  LIC3D_TRY_ASSIGN(target_, Image::create(*context_, desc));
  LIC3D_TRY_ASSIGN(targetReadback_,
                   Buffer::create(*context_, static_cast<VkDeviceSize>(width) * height * 8,
                                  VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback,
                                  "offscreen readback"));
  return {};
}

void LicRenderer::recordFrame(VkCommandBuffer cmd, const ViewParams& view, Result<void>& status) {
  // The previous frame's copy must finish reading before the target is cleared again.
  imageBarrier(cmd, target_.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = target_.view();
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color = {{view.background.r, view.background.g, view.background.b, 1.0f}};
  const VkExtent2D extent{target_.extent().width, target_.extent().height};
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = 1;
  rendering.pColorAttachments = &color;
  vkCmdBeginRendering(cmd, &rendering);

  const VolumeFacts facts = volumeFacts();
  const VkExtent2D eyeExtent{static_cast<std::uint32_t>(view.width),
                             static_cast<std::uint32_t>(view.height)};
  const float aspect = static_cast<float>(view.width) / static_cast<float>(view.height);
  struct Draw {
    Eye eye;
    VkRect2D viewport;
  };
  std::vector<Draw> draws;
  switch (view.stereo) {
    case StereoMode::None: draws = {{Eye::Mono, {{0, 0}, eyeExtent}}}; break;
    case StereoMode::Anaglyph:
      draws = {{Eye::Left, {{0, 0}, eyeExtent}}, {Eye::Right, {{0, 0}, eyeExtent}}};
      break;
    case StereoMode::SideBySide:
      draws = {{Eye::Left, {{0, 0}, eyeExtent}},
               {Eye::Right, {{static_cast<std::int32_t>(view.width), 0}, eyeExtent}}};
      break;
  }
  for (std::uint32_t i = 0; i < draws.size() && status.ok(); ++i) {
    const SliceFrame frame = makeSliceFrame(view, facts, draws[i].eye, aspect);
    status = slicePass_.record(cmd, target_.format(), draws[i].viewport, licVolume_, field_, frame,
                               i);
  }
  vkCmdEndRendering(cmd);
}

Result<RgbaImage> LicRenderer::render(const LicParams& params, const ViewParams& view) {
  LIC3D_TRY(validate(view));
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool recomputed, updateLic(params));
  const int width = view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width;
  LIC3D_TRY(ensureTarget(width, view.height));
  Result<void> status;
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        recordFrame(cmd, view, status);
        imageBarrier(cmd, target_.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_TRANSFER_READ_BIT);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.imageExtent = target_.extent();
        vkCmdCopyImageToBuffer(cmd, target_.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                               targetReadback_.handle(), 1, &region);
        memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                      VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT);
      },
      "render frame"));
  LIC3D_TRY(std::move(status));

  RgbaImage image;
  image.width = width;
  image.height = view.height;
  image.pixels.resize(static_cast<std::size_t>(width) * view.height * 4);
  if (frameFormat_ == VK_FORMAT_R8G8B8A8_UNORM) {
    std::memcpy(image.pixels.data(), targetReadback_.mapped(), image.pixels.size());
  } else {
    const auto* halves = static_cast<const std::uint16_t*>(targetReadback_.mapped());
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      const float v = std::clamp(glm::unpackHalf1x16(halves[i]), 0.0f, 1.0f);
      image.pixels[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
    }
  }
  if (view.legend && view.color == ColorMode::Magnitude) {
    const VolumeFacts facts = volumeFacts();
    const float low = view.autoColorRange ? facts.minMagnitude : view.colorLow;
    const float high = view.autoColorRange ? facts.maxMagnitude : view.colorHigh;
    drawLegend(image, view.colormap, low, high, "|v|", view.background);
  }
  return image;
}

Result<ScalarVolume> LicRenderer::readLicVolume() const {
  if (!licParams_) return inputError("no LIC volume has been computed");
  LIC3D_TRY_ASSIGN(std::vector<std::byte> bytes,
                   readImage(*context_, licVolume_, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4));
  ScalarVolume volume;
  volume.dims = field_.dims;
  volume.geometry = field_.geometry;
  volume.values.resize(voxelCount(field_.dims));
  const bool sparse = licParams_->sparsity.distribution != SparsityDistribution::None;
  if (sparse) volume.drawn.resize(volume.values.size());
  for (std::size_t i = 0; i < volume.values.size(); ++i) {
    std::uint16_t texel[2];
    std::memcpy(texel, bytes.data() + 4 * i, 4);
    volume.values[i] = static_cast<float>(texel[0]) / 65535.0f;
    if (sparse) volume.drawn[i] = texel[1] >= 32768 ? 1 : 0;
  }
  return volume;
}

Result<double> LicRenderer::timeLicDispatch(const LicParams& params) {
  LIC3D_TRY(validate(params));
  if (!timer_.valid()) return unsupportedError("the device has no timestamp queries");
  LIC3D_TRY(ensureLicVolume());
  licParams_.reset();
  LIC3D_TRY(ensureMask(params.sparsity));
  Result<void> status;
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        timer_.reset(cmd, 0);
        imageBarrier(cmd, licVolume_.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                     kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        timer_.begin(cmd, 0);
        status = licPass_.record(cmd, field_, maskFor(params), licVolume_, params, 0,
                                 field_.dims.z);
        timer_.end(cmd, 0);
        imageBarrier(cmd, licVolume_.handle(), VK_IMAGE_LAYOUT_GENERAL,
                     VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                     kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
        histogramPass_.record(cmd, licVolume_, field_.dims);
      },
      "lic timing"));
  LIC3D_TRY(std::move(status));
  ++licDispatches_;
  statistics_ = lic3d::intensityStatistics(histogramPass_.counts());
  licParams_ = params;
  return timer_.milliseconds(0);
}

Result<double> LicRenderer::timeFrame(const ViewParams& view) {
  if (!timer_.valid()) return unsupportedError("the device has no timestamp queries");
  if (!licParams_) return inputError("no LIC volume has been computed");
  LIC3D_TRY(validate(view));
  LIC3D_TRY(ensureTarget(view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width,
                         view.height));
  Result<void> status;
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        timer_.reset(cmd, 1);
        timer_.begin(cmd, 1);
        recordFrame(cmd, view, status);
        timer_.end(cmd, 1);
        // Leave the target as the next frame's barrier expects it (after a copy).
        imageBarrier(cmd, target_.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
                     VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                     VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                     VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                     VK_ACCESS_2_NONE);
      },
      "frame timing"));
  LIC3D_TRY(std::move(status));
  return timer_.milliseconds(1);
}

}  // namespace lic3d
