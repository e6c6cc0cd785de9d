// SPDX-License-Identifier: BSD-3-Clause
// The field texture: uploaded from a host field, made on the device from an analytic field, or
// blended between two resident steps of a time series.
#include "render/field_textures.h"

#include <cmath>
#include <string>
#include <vector>

#include "core/look.h"
#include "gpu/submit.h"

namespace lic3d {

FieldTextures::FieldTextures(const Context& context, FieldPrecision precision, bool separateNoise)
    : context_(&context),
      precision_(resolvePrecision(context, precision)),
      keepSeparateNoise_(separateNoise) {}

double FieldTextures::emptySpeed() const {
  if (!field_.speeds) return 0.0;
  return emptySpaceSpeed(*field_.speeds);
}

std::uint64_t FieldTextures::bytes() const {
  std::uint64_t bytes = field_.image ? field_.image.memorySize() : 0;
  for (const FieldStep& step : timeSteps_) bytes += step.image ? step.image.memorySize() : 0;
  if (blend_) bytes += blend_->noiseBytes();
  return bytes;
}

Result<void> FieldTextures::ensureScalarTexture() {
  if (scalars_.image) return {};
  // Both follow the speed: a texture of one texel stands in (made with the field's upload
  // rather than at creation, so creating a renderer submits nothing).
  LIC3D_TRY_ASSIGN(scalars_, uploadScalars(*context_, Dims{1}, nullptr, nullptr));
  return {};
}

Result<void> FieldTextures::setScalars(const PointScalars* color, const PointScalars* opacity) {
  scalars_ = ScalarTexture();
  LIC3D_TRY_ASSIGN(scalars_, uploadScalars(*context_, field_.dims, color, opacity));
  return {};
}

// ---- Steady fields -----------------------------------------------------------------------------

Result<void> FieldTextures::dropField(Dims dims) {
  // The scalars live on the field's grid.
  if (dims != field_.dims && (scalars_.color || scalars_.opacity)) scalars_ = ScalarTexture();
  LIC3D_TRY(ensureScalarTexture());
  blended_.reset();  // a steady field: any time series' steps are no longer needed
  timeTexture_ = false;
  for (FieldStep& step : timeSteps_) step = FieldStep();
  return {};
}

Result<void> FieldTextures::setAnalyticInputs(const AnalyticInputs& inputs) {
  const Dims dims = inputs.texelDims();
  // Bricks of one size share a texture: only its place in the grid changes.
  const bool reuse = analyticTexture_ && field_.dims == dims &&
                     (inputs.isBrick() || field_.geometry == inputs.texelGeometry());
  if (!analytic_) {
    LIC3D_TRY_ASSIGN(analytic_, AnalyticFieldPass::create(*context_));
  }
  if (!reuse) {
    field_ = FieldTexture();  // free the old texture before allocating the new one
    analyticTexture_ = false;
    LIC3D_TRY_ASSIGN(field_, analytic_->createTarget(inputs, precision_));
    analyticTexture_ = true;
  }
  field_.geometry = inputs.texelGeometry();
  return analytic_->write(inputs, field_);
}

Result<void> FieldTextures::setInputs(const VectorField& field, const NoiseVolume& noise) {
  field_ = FieldTexture();  // free the old texture before allocating the new one
  analyticTexture_ = false;
  LIC3D_TRY_ASSIGN(field_, uploadLicInputs(*context_, field, noise, precision_));
  if (keepSeparateNoise_) {
    separateNoise_ = Image();
    ImageDesc desc;
    desc.format = VK_FORMAT_R8_UNORM;
    desc.extent = extentOf(field.dims);
    desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    desc.name = "separate noise (naive kernel)";
    std::vector<std::uint8_t> bytes(voxelCount(field.dims));
    for (std::size_t i = 0; i < bytes.size(); ++i)
      bytes[i] = static_cast<std::uint8_t>(std::lround(noise.value(i) * 255.0f));
    LIC3D_TRY_ASSIGN(separateNoise_, Image::create(*context_, desc));
    LIC3D_TRY(uploadImage(*context_, separateNoise_, bytes.data(), bytes.size()));
  }
  return {};
}

// ---- Unsteady fields ---------------------------------------------------------------------------

Result<void> FieldTextures::setTimeNoise(const NoiseVolume& noise) {
  LIC3D_TRY(ensureScalarTexture());
  if (!blend_) {
    LIC3D_TRY_ASSIGN(TimeBlendPass pass, TimeBlendPass::create(*context_));
    blend_.emplace(std::move(pass));
  }
  vkQueueWaitIdle(context_->queue());  // a blend may still read the old noise
  LIC3D_TRY(blend_->setNoise(noise));
  blended_.reset();  // the texture's noise must be written again
  // A new series: its step k is not the last series' step k.
  for (FieldStep& step : timeSteps_) step = FieldStep();
  return {};
}

const FieldStep* FieldTextures::residentStep(int index) const {
  for (const FieldStep& step : timeSteps_)
    if (step.image && step.index == index) return &step;
  return nullptr;
}

bool FieldTextures::hasTimeStep(int index) const { return residentStep(index) != nullptr; }

Result<void> FieldTextures::setTimeStep(int index, const VectorField& step, int keep) {
  if (hasTimeStep(index)) return {};
  const int slot = timeSteps_[0].image && timeSteps_[0].index == keep ? 1 : 0;
  const int replaced = timeSteps_[slot].index;
  if (blended_ && (blended_->first == replaced || blended_->second == replaced)) blended_.reset();
  timeSteps_[slot] = FieldStep();  // free the old step before allocating the new one
  LIC3D_TRY_ASSIGN(timeSteps_[slot], uploadFieldStep(*context_, step, index, precision_));
  return {};
}

Result<std::optional<Dims>> FieldTextures::blendGrid(int first, int second, double weight) const {
  const FieldStep* a = residentStep(first);
  if (!a || !residentStep(second))
    return inputError("time steps " + std::to_string(first) + " and " + std::to_string(second) +
                      " must be resident before interpolating between them");
  if (!blend_) return inputError("the time series' noise was not set");
  if (blended_ && *blended_ == TimeKey{first, second, weight}) return std::optional<Dims>();
  // The texture the blend writes, made once per grid (it replaces a steady field's).
  if (!timeTexture_ || field_.dims != a->dims || !(field_.geometry == a->geometry))
    return std::optional<Dims>(a->dims);
  return std::optional<Dims>();
}

Result<bool> FieldTextures::blendTime(int first, int second, double weight) {
  LIC3D_TRY_ASSIGN(const std::optional<Dims> grid, blendGrid(first, second, weight));
  const TimeKey key{first, second, weight};
  if (blended_ && *blended_ == key) return false;
  const FieldStep& a = *residentStep(first);
  const FieldStep& b = *residentStep(second);
  if (grid) {
    vkDeviceWaitIdle(context_->device());  // frames in flight may read the old texture
    field_ = FieldTexture();
    timeTexture_ = false;
    analyticTexture_ = false;
    LIC3D_TRY_ASSIGN(field_, blend_->createTarget(a.dims, a.geometry, precision_));
    timeTexture_ = true;
  }
  blended_.reset();
  LIC3D_TRY(blend_->blend(a, b, weight, field_));
  blended_ = key;
  return true;
}

}  // namespace lic3d
