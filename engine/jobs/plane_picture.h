// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// One 2D LIC picture of a session's plane (thesis chapter 3): the recipe `lic3d render2d` and the
// app's 2D mode share. The plane of the field (plane_inputs.h), the noise at the image's size, the
// LIC image on the GPU (passes/lic2d_pass.h) or with the CPU reference (lic/lic2d_reference.h),
// and its colouring (lic/colouring.h). Each step is redone only when what it depends on changed,
// so that the frames of an animation and the app's edits redo the least.

#include <optional>

#include "core/error.h"
#include "core/rgba_image.h"
#include "core/session.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"
#include "lic/lic_reference.h"
#include "loading/plane_inputs.h"
#include "passes/lic2d_pass.h"

namespace lic3d {

class PlanePicture {
 public:
  // Until useGpu, the LIC comes from the CPU reference. The GPU is taken separately so that a
  // command can check its inputs before it opens a device.
  PlanePicture() = default;
  // Makes the LIC on `context`'s GPU from now on; `context` must outlive the picture.
  Result<void> useGpu(const Context& context);
  bool onGpu() const { return pass_.has_value(); }

  // Brings the field and the noise to `session`. The plane of its field at session.time is made
  // again when the field source, the plane or the time changed (the series of files is kept
  // while the source stays); the noise when its source or the image's size changed, after
  // checking that the image fits the host's memory. `gridGiven`: as planeField's.
  Result<void> setInputs(const Session& session, bool gridGiven = false);

  // The LIC image of the inputs for `lic`, made again only when they or `lic` changed.
  // `progress` gets the CPU reference's fraction done.
  Result<void> computeLic(const LicParams& lic, const ProgressCallback& progress = {});

  // The picture as `lic3d render2d` writes it: the LIC image coloured by `view` (with the legend
  // unless `view` turns it off).
  RgbaImage colour(const ViewParams& view) const;

  const VectorField& field() const { return field_; }
  const FieldReadInfo& readInfo() const { return source_.info; }
  Dims imageDims() const { return noise_.dims; }
  float minMagnitude() const { return minMagnitude_; }
  float maxMagnitude() const { return maxMagnitude_; }
  // Wall time of the last LIC image, and on the GPU its dispatch alone (0 on the CPU).
  double licMilliseconds() const { return licMs_; }
  double gpuMilliseconds() const { return pass_ ? pass_->lastMilliseconds() : 0.0; }

 private:
  const Context* context_ = nullptr;
  std::optional<Lic2DPass> pass_;
  PlaneSource source_;
  VectorField field_;
  NoiseVolume noise_;
  std::optional<Lic2DInputs> uploaded_;
  ScalarVolume lic_;
  // What each stage was last made from (none: to be made).
  std::optional<Session> fieldOf_;
  std::optional<NoiseSource> noiseOf_;
  FieldPrecision precision_ = FieldPrecision::Auto;  // of the uploaded inputs
  std::optional<LicParams> licOf_;
  float minMagnitude_ = 0.0f, maxMagnitude_ = 1.0f;
  double licMs_ = 0.0;
};

}  // namespace lic3d
