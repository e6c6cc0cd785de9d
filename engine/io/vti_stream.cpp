// SPDX-License-Identifier: BSD-3-Clause
// A .vti's arrays located in its appended raw data for FieldStream: the structure checked by
// vti_file, each array's byte count read from the file and compared with its size.

#include "io/vti_stream.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <memory>
#include <utility>
#include <vector>

#include "core/text.h"
#include "io/volume_io.h"
#include "io/vti_file.h"

namespace lic3d::vti {
namespace {

// The byte count VTK writes before an appended array's values.
Result<std::uint64_t> readByteCount(const VtiFile& file, const FileReader& reader, std::uint64_t at,
                                    const std::string& what) {
  const std::size_t headerBytes = file.header64 ? 8 : 4;
  std::array<unsigned char, 8> header{};
  LIC3D_TRY(reader.readAt(at, header.data(), headerBytes, what + " (its byte count)"));
  if (file.order != std::endian::native)
    std::reverse(header.begin(), header.begin() + static_cast<std::ptrdiff_t>(headerBytes));
  if (headerBytes == 8) {
    std::uint64_t size = 0;
    std::memcpy(&size, header.data(), 8);
    return size;
  }
  std::uint32_t size32 = 0;
  std::memcpy(&size32, header.data(), 4);
  return std::uint64_t{size32};
}

// Where an array's values start: after its block's byte count, which must be the array's size.
Result<StoredArray> locate(const VtiFile& file, const FileReader& reader, const ArrayRef& array,
                           Dims dims) {
  const std::string what = describe(array);
  const std::uint64_t tuples = voxelCount(dims);
  LIC3D_TRY(checkArray(file, array, tuples));
  const std::string format = array.node.attribute("format").value();
  if (format != "appended")
    return readWholeError(file.path, what + " is stored inline as " +
                                         (format == "binary" ? std::string("base64") : format));
  if (file.appendedBase64) return readWholeError(file.path, "its appended data is base64 encoded");
  LIC3D_TRY_ASSIGN(const std::uint64_t offset, appendedOffset(file, array));
  LIC3D_TRY_ASSIGN(const std::uint64_t size,
                   readByteCount(file, reader, file.appendedAt + offset, what));
  StoredArray stored;
  stored.offset = file.appendedAt + offset + (file.header64 ? 8 : 4);
  stored.type = array.type->type;
  stored.order = file.order;
  stored.components = static_cast<std::size_t>(array.components);
  const std::uint64_t expected = tuples * stored.components * array.type->bytes;
  if (size != expected)
    return file.fail(what + ": the data block holds " + std::to_string(size) + " bytes, expected " +
                     std::to_string(expected) + " (" + std::to_string(tuples) + " tuples of " +
                     std::to_string(stored.components) + " " + std::string(array.type->vtkXmlName) +
                     ")");
  return stored;
}

}  // namespace

Result<StreamedVti> openStreamedVti(const std::filesystem::path& path, std::string_view name,
                                    const CheckStored& check) {
  LIC3D_TRY_ASSIGN(const std::unique_ptr<VtiFile> file, openVti(path, true));
  if (file->zlib) return readWholeError(path, "its arrays are compressed (vtkZLibDataCompressor)");
  LIC3D_TRY_ASSIGN(const std::vector<ArrayRef> arrays, listArrays(*file));
  LIC3D_TRY_ASSIGN(const ArrayRef array, chooseArray(*file, arrays, name, 3, "Vectors", 2));
  // Cell data on N cells is a field of N voxels at the cell centres, as the whole-file reader has.
  const CellCentredGrid grid = array.cellData ? cellCentredGrid(file->dims, file->geometry)
                                              : CellCentredGrid{file->dims, file->geometry};
  if (array.components == 2 && grid.dims.z != 1)
    return file->fail(describe(array) + " holds 2D vectors (2 components) on a grid of " +
                      std::to_string(grid.dims.z) + " layers along z; they need a 2D grid");
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  StreamedVti streamed{std::move(reader), grid.dims, grid.geometry, array.name, {}, std::nullopt};
  LIC3D_TRY_ASSIGN(streamed.vectors, locate(*file, streamed.file, array, grid.dims));
  LIC3D_TRY(check(streamed.file, grid.dims, streamed.vectors));
  // VTK's mask of valid points: the vectors it marks invalid are zero, as readVectorField has them.
  const auto mask = std::find_if(arrays.begin(), arrays.end(), [](const ArrayRef& each) {
    return !each.cellData && each.components == 1 && each.name == kValidPointMaskName;
  });
  if (!array.cellData && mask != arrays.end()) {
    LIC3D_TRY_ASSIGN(const StoredArray stored, locate(*file, streamed.file, *mask, grid.dims));
    LIC3D_TRY(check(streamed.file, grid.dims, stored));
    streamed.mask = stored;
  }
  return streamed;
}

}  // namespace lic3d::vti
