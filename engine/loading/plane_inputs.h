// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The field of 2D LIC for the command line and the app: a 2D analytic field, a plane of a 3D
// analytic field, a 2D file or a plane of a 3D one, or a series of such files, each at a time,
// from the session's field source and plane (docs/TIME.md).

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/session.h"
#include "core/volume.h"
#include "io/volume_io.h"
#include "lic/time_series.h"

namespace lic3d {

// What stays between the times of one source: the series of files and the planes of its steps
// in use (two at most: 2D steps are small, so they are blended on the host).
struct PlaneSource {
  std::optional<TimeSeries> series;
  std::map<int, VectorField> steps;
  FieldReadInfo info;  // of the last file read
  // A plane at any orientation (PlaneParams::oblique): its points outside the field's box, 1 per
  // voxel of the plane's grid (lic/field_plane.h); empty otherwise.
  std::vector<std::uint8_t> outside;
};

// The plane of `session`'s field at `time` (see above). `gridGiven`: the grid was given
// explicitly, which a file refuses. The first call finds out whether the field is a series and
// keeps it in `source`.
Result<VectorField> planeField(const Session& session, bool gridGiven, double time,
                               PlaneSource& source);

// The LIC image's size: the plane's grid, or PlaneParams' width and height (one alone keeps the
// grid's aspect).
Dims imageSize(Dims plane, const PlaneParams& params);

}  // namespace lic3d
