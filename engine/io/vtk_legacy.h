// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Vector fields and scalar arrays from VTK legacy files (the "simple legacy format" of the VTK file
// formats guide): `DATASET STRUCTURED_POINTS` (DIMENSIONS, SPACING or ASPECT_RATIO, ORIGIN) or
// `DATASET RECTILINEAR_GRID` with evenly spaced X/Y/Z_COORDINATES, ASCII or BINARY (big endian),
// VECTORS in POINT_DATA or CELL_DATA, and as scalars SCALARS of 1 component (with their
// LOOKUP_TABLE line) or 1-component arrays of a FIELD block of one tuple per point or cell.
//
// Other attributes (SCALARS of several components, LOOKUP_TABLE tables, COLOR_SCALARS, NORMALS,
// TENSORS, TEXTURE_COORDINATES, other FIELD arrays, METADATA blocks) are skipped. Inputs are
// untrusted: DIMENSIONS are limited (each in [1, 16384], at most 2^31 points) and every data block
// is checked against the bytes left in the file before it is allocated or skipped. Every error is
// InvalidInput and its message names the file and the problem.

#include <filesystem>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"
#include "io/volume_io.h"

namespace lic3d {

// The VECTORS array named `arrayName` (names are compared after VTK's %XX decoding), or when
// `arrayName` is empty the first point-data VECTORS array, else the first cell-data one. Point
// data wins over cell data of the same name. Cell data on a grid of N cells becomes a field of N
// voxels at the cell centres, its origin moved by half a spacing (cellCentredGrid). Float and
// double arrays are read as float; vectors with a NaN or infinite component become zero and are
// counted (finishVectorField). Where a 1-component POINT_DATA array (SCALARS or FIELD) named
// vtkValidPointMask is 0, point-data vectors are set to zero first and counted in
// `info->maskedVectors` (kValidPointMaskName). Spacing and origin default to 1 and 0 like VTK's
// reader. When the array is missing the error lists the VECTORS arrays found. `info` also gets
// every VECTORS name and every point-data scalar name (the mask left out).
Result<VectorField> readVectorFieldVtk(const std::filesystem::path& path,
                                       std::string_view arrayName = {},
                                       FieldReadInfo* info = nullptr);

// The scalar array (SCALARS of 1 component, or a 1-component FIELD array of one tuple per point or
// cell) named `name`, or when `name` is empty the first one, point data before cell data; the
// validity mask is read only by name. Point data wins over cell data of the same name; cell data
// lies at the cell centres (cellCentredGrid). Any numeric type is read as float; NaN is kept.
// When the array is missing the error lists the scalar arrays found.
Result<PointScalars> readPointScalarsVtk(const std::filesystem::path& path, std::string_view name);

}  // namespace lic3d
