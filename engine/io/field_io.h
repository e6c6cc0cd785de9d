#pragma once
// Reading input volumes by file type, for the CLI and the app: one call, whatever the format.

#include <filesystem>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"
#include "io/volume_io.h"  // FieldReadInfo

namespace lic3d {

// By extension, compared case-insensitively:
//   .vtk          readVectorFieldVtk  (VTK legacy)
//   .vti          readVectorFieldVti  (VTK XML ImageData)
//   .nrrd, .nhdr  readVectorFieldNrrd (attached or detached header)
//   .raw          readVectorFieldRaw  (with its JSON sidecar)
// `arrayName` picks a vector array in .vtk and .vti files; NRRD and raw files hold one unnamed
// array, so a name given for one is an error. Spacing and origin come from the file. Vectors with
// a NaN or infinite component are read as zero and counted in `info` (when given), which also
// gets the array read and every vector array of the file; a field with no non-zero vector is an
// error.
Result<VectorField> readVectorField(const std::filesystem::path& path,
                                    std::string_view arrayName = {}, FieldReadInfo* info = nullptr);

// `.nrrd` or `.nhdr` (readNoiseNrrd).
Result<NoiseVolume> readNoise(const std::filesystem::path& path);

}  // namespace lic3d
