#include "io/nrrd.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <glm/geometric.hpp>
#include <map>
#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "io/file_util.h"
#include "io/volume_io.h"

namespace lic3d {
namespace {

constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
// A multiple of every value size, so chunks never split a value.
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "vectors are written as packed floats");

enum class ValueType {
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64,
  Float,
  Double,
  Block
};

struct TypeSpelling {
  std::string_view spelling;
  ValueType type;
};

// Every spelling the NRRD format allows, after lower-casing and collapsing spaces.
constexpr TypeSpelling kTypeSpellings[] = {
    {"signed char", ValueType::Int8},
    {"int8", ValueType::Int8},
    {"int8_t", ValueType::Int8},
    {"uchar", ValueType::UInt8},
    {"unsigned char", ValueType::UInt8},
    {"uint8", ValueType::UInt8},
    {"uint8_t", ValueType::UInt8},
    {"short", ValueType::Int16},
    {"short int", ValueType::Int16},
    {"signed short", ValueType::Int16},
    {"signed short int", ValueType::Int16},
    {"int16", ValueType::Int16},
    {"int16_t", ValueType::Int16},
    {"ushort", ValueType::UInt16},
    {"unsigned short", ValueType::UInt16},
    {"unsigned short int", ValueType::UInt16},
    {"uint16", ValueType::UInt16},
    {"uint16_t", ValueType::UInt16},
    {"int", ValueType::Int32},
    {"signed int", ValueType::Int32},
    {"int32", ValueType::Int32},
    {"int32_t", ValueType::Int32},
    {"uint", ValueType::UInt32},
    {"unsigned int", ValueType::UInt32},
    {"uint32", ValueType::UInt32},
    {"uint32_t", ValueType::UInt32},
    {"longlong", ValueType::Int64},
    {"long long", ValueType::Int64},
    {"long long int", ValueType::Int64},
    {"signed long long", ValueType::Int64},
    {"signed long long int", ValueType::Int64},
    {"int64", ValueType::Int64},
    {"int64_t", ValueType::Int64},
    {"ulonglong", ValueType::UInt64},
    {"unsigned long long", ValueType::UInt64},
    {"unsigned long long int", ValueType::UInt64},
    {"uint64", ValueType::UInt64},
    {"uint64_t", ValueType::UInt64},
    {"float", ValueType::Float},
    {"double", ValueType::Double},
    {"block", ValueType::Block},
};

std::size_t valueBytes(ValueType type) {
  switch (type) {
    case ValueType::Int8:
    case ValueType::UInt8:
    case ValueType::Block: return 1;
    case ValueType::Int16:
    case ValueType::UInt16: return 2;
    case ValueType::Int32:
    case ValueType::UInt32:
    case ValueType::Float: return 4;
    case ValueType::Int64:
    case ValueType::UInt64:
    case ValueType::Double: return 8;
  }
  return 1;
}

enum class Encoding { Raw, Gzip };

struct HeaderField {
  std::string value;
  int line = 0;
};

// Field names lower-cased with spaces removed, so "space directions" and "spacedirections" (both
// allowed by the format) are one key.
using HeaderFields = std::map<std::string, HeaderField>;

// What the header says about the payload, after every check.
struct Layout {
  ValueType type = ValueType::Float;
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

  std::uint64_t payloadBytes() const { return voxels * components * valueBytes(type); }
};

// What one reader accepts.
struct Expectation {
  std::size_t dimension;   // 3, or 4 with the components on the first axis
  std::size_t components;  // the size of that first axis
  std::string_view dimensionMeaning;
  std::string_view componentsMeaning;
  std::vector<ValueType> types;
  std::string_view typesText;
  // Vector fields: also a 2D grid (one layer along z), `dimension` - 1 axes, whose first axis
  // holds 2 or `components` values (2D vectors lie in the x-y plane).
  bool planar = false;
};

std::string_view trim(std::string_view text) {
  while (!text.empty() && isAsciiSpace(text.front())) text.remove_prefix(1);
  while (!text.empty() && isAsciiSpace(text.back())) text.remove_suffix(1);
  return text;
}

// Splits "none (1,0,0) ( 0, 1, 0 )" into "none", "(1,0,0)", "( 0, 1, 0 )": vectors may hold spaces.
std::vector<std::string_view> splitVectorList(std::string_view text) {
  std::vector<std::string_view> items;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isAsciiSpace(text[i])) ++i;
    if (i == text.size()) break;
    const std::size_t start = i;
    if (text[i] == '(') {
      const std::size_t close = text.find(')', i);
      i = close == std::string_view::npos ? text.size() : close + 1;
    } else {
      while (i < text.size() && !isAsciiSpace(text[i])) ++i;
    }
    items.push_back(text.substr(start, i - start));
  }
  return items;
}

// "(x,y,z)", or "(x,y)" for a 2D space (`count` 2; z is then 0).
std::optional<glm::dvec3> parseVector(std::string_view text, int count = 3) {
  text = trim(text);
  if (text.size() < 2 || text.front() != '(' || text.back() != ')') return std::nullopt;
  text = text.substr(1, text.size() - 2);
  glm::dvec3 vector{0.0};
  for (int axis = 0; axis < count; ++axis) {
    const bool last = axis == count - 1;
    const std::size_t comma = text.find(',');
    if (last != (comma == std::string_view::npos)) return std::nullopt;
    const std::string_view item = last ? text : text.substr(0, comma);
    if (!parseDouble(trim(item), vector[axis]) || !std::isfinite(vector[axis])) return std::nullopt;
    if (!last) text.remove_prefix(comma + 1);
  }
  return vector;
}

// Appends rather than "(" + ...: GCC 12 at -O3 gives a false -Wrestrict on prepending a literal.
std::string formatVector(const glm::dvec3& v) {
  std::string text = "(";
  text += formatDouble(v.x);
  text += ',';
  text += formatDouble(v.y);
  text += ',';
  text += formatDouble(v.z);
  text += ')';
  return text;
}

enum class LineStatus { Ok, End, TooLong };

// One header line without its "\n" or "\r\n"; `budget` bounds the bytes read over all lines.
LineStatus readHeaderLine(FileReader& reader, std::string& line, std::size_t& budget) {
  line.clear();
  int c = reader.get();
  if (c < 0) return LineStatus::End;
  for (; c >= 0 && c != '\n'; c = reader.get()) {
    if (budget == 0) return LineStatus::TooLong;
    --budget;
    line.push_back(static_cast<char>(c));
  }
  if (c == '\n') {
    if (budget == 0) return LineStatus::TooLong;
    --budget;
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return LineStatus::Ok;
}

// Reads from the magic line to the blank line that ends the header; the reader is then at the
// first payload byte. A detached header (one with a `data file` field) may also end with the file.
Result<HeaderFields> readHeader(FileReader& reader) {
  const std::filesystem::path& path = reader.path();
  std::string line;
  std::size_t magicBudget = 64;
  const LineStatus magicStatus = readHeaderLine(reader, line, magicBudget);
  if (magicStatus == LineStatus::End)
    return fileError(path, "empty file (expected a NRRD header starting with NRRD0001..NRRD0005)");
  const bool isNrrd = magicStatus == LineStatus::Ok && line.size() == 8 && line.starts_with("NRRD");
  if (!isNrrd)
    return fileError(path, "not a NRRD file: the first line is " + quoteForMessage(line) +
                               ", expected NRRD0001..NRRD0005");
  if (!line.starts_with("NRRD000") || line[7] < '1' || line[7] > '5')
    return fileError(path, "unsupported NRRD version " + quoteForMessage(line) +
                               " (expected NRRD0001..NRRD0005)");

  HeaderFields fields;
  std::size_t budget = kMaxHeaderBytes;
  for (int lineNumber = 2;; ++lineNumber) {
    const LineStatus status = readHeaderLine(reader, line, budget);
    if (status == LineStatus::TooLong)
      return fileError(path,
                       "the header is longer than 64 KiB (or lacks the blank line that ends it)");
    if (status == LineStatus::End && fields.contains("datafile") && reader.remaining() == 0)
      return fields;
    if (status == LineStatus::End) {
      std::string problem = "the header ends without the blank line that must precede the data";
      problem +=
          reader.remaining() > 0 ? " (" + reader.failureReason() + ")" : " (file truncated?)";
      return fileError(path, problem);
    }
    if (line.empty()) return fields;
    if (line.front() == '#') continue;
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos)
      return fileError(path, "line " + std::to_string(lineNumber) +
                                 ": expected 'field: value', found " + quoteForMessage(line));
    if (colon + 1 < line.size() && line[colon + 1] == '=')
      continue;  // key:=value pairs carry no layout
    std::string name;
    for (char c : asciiLowerCase(line.substr(0, colon)))
      if (!isAsciiSpace(c)) name += c;
    const auto [where, inserted] = fields.emplace(
        name, HeaderField{std::string(trim(std::string_view(line).substr(colon + 1))), lineNumber});
    if (!inserted)
      return fileError(path, "field " + quoteForMessage(line.substr(0, colon)) +
                                 " appears twice (lines " + std::to_string(where->second.line) +
                                 " and " + std::to_string(lineNumber) + ")");
  }
}

// Turns header fields into a Layout, checking every field the payload depends on so that nothing
// is allocated from a bad number.
class HeaderInterpreter {
 public:
  HeaderInterpreter(const std::filesystem::path& path, const HeaderFields& fields,
                    const Expectation& expected)
      : path_(path), fields_(fields), expected_(expected) {}

  Result<Layout> interpret() {
    Layout layout;
    LIC3D_TRY(readDataFile(layout));
    LIC3D_TRY(readGrid(layout));
    LIC3D_TRY(readValues(layout));
    LIC3D_TRY(readGeometry(layout));
    return layout;
  }

 private:
  Error fail(std::string_view field, const std::string& problem) const {
    return fileError(path_, std::string(field) + ": " + problem);
  }
  Error missing(std::string_view field) const {
    return fileError(path_, "missing field '" + std::string(field) + "'");
  }
  // Looks a field up by its name as the format spells it ("space directions").
  const HeaderField* find(std::string_view name) const {
    std::string key;
    for (const char c : name)
      if (c != ' ') key += c;
    const auto where = fields_.find(key);
    return where == fields_.end() ? nullptr : &where->second;
  }
  std::size_t firstSpatialAxis() const { return dimension_ - spatialAxes_; }

  // data file, line skip, byte skip
  Result<void> readDataFile(Layout& layout) const {
    if (const HeaderField* dataFile = find("data file")) {
      const std::vector<std::string_view> words = splitWords(dataFile->value);
      if (words.empty()) return fail("data file", "no file name");
      // The multi-file forms: "LIST" followed by one name per line, or "name%03d.raw min max
      // step [subdim]". lic3d volumes are single files.
      if (asciiLowerCase(words[0]) == "list" ||
          (words.size() >= 4 && words[0].find('%') != std::string_view::npos))
        return fail("data file", quoteForMessage(dataFile->value) +
                                     " names several files, which is not supported (expected "
                                     "one data file)");
      const std::filesystem::path name(std::string(trim(dataFile->value)));
      layout.dataFile = name.is_absolute() ? name : path_.parent_path() / name;
    }
    if (const HeaderField* lineSkip = find("line skip")) {
      if (!parseUnsigned(lineSkip->value, layout.lineSkip))
        return fail("line skip",
                    "expected a whole number, found " + quoteForMessage(lineSkip->value));
    }
    if (const HeaderField* byteSkip = find("byte skip")) {
      std::uint64_t value = 0;
      if (byteSkip->value == "-1") {
        layout.byteSkip = -1;
      } else if (parseUnsigned(byteSkip->value, value) &&
                 value <= static_cast<std::uint64_t>(INT64_MAX)) {
        layout.byteSkip = static_cast<std::int64_t>(value);
      } else {
        return fail("byte skip",
                    "expected -1 or a whole number, found " + quoteForMessage(byteSkip->value));
      }
    }
    return {};
  }

  // dimension and sizes
  Result<void> readGrid(Layout& layout) const {
    const HeaderField* dimension = find("dimension");
    if (!dimension) return missing("dimension");
    std::uint64_t dimensionValue = 0;
    if (!parseUnsigned(dimension->value, dimensionValue))
      return fail("dimension", quoteForMessage(dimension->value) + " is not a whole number");
    if (expected_.planar && dimensionValue + 1 == expected_.dimension) {
      dimension_ = dimensionValue;  // a 2D grid: one layer along z
      spatialAxes_ = 2;
    } else if (dimensionValue != expected_.dimension) {
      return fail(
          "dimension",
          "expected " + std::to_string(expected_.dimension) + " (" +
              std::string(expected_.dimensionMeaning) + ")" +
              (expected_.planar ? " or " + std::to_string(expected_.dimension - 1) + " (a 2D grid)"
                                : std::string()) +
              ", found " + std::to_string(dimensionValue));
    }

    const HeaderField* sizes = find("sizes");
    if (!sizes) return missing("sizes");
    const std::vector<std::string_view> words = splitWords(sizes->value);
    if (words.size() != dimension_)
      return fail("sizes", "expected " + std::to_string(dimension_) +
                               " numbers (one per axis), found " + std::to_string(words.size()));
    std::vector<std::uint64_t> values;
    for (const std::string_view word : words) {
      std::uint64_t value = 0;
      if (!parseUnsigned(word, value))
        return fail("sizes", quoteForMessage(word) + " is not a whole number");
      if (value < 1 || value > kMaxAxisSize)
        return fail("sizes",
                    std::string(word) + " is outside [1, " + std::to_string(kMaxAxisSize) + "]");
      values.push_back(value);
    }
    const std::size_t first = firstSpatialAxis();
    const bool twoComponents = spatialAxes_ == 2 && first == 1 && values[0] == 2;
    if (first == 1 && values[0] != expected_.components && !twoComponents)
      return fail("sizes", "the first axis holds the " + std::string(expected_.componentsMeaning) +
                               " and must have size " + std::to_string(expected_.components) +
                               (spatialAxes_ == 2 ? " or 2" : "") + ", found " +
                               std::to_string(values[0]));
    layout.components = first == 1 ? static_cast<std::size_t>(values[0]) : 1;
    const std::uint64_t depth = spatialAxes_ == 3 ? values[first + 2] : 1;
    layout.dims = Dims(static_cast<int>(values[first]), static_cast<int>(values[first + 1]),
                       static_cast<int>(depth));
    layout.voxels = values[first] * values[first + 1] * depth;
    if (layout.voxels > kMaxVoxels)
      return fail("sizes", std::to_string(layout.voxels) + " voxels exceed the limit of " +
                               std::to_string(kMaxVoxels));
    return {};
  }

  // type, encoding and endian
  Result<void> readValues(Layout& layout) const {
    const HeaderField* type = find("type");
    if (!type) return missing("type");
    const std::string lowered = asciiLowerCase(type->value);
    std::string key;
    for (const std::string_view word : splitWords(lowered)) {
      if (!key.empty()) key += ' ';
      key += word;
    }
    const auto spelling = std::find_if(std::begin(kTypeSpellings), std::end(kTypeSpellings),
                                       [&](const TypeSpelling& s) { return s.spelling == key; });
    const std::string allowed = " (expected " + std::string(expected_.typesText) + ")";
    if (spelling == std::end(kTypeSpellings))
      return fail("type", "unknown type " + quoteForMessage(type->value) + allowed);
    if (std::find(expected_.types.begin(), expected_.types.end(), spelling->type) ==
        expected_.types.end())
      return fail("type", quoteForMessage(type->value) + " is not supported here" + allowed);
    layout.type = spelling->type;

    const HeaderField* encoding = find("encoding");
    if (!encoding) return missing("encoding");
    const std::string encodingKey = asciiLowerCase(encoding->value);
    if (encodingKey == "raw") {
      layout.encoding = Encoding::Raw;
    } else if (encodingKey == "gzip" || encodingKey == "gz") {
      layout.encoding = Encoding::Gzip;
    } else {
      constexpr std::string_view kOtherEncodings[] = {"txt", "text",  "ascii", "hex",
                                                      "bz2", "bzip2", "zrl"};
      const bool known = std::find(std::begin(kOtherEncodings), std::end(kOtherEncodings),
                                   encodingKey) != std::end(kOtherEncodings);
      const std::string quoted = quoteForMessage(encoding->value);
      return fail("encoding",
                  (known ? quoted + " is not supported" : "unknown encoding " + quoted) +
                      " (expected raw or gzip)");
    }

    if (layout.encoding == Encoding::Gzip && layout.byteSkip < 0)
      return fail("byte skip", "-1 (data at the end of the file) needs raw encoding, not gzip");

    const HeaderField* endian = find("endian");
    if (!endian) {
      if (valueBytes(layout.type) > 1)
        return fileError(path_, "missing field 'endian' (needed for " +
                                    std::to_string(valueBytes(layout.type)) + "-byte values)");
      return {};
    }
    const std::string endianKey = asciiLowerCase(endian->value);
    if (endianKey != "little" && endianKey != "big")
      return fail("endian", "expected little or big, found " + quoteForMessage(endian->value));
    layout.order = endianKey == "little" ? std::endian::little : std::endian::big;
    return {};
  }

  // space dimension, space directions or spacings, space origin
  Result<void> readGeometry(Layout& layout) const {
    const HeaderField* spaceDimension = find("space dimension");
    // A 2D grid may lie in a 2D space: its vectors and origin then have two numbers.
    const bool space2D = spatialAxes_ == 2 && spaceDimension && spaceDimension->value == "2";
    if (spaceDimension && spaceDimension->value != "3" && !space2D)
      return fail("space dimension",
                  std::string(spatialAxes_ == 2 ? "expected 2 or 3" : "expected 3") + ", found " +
                      quoteForMessage(spaceDimension->value));
    const int spaceAxes = space2D ? 2 : 3;
    const std::size_t first = firstSpatialAxis();
    // NRRD forbids both; when a writer emits both anyway the directions are the fuller description.
    if (const HeaderField* directions = find("space directions")) {
      const std::vector<std::string_view> items = splitVectorList(directions->value);
      if (items.size() != dimension_)
        return fail("space directions", "expected " + std::to_string(dimension_) +
                                            " entries (one per axis), found " +
                                            std::to_string(items.size()));
      for (std::size_t axis = 0; axis < items.size(); ++axis) {
        if (axis < first) {
          if (asciiLowerCase(items[axis]) != "none")
            return fail("space directions", "the vector-component axis must be 'none', found " +
                                                quoteForMessage(items[axis]));
          continue;
        }
        const std::optional<glm::dvec3> direction = parseVector(items[axis], spaceAxes);
        if (!direction)
          return fail("space directions", "axis " + std::to_string(axis) +
                                              ": expected a vector of " +
                                              std::to_string(spaceAxes) + " finite numbers like " +
                                              (spaceAxes == 2 ? "(1,0)" : "(1,0,0)") + ", found " +
                                              quoteForMessage(items[axis]));
        // lic3d grids are axis aligned: an oblique or rotated frame keeps only each axis' length.
        const double length = std::sqrt(glm::dot(*direction, *direction));
        if (!(length > 0.0) || !std::isfinite(length))
          return fail("space directions", "axis " + std::to_string(axis) + " has zero length");
        layout.geometry.spacing[static_cast<glm::length_t>(axis - first)] = length;
      }
    } else if (const HeaderField* spacings = find("spacings")) {
      const std::vector<std::string_view> words = splitWords(spacings->value);
      if (words.size() != dimension_)
        return fail("spacings", "expected " + std::to_string(dimension_) +
                                    " numbers (one per axis), found " +
                                    std::to_string(words.size()));
      // The component axis' spacing is conventionally nan and means nothing: it is not checked.
      for (std::size_t axis = first; axis < words.size(); ++axis) {
        double value = 0.0;
        if (!parseDouble(words[axis], value) || !std::isfinite(value) || !(value > 0.0))
          return fail("spacings", "axis " + std::to_string(axis) +
                                      ": expected a positive number, found " +
                                      quoteForMessage(words[axis]));
        layout.geometry.spacing[static_cast<glm::length_t>(axis - first)] = value;
      }
    }
    if (const HeaderField* origin = find("space origin")) {
      const std::optional<glm::dvec3> value = parseVector(origin->value, spaceAxes);
      if (!value)
        return fail("space origin", std::string(spaceAxes == 2 ? "expected (x,y) with 2"
                                                               : "expected (x,y,z) with 3") +
                                        " finite numbers, found " + quoteForMessage(origin->value));
      layout.geometry.origin = *value;
    }
    return {};
  }

  const std::filesystem::path& path_;
  const HeaderFields& fields_;
  const Expectation& expected_;
  // As the header gives them: expected_.dimension and 3, or one less and 2 for a planar grid.
  mutable std::size_t dimension_ = expected_.dimension;
  mutable std::size_t spatialAxes_ = 3;
};

// Moves `reader` past `line skip` lines and, for raw data, `byte skip` bytes.
Result<void> skipToPayload(FileReader& reader, const Layout& layout) {
  for (std::uint64_t line = 0; line < layout.lineSkip; ++line) {
    int c = reader.get();
    while (c >= 0 && c != '\n') c = reader.get();
    if (c < 0)
      return fileError(reader.path(), "line skip: the data ends after " + std::to_string(line) +
                                          " of the " + std::to_string(layout.lineSkip) +
                                          " lines to skip");
  }
  if (layout.encoding != Encoding::Raw || layout.byteSkip == 0) return {};
  const std::uint64_t needed = layout.payloadBytes();
  // -1: the data is the last bytes of the file, whatever precedes it.
  const std::uint64_t skip = layout.byteSkip > 0 ? static_cast<std::uint64_t>(layout.byteSkip)
                             : reader.remaining() >= needed ? reader.remaining() - needed
                                                            : 0;
  if (skip > reader.remaining())
    return fileError(reader.path(), "byte skip: " + std::to_string(skip) + " bytes to skip, only " +
                                        std::to_string(reader.remaining()) + " left in the file");
  if (reader.skip(skip) != skip)
    return fileError(reader.path(), "cannot read: " + reader.failureReason());
  return {};
}

// Refuses a payload that the file cannot hold, before the caller allocates the volume.
Result<void> checkPayloadFits(FileReader& reader, const Layout& layout) {
  const std::uint64_t needed = layout.payloadBytes();
  const std::uint64_t available = reader.remaining();
  if (layout.encoding == Encoding::Raw) {
    if (available < needed)
      return fileError(reader.path(), "data is truncated: the header promises " +
                                          std::to_string(needed) + " bytes, the file holds " +
                                          std::to_string(available) + " where the data starts");
    return {};
  }
  if (available == 0) return fileError(reader.path(), "gzip data is missing: the data is empty");
  // A gzip byte skip counts decompressed bytes, which the stream must hold as well.
  const std::uint64_t inflated =
      needed + static_cast<std::uint64_t>(std::max<std::int64_t>(layout.byteSkip, 0));
  if (inflated < needed || inflated / kMaxDeflateRatio > available)
    return fileError(reader.path(), "gzip data of " + std::to_string(available) +
                                        " bytes cannot inflate to the " + std::to_string(needed) +
                                        " bytes the header promises (truncated?)");
  return {};
}

using ChunkSink = std::function<void(const char* data, std::size_t bytes)>;

// Calls `use` with each float or double of a chunk in native byte order.
template <class Use>
void forEachValue(ValueType type, const char* data, std::size_t bytes, Use&& use) {
  if (type == ValueType::Double) {
    for (std::size_t offset = 0; offset + 8 <= bytes; offset += 8) {
      double value;
      std::memcpy(&value, data + offset, 8);
      use(value);
    }
  } else {
    for (std::size_t offset = 0; offset + 4 <= bytes; offset += 4) {
      float value;
      std::memcpy(&value, data + offset, 4);
      use(static_cast<double>(value));
    }
  }
}

// Hands the payload to `sink` in native byte order, in chunks of whole values.
Result<void> readRaw(FileReader& reader, const Layout& layout, const ChunkSink& sink) {
  const std::size_t bytesPerValue = valueBytes(layout.type);
  std::uint64_t left = layout.payloadBytes();
  std::vector<char> chunk(static_cast<std::size_t>(std::min<std::uint64_t>(kChunkBytes, left)));
  while (left > 0) {
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), left));
    if (reader.read(chunk.data(), count) != count)
      return fileError(reader.path(), "data is truncated: " + reader.failureReason());
    toNativeOrder(chunk.data(), count / bytesPerValue, bytesPerValue, layout.order);
    sink(chunk.data(), count);
    left -= count;
  }
  return {};
}

// The gzip counterpart of readRaw. The stream must hold exactly the promised bytes: shorter is
// truncation, longer means the header and data disagree. Bytes after the stream's end are ignored.
Result<void> readGzip(FileReader& reader, const Layout& layout, const ChunkSink& sink) {
  const std::filesystem::path& path = reader.path();
  const std::size_t bytesPerValue = valueBytes(layout.type);
  const std::uint64_t total = layout.payloadBytes();
  InflateStream inflater;
  if (!inflater.init()) return runtimeError("zlib: cannot initialise inflate for " + path.string());
  z_stream& zs = inflater.stream();
  // Small files get a small buffer: the data's size bounds what can be read.
  std::vector<unsigned char> input(
      static_cast<std::size_t>(std::clamp<std::uint64_t>(reader.remaining(), 1, kChunkBytes)));
  std::vector<char> output(static_cast<std::size_t>(std::min<std::uint64_t>(kChunkBytes, total)));
  std::uint64_t produced = 0;
  bool ended = false;
  // teem applies a gzip byte skip to the decompressed stream.
  std::uint64_t toSkip = static_cast<std::uint64_t>(std::max<std::int64_t>(layout.byteSkip, 0));

  // Inflates into [out, out + capacity) until it is full or the stream ends.
  const auto inflateInto = [&](char* out, std::size_t capacity) -> Result<std::size_t> {
    zs.next_out = reinterpret_cast<Bytef*>(out);
    zs.avail_out = static_cast<uInt>(capacity);
    while (zs.avail_out > 0 && !ended) {
      if (zs.avail_in == 0) {
        const std::size_t got = reader.read(input.data(), input.size());
        if (got == 0) {
          if (toSkip > 0)
            return fileError(path, "gzip data is truncated within the " +
                                       std::to_string(layout.byteSkip) + " bytes of 'byte skip'");
          const std::uint64_t done = produced + capacity - zs.avail_out;
          if (done >= total)
            return fileError(path, "gzip data is truncated: the stream lacks its end and checksum");
          return fileError(path, "gzip data is truncated after " + std::to_string(done) + " of " +
                                     std::to_string(total) + " bytes (" + reader.failureReason() +
                                     ")");
        }
        zs.next_in = input.data();
        zs.avail_in = static_cast<uInt>(got);
      }
      const int status = inflate(&zs, Z_NO_FLUSH);
      if (status == Z_STREAM_END) {
        ended = true;
      } else if (status == Z_MEM_ERROR) {
        return runtimeError("zlib: out of memory while reading " + path.string());
      } else if (status == Z_DATA_ERROR || status == Z_NEED_DICT || status == Z_STREAM_ERROR ||
                 (status == Z_BUF_ERROR && zs.avail_in > 0)) {
        return fileError(
            path, std::string("gzip data is corrupt: ") + (zs.msg ? zs.msg : "inflate failed"));
      }
    }
    return capacity - zs.avail_out;
  };

  while (toSkip > 0) {
    const std::size_t capacity =
        static_cast<std::size_t>(std::min<std::uint64_t>(output.size(), toSkip));
    LIC3D_TRY_ASSIGN(const std::size_t got, inflateInto(output.data(), capacity));
    if (got < capacity)
      return fileError(path, "gzip data ends within the " + std::to_string(layout.byteSkip) +
                                 " bytes of 'byte skip'");
    toSkip -= got;
  }
  while (produced < total) {
    const std::size_t capacity =
        static_cast<std::size_t>(std::min<std::uint64_t>(output.size(), total - produced));
    LIC3D_TRY_ASSIGN(const std::size_t got, inflateInto(output.data(), capacity));
    if (got < capacity)
      return fileError(path, "gzip data holds only " + std::to_string(produced + got) +
                                 " bytes, the header promises " + std::to_string(total));
    toNativeOrder(output.data(), got / bytesPerValue, bytesPerValue, layout.order);
    sink(output.data(), got);
    produced += got;
  }
  char extra = 0;
  LIC3D_TRY_ASSIGN(const std::size_t more, inflateInto(&extra, 1));
  if (more > 0)
    return fileError(path, "gzip data holds more than the " + std::to_string(total) +
                               " bytes the header promises");
  return {};
}

Result<void> readPayload(FileReader& reader, const Layout& layout, const ChunkSink& sink) {
  return layout.encoding == Encoding::Raw ? readRaw(reader, layout, sink)
                                          : readGzip(reader, layout, sink);
}

struct Opened {
  std::filesystem::path header;
  FileReader reader;  // at the first payload byte, in the header's file or its data file
  Layout layout;
};

// An error about a detached header's data file names both files.
Error inDataFile(const std::filesystem::path& header, Error error) {
  error.message = header.string() + ": data file " + error.message;
  return error;
}

Result<Opened> openNrrd(const std::filesystem::path& path, const Expectation& expected) {
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  LIC3D_TRY_ASSIGN(const HeaderFields fields, readHeader(reader));
  LIC3D_TRY_ASSIGN(const Layout layout, HeaderInterpreter(path, fields, expected).interpret());
  if (!layout.dataFile.empty()) {
    Result<FileReader> data = FileReader::open(layout.dataFile);
    if (!data.ok()) return inDataFile(path, std::move(data).error());
    reader = std::move(data).value();
  }
  Result<void> positioned = skipToPayload(reader, layout);
  if (positioned.ok()) positioned = checkPayloadFits(reader, layout);
  if (!positioned.ok())
    return layout.dataFile.empty() ? std::move(positioned).error()
                                   : inDataFile(path, std::move(positioned).error());
  return Opened{path, std::move(reader), layout};
}

Result<void> readPayload(Opened& opened, const ChunkSink& sink) {
  Result<void> read = readPayload(opened.reader, opened.layout, sink);
  if (read.ok() || opened.layout.dataFile.empty()) return read;
  return inDataFile(opened.header, std::move(read).error());
}

// Writes `count` values of `bytesPerValue` bytes, stored in native order, as little endian.
bool writeLittleEndian(std::ostream& out, const void* data, std::size_t count,
                       std::size_t bytesPerValue) {
  const char* bytes = static_cast<const char*>(data);
  if (std::endian::native == std::endian::little || bytesPerValue < 2)
    return static_cast<bool>(out.write(bytes, static_cast<std::streamsize>(count * bytesPerValue)));
  std::vector<char> chunk(kChunkBytes);
  const std::size_t perChunk = kChunkBytes / bytesPerValue;
  for (std::size_t first = 0; first < count && out; first += perChunk) {
    const std::size_t n = std::min(perChunk, count - first);
    std::memcpy(chunk.data(), bytes + first * bytesPerValue, n * bytesPerValue);
    toNativeOrder(chunk.data(), n, bytesPerValue, std::endian::big);
    out.write(chunk.data(), static_cast<std::streamsize>(n * bytesPerValue));
  }
  return static_cast<bool>(out);
}

std::string sizesText(Dims dims) {
  return std::to_string(dims.x) + " " + std::to_string(dims.y) + " " + std::to_string(dims.z);
}

std::string directionsText(const GridGeometry& geometry) {
  return formatVector({geometry.spacing.x, 0.0, 0.0}) + " " +
         formatVector({0.0, geometry.spacing.y, 0.0}) + " " +
         formatVector({0.0, 0.0, geometry.spacing.z});
}

}  // namespace

Result<VectorField> readVectorFieldNrrd(const std::filesystem::path& path, FieldReadInfo* info) {
  const Expectation expected{4,
                             3,
                             "3 vector components on a 3D grid",
                             "vector components",
                             {ValueType::Float, ValueType::Double},
                             "float or double",
                             true};
  LIC3D_TRY_ASSIGN(Opened opened, openNrrd(path, expected));
  const Layout& layout = opened.layout;
  VectorField field;
  field.dims = layout.dims;
  field.geometry = layout.geometry;
  field.vectors.resize(static_cast<std::size_t>(layout.voxels));

  // 3 components per voxel, or 2 on a 2D grid (z stays 0).
  const glm::length_t components = static_cast<glm::length_t>(layout.components);
  std::size_t voxel = 0;  // of the next value
  glm::length_t component = 0;
  const auto store = [&](double value) {
    field.vectors[voxel][component] = vectorComponent(value);
    if (++component == components) {
      component = 0;
      ++voxel;
    }
  };
  LIC3D_TRY(readPayload(opened, [&](const char* data, std::size_t bytes) {
    forEachValue(layout.type, data, bytes, store);
  }));
  if (info) *info = FieldReadInfo{};
  LIC3D_TRY(finishVectorField(path, field, info));
  return field;
}

Result<ScalarVolume> readScalarNrrd(const std::filesystem::path& path) {
  const Expectation expected{
      3, 1, "a 3D grid of scalars", "", {ValueType::Float, ValueType::Double}, "float or double"};
  LIC3D_TRY_ASSIGN(Opened opened, openNrrd(path, expected));
  const Layout& layout = opened.layout;
  ScalarVolume volume;
  volume.dims = layout.dims;
  volume.geometry = layout.geometry;
  volume.values.resize(static_cast<std::size_t>(layout.voxels));
  std::size_t next = 0;
  LIC3D_TRY(readPayload(opened, [&](const char* data, std::size_t bytes) {
    forEachValue(layout.type, data, bytes,
                 [&](double value) { volume.values[next++] = vectorComponent(value); });
  }));
  return volume;
}

Result<RgbaVolume> readRgbaNrrd(const std::filesystem::path& path) {
  const Expectation expected{
      4, 4, "4 colour channels on a 3D grid", "RGBA channels", {ValueType::UInt8}, "uchar"};
  LIC3D_TRY_ASSIGN(Opened opened, openNrrd(path, expected));
  const Layout& layout = opened.layout;
  RgbaVolume volume;
  volume.dims = layout.dims;
  volume.geometry = layout.geometry;
  volume.rgba.resize(static_cast<std::size_t>(layout.payloadBytes()));
  std::size_t offset = 0;
  LIC3D_TRY(readPayload(opened, [&](const char* data, std::size_t bytes) {
    std::memcpy(volume.rgba.data() + offset, data, bytes);
    offset += bytes;
  }));
  return volume;
}

Result<NoiseVolume> readNoiseNrrd(const std::filesystem::path& path) {
  const Expectation expected{3,
                             1,
                             "a 3D grid of scalars",
                             "",
                             {ValueType::UInt8, ValueType::UInt16, ValueType::Float},
                             "uchar, ushort or float"};
  LIC3D_TRY_ASSIGN(Opened opened, openNrrd(path, expected));
  const Layout& layout = opened.layout;
  NoiseVolume noise;
  noise.dims = layout.dims;
  noise.type = layout.type == ValueType::UInt8    ? NoiseType::UInt8
               : layout.type == ValueType::UInt16 ? NoiseType::UInt16
                                                  : NoiseType::Float32;
  noise.bytes.resize(static_cast<std::size_t>(layout.payloadBytes()));
  std::size_t offset = 0;
  LIC3D_TRY(readPayload(opened, [&](const char* data, std::size_t bytes) {
    std::memcpy(noise.bytes.data() + offset, data, bytes);
    offset += bytes;
  }));
  if (noise.type != NoiseType::Float32) return noise;

  const std::size_t count = static_cast<std::size_t>(layout.voxels);
  float low = 0.0f;
  float high = 0.0f;
  for (std::size_t i = 0; i < count; ++i) {
    float value;
    std::memcpy(&value, noise.bytes.data() + 4 * i, 4);
    if (!std::isfinite(value))
      return fileError(path,
                       "float noise at voxel " + voxelText(layout.dims, i) + " is NaN or infinite");
    low = i == 0 ? value : std::min(low, value);
    high = i == 0 ? value : std::max(high, value);
  }
  if (low >= 0.0f && high <= 1.0f) return noise;
  if (low == high)
    return fileError(path, "float noise is the constant " + formatDouble(low) +
                               ", outside [0,1], and cannot be rescaled to [0,1]");
  const double range = static_cast<double>(high) - static_cast<double>(low);
  for (std::size_t i = 0; i < count; ++i) {
    float value;
    std::memcpy(&value, noise.bytes.data() + 4 * i, 4);
    const double scaled = (static_cast<double>(value) - static_cast<double>(low)) / range;
    value = static_cast<float>(std::clamp(scaled, 0.0, 1.0));
    std::memcpy(noise.bytes.data() + 4 * i, &value, 4);
  }
  return noise;
}

Result<void> writeScalarNrrd(const std::filesystem::path& path, const ScalarVolume& volume) {
  LIC3D_TRY(checkVolumeForWriting(path, volume.dims, volume.values.size(), 1, &volume.geometry));
  const std::string header =
      "NRRD0004\n# written by lic3d\ntype: float\ndimension: 3\nspace dimension: 3\n"
      "sizes: " +
      sizesText(volume.dims) + "\nspace directions: " + directionsText(volume.geometry) +
      "\nkinds: domain domain domain\nendian: little\nencoding: raw\nspace origin: " +
      formatVector(volume.geometry.origin) + "\n\n";
  return writeFileAtomically(path, [&](std::ostream& out) {
    out << header;
    return writeLittleEndian(out, volume.values.data(), volume.values.size(), sizeof(float));
  });
}

Result<void> writeVectorFieldNrrd(const std::filesystem::path& path, const VectorField& field) {
  LIC3D_TRY(checkVolumeForWriting(path, field.dims, field.vectors.size(), 1, &field.geometry));
  const std::string header =
      "NRRD0004\n# written by lic3d\ntype: float\ndimension: 4\nspace dimension: 3\n"
      "sizes: 3 " +
      sizesText(field.dims) + "\nspace directions: none " + directionsText(field.geometry) +
      "\nkinds: vector domain domain domain\nendian: little\nencoding: raw\n"
      "space origin: " +
      formatVector(field.geometry.origin) + "\n\n";
  return writeFileAtomically(path, [&](std::ostream& out) {
    out << header;
    return writeLittleEndian(out, field.vectors.data(), 3 * field.vectors.size(), sizeof(float));
  });
}

Result<void> writeNoiseNrrd(const std::filesystem::path& path, const NoiseVolume& noise) {
  const std::size_t bytesPerValue = lic3d::bytesPerValue(noise.type);
  if (noise.bytes.size() % bytesPerValue != 0)
    return inputError("cannot write '" + path.string() + "': the noise holds " +
                      std::to_string(noise.bytes.size()) + " bytes, not a whole number of values");
  LIC3D_TRY(
      checkVolumeForWriting(path, noise.dims, noise.bytes.size() / bytesPerValue, 1, nullptr));
  const char* type = noise.type == NoiseType::UInt8    ? "uchar"
                     : noise.type == NoiseType::UInt16 ? "ushort"
                                                       : "float";
  const std::string header = std::string("NRRD0004\n# written by lic3d\ntype: ") + type +
                             "\ndimension: 3\nsizes: " + sizesText(noise.dims) +
                             "\nkinds: domain domain domain\n" +
                             (bytesPerValue > 1 ? "endian: little\n" : "") + "encoding: raw\n\n";
  return writeFileAtomically(path, [&](std::ostream& out) {
    out << header;
    return writeLittleEndian(out, noise.bytes.data(), noise.bytes.size() / bytesPerValue,
                             bytesPerValue);
  });
}

Result<void> writeRgbaNrrd(const std::filesystem::path& path, const RgbaVolume& volume) {
  LIC3D_TRY(checkVolumeForWriting(path, volume.dims, volume.rgba.size(), 4, &volume.geometry));
  const std::string header =
      "NRRD0004\n# written by lic3d\ntype: uchar\ndimension: 4\nspace dimension: 3\n"
      "sizes: 4 " +
      sizesText(volume.dims) + "\nspace directions: none " + directionsText(volume.geometry) +
      "\nkinds: RGBA-color domain domain domain\nencoding: raw\nspace origin: " +
      formatVector(volume.geometry.origin) + "\n\n";
  return writeFileAtomically(path, [&](std::ostream& out) {
    out << header;
    return static_cast<bool>(out.write(reinterpret_cast<const char*>(volume.rgba.data()),
                                       static_cast<std::streamsize>(volume.rgba.size())));
  });
}

}  // namespace lic3d
