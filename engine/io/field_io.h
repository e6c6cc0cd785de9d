// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reading input volumes by file type, for the CLI and the app: one call, whatever the format.

#include <filesystem>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"
#include "io/volume_io.h"  // FieldReadInfo, PointScalars

namespace lic3d {

// By extension, compared case-insensitively:
//   .vtk          readVectorFieldVtk  (VTK legacy)
//   .vti          readVectorFieldVti  (VTK XML ImageData)
//   .pvti         readVectorFieldPvti (its pieces, as ParaView writes under MPI)
//   .nrrd, .nhdr  readVectorFieldNrrd (attached or detached header)
//   .raw          readVectorFieldRaw  (with its JSON sidecar)
// `arrayName` picks a vector array in .vtk and .vti files; NRRD and raw files hold one unnamed
// array, so a name given for one is an error. Spacing and origin come from the file. Vectors with
// a NaN or infinite component are read as zero and counted in `info` (when given), which also
// gets the array read and every vector array of the file; a field with no non-zero vector is an
// error.
Result<VectorField> readVectorField(const std::filesystem::path& path,
                                    std::string_view arrayName = {}, FieldReadInfo* info = nullptr);

// A scalar of a field's file, to colour the field by or to set its opacity (PointScalars, in
// io/volume_io.h, since each format's reader makes one). By extension, compared case-insensitively:
//   .vtk          readPointScalarsVtk  (a SCALARS array of 1 component, or a 1-component FIELD
//                                       array, in POINT_DATA)
//   .vti          readPointScalarsVti  (a 1-component PointData array)
//   .nrrd, .nhdr  readPointScalarsNrrd (the file's single scalar array; `name` must be empty)
// An empty `name` picks the file's active or first scalar array. Cell-data scalars are read when
// no point array of that name exists, on the cell-centred grid (cellCentredGrid). Values of any
// numeric type become float, NaN kept. An error names the file and, when the array is missing,
// lists the scalar arrays the file has.
Result<PointScalars> readPointScalars(const std::filesystem::path& path, std::string_view name);

// `.nrrd` or `.nhdr` (readNoiseNrrd).
Result<NoiseVolume> readNoise(const std::filesystem::path& path);

}  // namespace lic3d
