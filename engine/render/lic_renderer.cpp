// SPDX-License-Identifier: BSD-3-Clause
#include "render/lic_renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <glm/gtc/packing.hpp>

#include "core/look.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "gpu/submit.h"
#include "gpu/vk_check.h"
#include "lic/legend.h"

namespace lic3d {
namespace {

// With progress reporting the pass is split into this many slabs along z (at most).
constexpr int kProgressSlabs = 16;

constexpr VkPipelineStageFlags2 kVolumeReaders =
    VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;

}  // namespace

Result<LicRenderer> LicRenderer::create(const Context& context, const RendererOptions& options) {
  const StageTimer timer("pipelines");
  LicRenderer renderer;
  renderer.context_ = &context;
  renderer.precision_ = resolvePrecision(context, options.fieldPrecision);
  renderer.doubleBuffered_ = options.doubleBuffered;
  LIC3D_TRY(renderer.setFramePrecision(options.framePrecision));
  LIC3D_TRY_ASSIGN(renderer.licPass_,
                   LicPass::create(context, options.naiveLicKernel, options.licLaunch));
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
                            " cannot use RG16_UNORM as a filtered storage image");
  return renderer;
}

double LicRenderer::emptySpeed() const {
  if (!field_.speeds) return 0.0;
  return kEmptySpeedFraction * field_.speeds->percentile(1.0 - kLookRangeTail);
}

Result<void> LicRenderer::ensureScalarTexture() {
  if (scalars_.image) return {};
  // Both follow the speed: a texture of one texel stands in (made with the field's upload
  // rather than at creation, so creating a renderer submits nothing).
  LIC3D_TRY_ASSIGN(scalars_, uploadScalars(*context_, Dims{1}, nullptr, nullptr));
  return {};
}

Result<void> LicRenderer::setScalars(const PointScalars* color, const PointScalars* opacity) {
  vkDeviceWaitIdle(context_->device());  // in-flight frames may sample the old texture
  scalars_ = ScalarTexture();
  LIC3D_TRY_ASSIGN(scalars_, uploadScalars(*context_, field_.dims, color, opacity));
  return {};
}

Result<void> LicRenderer::setFramePrecision(FramePrecision precision) {
  const VkFormat format = precision == FramePrecision::Float16   ? VK_FORMAT_R16G16B16A16_SFLOAT
                          : precision == FramePrecision::Unorm16 ? VK_FORMAT_R16G16B16A16_UNORM
                          : precision == FramePrecision::Unorm10
                              ? VK_FORMAT_A2B10G10R10_UNORM_PACK32
                              : VK_FORMAT_R8G8B8A8_UNORM;
  if (!supportsFormat(*context_, format, VK_FORMAT_FEATURE_2_COLOR_ATTACHMENT_BLEND_BIT))
    return unsupportedError(context_->deviceInfo().name + " cannot blend into the frame format");
  frameFormat_ = format;
  return {};
}

LicRenderer::~LicRenderer() {
  // Frames recorded by the caller may still use the volumes.
  if (context_) vkDeviceWaitIdle(context_->device());
}

Result<void> LicRenderer::ensureVolumes() {
  if (!field_.image) return inputError("no vector field and noise were set");
  for (int i = 0; i < (doubleBuffered_ ? 2 : 1); ++i) {
    if (volumes_[i]) continue;
    ImageDesc desc;
    desc.format = kLicVolumeFormat;
    desc.extent = extentOf(field_.dims);
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                 VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.name = i == 0 ? "lic volume A" : "lic volume B";
    LIC3D_TRY_ASSIGN(volumes_[i], Image::create(*context_, desc));
  }
  return {};
}

Result<void> LicRenderer::setLicVolume(const ScalarVolume& volume, const LicParams& params) {
  if (!field_.image || volume.dims != field_.dims)
    return inputError("the LIC volume's grid does not match the field's");
  LIC3D_TRY(ensureVolumes());
  job_.reset();
  // RG16: the value, and whether the voxel is drawn.
  std::vector<std::uint16_t> texels(2 * volume.values.size());
  for (std::size_t i = 0; i < volume.values.size(); ++i) {
    texels[2 * i] = static_cast<std::uint16_t>(
        std::lround(std::clamp(volume.values[i], 0.0f, 1.0f) * 65535.0f));
    texels[2 * i + 1] = volume.drawn.empty() || volume.drawn[i] ? 65535 : 0;
  }
  vkQueueWaitIdle(context_->queue());  // frames may still read the shown volume
  LIC3D_TRY(
      uploadImage(*context_, frontVolume(), texels.data(), texels.size() * sizeof(std::uint16_t)));
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        histogramPass_.record(cmd, frontVolume(), field_, emptySpeed(), 0);
      },
      "lic histogram"));
  // No job finished here: the statistics are this volume's histogram, taken directly.
  finished_.reset();
  statistics_ = lic3d::intensityStatistics(histogramPass_.counts(0));
  shownParams_ = params;
  return {};
}

const Image& LicRenderer::maskFor(const LicParams& params) const {
  return params.sparsity.distribution == SparsityDistribution::None ? emptyMask_ : mask_;
}

std::optional<double> LicRenderer::hiddenFraction() const {
  if (!hasVolume() || !shownParams_ ||
      shownParams_->sparsity.distribution == SparsityDistribution::None)
    return std::nullopt;
  return static_cast<double>(statistics_.maskedVoxels) /
         static_cast<double>(std::max<std::size_t>(voxelCount(field_.dims), 1));
}

VolumeFacts LicRenderer::volumeFacts() const {
  VolumeFacts facts;
  facts.dims = field_.dims;
  facts.geometry = field_.geometry;
  facts.minMagnitude = static_cast<float>(field_.minMagnitude);
  facts.maxMagnitude = static_cast<float>(field_.maxMagnitude);
  facts.texelToPhysical = glm::vec3(field_.texelToPhysical);
  facts.fieldPrecision = field_.precision;
  facts.intensityMean = statistics_.mean;
  facts.intensityDeviation = statistics_.deviation;
  facts.intensities = statistics_.histogram;
  facts.colorValues = field_.speeds;
  facts.opacityValues = field_.speeds;
  facts.colorScalar = scalars_.color;
  facts.opacityScalar = scalars_.opacity;
  facts.scalarRange = scalars_.range;
  facts.colorUnit = field_.unit;
  if (scalars_.color) {
    facts.colorValues = scalars_.colorValues;
    facts.minMagnitude = static_cast<float>(scalars_.colorValues->min);
    facts.maxMagnitude = static_cast<float>(scalars_.colorValues->max);
    facts.colorName = scalars_.colorName;
    facts.colorUnit = scalars_.colorUnit;
  }
  if (scalars_.opacity) facts.opacityValues = scalars_.opacityValues;
  const std::size_t voxels = voxelCount(field_.dims);
  facts.drawnFraction = statistics_.histogram && voxels > 0
                            ? static_cast<float>(static_cast<double>(statistics_.voxels) /
                                                 static_cast<double>(voxels))
                            : 1.0f;
  facts.sparsity =
      shownParams_ && shownParams_->sparsity.distribution != SparsityDistribution::None;
  return facts;
}

std::uint64_t LicRenderer::volumeBytes() const {
  std::uint64_t bytes = field_.image ? field_.image.memorySize() : 0;
  for (const Image& v : volumes_) bytes += v ? v.memorySize() : 0;
  for (const FieldStep& step : timeSteps_) bytes += step.image ? step.image.memorySize() : 0;
  if (interpolation_) bytes += interpolation_->noiseBytes();
  return bytes + (mask_ ? mask_.memorySize() : 0);
}

LicStatus LicRenderer::licStatus() const {
  LicStatus status;
  if (!job_) {
    status.pending = finished_.has_value();
    return status;
  }
  status.pending = true;
  status.fraction = field_.dims.z > 0 ? static_cast<double>(job_->nextZ) / field_.dims.z : 0.0;
  status.waitingForMask = job_->needsMask;
  return status;
}

// ---- Jobs --------------------------------------------------------------------------------------

Result<void> LicRenderer::startJob(const LicParams& params, bool force) {
  LIC3D_TRY(validate(params));
  if (!field_.image) return inputError("no vector field and noise were set");
  const SparsityParams sparsity = maskParams(params);
  LIC3D_TRY(validate(sparsity, piece_ ? piece_->wholeDims : field_.dims));
  if (!force && job_ && job_->params == params) return {};
  fieldChanged_ = false;  // the job reads the field texture as it is now
  Job job;
  job.params = params;
  job.needsMask = sparsity.distribution != SparsityDistribution::None &&
                  !(maskParams_ && *maskParams_ == sparsity);
  if (job.needsMask && job_ && job_->needsMask && maskParams(job_->params) == sparsity) {
    // The mask the dropped job was waiting for serves this one (a new field, e.g. the next
    // time of a series, does not change it): not made again, and not waited for here.
    job.mask = job_->mask;
  } else if (job.needsMask) {
    // Some distributions take seconds (best candidate): never on the thread that draws.
    job.mask = std::async(std::launch::async, [sparsity, dims = field_.dims, piece = piece_] {
                 return piece ? makeSparsityMaskPiece(sparsity, *piece, dims)
                              : makeSparsityMask(sparsity, dims);
               }).share();
  }
  job_ = std::move(job);
  return {};
}

Result<void> LicRenderer::requestLic(const LicParams& params) {
  const std::optional<LicParams>& latest = finished_ ? finished_->params : shownParams_;
  if (!job_ && latest && *latest == params && !fieldChanged_) return {};
  return startJob(params, fieldChanged_);
}

Result<void> LicRenderer::uploadMask(const SparsityMask& mask) {
  ImageDesc desc;
  desc.format = kSparsityMaskFormat;
  desc.extent = extentOf(field_.dims);
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "sparsity mask";
  // Slabs of an earlier job recorded into frames still in flight may read the old mask.
  vkQueueWaitIdle(context_->queue());
  maskParams_.reset();
  mask_ = Image();
  LIC3D_TRY_ASSIGN(mask_, Image::create(*context_, desc));
  LIC3D_TRY(uploadImage(*context_, mask_, mask.black.data(), mask.black.size()));
  maskBeyond_ = mask.beyond;
  ++maskBuilds_;
  return {};
}

// Whether the job's mask is on the GPU; uploads it when the worker has finished it.
Result<bool> LicRenderer::prepareMask() {
  if (!job_->needsMask) return true;
  if (job_->mask.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return false;
  const Result<SparsityMask> mask = job_->mask.get();
  if (!mask) {
    Error error = mask.error();
    job_.reset();
    return error;
  }
  StageTimer uploading("mask upload");
  LIC3D_TRY(uploadMask(*mask));
  uploading.stop();
  maskParams_ = maskParams(job_->params);
  job_->needsMask = false;
  return true;
}

Result<LicWork> LicRenderer::recordLicWork(VkCommandBuffer cmd, int maxSlices, std::uint32_t slot) {
  LicWork work;
  // A finished volume waits for collectStatistics; the next job would overwrite it.
  if (!job_ || finished_) return work;
  LIC3D_TRY_ASSIGN(const bool maskReady, prepareMask());
  if (!maskReady) {
    work.waitingForMask = true;
    return work;
  }
  LIC3D_TRY(ensureVolumes());
  const Dims dims = field_.dims;
  Image& back = backVolume();
  const int zBegin = job_->nextZ;
  // Whole workgroups: a slab thinner than a workgroup is deep would leave invocations idle.
  const int depth = licPass_.launchDepth();
  const int slices = (std::max(1, maxSlices) + depth - 1) / depth * depth;
  const int zEnd = std::min(dims.z, zBegin + slices);
  if (zBegin == 0) {
    // The old contents are discarded; earlier frames and histograms must be done reading.
    if (!doubleBuffered_) shownParams_.reset();
    imageBarrier(cmd, back.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                 kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE,
                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  } else {
    memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
                  VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  }
  LIC3D_TRY(licPass_.record(cmd, field_, maskFor(job_->params), maskBeyond_, back, job_->params,
                            zBegin, zEnd, separateNoise_ ? &separateNoise_ : nullptr));
  work.slicesRecorded = zEnd - zBegin;
  job_->nextZ = zEnd;
  if (zEnd < dims.z) return work;

  imageBarrier(cmd, back.handle(), VK_IMAGE_LAYOUT_GENERAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
               VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, kVolumeReaders | VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_TRANSFER_READ_BIT);
  histogramPass_.record(cmd, back, field_, emptySpeed(), slot);
  // Shown once its statistics are read back: a frame never draws a volume with another's
  // contrast stretch.
  finished_ = Finished{job_->params, slot};
  job_.reset();
  ++licDispatches_;
  work.finished = true;
  return work;
}

void LicRenderer::collectStatistics(std::uint32_t slot) {
  if (!finished_ || finished_->slot != slot) return;
  statistics_ = lic3d::intensityStatistics(histogramPass_.counts(slot));
  if (doubleBuffered_) front_ = 1 - front_;
  shownParams_ = finished_->params;
  finished_.reset();
}

Result<bool> LicRenderer::updateLic(const LicParams& params, const ProgressCallback& progress) {
  if (!job_ && shownParams_ && *shownParams_ == params && !fieldChanged_) return false;
  LIC3D_TRY(startJob(params, fieldChanged_));
  const int slab = progress ? (field_.dims.z + kProgressSlabs - 1) / kProgressSlabs : field_.dims.z;
  while (job_) {
    if (job_->needsMask) {
      const StageTimer timer("mask");
      job_->mask.wait();
    }
    Result<LicWork> work = LicWork{};
    const StageTimer timer("LIC");
    LIC3D_TRY(submitAndWait(
        *context_, [&](VkCommandBuffer cmd) { work = recordLicWork(cmd, slab, 0); },
        "lic compute"));
    LIC3D_TRY(work);
    if (work->finished) collectStatistics(0);
    if (progress && work->slicesRecorded > 0)
      progress(job_ ? static_cast<double>(job_->nextZ) / field_.dims.z : 1.0);
  }
  return true;
}

// ---- Drawing -----------------------------------------------------------------------------------

Result<void> LicRenderer::recordDraw(VkCommandBuffer cmd, VkFormat format, VkRect2D area,
                                     const ViewParams& view, std::uint32_t slotBase) {
  if (!hasVolume()) return {};
  LIC3D_TRY(validate(view));
  LIC3D_TRY(slicePass_.setTransferFunction(view.transfer, view.colormap));
  const VolumeFacts facts = volumeFacts();
  const bool sideBySide = view.stereo == StereoMode::SideBySide;
  const VkExtent2D eyeExtent{sideBySide ? area.extent.width / 2 : area.extent.width,
                             area.extent.height};
  const float aspect = static_cast<float>(eyeExtent.width) / static_cast<float>(eyeExtent.height);
  struct Draw {
    Eye eye;
    VkRect2D viewport;
  };
  std::vector<Draw> draws;
  const VkOffset2D at = area.offset;
  const VkOffset2D right{at.x + static_cast<std::int32_t>(eyeExtent.width), at.y};
  switch (view.stereo) {
    case StereoMode::None: draws = {{Eye::Mono, {at, eyeExtent}}}; break;
    case StereoMode::Anaglyph:
      draws = {{Eye::Left, {at, eyeExtent}}, {Eye::Right, {at, eyeExtent}}};
      break;
    case StereoMode::SideBySide:
      draws = {{Eye::Left, {at, eyeExtent}}, {Eye::Right, {right, eyeExtent}}};
      break;
  }
  for (std::uint32_t i = 0; i < draws.size(); ++i) {
    const SliceFrame frame = makeSliceFrame(view, facts, draws[i].eye, aspect);
    LIC3D_TRY(slicePass_.record(cmd, format, draws[i].viewport, frontVolume(), field_,
                                scalars_.image, frame, slotBase + i));
  }
  return {};
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
  LIC3D_TRY_ASSIGN(
      targetReadback_,
      Buffer::create(*context_, static_cast<VkDeviceSize>(width) * height * 8,
                     VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback, "offscreen readback"));
  return {};
}

void LicRenderer::recordOffscreenFrame(VkCommandBuffer cmd, const ViewParams& view,
                                       Result<void>& status) {
  // The previous frame's copy must finish reading before the target is cleared again.
  imageBarrier(cmd, target_.handle(), VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT);
  const VkExtent2D extent{target_.extent().width, target_.extent().height};
  beginClearedRendering(cmd, target_.view(), extent, view.background);
  const glm::ivec4 p = pictureLayoutFor(view).picture;
  status = recordDraw(
      cmd, target_.format(),
      {{p.x, p.y}, {static_cast<std::uint32_t>(p.z), static_cast<std::uint32_t>(p.w)}}, view, 0);
  vkCmdEndRendering(cmd);
}

Result<RgbaImage> LicRenderer::render(const LicParams& params, const ViewParams& view) {
  LIC3D_TRY(validate(view));
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool recomputed, updateLic(params));
  const int width = view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width;
  LIC3D_TRY(ensureTarget(width, view.height));
  Result<void> status;
  StageTimer drawing("frame");
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        recordOffscreenFrame(cmd, view, status);
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
  drawing.stop();

  StageTimer reading("frame read-back");
  RgbaImage image;
  image.width = width;
  image.height = view.height;
  image.pixels.resize(static_cast<std::size_t>(width) * view.height * 4);
  if (frameFormat_ == VK_FORMAT_R8G8B8A8_UNORM) {
    std::memcpy(image.pixels.data(), targetReadback_.mapped(), image.pixels.size());
  } else if (frameFormat_ == VK_FORMAT_A2B10G10R10_UNORM_PACK32) {
    const auto* packed = static_cast<const std::uint32_t*>(targetReadback_.mapped());
    parallelChunks(image.pixels.size() / 4, [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const std::uint32_t p = packed[i];
        for (int c = 0; c < 3; ++c)  // round(v / 1023 * 255) in integers
          image.pixels[4 * i + c] =
              static_cast<std::uint8_t>((((p >> (10 * c)) & 1023u) * 255u + 511u) / 1023u);
        image.pixels[4 * i + 3] = static_cast<std::uint8_t>((p >> 30) * 85u);
      }
    });
  } else if (frameFormat_ == VK_FORMAT_R16G16B16A16_UNORM) {
    const auto* shorts = static_cast<const std::uint16_t*>(targetReadback_.mapped());
    parallelChunks(image.pixels.size(), [&](std::size_t begin, std::size_t end) {
      // Exactly round(v / 65535 * 255): (v * 255 + 32767) / 65535 in integers.
      for (std::size_t i = begin; i < end; ++i)
        image.pixels[i] = static_cast<std::uint8_t>((shorts[i] * 255u + 32767u) / 65535u);
    });
  } else {
    const auto* halves = static_cast<const std::uint16_t*>(targetReadback_.mapped());
    parallelChunks(image.pixels.size(), [&](std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) {
        const float v = std::clamp(glm::unpackHalf1x16(halves[i]), 0.0f, 1.0f);
        image.pixels[i] = static_cast<std::uint8_t>(std::lround(v * 255.0f));
      }
    });
  }
  reading.stop();
  const StageTimer annotating("annotation");
  const std::optional<LegendSpec> legend = legendFor(view);
  const PictureLayout layout = pictureLayoutFor(view);
  if (legend) drawLegend(image, layout, *legend, view.background);
  drawTitle(image, layout, view.title, view.background);
  if (view.axes && view.stereo != StereoMode::SideBySide) {
    const VolumeFacts facts = volumeFacts();
    const glm::ivec4 area = layout.picture;
    const SliceFrame frame = makeSliceFrame(
        view, facts, Eye::Mono, static_cast<float>(area.z) / static_cast<float>(area.w));
    drawBoxAxes(image,
                projectBoxAxes(frame.camera, view.camera.orthographic, frame.halfExtent, facts.dims,
                               facts.geometry, area),
                view.background);
  }
  return image;
}

std::optional<LegendSpec> LicRenderer::legendFor(const ViewParams& view) const {
  if (!view.legend || view.color != ColorMode::Magnitude) return std::nullopt;
  const VolumeFacts facts = volumeFacts();
  const ColorRange range = colorRange(view, facts.transfer());
  return LegendSpec{[view](float t) { return viewColor(view, t); }, range.low, range.high,
                    legendTitle(facts.colorName, facts.colorUnit)};
}

PictureLayout LicRenderer::pictureLayoutFor(const ViewParams& view) const {
  const int width = view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width;
  const std::optional<LegendSpec> legend = legendFor(view);
  return pictureLayout(width, view.height, legend ? &*legend : nullptr, view.title);
}

Result<ScalarVolume> LicRenderer::readLicVolume() const {
  if (!shownParams_) return inputError("no LIC volume has been computed");
  const StageTimer timer("volume read-back");
  ScalarVolume volume;
  volume.dims = field_.dims;
  volume.geometry = field_.geometry;
  resizeLarge(volume.values, voxelCount(field_.dims));
  const bool sparse = shownParams_->sparsity.distribution != SparsityDistribution::None;
  if (sparse) resizeLarge(volume.drawn, volume.values.size());
  // Converted straight from the read-back buffer: RG16, the value and whether it is drawn.
  LIC3D_TRY(readImageWith(*context_, frontVolume(), VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, 4,
                          [&](const void* texels, std::size_t) {
                            const auto* bytes = static_cast<const std::byte*>(texels);
                            parallelChunks(
                                volume.values.size(), [&](std::size_t begin, std::size_t end) {
                                  for (std::size_t i = begin; i < end; ++i) {
                                    std::uint16_t texel[2];
                                    std::memcpy(texel, bytes + 4 * i, 4);
                                    volume.values[i] = static_cast<float>(texel[0]) / 65535.0f;
                                    if (sparse) volume.drawn[i] = texel[1] >= 32768 ? 1 : 0;
                                  }
                                });
                          }));
  return volume;
}

Result<double> LicRenderer::timeLicDispatch(const LicParams& params) {
  if (!timer_.valid()) return unsupportedError("the device has no timestamp queries");
  LIC3D_TRY(startJob(params, true));
  if (job_->needsMask) job_->mask.wait();
  LIC3D_TRY_ASSIGN([[maybe_unused]] const bool maskReady, prepareMask());
  Result<LicWork> work = LicWork{};
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        timer_.reset(cmd, 0);
        timer_.begin(cmd, 0);
        work = recordLicWork(cmd, field_.dims.z, 0);
        timer_.end(cmd, 0);
      },
      "lic timing"));
  LIC3D_TRY(work);
  collectStatistics(0);
  return timer_.milliseconds(0);
}

Result<double> LicRenderer::timeFrame(const ViewParams& view) {
  if (!timer_.valid()) return unsupportedError("the device has no timestamp queries");
  if (!hasVolume()) return inputError("no LIC volume has been computed");
  LIC3D_TRY(validate(view));
  LIC3D_TRY(ensureTarget(view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width,
                         view.height));
  Result<void> status;
  LIC3D_TRY(submitAndWait(
      *context_,
      [&](VkCommandBuffer cmd) {
        timer_.reset(cmd, 1);
        timer_.begin(cmd, 1);
        recordOffscreenFrame(cmd, view, status);
        timer_.end(cmd, 1);
        // Leave the target as the next frame's barrier expects it (after a copy).
        imageBarrier(
            cmd, target_.handle(), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
            VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
            VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_NONE);
      },
      "frame timing"));
  LIC3D_TRY(std::move(status));
  return timer_.milliseconds(1);
}

}  // namespace lic3d
