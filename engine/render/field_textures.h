// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The textures a LIC volume is made from and drawn with: the field and its noise in one texture
// (uploaded from the host, made on the device from an analytic field, or blended on the device
// between two resident steps of a time series), and the scalars colour and opacity follow.

#include <cstdint>
#include <optional>

#include "core/error.h"
#include "core/volume.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "passes/analytic_field_pass.h"
#include "passes/time_blend_pass.h"
#include "passes/volume_textures.h"

namespace lic3d {

class FieldTextures {
 public:
  FieldTextures() = default;
  // `context` must outlive the textures. With `separateNoise` the noise of host inputs is also
  // kept in an R8 texture of its own (the naive LIC kernel's).
  FieldTextures(const Context& context, FieldPrecision precision, bool separateNoise);

  // What any new field resets: the scalars of another grid, a time series' steps and blend.
  // The caller makes sure no work in flight reads the textures.
  Result<void> dropField(Dims dims);
  // The field texture from a host field and noise on its grid (after dropField).
  Result<void> setInputs(const VectorField& field, const NoiseVolume& noise);
  // The field texture made on the device (after dropField); a texture of the same grid is
  // rewritten in place.
  Result<void> setAnalyticInputs(const AnalyticInputs& inputs);
  // Scalars on the field's grid, null for the speed. The caller makes sure no work in flight
  // reads the old texture.
  Result<void> setScalars(const PointScalars* color, const PointScalars* opacity);

  // ---- Unsteady fields (docs/TIME.md) ---------------------------------------------------------
  Result<void> setTimeNoise(const NoiseVolume& noise);
  Result<void> setTimeStep(int index, const VectorField& step, int keep);
  bool hasTimeStep(int index) const;
  // The grid of the new field texture blendTime(first, second, weight) would make; nullopt when
  // it writes the current one or nothing at all. Fails as blendTime does.
  Result<std::optional<Dims>> blendGrid(int first, int second, double weight) const;
  // The field becomes (1 - w) step `first` + w step `second`, both resident. Returns whether
  // the field texture changed.
  Result<bool> blendTime(int first, int second, double weight);
  // GPU milliseconds of the last blend (0 before any or without timestamp queries).
  double lastBlendMilliseconds() const { return blend_ ? blend_->lastMilliseconds() : 0.0; }

  const FieldTexture& field() const { return field_; }
  const ScalarTexture& scalars() const { return scalars_; }
  // The noise in a texture of its own (separateNoise), null otherwise.
  const Image* separateNoise() const { return separateNoise_ ? &separateNoise_ : nullptr; }
  bool keepsSeparateNoise() const { return keepSeparateNoise_; }
  // Physical |v| below which voxels are empty space, left out of the LIC histogram: a fraction
  // kEmptySpeedFraction of the field's fast speeds (core/look.h).
  double emptySpeed() const;
  // Bytes of device memory the field texture and the resident steps hold.
  std::uint64_t bytes() const;

 private:
  Result<void> ensureScalarTexture();
  const FieldStep* residentStep(int index) const;

  const Context* context_ = nullptr;
  FieldPrecision precision_ = FieldPrecision::Auto;
  bool keepSeparateNoise_ = false;
  FieldTexture field_;
  Image separateNoise_;    // R8, only for the naive kernel
  ScalarTexture scalars_;  // colour and opacity scalars (1x1x1 while both follow the speed)
  // Unsteady fields: the pass, the two resident steps and what the field texture was made from.
  std::optional<TimeBlendPass> blend_;
  FieldStep timeSteps_[2];
  struct TimeKey {
    int first, second;
    double weight;
    bool operator==(const TimeKey&) const = default;
  };
  std::optional<TimeKey> blended_;
  bool timeTexture_ = false;  // field_ is written by blend_ (not uploaded)
  std::optional<AnalyticFieldPass> analytic_;
  bool analyticTexture_ = false;  // field_ is written by analytic_ (not uploaded)
};

}  // namespace lic3d
