// SPDX-License-Identifier: BSD-3-Clause
#include "io/field_io.h"

#include <string>
#include <system_error>

#include "core/text.h"
#include "io/file_util.h"
#include "io/nrrd.h"
#include "io/raw_volume.h"
#include "io/vti.h"
#include "io/vtk_legacy.h"

namespace lic3d {
namespace {

constexpr char kVectorExtensions[] = ".vtk, .vti, .pvti, .nrrd, .nhdr, .raw";

// The readers would say much the same, but this wording is what a user needs for a mistyped path.
Result<void> checkRegularFile(const std::filesystem::path& path) {
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (status.type() == std::filesystem::file_type::not_found)
    return fileError(path, "no such file");
  if (error) return fileError(path, "cannot access: " + error.message());
  if (status.type() == std::filesystem::file_type::directory)
    return fileError(path, "is a directory, not a file");
  if (status.type() != std::filesystem::file_type::regular)
    return fileError(path, "not a regular file");
  return {};
}

std::string describeExtension(const std::string& extension) {
  return extension.empty() ? "no extension" : "unsupported extension '" + extension + "'";
}

}  // namespace

Result<VectorField> readVectorField(const std::filesystem::path& path, std::string_view arrayName,
                                    FieldReadInfo* info) {
  const std::string extension = lowerCaseExtension(path);
  const bool named = extension == ".vtk" || extension == ".vti" || extension == ".pvti";
  const bool single = extension == ".nrrd" || extension == ".nhdr" || extension == ".raw";
  if (!named && !single)
    return fileError(path, "cannot read a vector field from a file with " +
                               describeExtension(extension) + " (supported: " + kVectorExtensions +
                               ")");
  LIC3D_TRY(checkRegularFile(path));
  if (extension == ".vtk") return readVectorFieldVtk(path, arrayName, info);
  if (extension == ".vti") return readVectorFieldVti(path, arrayName, info);
  if (extension == ".pvti") return readVectorFieldPvti(path, arrayName, info);
  if (!arrayName.empty())
    return fileError(path, "an array name (" + quoteForMessage(arrayName) +
                               ") applies only to .vtk and .vti files; a " +
                               (extension == ".raw" ? "raw" : "NRRD") +
                               " file holds one unnamed array");
  if (extension == ".raw") return readVectorFieldRaw(path, info);
  return readVectorFieldNrrd(path, info);
}

Result<PointScalars> readPointScalars(const std::filesystem::path& path, std::string_view name) {
  const std::string extension = lowerCaseExtension(path);
  const bool named = extension == ".vtk" || extension == ".vti";
  if (!named && extension != ".nrrd" && extension != ".nhdr")
    return fileError(path, "cannot read scalars from a file with " + describeExtension(extension) +
                               " (supported: .vtk, .vti, .nrrd, .nhdr)");
  LIC3D_TRY(checkRegularFile(path));
  if (extension == ".vtk") return readPointScalarsVtk(path, name);
  if (extension == ".vti") return readPointScalarsVti(path, name);
  if (!name.empty())
    return fileError(path, "an array name (" + quoteForMessage(name) +
                               ") applies only to .vtk and .vti files; a NRRD file holds one "
                               "unnamed array");
  return readPointScalarsNrrd(path);
}

Result<NoiseVolume> readNoise(const std::filesystem::path& path) {
  const std::string extension = lowerCaseExtension(path);
  if (extension != ".nrrd" && extension != ".nhdr")
    return fileError(path, "cannot read noise from a file with " + describeExtension(extension) +
                               " (supported: .nrrd, .nhdr)");
  LIC3D_TRY(checkRegularFile(path));
  return readNoiseNrrd(path);
}

}  // namespace lic3d
