// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to the VTK XML ImageData reader (vti_file.cpp, vti_read.cpp): the file's structure,
// checked once, apart from the decoding of the arrays' data that it points to.

#include <array>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <pugixml.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/volume.h"
#include "io/file_util.h"
#include "io/number_type.h"

namespace lic3d::vti {

// The parsed file. pugixml parses in place and keeps pointers into `xml`, so this stays put
// (held by unique_ptr).
struct VtiFile {
  std::filesystem::path path;
  std::string bytes;  // the whole file
  std::string xml;    // the XML before the appended data, closed; empty when `bytes` is all XML
  pugi::xml_document document;
  std::string_view appended;  // the bytes after AppendedData's '_' (when read with the XML)
  bool hasAppended = false;
  // The appended raw data of a large file is not read with the XML: readers stream it from the
  // file into their arrays, so the host holds an array once rather than the file and the array.
  bool appendedInFile = false;
  std::uint64_t appendedAt = 0;    // where it starts in the file (either way)
  std::uint64_t appendedSize = 0;  // its bytes, up to the end of the file (either way)
  bool appendedBase64 = false;
  std::endian order = std::endian::little;
  bool header64 = false;
  bool zlib = false;
  Dims dims{0};
  GridGeometry geometry;
  pugi::xml_node piece;

  Error fail(const std::string& problem) const { return fileError(path, problem); }
};

// A WholeExtent or a Piece's Extent: the first and last point index along x, y and z.
struct Extent {
  std::array<std::int64_t, 6> bounds{};
  bool operator==(const Extent&) const = default;
};

// "x0 x1 y0 y1 z0 z1": six whole numbers (each at most 2^40 from zero) with each first <= last;
// nullopt for anything else. .vti and .pvti files write their extents so.
std::optional<Extent> parseExtent(std::string_view text);

// The attribute `name` of `node` ("Origin", "Spacing"): three finite numbers, positive with
// `positive`; `fallback` on each axis where it is missing. The error names `path`.
Result<glm::dvec3> parseTriple(const std::filesystem::path& path, const pugi::xml_node& node,
                               const char* name, double fallback, bool positive);

// A DataArray of PointData or CellData.
struct ArrayRef {
  pugi::xml_node node;
  std::string name;
  bool cellData = false;
  std::uint64_t components = 1;
  const NumberTypeInfo* type = nullptr;  // null for a type lic3d does not read
};

// The whole file read and parsed, with its grid (WholeExtent, Origin, Spacing) and its one Piece
// checked; the error names the file and the problem.
// `stream` (FieldStream): only the XML is read, never the data, and the grid may have up to
// kMaxStreamedVoxels points; a file larger than 64 KiB whose XML does not end in AppendedData
// within its first 64 KiB is Unsupported, and base64 appended data stays unread.
Result<std::unique_ptr<VtiFile>> openVti(const std::filesystem::path& path, bool stream = false);

// "DataArray 'name'", marked when it is cell data: how every error names an array.
std::string describe(const ArrayRef& array);

// What every reader checks of an array before its data: a type lic3d reads, and NumberOfTuples
// (where given) equal to the grid's `tuples`. The error starts with describe(array).
Result<void> checkArray(const VtiFile& file, const ArrayRef& array, std::uint64_t tuples);
// An appended array's `offset` attribute: a whole number within AppendedData.
Result<std::uint64_t> appendedOffset(const VtiFile& file, const ArrayRef& array);

// Every DataArray of PointData, then of CellData, in file order.
Result<std::vector<ArrayRef>> listArrays(const VtiFile& file);

// The array to read: by name, else the section's active attribute (`Vectors`, `Scalars`), else
// the first with `components` components, else the first with `alternative` components (2D
// vectors: 2); PointData before CellData.
Result<ArrayRef> chooseArray(const VtiFile& file, const std::vector<ArrayRef>& arrays,
                             std::string_view name, std::uint64_t components,
                             const char* activeAttribute, std::uint64_t alternative = 0);

}  // namespace lic3d::vti
