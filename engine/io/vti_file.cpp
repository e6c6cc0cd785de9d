// SPDX-License-Identifier: BSD-3-Clause
// The structure of a VTK XML ImageData file: the XML split from raw appended data, the grid and
// its one Piece checked, and the DataArray a reader asks for found by name or by VTK's rules.

#include "io/vti_file.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>

#include "core/text.h"
#include "io/file_util.h"
#include "io/volume_io.h"

namespace lic3d::vti {
namespace {

// A whole .vti is read into memory (pugixml parses it in place). The largest grid lic3d reads,
// as base64 doubles, stays below this; a larger file is refused from its size.
constexpr std::uint64_t kMaxFileBytes = std::uint64_t{1} << 36;
// Files larger than this whose XML fits in it are read as a head and streamed (openHead).
constexpr std::size_t kHeadBytes = std::size_t{64} << 10;

Result<std::int64_t> parseExtentNumber(std::string_view word) {
  const bool negative = !word.empty() && word.front() == '-';
  if (negative) word.remove_prefix(1);
  std::uint64_t magnitude = 0;
  // Extents beyond 2^40 cannot describe a grid lic3d reads, and keep the arithmetic exact.
  if (!parseUnsigned(word, magnitude) || magnitude > (std::uint64_t{1} << 40)) return Error{};
  return negative ? -static_cast<std::int64_t>(magnitude) : static_cast<std::int64_t>(magnitude);
}

// Where AppendedData's data starts in `bytes`: the end of its opening tag and the byte after its
// '_'. Empty when there is no AppendedData or it is empty (<AppendedData/>).
struct AppendedSplit {
  std::size_t tagEnd = 0;
  std::size_t data = 0;
};

Result<std::optional<AppendedSplit>> findAppended(const VtiFile& file, std::string_view bytes) {
  const std::size_t tag = bytes.find("<AppendedData");
  if (tag == std::string_view::npos) return std::optional<AppendedSplit>();
  const std::size_t close = bytes.find('>', tag);
  if (close == std::string_view::npos) return file.fail("the AppendedData tag is not closed");
  if (bytes[close - 1] == '/') return std::optional<AppendedSplit>();  // <AppendedData .../>
  std::size_t underscore = close + 1;
  while (underscore < bytes.size() && isAsciiSpace(bytes[underscore])) ++underscore;
  if (underscore == bytes.size() || bytes[underscore] != '_')
    return file.fail("AppendedData: expected '_' before the data, found " +
                     quoteForMessage(bytes.substr(underscore, 16)));
  return std::optional<AppendedSplit>(AppendedSplit{close, underscore + 1});
}

// Appended raw data is binary, not XML: pugixml gets only what precedes it, closed by hand.
void useAppended(VtiFile& file, std::string_view bytes, const AppendedSplit& split) {
  file.hasAppended = true;
  file.xml.assign(bytes.substr(0, split.tagEnd + 1));
  file.xml += "</AppendedData></VTKFile>";
}

// What openHead read of a file: the head of a large file whose XML, up to AppendedData's '_', lies
// in its first kHeadBytes (the appended data stays in the file); the whole of a file no larger
// than that, through the same descriptor (a .pvti of 50,000 small pieces opened each twice); or
// nothing, and the file is then read whole.
enum class HeadRead { Nothing, Head, Whole };

HeadRead openHead(VtiFile& file, bool stream) {
  Result<FileReader> reader = FileReader::open(file.path);
  if (!reader || (!stream && reader->size() > kMaxFileBytes)) return HeadRead::Nothing;
  if (reader->size() <= kHeadBytes) {
    std::string whole(static_cast<std::size_t>(reader->size()), '\0');
    char extra = 0;  // a file that grew since it was opened is read again, with its limit
    if (reader->read(whole.data(), whole.size()) != whole.size() || reader->read(&extra, 1) != 0)
      return HeadRead::Nothing;
    file.bytes = std::move(whole);
    return HeadRead::Whole;
  }
  std::string head(kHeadBytes, '\0');
  if (reader->read(head.data(), head.size()) != head.size()) return HeadRead::Nothing;
  const Result<std::optional<AppendedSplit>> split = findAppended(file, head);
  if (!split || !*split) return HeadRead::Nothing;
  file.bytes = std::move(head);
  useAppended(file, file.bytes, **split);
  file.appendedInFile = true;
  file.appendedAt = (*split)->data;
  file.appendedSize = reader->size() - file.appendedAt;
  return HeadRead::Head;
}

}  // namespace

Result<glm::dvec3> parseTriple(const std::filesystem::path& path, const pugi::xml_node& node,
                               const char* name, double fallback, bool positive) {
  const pugi::xml_attribute attribute = node.attribute(name);
  if (!attribute) return glm::dvec3(fallback);
  const std::vector<std::string_view> words = splitWords(attribute.value());
  glm::dvec3 value{0.0};
  bool good = words.size() == 3;
  for (glm::length_t axis = 0; good && axis < 3; ++axis)
    good = parseDouble(words[static_cast<std::size_t>(axis)], value[axis]) &&
           std::isfinite(value[axis]) && (!positive || value[axis] > 0.0);
  if (!good)
    return fileError(path, std::string(node.name()) + " " + name + ": expected 3 " +
                               (positive ? "positive" : "finite") + " numbers, found " +
                               quoteForMessage(attribute.value()));
  return value;
}

namespace {

Result<Extent> readExtent(const VtiFile& file, const pugi::xml_node& node, const char* name) {
  const pugi::xml_attribute attribute = node.attribute(name);
  if (!attribute) return file.fail(std::string(node.name()) + ": missing " + name);
  const std::optional<Extent> extent = parseExtent(attribute.value());
  if (!extent)
    return file.fail(
        std::string(node.name()) + " " + name +
        ": expected 6 whole numbers x0 x1 y0 y1 z0 z1 with each first <= last, found " +
        quoteForMessage(attribute.value()));
  return *extent;
}

std::string listNames(const std::vector<ArrayRef>& arrays, std::uint64_t components) {
  std::string list;
  for (const ArrayRef& array : arrays) {
    if (array.components != components) continue;
    list += (list.empty() ? "" : ", ") + quoteForMessage(array.name) +
            (array.cellData ? " (cell data)" : "");
  }
  return list.empty() ? "none" : list;
}

// The file's bytes (or, for a large file, its head: openHead) read and its XML parsed.
Result<void> readXml(VtiFile& file, bool stream) {
  const std::filesystem::path& path = file.path;
  const HeadRead read = openHead(file, stream);
  const bool head = read == HeadRead::Head;
  if (read == HeadRead::Nothing && stream) {
    LIC3D_TRY_ASSIGN(const FileReader reader, FileReader::open(path));
    if (reader.size() > kHeadBytes)
      return readWholeError(path,
                            "its data is not all appended raw after an XML header of at "
                            "most 64 KiB (inline ascii or base64 arrays)");
  }
  if (read == HeadRead::Nothing) {
    LIC3D_TRY_ASSIGN(file.bytes, readFile(path, kMaxFileBytes));
  }
  const std::size_t first = file.bytes.find_first_not_of(" \t\r\n");
  if (first == std::string::npos || file.bytes[first] != '<')
    return file.fail(first == std::string::npos
                         ? "empty file (expected a VTK XML ImageData file)"
                         : "not an XML file: it starts with " +
                               quoteForMessage(std::string_view(file.bytes).substr(first, 16)) +
                               ", expected '<?xml' or '<VTKFile'");
  if (!head) {
    LIC3D_TRY_ASSIGN(const std::optional<AppendedSplit> split, findAppended(file, file.bytes));
    if (split) {
      useAppended(file, file.bytes, *split);
      file.appended = std::string_view(file.bytes).substr(split->data);
      file.appendedAt = split->data;
      file.appendedSize = file.appended.size();
    }
  }
  std::string& xml = file.hasAppended ? file.xml : file.bytes;
  const pugi::xml_parse_result parsed = file.document.load_buffer_inplace(
      xml.data(), xml.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed)
    return file.fail(std::string("invalid XML at byte ") + std::to_string(parsed.offset) + ": " +
                     parsed.description());
  return {};
}

// VTKFile's attributes: the type, the byte order, the header type, the compressor, and the
// appended data's encoding.
Result<void> readRoot(VtiFile& file, const pugi::xml_node& root, bool stream) {
  const std::filesystem::path& path = file.path;
  if (!root) return file.fail("not a VTK XML file: the root element is not VTKFile");
  const std::string type = root.attribute("type").value();
  if (type != "ImageData")
    return file.fail("VTKFile type " + quoteForMessage(type) +
                     " is not supported (expected ImageData)");
  const std::string order = root.attribute("byte_order").value();
  if (order == "BigEndian") {
    file.order = std::endian::big;
  } else if (!order.empty() && order != "LittleEndian") {
    return file.fail("byte_order: expected LittleEndian or BigEndian, found " +
                     quoteForMessage(order));
  }
  const std::string headerType = root.attribute("header_type").value();
  if (headerType == "UInt64") {
    file.header64 = true;
  } else if (!headerType.empty() && headerType != "UInt32") {
    return file.fail("header_type: expected UInt32 or UInt64, found " +
                     quoteForMessage(headerType));
  }
  const std::string compressor = root.attribute("compressor").value();
  if (compressor == "vtkZLibDataCompressor") {
    file.zlib = true;
  } else if (!compressor.empty()) {
    return file.fail("compressor " + quoteForMessage(compressor) +
                     " is not supported (expected vtkZLibDataCompressor or none)");
  }
  if (file.hasAppended) {
    const std::string encoding = root.child("AppendedData").attribute("encoding").value();
    if (encoding != "raw" && encoding != "base64")
      return file.fail("AppendedData encoding: expected raw or base64, found " +
                       quoteForMessage(encoding));
    file.appendedBase64 = encoding == "base64";
    if (file.appendedInFile && file.appendedBase64 && !stream) {
      // Base64 is decoded from memory: the rest of the file is read after all.
      LIC3D_TRY_ASSIGN(file.bytes, readFile(path, kMaxFileBytes));
      file.appended = std::string_view(file.bytes).substr(file.appendedAt);
      file.appendedSize = file.appended.size();
      file.appendedInFile = false;
    }
  }
  return {};
}

// ImageData's grid (WholeExtent, Origin, Spacing) and its one Piece.
Result<void> readGrid(VtiFile& file, const pugi::xml_node& image, bool stream) {
  LIC3D_TRY_ASSIGN(const Extent whole, readExtent(file, image, "WholeExtent"));
  std::array<std::uint64_t, 3> sizes{};
  for (std::size_t axis = 0; axis < 3; ++axis)
    sizes[axis] =
        static_cast<std::uint64_t>(whole.bounds[2 * axis + 1] - whole.bounds[2 * axis]) + 1;
  if (const std::string problem =
          gridLimitProblem(sizes[0], sizes[1], sizes[2], stream ? kMaxStreamedVoxels : kMaxVoxels);
      !problem.empty())
    return file.fail("WholeExtent: " + problem);
  file.dims =
      Dims(static_cast<int>(sizes[0]), static_cast<int>(sizes[1]), static_cast<int>(sizes[2]));
  LIC3D_TRY_ASSIGN(const glm::dvec3 origin, parseTriple(file.path, image, "Origin", 0.0, false));
  LIC3D_TRY_ASSIGN(file.geometry.spacing, parseTriple(file.path, image, "Spacing", 1.0, true));
  // Point (i,j,k) of the extent sits at Origin + (i,j,k) * Spacing, so an extent that does not
  // start at 0 moves the first voxel.
  for (glm::length_t axis = 0; axis < 3; ++axis)
    file.geometry.origin[axis] =
        origin[axis] + static_cast<double>(whole.bounds[2 * static_cast<std::size_t>(axis)]) *
                           file.geometry.spacing[axis];
  for (glm::length_t axis = 0; axis < 3; ++axis)
    if (!std::isfinite(file.geometry.origin[axis]))
      return file.fail("ImageData: Origin + WholeExtent * Spacing is not finite");

  std::size_t pieces = 0;
  for (const pugi::xml_node piece : image.children("Piece")) {
    ++pieces;
    file.piece = piece;
  }
  if (pieces != 1)
    return file.fail("ImageData holds " + std::to_string(pieces) +
                     " Piece elements; lic3d reads files with exactly one (as ParaView and VTK "
                     "write them by default)");
  if (file.piece.attribute("Extent")) {
    LIC3D_TRY_ASSIGN(const Extent extent, readExtent(file, file.piece, "Extent"));
    if (!(extent == whole))
      return file.fail(
          "the Piece's Extent " + quoteForMessage(file.piece.attribute("Extent").value()) +
          " differs from WholeExtent " + quoteForMessage(image.attribute("WholeExtent").value()) +
          " (lic3d reads one piece covering the whole grid)");
  }
  return {};
}

}  // namespace

std::optional<Extent> parseExtent(std::string_view text) {
  const std::vector<std::string_view> words = splitWords(text);
  if (words.size() != 6) return std::nullopt;
  Extent extent;
  for (std::size_t i = 0; i < 6; ++i) {
    Result<std::int64_t> number = parseExtentNumber(words[i]);
    if (!number) return std::nullopt;
    extent.bounds[i] = *number;
  }
  for (std::size_t axis = 0; axis < 3; ++axis)
    if (extent.bounds[2 * axis] > extent.bounds[2 * axis + 1]) return std::nullopt;
  return extent;
}

Result<std::unique_ptr<VtiFile>> openVti(const std::filesystem::path& path, bool stream) {
  auto file = std::make_unique<VtiFile>();
  file->path = path;
  LIC3D_TRY(readXml(*file, stream));
  const pugi::xml_node root = file->document.child("VTKFile");
  LIC3D_TRY(readRoot(*file, root, stream));
  const pugi::xml_node image = root.child("ImageData");
  if (!image) return file->fail("VTKFile holds no ImageData element");
  LIC3D_TRY(readGrid(*file, image, stream));
  return file;
}

std::string describe(const ArrayRef& array) {
  return "DataArray " + quoteForMessage(array.name) + (array.cellData ? " (cell data)" : "");
}

Result<void> checkArray(const VtiFile& file, const ArrayRef& array, std::uint64_t tuples) {
  const std::string what = describe(array);
  if (!array.type)
    return file.fail(what + ": type " + quoteForMessage(array.node.attribute("type").value()) +
                     " is not supported (expected Int8 .. UInt64, Float32 or Float64)");
  if (const pugi::xml_attribute count = array.node.attribute("NumberOfTuples")) {
    std::uint64_t declared = 0;
    if (!parseUnsigned(count.value(), declared) || declared != tuples)
      return file.fail(what + ": NumberOfTuples " + quoteForMessage(count.value()) +
                       " does not match the " + std::to_string(tuples) +
                       (array.cellData ? " cells" : " points") + " of the grid");
  }
  return {};
}

Result<std::uint64_t> appendedOffset(const VtiFile& file, const ArrayRef& array) {
  std::uint64_t offset = 0;
  const pugi::xml_attribute attribute = array.node.attribute("offset");
  if (!attribute || !parseUnsigned(attribute.value(), offset))
    return file.fail(describe(array) + ": an appended array needs a whole-number offset, found " +
                     quoteForMessage(attribute.value()));
  if (offset > file.appendedSize)
    return file.fail(describe(array) + ": offset " + std::to_string(offset) + " is beyond the " +
                     std::to_string(file.appendedSize) + " bytes of AppendedData");
  return offset;
}

Result<std::vector<ArrayRef>> listArrays(const VtiFile& file) {
  std::vector<ArrayRef> arrays;
  for (const bool cellData : {false, true}) {
    const pugi::xml_node section = file.piece.child(cellData ? "CellData" : "PointData");
    for (const pugi::xml_node node : section.children("DataArray")) {
      ArrayRef array;
      array.node = node;
      array.name = node.attribute("Name").value();
      array.cellData = cellData;
      array.type = findVtkXmlType(node.attribute("type").value());
      if (const pugi::xml_attribute components = node.attribute("NumberOfComponents")) {
        if (!parseUnsigned(components.value(), array.components) || array.components < 1 ||
            array.components > 64)
          return file.fail(describe(array) + ": NumberOfComponents: expected 1 to 64, found " +
                           quoteForMessage(components.value()));
      }
      arrays.push_back(std::move(array));
    }
  }
  return arrays;
}

Result<ArrayRef> chooseArray(const VtiFile& file, const std::vector<ArrayRef>& arrays,
                             std::string_view name, std::uint64_t components,
                             const char* activeAttribute, std::uint64_t alternative) {
  const std::string kind = std::to_string(components) + "-component";
  const auto fits = [&](const ArrayRef& array) {
    return array.components == components || (alternative > 0 && array.components == alternative);
  };
  if (!name.empty()) {
    for (const bool cellData : {false, true}) {
      for (const ArrayRef& array : arrays) {
        if (array.cellData != cellData || array.name != name) continue;
        if (!fits(array))
          return file.fail(describe(array) + " has " + std::to_string(array.components) +
                           " components, expected " + std::to_string(components) + "; " + kind +
                           " arrays: " + listNames(arrays, components));
        return array;
      }
    }
    return file.fail("no " + kind + " DataArray named " + quoteForMessage(name) +
                     "; found: " + listNames(arrays, components));
  }
  for (const bool cellData : {false, true}) {
    const std::string active =
        file.piece.child(cellData ? "CellData" : "PointData").attribute(activeAttribute).value();
    for (const ArrayRef& array : arrays)
      if (array.cellData == cellData && !active.empty() && array.name == active && fits(array))
        return array;
    for (const ArrayRef& array : arrays)
      if (array.cellData == cellData && array.components == components) return array;
    for (const ArrayRef& array : arrays)
      if (array.cellData == cellData && fits(array)) return array;
  }
  return file.fail("no " + kind + " DataArray in PointData or CellData");
}

}  // namespace lic3d::vti
