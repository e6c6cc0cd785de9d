// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What colour and opacity follow (ViewParams::colorBy, opacityBy) as point scalars on the LIC
// grid: a quantity derived from the field (lic/derived_fields.h) or an array of the field's file,
// or a scalar file of its own (io/field_io.h).

#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/session.h"
#include "io/field_io.h"
#include "lic/colouring.h"
#include "loading/session_inputs.h"
#include "render/lic_renderer.h"

namespace lic3d {

// The scalar `name` names for these inputs, on their field's grid:
//   "speed"                  nullopt: the slices take |v| from the field texture itself
//   "vorticity", "helicity"  derived from the field on the host
//   a path ending in .nrrd or .nhdr   that file's scalar, which must have the field's grid
//   an array of inputs.arrays  that array (held in memory by the front end)
//   any other name           the point (or cell) scalar array of that name in the field's file
// Resampled to the LIC grid with field.resolution. `key` names the parameter in errors
// (view.color_by, view.opacity_by). A time series blended on the GPU has only speed.
Result<std::optional<PointScalars>> loadScalars(const std::string& name, const std::string& key,
                                                const Session& session,
                                                const SessionInputs& inputs);

// Whether the view's colour and opacity name scalars these inputs have (InvalidInput naming
// view.color_by or view.opacity_by and listing the names), before any work: without `inputs`
// (the field not read yet) what the names alone tell (an analytic field has no arrays), with
// them the arrays of the field's file too.
Result<void> checkViewScalarNames(const Session& session, const SessionInputs* inputs);

// The names a colour-by or opacity-by choice can take for these inputs: the derived quantities,
// then the scalar arrays of the field's file (the app's menu).
std::vector<std::string> scalarChoices(const SessionInputs& inputs);

// The scalars a view's colour and opacity follow, when they are not the speed: loaded only where
// the view uses them, once when both name the same one.
struct ViewScalars {
  std::optional<PointScalars> color;
  std::optional<PointScalars> opacity;
  VolumeScalars pointers() const {
    return {color ? &*color : nullptr, opacity ? &*opacity : nullptr};
  }
};

// Whether opacity follows a scalar: the magnitude ramp, a threshold or a transfer function.
bool opacityWeighted(const ViewParams& view);
// Whether colour or opacity follow a quantity derived from the field's vectors on the host (the
// field must then be on the host, InputOptions::fieldOnDevice off).
bool viewDerivesFromField(const ViewParams& view);

Result<ViewScalars> loadViewScalars(const Session& session, const SessionInputs& inputs);
Result<void> setViewScalars(LicRenderer& renderer, const ViewScalars& scalars);

}  // namespace lic3d
