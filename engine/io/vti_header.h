// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What lic3d's VTK XML ImageData files hold around their one point-data array, appended raw
// (vti_write.cpp, and ScalarVolumeStream, which writes the same file piece by piece).

#include <filesystem>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"
#include "io/number_type.h"

namespace lic3d::vti {

// The XML up to AppendedData's '_': the array's UInt64 byte count and its values follow, both in
// the host's byte order (the file's byte_order), then kAppendedEnd. InvalidInput naming `path`
// for an empty array name or one holding a control character.
Result<std::string> appendedHeader(const std::filesystem::path& path, Dims dims,
                                   const GridGeometry& geometry, NumberType type, int components,
                                   std::string_view arrayName);

inline constexpr std::string_view kAppendedEnd = "\n  </AppendedData>\n</VTKFile>\n";

}  // namespace lic3d::vti
