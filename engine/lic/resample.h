// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A file's field on a finer (or coarser) LIC grid (FieldSource::resolution, core/resolution.h):
// the same box, its first and last points where they were, the values trilinearly interpolated.

#include "core/volume.h"
#include "io/field_io.h"

namespace lic3d {

// The geometry of `dims` points over the box of `geometry` on `from` points: the same origin,
// spacing (from - 1) / (dims - 1) times the old on each axis (kept on an axis of one point).
GridGeometry resampledGeometry(const GridGeometry& geometry, Dims from, Dims dims);

// The field on `dims` points: point p of the new grid takes the trilinear interpolation of the old
// grid at the same physical position. Threads: 0 = availableThreads(). A piece is not resampled
// (the caller refuses it).
VectorField resampleField(const VectorField& field, Dims dims, unsigned threads = 0);
// The same for a scalar on the field's grid; NaN spreads to the new points next to it.
PointScalars resampleScalars(const PointScalars& scalars, Dims dims, unsigned threads = 0);

}  // namespace lic3d
