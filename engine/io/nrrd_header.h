// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to the NRRD reader and writer (nrrd_header.cpp, nrrd_read.cpp, nrrd_write.cpp) and the
// streams (field_stream.cpp, volume_stream.cpp): the payload's layout as one checked description,
// so the payload readers never meet a raw header.

#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/volume.h"
#include "io/file_util.h"
#include "io/number_type.h"

namespace lic3d::nrrd {

enum class Encoding { Raw, Gzip };

// What the header says about the payload, after every check.
struct Layout {
  NumberType type = NumberType::Float32;
  std::size_t components = 1;  // values per voxel: 3 for vector fields, 4 for RGBA, 1 for scalars
  Dims dims{0};
  std::uint64_t voxels = 0;
  Encoding encoding = Encoding::Raw;
  std::endian order = std::endian::little;
  GridGeometry geometry;
  // Detached headers name the file holding the data; empty when it follows the header.
  std::filesystem::path dataFile;
  std::uint64_t lineSkip = 0;
  // Bytes skipped before the data (in the file for raw, in the decompressed stream for gzip);
  // -1 (raw only) puts the data at the end of the file.
  std::int64_t byteSkip = 0;
  // `sample units`: the unit of the values, without the quotes teem writes around it; empty when
  // the header gives none.
  std::string sampleUnits;

  std::uint64_t payloadBytes() const { return voxels * components * numberType(type).bytes; }
};

// What one reader accepts.
struct Expectation {
  std::size_t dimension;   // 3, or 4 with the components on the first axis
  std::size_t components;  // the size of that first axis
  std::string_view dimensionMeaning;
  std::string_view componentsMeaning;
  std::vector<NumberType> types;
  std::string_view typesText;
  // Also a 2D grid (one layer along z), `dimension` - 1 axes. For vector fields the first axis
  // holds 2 or `components` values (2D vectors lie in the x-y plane); scalars have no such axis.
  bool planar = false;
  // kMaxVoxels for the whole-file readers, kMaxStreamedVoxels for a stream.
  std::uint64_t maxVoxels = kMaxVoxels;
};

// Reads the header from its magic line to the blank line that ends it (a detached header may end
// with the file instead) and checks every field the payload depends on against `expected`, so
// that nothing is allocated from a bad number. The reader is then at the first byte after the
// header. An error names reader.path() and the field.
Result<Layout> readLayout(FileReader& reader, const Expectation& expected);

// A file's header read and checked, and a reader at the first payload byte, in the header's file
// or its detached data file (past `line skip` and, for raw data, `byte skip`), the payload's size
// checked against the bytes there. Errors about the data file name the header too.
struct Opened {
  std::filesystem::path header;
  FileReader reader;
  Layout layout;
};
Result<Opened> openPayload(const std::filesystem::path& path, const Expectation& expected);

// The header writeScalarNrrd writes before the values: float, raw, little endian, with the
// geometry and `labels` whose first names the array.
std::string scalarHeader(Dims dims, const GridGeometry& geometry, std::string_view name);

}  // namespace lic3d::nrrd
