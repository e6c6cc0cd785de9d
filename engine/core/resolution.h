// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The LIC grid of a file's field when it should differ from the file's (FieldSource::resolution):
// coarse data such as a 76x49x45 MRI scan carries no visible streaks at its own grid, so the
// field is sampled trilinearly on a finer grid and the noise made there (lic/resample.h).

#include <string>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"

namespace lic3d {

// One of three forms, as the CLI and sessions write it:
//   "N"          the longest axis gets N voxels, the others as many as scale by the same factor
//   "NX,NY,NZ"   exactly this grid
//   "Fx"         every axis's voxel count times F (e.g. "2x", "1.5x")
// The empty string keeps the file's grid.
struct Resolution {
  Dims dims{0};         // NX,NY,NZ
  int longest = 0;      // N
  double factor = 0.0;  // F
  bool given() const { return dims.x > 0 || longest > 0 || factor > 0.0; }
};

// InvalidInput naming field.resolution for anything else, or a grid outside [2, kMaxGridSize]
// per axis, or a factor outside (0, 16].
Result<Resolution> parseResolution(std::string_view text);

// The grid `resolution` gives a file of `fileDims`. Axes of one voxel stay one voxel (a plane);
// the others get at least 2.
Dims resolvedGrid(const Resolution& resolution, Dims fileDims);
// The same, refused (InvalidInput naming field.resolution, `text` and the range) where a factor
// or N would put an axis outside [2, kMaxGridSize] rather than clamping it there: 1e-300x is not
// a 2^3 LIC.
Result<Dims> resolveGrid(const Resolution& resolution, Dims fileDims, std::string_view text);

}  // namespace lic3d
