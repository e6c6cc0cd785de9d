#include "field_io.h"

#include <string>
#include <system_error>

#include "file_util.h"
#include "nrrd.h"
#include "vtk_legacy.h"

namespace lic3d {
namespace {

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

std::string lowerCaseExtension(const std::filesystem::path& path) {
  return asciiLowerCase(path.extension().string());
}

std::string describeExtension(const std::string& extension) {
  return extension.empty() ? "no extension" : "unsupported extension '" + extension + "'";
}

}  // namespace

Result<VectorField> readVectorField(const std::filesystem::path& path, std::string_view arrayName) {
  const std::string extension = lowerCaseExtension(path);
  if (extension == ".nhdr")
    return fileError(path, "detached NRRD headers (.nhdr) are not supported yet; use a .nrrd file");
  if (extension != ".nrrd" && extension != ".vtk")
    return fileError(path, "cannot read a vector field from a file with " +
                               describeExtension(extension) + " (supported: .nrrd, .vtk)");
  LIC3D_TRY(checkRegularFile(path));
  if (extension == ".vtk") return readVectorFieldVtk(path, arrayName);
  if (!arrayName.empty())
    return fileError(path, "an array name (" + quoteForMessage(arrayName) +
                               ") applies only to .vtk files; a NRRD file holds one array");
  return readVectorFieldNrrd(path);
}

Result<NoiseVolume> readNoise(const std::filesystem::path& path) {
  const std::string extension = lowerCaseExtension(path);
  if (extension != ".nrrd")
    return fileError(path, "cannot read noise from a file with " + describeExtension(extension) +
                               " (supported: .nrrd)");
  LIC3D_TRY(checkRegularFile(path));
  return readNoiseNrrd(path);
}

}  // namespace lic3d
