// SPDX-License-Identifier: BSD-3-Clause
#include "jobs/plane_picture.h"

#include <chrono>
#include <utility>

#include "lic/colouring.h"
#include "lic/lic2d_reference.h"
#include "loading/session_inputs.h"

namespace lic3d {
namespace {

// The plane's field does not depend on the image's size: a new size (the app's window resized)
// makes only the noise and the LIC again, and does not read the field's file again.
bool sameField(const PlaneParams& a, const PlaneParams& b) {
  PlaneParams sizeless = b;
  sizeless.width = a.width;
  sizeless.height = a.height;
  return a == sizeless;
}

}  // namespace

Result<void> PlanePicture::useGpu(const Context& context) {
  LIC3D_TRY_ASSIGN(Lic2DPass pass, Lic2DPass::create(context));
  context_ = &context;
  pass_.emplace(std::move(pass));
  uploaded_.reset();
  licOf_.reset();
  return {};
}

Result<void> PlanePicture::setInputs(const Session& session, bool gridGiven) {
  const bool newSource = !fieldOf_ || !(fieldOf_->field == session.field);
  if (newSource || !sameField(fieldOf_->plane, session.plane) || fieldOf_->time != session.time) {
    // A series' files and steps stay while the source does: the next time blends them again.
    if (newSource) source_ = PlaneSource{};
    // Until the plane is made again, what field_ holds is no session's.
    fieldOf_.reset();
    uploaded_.reset();
    licOf_.reset();
    LIC3D_TRY_ASSIGN(field_, planeField(session, gridGiven, session.time, source_));
    fieldOf_ = session;
    minMagnitude_ = static_cast<float>(lic3d::minMagnitude(field_));
    maxMagnitude_ = static_cast<float>(lic3d::maxMagnitude(field_));
  }
  const Dims size = imageSize(field_.dims, session.plane);
  if (!noiseOf_ || !(*noiseOf_ == session.noise) || noise_.dims != size) {
    noiseOf_.reset();
    uploaded_.reset();
    licOf_.reset();
    LIC3D_TRY(checkHostMemory(size));
    LIC3D_TRY_ASSIGN(noise_, loadNoise(session.noise, size));
    noiseOf_ = session.noise;
  }
  if (precision_ != session.precision) {
    precision_ = session.precision;
    uploaded_.reset();
    licOf_.reset();
  }
  return {};
}

Result<void> PlanePicture::computeLic(const LicParams& lic, const ProgressCallback& progress) {
  if (licOf_ && *licOf_ == lic) return {};
  licOf_.reset();
  if (pass_ && !uploaded_) {
    LIC3D_TRY_ASSIGN(uploaded_, uploadLic2DInputs(*context_, field_, noise_, precision_));
  }
  const auto start = std::chrono::steady_clock::now();
  if (pass_) {
    LIC3D_TRY_ASSIGN(lic_, pass_->compute(*uploaded_, lic));
  } else {
    LIC3D_TRY_ASSIGN(lic_, computeLic2DReference(field_, noise_, lic, 0, progress));
  }
  licMs_ =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  lic_.geometry = imageGeometry(field_, noise_.dims);
  licOf_ = lic;
  return {};
}

RgbaImage PlanePicture::colour(const ViewParams& view) const {
  return colourLic2D(lic_, field_, view, source_.outside);
}

}  // namespace lic3d
