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
#include "inputs/session_inputs.h"
#include "io/field_io.h"

namespace lic3d {

// The scalar `name` names for these inputs, on their field's grid:
//   "speed"                  nullopt: the slices take |v| from the field texture itself
//   "vorticity", "helicity"  derived from the field on the host
//   a path ending in .nrrd or .nhdr   that file's scalar, which must have the field's grid
//   any other name           the point (or cell) scalar array of that name in the field's file
// Resampled to the LIC grid with field.resolution. `key` names the parameter in errors
// (view.color_by, view.opacity_by). A time series blended on the GPU has only speed.
Result<std::optional<PointScalars>> loadScalars(const std::string& name, const std::string& key,
                                                const Session& session,
                                                const SessionInputs& inputs);

// The names a colour-by or opacity-by choice can take for these inputs: the derived quantities,
// then the scalar arrays of the field's file (the app's menu).
std::vector<std::string> scalarChoices(const SessionInputs& inputs);

}  // namespace lic3d
