// SPDX-License-Identifier: BSD-3-Clause
// LicRenderer's field texture (render/lic_renderer.h): uploaded from a host field, made on the
// device from an analytic field, or interpolated between two resident steps of a time series.
#include <cmath>
#include <vector>

#include "gpu/submit.h"
#include "render/lic_renderer.h"

namespace lic3d {

// ---- Steady fields -----------------------------------------------------------------------------

Result<void> LicRenderer::replaceField(Dims dims, const std::optional<FieldPiece>& piece) {
  // In-flight frames may still read the old texture and volumes.
  vkDeviceWaitIdle(context_->device());
  job_.reset();
  finished_.reset();
  shownParams_.reset();
  if (piece != piece_) maskParams_.reset();  // a piece's mask is cut from the whole one
  piece_ = piece;
  if (dims != field_.dims) {
    maskParams_.reset();  // the mask, the volumes and the scalars live on the field's grid
    mask_ = Image();
    volumes_[0] = Image();
    volumes_[1] = Image();
    if (scalars_.color || scalars_.opacity) scalars_ = ScalarTexture();
  }
  LIC3D_TRY(ensureScalarTexture());
  interpolated_.reset();  // a steady field: any time series' steps are no longer needed
  fieldChanged_ = false;
  timeTexture_ = false;
  for (FieldStep& step : timeSteps_) step = FieldStep();
  return {};
}

Result<void> LicRenderer::setAnalyticInputs(const AnalyticInputs& inputs) {
  if (licPass_.separateNoise())
    return unsupportedError(
        "the naive kernel reads the noise from a texture of its own: set the "
        "field and noise from the host");
  const Dims dims = inputs.texelDims();
  // Bricks of one size share a texture: only its place in the grid changes.
  const bool reuse = analyticTexture_ && field_.dims == dims &&
                     (inputs.isBrick() || field_.geometry == inputs.texelGeometry());
  std::optional<FieldPiece> piece;
  if (inputs.isBrick()) piece = FieldPiece{.wholeDims = inputs.dims, .offset = inputs.brickOffset};
  LIC3D_TRY(replaceField(dims, piece));
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

Result<void> LicRenderer::setInputs(const VectorField& field, const NoiseVolume& noise) {
  LIC3D_TRY(replaceField(field.dims, field.piece));
  field_ = FieldTexture();  // free the old texture before allocating the new one
  analyticTexture_ = false;
  LIC3D_TRY_ASSIGN(field_, uploadLicInputs(*context_, field, noise, precision_));
  if (licPass_.separateNoise()) {
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

Result<void> LicRenderer::setTimeNoise(const NoiseVolume& noise) {
  LIC3D_TRY(ensureScalarTexture());
  if (!interpolation_) {
    LIC3D_TRY_ASSIGN(TimeBlendPass pass, TimeBlendPass::create(*context_));
    interpolation_.emplace(std::move(pass));
  }
  vkQueueWaitIdle(context_->queue());  // an interpolation may still read the old noise
  LIC3D_TRY(interpolation_->setNoise(noise));
  interpolated_.reset();  // the texture's noise must be written again
  // A new series: its step k is not the last series' step k.
  for (FieldStep& step : timeSteps_) step = FieldStep();
  return {};
}

bool LicRenderer::hasTimeStep(int index) const {
  for (const FieldStep& step : timeSteps_)
    if (step.image && step.index == index) return true;
  return false;
}

Result<void> LicRenderer::setTimeStep(int index, const VectorField& step, int keep) {
  if (hasTimeStep(index)) return {};
  const int slot = timeSteps_[0].image && timeSteps_[0].index == keep ? 1 : 0;
  const int replaced = timeSteps_[slot].index;
  if (interpolated_ && (interpolated_->first == replaced || interpolated_->second == replaced))
    interpolated_.reset();
  timeSteps_[slot] = FieldStep();  // free the old step before allocating the new one
  LIC3D_TRY_ASSIGN(timeSteps_[slot], uploadFieldStep(*context_, step, index, precision_));
  return {};
}

Result<void> LicRenderer::blendTime(int first, int second, double weight) {
  const FieldStep* a = nullptr;
  const FieldStep* b = nullptr;
  for (const FieldStep& step : timeSteps_) {
    if (step.image && step.index == first) a = &step;
    if (step.image && step.index == second) b = &step;
  }
  if (!a || !b)
    return inputError("time steps " + std::to_string(first) + " and " + std::to_string(second) +
                      " must be resident before interpolating between them");
  if (!interpolation_) return inputError("the time series' noise was not set");
  const TimeKey key{first, second, weight};
  if (interpolated_ && *interpolated_ == key) return {};
  // The texture the interpolation writes, made once per grid (it replaces a steady field's).
  if (!timeTexture_ || field_.dims != a->dims || !(field_.geometry == a->geometry)) {
    vkDeviceWaitIdle(context_->device());  // frames in flight may read the old texture
    if (a->dims != field_.dims) {
      job_.reset();
      finished_.reset();
      shownParams_.reset();
      maskParams_.reset();
      mask_ = Image();
      volumes_[0] = Image();
      volumes_[1] = Image();
    }
    piece_.reset();
    field_ = FieldTexture();
    timeTexture_ = false;
    analyticTexture_ = false;
    LIC3D_TRY_ASSIGN(field_, interpolation_->createTarget(a->dims, a->geometry, precision_));
    timeTexture_ = true;
  }
  interpolated_.reset();
  LIC3D_TRY(interpolation_->blend(*a, *b, weight, field_));
  interpolated_ = key;
  fieldChanged_ = true;
  return {};
}

}  // namespace lic3d
