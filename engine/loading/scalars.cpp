// SPDX-License-Identifier: BSD-3-Clause
#include "loading/scalars.h"

#include <filesystem>

#include "core/resolution.h"
#include "core/stage_times.h"
#include "core/text.h"
#include "io/file_util.h"
#include "lic/analytic_fields.h"
#include "lic/derived_fields.h"
#include "lic/resample.h"

namespace lic3d {
namespace {

bool isScalarFile(const std::string& name) {
  const std::string extension = lowerCaseExtension(name);
  return extension == ".nrrd" || extension == ".nhdr";
}

const PointScalars* heldArray(const std::string& name, const SessionInputs& inputs) {
  for (const PointScalars& array : inputs.arrays)
    if (array.name == name) return &array;
  return nullptr;
}

}  // namespace

Result<std::optional<PointScalars>> loadScalars(const std::string& name, const std::string& key,
                                                const Session& session,
                                                const SessionInputs& inputs) {
  const std::optional<DerivedQuantity> derived = derivedQuantity(name);
  if (derived == DerivedQuantity::Speed) return std::optional<PointScalars>();
  if (inputs.series)
    return parameterError(key, "'" + name +
                                   "': a time series is blended on the GPU, which has the speed "
                                   "alone; colour and opacity of a series follow speed");
  if (derived)
    return std::optional<PointScalars>(derivedScalars(inputs.field, *derived, inputs.info.unit));
  const PointScalars* held = heldArray(name, inputs);
  if (!held && !inputs.fromFile && !isScalarFile(name))
    return parameterError(key, "'" + name + "' is not speed, vorticity or helicity, and " +
                                   session.field.field +
                                   " is an analytic field with no arrays; a scalar file "
                                   "(.nrrd, .nhdr) on its grid may be given instead");
  PointScalars scalars;
  if (held) {
    scalars = *held;
  } else if (isScalarFile(name)) {
    LIC3D_TRY_ASSIGN(scalars, readPointScalars(name, {}));
  } else {
    LIC3D_TRY_ASSIGN(scalars, readPointScalars(session.field.field, name));
  }
  LIC3D_TRY_ASSIGN(const Resolution resolution, parseResolution(session.field.resolution));
  // On the file's grid, which the field was resampled from: resampled the same way.
  if (resolution.given() && resolvedGrid(resolution, scalars.dims) == inputs.field.dims &&
      scalars.dims != inputs.field.dims)
    scalars = resampleScalars(scalars, inputs.field.dims);
  if (scalars.dims != inputs.field.dims)
    return parameterError(key, "'" + name + "' has the grid " + gridText(scalars.dims) +
                                   ", the field " + gridText(inputs.field.dims) +
                                   ": they must be the same");
  return std::optional<PointScalars>(std::move(scalars));
}

namespace {

Result<void> checkScalarName(const std::string& name, const std::string& key,
                             const Session& session, const SessionInputs* inputs) {
  const std::optional<DerivedQuantity> derived = derivedQuantity(name);
  if (derived == DerivedQuantity::Speed) return {};
  if (inputs && inputs->series)
    return parameterError(key, "'" + name +
                                   "': a time series is blended on the GPU, which has the speed "
                                   "alone; colour and opacity of a series follow speed");
  if (derived || isScalarFile(name)) return {};
  const bool analytic = parseEnum<AnalyticField>(session.field.field).has_value() ||
                        parseEnum<AnalyticField2D>(session.field.field).has_value();
  if (!inputs && !analytic) return {};  // the file's arrays are known once it is read
  std::vector<std::string> names = {"speed", "vorticity", "helicity"};
  if (inputs) {
    if (heldArray(name, *inputs)) return {};
    for (const std::string& array : inputs->info.scalarNames)
      if (array == name) return {};
    names = scalarChoices(*inputs);
  }
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return parameterError(
      key, "'" + name + "' is not a scalar of " + session.field.field + ": the names are " + list +
               (analytic ? " (an analytic field has no arrays)" : " (the arrays of its file)") +
               ", or a scalar file (.nrrd, .nhdr) on the field's grid");
}

}  // namespace

Result<void> checkViewScalarNames(const Session& session, const SessionInputs* inputs) {
  const ViewParams& view = session.view;
  if (view.color == ColorMode::Magnitude)
    LIC3D_TRY(checkScalarName(view.colorBy, "view.color_by", session, inputs));
  if (opacityWeighted(view))
    LIC3D_TRY(checkScalarName(view.opacityBy, "view.opacity_by", session, inputs));
  return {};
}

std::vector<std::string> scalarChoices(const SessionInputs& inputs) {
  std::vector<std::string> names;
  for (const DerivedQuantity q :
       {DerivedQuantity::Speed, DerivedQuantity::Vorticity, DerivedQuantity::Helicity})
    names.emplace_back(enumName(q));
  for (const PointScalars& array : inputs.arrays) names.push_back(array.name);
  for (const std::string& name : inputs.info.scalarNames) names.push_back(name);
  return names;
}

bool opacityWeighted(const ViewParams& view) {
  return view.magnitudeOpacity > 0.0f || view.magnitudeThreshold > 0.0f ||
         !view.transfer.opacities.empty();
}

bool viewDerivesFromField(const ViewParams& view) {
  const auto derived = [](const std::string& name) {
    const std::optional<DerivedQuantity> quantity = derivedQuantity(name);
    return quantity && *quantity != DerivedQuantity::Speed;
  };
  return (view.color == ColorMode::Magnitude && derived(view.colorBy)) ||
         (opacityWeighted(view) && derived(view.opacityBy));
}

Result<ViewScalars> loadViewScalars(const Session& session, const SessionInputs& inputs) {
  const StageTimer timer("scalars");
  const ViewParams& view = session.view;
  ViewScalars scalars;
  if (view.color == ColorMode::Magnitude) {
    LIC3D_TRY_ASSIGN(scalars.color, loadScalars(view.colorBy, "view.color_by", session, inputs));
  }
  const bool weighted = opacityWeighted(view);
  if (weighted && view.opacityBy == view.colorBy && view.color == ColorMode::Magnitude) {
    scalars.opacity = scalars.color;
  } else if (weighted) {
    LIC3D_TRY_ASSIGN(scalars.opacity,
                     loadScalars(view.opacityBy, "view.opacity_by", session, inputs));
  }
  return scalars;
}

Result<void> setViewScalars(LicRenderer& renderer, const ViewScalars& scalars) {
  return renderer.setScalars(scalars.color ? &*scalars.color : nullptr,
                             scalars.opacity ? &*scalars.opacity : nullptr);
}

}  // namespace lic3d
