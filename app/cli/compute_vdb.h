// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// compute's OpenVDB output (-o FILE.vdb, io/vdb_write.h): the LIC volume as the grid LIC, the
// field's speed as the grid speed and a colour scalar (--color-by) as a grid of its name, with
// only the voxels that are drawn and not empty space active.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/volume.h"
#include "io/volume_io.h"
#include "loading/session_inputs.h"
#include "options/session_options.h"

namespace lic3d::cli {

// Whether compute writes `output` as OpenVDB.
bool isVdbOutput(const std::string& output);

// The grids besides the LIC, on the LIC grid, loaded before the LIC is made so that a bad
// colour scalar stops the run early.
struct VdbScalars {
  PointScalars speed;                 // |v| at each voxel (lic/derived_fields.h), the field's unit
  std::optional<PointScalars> color;  // the session's colour scalar, when it is not the speed
  double emptySpeed = 0.0;            // speeds at or below it are empty space (core/look.h)
};
// The speed of the field the LIC is made of (at the session's time, for a time series) and the
// scalar the view colours by (view.color_by, when the colour is by magnitude or --color-by is
// given). The field must be on the host (loadInputs without fieldOnDevice).
Result<VdbScalars> loadVdbScalars(const ComputeOptions& options, SessionInputs& inputs);

// 1 at the voxels a .vdb keeps active: drawn (not hidden by sparsity) and faster than the empty
// space speed, as the looks leave empty space transparent; 0 elsewhere.
std::vector<std::uint8_t> vdbActiveVoxels(const ScalarVolume& lic, const VdbScalars& scalars);

// Writes `lic` with `scalars` to `path` (writeVdb: atomically, errors naming the file).
Result<void> writeLicVdb(const std::string& path, const ScalarVolume& lic,
                         const VdbScalars& scalars);

}  // namespace lic3d::cli
