// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to FieldStream (field_stream.cpp): a .vti's vectors found where they lie in its
// appended raw data, by the VTK XML reader (vti_stream.cpp), so that its XML parser stays inside
// the reader and reaches no user of the stream.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"
#include "io/file_util.h"
#include "io/number_type.h"

namespace lic3d::vti {

// One array's values, interleaved, from byte `offset` of the file on.
struct StoredArray {
  std::uint64_t offset = 0;
  NumberType type = NumberType::Float32;
  std::endian order = std::endian::little;
  std::size_t components = 3;
};

struct StreamedVti {
  FileReader file;
  Dims dims{0};  // cell data on N cells: N voxels at the cell centres
  GridGeometry geometry;
  std::string arrayName;
  StoredArray vectors;
  std::optional<StoredArray> mask;  // vtkValidPointMask, on the same points
};

// Called with each array once it is found, before the next is looked for: the stream's check
// that the file holds it.
using CheckStored =
    std::function<Result<void>(const FileReader& file, Dims dims, const StoredArray& array)>;

// The header read and checked, and the vectors (chosen as readVectorField chooses them) and VTK's
// mask located in the appended data. InvalidInput for a bad file; Unsupported (readWholeError)
// for one whose data is not appended raw and uncompressed.
Result<StreamedVti> openStreamedVti(const std::filesystem::path& path, std::string_view name,
                                    const CheckStored& check);

}  // namespace lic3d::vti
