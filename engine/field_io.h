#pragma once
// Reading input volumes by file type, for the CLI and the app: one call, whatever the format.

#include <filesystem>
#include <string_view>

#include "error.h"
#include "volume.h"

namespace lic3d {

// `.nrrd` (readVectorFieldNrrd) or `.vtk` (readVectorFieldVtk, which takes `arrayName`; NRRD files
// hold one array, so a name given for one is an error). Extensions are compared case-insensitively.
Result<VectorField> readVectorField(const std::filesystem::path& path,
                                    std::string_view arrayName = {});

// `.nrrd` only (readNoiseNrrd).
Result<NoiseVolume> readNoise(const std::filesystem::path& path);

}  // namespace lic3d
