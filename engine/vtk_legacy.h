#pragma once
// Vector fields from VTK legacy files (the "simple legacy format" of the VTK file formats guide):
// `DATASET STRUCTURED_POINTS`, ASCII or BINARY (big endian), point data.
//
// Other attributes (SCALARS with their LOOKUP_TABLE line, LOOKUP_TABLE tables, COLOR_SCALARS,
// NORMALS, TENSORS, TEXTURE_COORDINATES, FIELD arrays, METADATA blocks) are skipped, as are
// CELL_DATA sections; vectors found only in cell data are refused as not supported yet. Inputs
// are untrusted: DIMENSIONS are limited (each in [1, 16384], at most 2^31 points) and every data
// block is checked against the bytes left in the file before it is allocated or skipped. Every
// error is InvalidInput and its message names the file and the problem.

#include <filesystem>
#include <string_view>

#include "error.h"
#include "volume.h"

namespace lic3d {

// The point-data VECTORS array named `arrayName`, or the first one when `arrayName` is empty
// (names are compared after VTK's %XX decoding). Float and double arrays are read as float; every
// component must be finite. Spacing (SPACING or ASPECT_RATIO) and ORIGIN come from the file and
// default to 1 and 0 like VTK's reader. When the array is missing the error lists the names found.
Result<VectorField> readVectorFieldVtk(const std::filesystem::path& path,
                                       std::string_view arrayName = {});

}  // namespace lic3d
