// SPDX-License-Identifier: BSD-3-Clause
// The NRRD header: every spelling the format allows, read line by line within a size limit and
// turned into a Layout only once each number the payload depends on has been checked.

#include "io/nrrd_header.h"

#include <algorithm>
#include <cmath>
#include <glm/geometric.hpp>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/text.h"
#include "io/file_util.h"

namespace lic3d::nrrd {
namespace {

constexpr std::size_t kMaxHeaderBytes = 64 * 1024;

struct HeaderField {
  std::string value;
  int line = 0;
};

// Field names lower-cased with spaces removed, so "space directions" and "spacedirections" (both
// allowed by the format) are one key.
using HeaderFields = std::map<std::string, HeaderField>;

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
    readSampleUnits(layout);
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
    if (layout.voxels > expected_.maxVoxels)
      return fail("sizes", std::to_string(layout.voxels) + " voxels exceed the limit of " +
                               std::to_string(expected_.maxVoxels));
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
    const NumberTypeInfo* info = findNrrdType(key);
    const std::string allowed = " (expected " + std::string(expected_.typesText) + ")";
    // `block` (opaque values of a given size) is a NRRD type, though no reader takes it.
    if (!info && key != "block")
      return fail("type", "unknown type " + quoteForMessage(type->value) + allowed);
    if (!info || std::find(expected_.types.begin(), expected_.types.end(), info->type) ==
                     expected_.types.end())
      return fail("type", quoteForMessage(type->value) + " is not supported here" + allowed);
    layout.type = info->type;

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
      if (numberType(layout.type).bytes > 1)
        return fileError(path_, "missing field 'endian' (needed for " +
                                    std::to_string(numberType(layout.type).bytes) +
                                    "-byte values)");
      return {};
    }
    const std::string endianKey = asciiLowerCase(endian->value);
    if (endianKey != "little" && endianKey != "big")
      return fail("endian", "expected little or big, found " + quoteForMessage(endian->value));
    layout.order = endianKey == "little" ? std::endian::little : std::endian::big;
    return {};
  }

  // sample units: free text, which teem writes in double quotes (like the per-axis `units`).
  void readSampleUnits(Layout& layout) const {
    const HeaderField* units = find("sample units");
    if (!units) return;
    std::string_view text = units->value;
    if (text.size() >= 2 && text.front() == '"' && text.back() == '"')
      text = trim(text.substr(1, text.size() - 2));
    layout.sampleUnits = text;
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
        // hypot: a vector of 1e200 has a length of 1e200, not the infinity of its square's root
        // (checkGridGeometry then refuses the spacing by its range).
        const double length = std::hypot(direction->x, direction->y, direction->z);
        if (!(length > 0.0))
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

}  // namespace

Result<Layout> readLayout(FileReader& reader, const Expectation& expected) {
  LIC3D_TRY_ASSIGN(const HeaderFields fields, readHeader(reader));
  return HeaderInterpreter(reader.path(), fields, expected).interpret();
}

}  // namespace lic3d::nrrd
