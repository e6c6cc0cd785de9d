// SPDX-License-Identifier: BSD-3-Clause
// io/vdb_write.h in a build without OpenVDB (LIC3D_OPENVDB OFF, or the library not found): .vdb is
// refused with the reason, and front ends refuse it before any work (openVdbAvailable).
#include "io/file_util.h"
#include "io/vdb_write.h"

namespace lic3d {

bool openVdbAvailable() { return false; }

Result<void> writeVdb(const std::filesystem::path& path, const VdbVolume&) {
  return fileError(path,
                   "this lic3d was built without OpenVDB (LIC3D_OPENVDB): it cannot write .vdb; "
                   "write .nrrd, .vti or .raw");
}

}  // namespace lic3d
