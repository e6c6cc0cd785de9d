#include "io/vtk_legacy.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "io/file_util.h"
#include "io/volume_io.h"

namespace lic3d {
namespace {

constexpr std::size_t kMaxLineBytes = 4096;
constexpr std::size_t kMaxTokenBytes = 256;
// A multiple of every value size, so chunks never split a value.
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

enum class Format { Ascii, Binary };
enum class Dataset { StructuredPoints, RectilinearGrid };
enum class NumberKind { Signed, Unsigned, Real };

struct DataType {
  std::string_view name;  // lower case, as VTK compares them
  std::size_t binaryBytes;
  NumberKind kind;
};

// The sizes in BINARY files. `long` is 8 bytes because VTK writes sizeof(long), and legacy files
// come from LP64 systems; vtkIdType is always written as a 32-bit int.
constexpr DataType kDataTypes[] = {
    {"unsigned_char", 1, NumberKind::Unsigned},
    {"char", 1, NumberKind::Signed},
    {"unsigned_short", 2, NumberKind::Unsigned},
    {"short", 2, NumberKind::Signed},
    {"unsigned_int", 4, NumberKind::Unsigned},
    {"int", 4, NumberKind::Signed},
    {"unsigned_long", 8, NumberKind::Unsigned},
    {"long", 8, NumberKind::Signed},
    {"vtktypeint64", 8, NumberKind::Signed},
    {"vtktypeuint64", 8, NumberKind::Unsigned},
    {"float", 4, NumberKind::Real},
    {"double", 8, NumberKind::Real},
    {"vtkidtype", 4, NumberKind::Signed},
};

// One BINARY value in native byte order, as a double.
double binaryValue(const char* data, const DataType& type) {
  if (type.kind == NumberKind::Real) {
    if (type.binaryBytes == 4) {
      float value;
      std::memcpy(&value, data, 4);
      return value;
    }
    double value;
    std::memcpy(&value, data, 8);
    return value;
  }
  std::uint64_t bits = 0;
  std::memcpy(&bits, data, type.binaryBytes);
  // On a big-endian host the value's bytes landed in the high end.
  if (std::endian::native == std::endian::big) bits >>= 8 * (8 - type.binaryBytes);
  if (type.kind == NumberKind::Unsigned) return static_cast<double>(bits);
  const unsigned shift = static_cast<unsigned>(64 - 8 * type.binaryBytes);
  return static_cast<double>(static_cast<std::int64_t>(bits << shift) >> shift);
}

std::string upperCase(std::string_view text) {
  std::string raised(text);
  for (char& c : raised)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return raised;
}

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

// VTK writes array names with spaces and other unsafe bytes as %XX.
std::string decodeName(std::string_view name) {
  std::string decoded;
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name[i] == '%' && i + 2 < name.size() && hexDigit(name[i + 1]) >= 0 &&
        hexDigit(name[i + 2]) >= 0) {
      decoded += static_cast<char>(hexDigit(name[i + 1]) * 16 + hexDigit(name[i + 2]));
      i += 2;
    } else {
      decoded += name[i];
    }
  }
  return decoded;
}

using Words = std::vector<std::string>;

Words wordsOf(std::string_view text) {
  const std::vector<std::string_view> views = splitWords(text);
  return Words(views.begin(), views.end());
}

class Parser {
 public:
  explicit Parser(FileReader& reader) : reader_(reader) {}

  Error fail(const std::string& problem) const { return fileError(reader_.path(), problem); }
  void setFormat(Format format) { format_ = format; }
  Format format() const { return format_; }

  // One line without its "\n" or "\r\n"; nullopt at the end of the file.
  Result<std::optional<std::string>> readLine() {
    int c = reader_.get();
    if (c < 0) return std::optional<std::string>();
    std::string line;
    for (; c >= 0 && c != '\n'; c = reader_.get()) {
      if (line.size() == kMaxLineBytes)
        return fail("a line near byte " + std::to_string(reader_.position()) + " is longer than " +
                    std::to_string(kMaxLineBytes) + " characters");
      line.push_back(static_cast<char>(c));
    }
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return std::optional<std::string>(std::move(line));
  }

  // The words of the next non-blank line; nullopt at the end of the file. Skipping whitespace
  // first also skips the newline VTK writes after each binary block.
  Result<std::optional<Words>> nextKeywordLine() {
    while (isAsciiSpace(reader_.peek())) reader_.get();
    LIC3D_TRY_ASSIGN(std::optional<std::string> line, readLine());
    if (!line) return std::optional<Words>();
    return std::optional<Words>(wordsOf(*line));
  }

  // A whitespace-separated ASCII value; empty at the end of the file.
  Result<std::string> readToken() {
    while (isAsciiSpace(reader_.peek())) reader_.get();
    std::string token;
    while (reader_.peek() >= 0 && !isAsciiSpace(reader_.peek())) {
      if (token.size() == kMaxTokenBytes)
        return fail("a value near byte " + std::to_string(reader_.position()) + " is longer than " +
                    std::to_string(kMaxTokenBytes) + " characters");
      token.push_back(static_cast<char>(reader_.get()));
    }
    return token;
  }

  // Skips `count` values: `binaryBytes` each in BINARY files, numbers in ASCII files.
  Result<void> skipValues(std::uint64_t count, std::size_t binaryBytes, const std::string& what) {
    if (format_ == Format::Binary) {
      std::uint64_t bytes = 0;
      if (__builtin_mul_overflow(count, binaryBytes, &bytes) || bytes > reader_.remaining())
        return truncated(what, count, binaryBytes);
      if (reader_.skip(bytes) != bytes)
        return fail(what + ": cannot read: " + reader_.failureReason());
      return {};
    }
    LIC3D_TRY(checkAsciiFits(count, what));
    for (std::uint64_t i = 0; i < count; ++i) {
      double value = 0.0;
      LIC3D_TRY(readAsciiNumber(value, count, i, what));
    }
    return {};
  }

  // Skips `count` values of a VTK data type named in the file.
  Result<void> skipTyped(std::uint64_t count, std::string_view typeName, const std::string& what) {
    LIC3D_TRY_ASSIGN(const std::size_t bytes, binarySize(typeName, what));
    return skipValues(count, bytes, what);
  }

  Result<std::size_t> binarySize(std::string_view typeName, const std::string& what) const {
    LIC3D_TRY_ASSIGN(const DataType* type, dataType(typeName, what));
    return type->binaryBytes;
  }

  Result<const DataType*> dataType(std::string_view typeName, const std::string& what) const {
    const std::string key = asciiLowerCase(typeName);
    if (key == "bit") return fail(what + ": bit arrays are not supported");
    if (key == "string" || key == "utf8_string" || key == "variant")
      return fail(what + ": " + quoteForMessage(typeName) + " arrays are not supported");
    for (const DataType& type : kDataTypes)
      if (type.name == key) return &type;
    return fail(what + ": unknown data type " + quoteForMessage(typeName));
  }

  // Reads `count` numbers of any VTK type as doubles; the caller bounds `count`.
  Result<std::vector<double>> readNumbers(std::uint64_t count, std::string_view typeName,
                                          const std::string& what) {
    LIC3D_TRY_ASSIGN(const DataType* type, dataType(typeName, what));
    std::vector<double> numbers;
    if (format_ == Format::Binary) {
      const std::uint64_t bytes = count * type->binaryBytes;
      if (bytes > reader_.remaining()) return truncated(what, count, type->binaryBytes);
      std::vector<char> data(static_cast<std::size_t>(bytes));
      if (reader_.read(data.data(), data.size()) != data.size())
        return fail(what + ": cannot read: " + reader_.failureReason());
      toNativeOrder(data.data(), static_cast<std::size_t>(count), type->binaryBytes,
                    std::endian::big);
      for (std::size_t i = 0; i < count; ++i)
        numbers.push_back(binaryValue(data.data() + i * type->binaryBytes, *type));
      return numbers;
    }
    LIC3D_TRY(checkAsciiFits(count, what));
    for (std::uint64_t i = 0; i < count; ++i) {
      double value = 0.0;
      LIC3D_TRY(readAsciiNumber(value, count, i, what));
      numbers.push_back(value);
    }
    return numbers;
  }

  // Reads `count` float or double vectors into `vectors`, checked against the file first.
  Result<void> readVectors(std::uint64_t count, std::string_view typeName, const std::string& what,
                           std::vector<glm::vec3>& vectors) {
    const std::string key = asciiLowerCase(typeName);
    if (key != "float" && key != "double")
      return fail(what + ": type " + quoteForMessage(typeName) +
                  " is not supported (expected float or double)");
    const bool isDouble = key == "double";
    const std::size_t bytesPerValue = isDouble ? 8 : 4;
    const std::uint64_t valueCount = 3 * count;
    if (format_ == Format::Binary) {
      if (valueCount * bytesPerValue > reader_.remaining())
        return truncated(what, valueCount, bytesPerValue);
    } else {
      LIC3D_TRY(checkAsciiFits(valueCount, what));
    }
    vectors.assign(static_cast<std::size_t>(count), glm::vec3(0.0f));

    std::uint64_t next = 0;
    const auto store = [&](double value) {
      vectors[static_cast<std::size_t>(next / 3)][static_cast<glm::length_t>(next % 3)] =
          vectorComponent(value);
      ++next;
    };

    if (format_ == Format::Binary) {
      std::vector<char> chunk(static_cast<std::size_t>(
          std::min<std::uint64_t>(kChunkBytes, valueCount * bytesPerValue)));
      const std::size_t perChunk = chunk.size() / bytesPerValue;
      while (next < valueCount) {
        const std::size_t n =
            static_cast<std::size_t>(std::min<std::uint64_t>(perChunk, valueCount - next));
        if (reader_.read(chunk.data(), n * bytesPerValue) != n * bytesPerValue)
          return fail(what + ": cannot read: " + reader_.failureReason());
        toNativeOrder(chunk.data(), n, bytesPerValue, std::endian::big);
        for (std::size_t i = 0; i < n; ++i) {
          if (isDouble) {
            double value;
            std::memcpy(&value, chunk.data() + 8 * i, 8);
            store(value);
          } else {
            float value;
            std::memcpy(&value, chunk.data() + 4 * i, 4);
            store(value);
          }
        }
      }
    } else {
      while (next < valueCount) {
        double value = 0.0;
        LIC3D_TRY(readAsciiNumber(value, valueCount, next, what, !isDouble));
        store(value);
      }
    }
    return {};
  }

 private:
  Error truncated(const std::string& what, std::uint64_t count, std::size_t bytesPerValue) const {
    return fail(what + ": the data is truncated: " + std::to_string(count) + " values of " +
                std::to_string(bytesPerValue) + " bytes do not fit in the " +
                std::to_string(reader_.remaining()) + " bytes left in the file");
  }

  // Each ASCII value takes at least one character and one separator.
  Result<void> checkAsciiFits(std::uint64_t count, const std::string& what) const {
    if (count > reader_.remaining() / 2 + 1)
      return fail(what + ": the data is truncated: " + std::to_string(count) +
                  " values do not fit in the " + std::to_string(reader_.remaining()) +
                  " bytes left in the file");
    return {};
  }

  // Float arrays parse as float directly: going through double could round differently. A
  // number beyond the float range is still a number: it is read as a double, becomes infinity
  // and then a zero vector (finishVectorField), like NaN.
  Result<void> readAsciiNumber(double& value, std::uint64_t count, std::uint64_t index,
                               const std::string& what, bool asFloat = false) {
    LIC3D_TRY_ASSIGN(const std::string token, readToken());
    if (token.empty())
      return fail(what + ": the data is truncated: expected " + std::to_string(count) +
                  " values, found " + std::to_string(index));
    bool parsed = false;
    if (asFloat) {
      float single = 0.0f;
      parsed = parseFloat(token, single);
      value = single;
      if (!parsed) parsed = parseDouble(token, value);
    } else {
      parsed = parseDouble(token, value);
    }
    if (!parsed)
      return fail(what + ": expected " + std::to_string(count) + " numbers, found " +
                  quoteForMessage(token) + " after " + std::to_string(index));
    return {};
  }

  FileReader& reader_;
  Format format_ = Format::Ascii;
};

Result<std::uint64_t> parseCount(const Parser& parser, const std::string& word,
                                 const std::string& what) {
  std::uint64_t value = 0;
  if (!parseUnsigned(word, value))
    return parser.fail(what + ": " + quoteForMessage(word) + " is not a whole number");
  return value;
}

// Checks that a keyword line has `minWords`..`maxWords` words, for a message showing the form.
Result<void> checkWords(const Parser& parser, const Words& words, std::size_t minWords,
                        std::size_t maxWords, std::string_view form) {
  if (words.size() < minWords || words.size() > maxWords) {
    std::string found;
    for (const std::string& word : words) found += (found.empty() ? "" : " ") + word;
    return parser.fail("expected '" + std::string(form) + "', found " + quoteForMessage(found));
  }
  return {};
}

// A METADATA block, which newer VTK writers put after arrays: lines up to the next blank line.
Result<void> skipMetadata(Parser& parser) {
  for (;;) {
    LIC3D_TRY_ASSIGN(const std::optional<std::string> line, parser.readLine());
    if (!line || splitWords(*line).empty()) return {};
  }
}

// FIELD name numArrays, then per array "name numComponents numTuples type" and its values.
Result<void> skipFieldData(Parser& parser, const Words& words) {
  LIC3D_TRY(checkWords(parser, words, 3, 3, "FIELD name numArrays"));
  const std::string what = "FIELD " + quoteForMessage(decodeName(words[1]));
  LIC3D_TRY_ASSIGN(const std::uint64_t arrays, parseCount(parser, words[2], what));
  for (std::uint64_t i = 0; i < arrays;) {
    LIC3D_TRY_ASSIGN(const std::optional<Words> line, parser.nextKeywordLine());
    if (!line)
      return parser.fail(what + ": the file ends after " + std::to_string(i) + " of " +
                         std::to_string(arrays) + " arrays");
    const std::string key = upperCase(line->front());
    if (key == "METADATA") {
      LIC3D_TRY(skipMetadata(parser));
      continue;
    }
    ++i;
    if (key == "NULL_ARRAY") continue;
    LIC3D_TRY(checkWords(parser, *line, 4, 4, "arrayName numComponents numTuples type"));
    const std::string arrayWhat = what + " array " + quoteForMessage(decodeName(line->at(0)));
    LIC3D_TRY_ASSIGN(const std::uint64_t components, parseCount(parser, line->at(1), arrayWhat));
    LIC3D_TRY_ASSIGN(const std::uint64_t tuples, parseCount(parser, line->at(2), arrayWhat));
    std::uint64_t values = 0;
    if (__builtin_mul_overflow(components, tuples, &values))
      return parser.fail(arrayWhat + ": " + line->at(1) + " x " + line->at(2) +
                         " values is too many");
    LIC3D_TRY(parser.skipTyped(values, line->at(3), arrayWhat));
  }
  return {};
}

struct Geometry {
  std::optional<Dims> dims;
  GridGeometry grid;
  int coordinateAxes = 0;  // RECTILINEAR_GRID: a bit per axis whose coordinates were read
};

Result<glm::dvec3> parseTriple(const Parser& parser, const Words& words, bool positive) {
  glm::dvec3 value{0.0};
  for (glm::length_t axis = 0; axis < 3; ++axis) {
    const std::string& word = words[static_cast<std::size_t>(axis) + 1];
    double number = 0.0;
    if (!parseDouble(word, number) || !std::isfinite(number) || (positive && !(number > 0.0)))
      return parser.fail(upperCase(words[0]) + ": expected " +
                         (positive ? "a positive" : "a finite") + " number, found " +
                         quoteForMessage(word));
    value[axis] = number;
  }
  return value;
}

// lic3d grids are uniform, so a rectilinear grid is read only when its coordinates are evenly
// spaced: each within 1e-6 of the spacing of where a uniform axis from the first to the last
// coordinate puts it. Float coordinates may also be off by their own rounding (2^-24 relative),
// since a uniform grid written as float cannot be closer than that.
Result<void> readUniformCoordinates(Parser& parser, const Words& words, Geometry& geometry) {
  const std::string key = upperCase(words[0]);
  LIC3D_TRY(checkWords(parser, words, 3, 3, key + " count type"));
  if (!geometry.dims) return parser.fail("missing DIMENSIONS before " + key);
  const glm::length_t axis = key[0] == 'X' ? 0 : key[0] == 'Y' ? 1 : 2;
  if (geometry.coordinateAxes & (1 << axis)) return parser.fail(key + " appears twice");
  LIC3D_TRY_ASSIGN(const std::uint64_t count, parseCount(parser, words[1], key));
  const int points = (*geometry.dims)[axis];
  if (count != static_cast<std::uint64_t>(points))
    return parser.fail(key + " " + words[1] + " does not match DIMENSIONS, which gives " +
                       std::to_string(points) + " points along this axis");
  LIC3D_TRY_ASSIGN(const std::vector<double> coordinates, parser.readNumbers(count, words[2], key));
  const double first = coordinates.front();
  const double last = coordinates.back();
  if (!std::isfinite(first) || !std::isfinite(last))
    return parser.fail(key + ": the coordinates must be finite numbers");
  geometry.coordinateAxes |= 1 << axis;
  geometry.grid.origin[axis] = first;
  if (points == 1) return {};
  const double spacing = (last - first) / static_cast<double>(points - 1);
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    return parser.fail(key + ": the coordinates must increase, found " + formatDouble(first) +
                       " first and " + formatDouble(last) + " last");
  const bool isFloat = asciiLowerCase(words[2]) == "float";
  for (std::size_t i = 0; i < coordinates.size(); ++i) {
    const double uniform = first + spacing * static_cast<double>(i);
    const double tolerance = 1e-6 * spacing + (isFloat ? std::abs(uniform) * 0x1p-24 : 0.0);
    if (!(std::abs(coordinates[i] - uniform) <= tolerance))
      return parser.fail(key + ": the coordinates are not uniform: coordinate " +
                         std::to_string(i) + " is " + formatDouble(coordinates[i]) +
                         ", a uniform axis from " + formatDouble(first) + " to " +
                         formatDouble(last) + " puts it at " + formatDouble(uniform) +
                         " (lic3d needs evenly spaced coordinates)");
  }
  geometry.grid.spacing[axis] = spacing;
  return {};
}

// The lines between DATASET and the first POINT_DATA or CELL_DATA, which is returned.
Result<Words> readGeometry(Parser& parser, Dataset dataset, Geometry& geometry) {
  const bool rectilinear = dataset == Dataset::RectilinearGrid;
  for (;;) {
    LIC3D_TRY_ASSIGN(const std::optional<Words> words, parser.nextKeywordLine());
    if (!words) return parser.fail("the file ends before POINT_DATA or CELL_DATA");
    const std::string key = upperCase(words->front());
    if (key == "POINT_DATA" || key == "CELL_DATA") {
      if (!geometry.dims) return parser.fail("missing DIMENSIONS before " + key);
      for (int axis = 0; rectilinear && axis < 3; ++axis)
        if (!(geometry.coordinateAxes & (1 << axis)))
          return parser.fail(std::string(1, static_cast<char>('X' + axis)) +
                             "_COORDINATES missing before " + key);
      return *words;
    }
    if (key == "DIMENSIONS") {
      LIC3D_TRY(checkWords(parser, *words, 4, 4, "DIMENSIONS nx ny nz"));
      if (geometry.dims) return parser.fail("DIMENSIONS appears twice");
      Dims dims{0};
      for (glm::length_t axis = 0; axis < 3; ++axis) {
        const std::string& word = words->at(static_cast<std::size_t>(axis) + 1);
        std::uint64_t value = 0;
        if (!parseUnsigned(word, value) || value < 1 || value > kMaxAxisSize)
          return parser.fail("DIMENSIONS: expected a whole number in [1, " +
                             std::to_string(kMaxAxisSize) + "], found " + quoteForMessage(word));
        dims[axis] = static_cast<int>(value);
      }
      if (voxelCount(dims) > kMaxVoxels)
        return parser.fail("DIMENSIONS: " + std::to_string(voxelCount(dims)) +
                           " points exceed the limit of " + std::to_string(kMaxVoxels));
      geometry.dims = dims;
    } else if (!rectilinear && (key == "SPACING" || key == "ASPECT_RATIO")) {
      LIC3D_TRY(checkWords(parser, *words, 4, 4, key + " sx sy sz"));
      LIC3D_TRY_ASSIGN(geometry.grid.spacing, parseTriple(parser, *words, true));
    } else if (!rectilinear && key == "ORIGIN") {
      LIC3D_TRY(checkWords(parser, *words, 4, 4, "ORIGIN x y z"));
      LIC3D_TRY_ASSIGN(geometry.grid.origin, parseTriple(parser, *words, false));
    } else if (rectilinear &&
               (key == "X_COORDINATES" || key == "Y_COORDINATES" || key == "Z_COORDINATES")) {
      LIC3D_TRY(readUniformCoordinates(parser, *words, geometry));
    } else if (key == "FIELD") {
      LIC3D_TRY(skipFieldData(parser, *words));
    } else if (key == "METADATA") {
      LIC3D_TRY(skipMetadata(parser));
    } else {
      return parser.fail("unexpected " + quoteForMessage(words->front()) +
                         (rectilinear ? " in the RECTILINEAR_GRID geometry (expected DIMENSIONS, "
                                        "X_COORDINATES, Y_COORDINATES, Z_COORDINATES"
                                      : " in the STRUCTURED_POINTS geometry (expected "
                                        "DIMENSIONS, SPACING, ORIGIN") +
                         std::string(", POINT_DATA or CELL_DATA)"));
    }
  }
}

std::uint64_t cellCount(Dims dims) { return voxelCount(cellCentredGrid(dims, {}).dims); }

// The first three lines and the DATASET line.
Result<Dataset> readPreamble(Parser& parser) {
  LIC3D_TRY_ASSIGN(const std::optional<std::string> version, parser.readLine());
  if (!version) return parser.fail("empty file (expected '# vtk DataFile Version x.y')");
  if (!asciiLowerCase(*version).starts_with("# vtk datafile version"))
    return parser.fail("not a VTK legacy file: the first line is " + quoteForMessage(*version) +
                       ", expected '# vtk DataFile Version x.y'");
  LIC3D_TRY_ASSIGN(const std::optional<std::string> title, parser.readLine());
  if (!title) return parser.fail("the file ends after its first line (expected a title line)");
  LIC3D_TRY_ASSIGN(const std::optional<std::string> formatLine, parser.readLine());
  const Words formatWords = formatLine ? wordsOf(*formatLine) : Words{};
  const std::string format = formatWords.size() == 1 ? upperCase(formatWords[0]) : std::string();
  if (format != "ASCII" && format != "BINARY")
    return parser.fail("line 3: expected ASCII or BINARY, found " +
                       quoteForMessage(formatLine.value_or("")));
  parser.setFormat(format == "ASCII" ? Format::Ascii : Format::Binary);

  LIC3D_TRY_ASSIGN(const std::optional<Words> dataset, parser.nextKeywordLine());
  if (!dataset || upperCase(dataset->front()) != "DATASET")
    return parser.fail(
        "expected 'DATASET STRUCTURED_POINTS' or 'DATASET RECTILINEAR_GRID' after line 3, found " +
        (dataset ? quoteForMessage(dataset->front()) : std::string("the end of the file")));
  const std::string type = dataset->size() == 2 ? upperCase(dataset->at(1)) : std::string();
  if (type == "STRUCTURED_POINTS") return Dataset::StructuredPoints;
  if (type == "RECTILINEAR_GRID") return Dataset::RectilinearGrid;
  return parser.fail("dataset type " + quoteForMessage(dataset->size() > 1 ? dataset->at(1) : "") +
                     " is not supported (expected STRUCTURED_POINTS or RECTILINEAR_GRID)");
}

// Skips one attribute other than VECTORS, whose data holds `tuples` tuples.
Result<void> skipAttribute(Parser& parser, const Words& line, std::uint64_t tuples,
                           std::string_view section) {
  const std::string key = upperCase(line.front());
  const std::string what = key + " " + quoteForMessage(line.size() > 1 ? decodeName(line[1]) : "");
  if (key == "SCALARS") {
    LIC3D_TRY(checkWords(parser, line, 3, 4, "SCALARS name type [numComponents]"));
    std::uint64_t components = 1;
    if (line.size() == 4) {
      LIC3D_TRY_ASSIGN(components, parseCount(parser, line[3], what));
      if (components < 1 || components > 4)
        return parser.fail(what + ": expected 1 to 4 components, found " + line[3]);
    }
    LIC3D_TRY_ASSIGN(const std::optional<Words> table, parser.nextKeywordLine());
    if (!table || upperCase(table->front()) != "LOOKUP_TABLE" || table->size() != 2)
      return parser.fail(what + ": expected a 'LOOKUP_TABLE name' line after SCALARS");
    return parser.skipTyped(tuples * components, line[2], what);
  }
  if (key == "LOOKUP_TABLE") {
    LIC3D_TRY(checkWords(parser, line, 3, 3, "LOOKUP_TABLE name size"));
    LIC3D_TRY_ASSIGN(const std::uint64_t entries, parseCount(parser, line[2], what));
    if (entries > kMaxVoxels) return parser.fail(what + ": " + line[2] + " entries is too many");
    // RGBA entries: bytes in BINARY files, numbers in [0,1] in ASCII files.
    return parser.skipValues(4 * entries, 1, what);
  }
  if (key == "COLOR_SCALARS") {
    LIC3D_TRY(checkWords(parser, line, 3, 3, "COLOR_SCALARS name numValues"));
    LIC3D_TRY_ASSIGN(const std::uint64_t components, parseCount(parser, line[2], what));
    if (components < 1 || components > 4)
      return parser.fail(what + ": expected 1 to 4 values per tuple, found " + line[2]);
    return parser.skipValues(tuples * components, 1, what);
  }
  if (key == "VECTORS" || key == "NORMALS") {
    LIC3D_TRY(checkWords(parser, line, 3, 3, key + " name type"));
    return parser.skipTyped(3 * tuples, line[2], what);
  }
  if (key == "TEXTURE_COORDINATES") {
    LIC3D_TRY(checkWords(parser, line, 4, 4, "TEXTURE_COORDINATES name dimension type"));
    LIC3D_TRY_ASSIGN(const std::uint64_t components, parseCount(parser, line[2], what));
    if (components < 1 || components > 3)
      return parser.fail(what + ": expected dimension 1 to 3, found " + line[2]);
    return parser.skipTyped(tuples * components, line[3], what);
  }
  if (key == "TENSORS" || key == "TENSORS6") {
    LIC3D_TRY(checkWords(parser, line, 3, 3, key + " name type"));
    return parser.skipTyped((key == "TENSORS" ? 9 : 6) * tuples, line[2], what);
  }
  if (key == "GLOBAL_IDS" || key == "PEDIGREE_IDS") {
    LIC3D_TRY(checkWords(parser, line, 3, 3, key + " name type"));
    return parser.skipTyped(tuples, line[2], what);
  }
  if (key == "FIELD") return skipFieldData(parser, line);
  if (key == "METADATA") return skipMetadata(parser);
  return parser.fail("unexpected " + quoteForMessage(line.front()) + " in " + std::string(section) +
                     " (expected SCALARS, VECTORS, NORMALS, TENSORS, TEXTURE_COORDINATES, "
                     "COLOR_SCALARS, LOOKUP_TABLE, FIELD, POINT_DATA or CELL_DATA)");
}

// The VECTORS arrays of a file, in file order.
struct VectorsSeen {
  std::vector<std::string> names;
  std::vector<bool> cellData;  // per name
  bool anyData = false;        // any POINT_DATA or CELL_DATA section
};

std::string listVectors(const VectorsSeen& seen) {
  if (seen.names.empty()) return "none";
  std::string list;
  for (std::size_t i = 0; i < seen.names.size(); ++i)
    list += (i == 0 ? "" : ", ") + quoteForMessage(seen.names[i]) +
            (seen.cellData[i] ? " (cell data)" : "");
  return list;
}

Error vectorsNotFound(const Parser& parser, std::string_view arrayName, const VectorsSeen& seen) {
  if (!arrayName.empty())
    return parser.fail("no VECTORS named " + quoteForMessage(arrayName) +
                       "; found: " + listVectors(seen));
  if (!seen.anyData) return parser.fail("no POINT_DATA or CELL_DATA section holds VECTORS");
  return parser.fail("no VECTORS in POINT_DATA or CELL_DATA");
}

// Where the data of a cell-data VECTORS array starts, to come back to it when no point-data
// array is chosen.
struct CellVectors {
  std::string name;
  std::string type;
  std::uint64_t tuples = 0;
  std::uint64_t offset = 0;
};

}  // namespace

Result<VectorField> readVectorFieldVtk(const std::filesystem::path& path,
                                       std::string_view arrayName, FieldReadInfo* info) {
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  Parser parser(reader);
  LIC3D_TRY_ASSIGN(const Dataset dataset, readPreamble(parser));
  const Format format = parser.format();
  Geometry geometry;
  LIC3D_TRY_ASSIGN(std::optional<Words> words, readGeometry(parser, dataset, geometry));
  const Dims dims = *geometry.dims;
  const CellCentredGrid cells = cellCentredGrid(dims, geometry.grid);

  bool inPointData = false;
  std::uint64_t tuples = 0;  // in the current POINT_DATA or CELL_DATA section
  VectorsSeen seen;
  std::optional<VectorField> chosen;  // point data is preferred: it is what lic3d samples
  std::string chosenName;
  std::optional<CellVectors> cellVectors;

  // One keyword line and its data.
  const auto readSection = [&](const Words& line) -> Result<void> {
    const std::string key = upperCase(line.front());
    const std::string_view section = inPointData ? "POINT_DATA" : "CELL_DATA";
    if (key == "POINT_DATA" || key == "CELL_DATA") {
      LIC3D_TRY(checkWords(parser, line, 2, 2, key + " count"));
      LIC3D_TRY_ASSIGN(tuples, parseCount(parser, line[1], key));
      inPointData = key == "POINT_DATA";
      seen.anyData = true;
      const std::uint64_t expected = inPointData ? voxelCount(dims) : cellCount(dims);
      if (tuples != expected)
        return parser.fail(key + " " + line[1] + " does not match the " + std::to_string(expected) +
                           (inPointData ? " points" : " cells") + " of the " +
                           std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                           std::to_string(dims.z) + " grid");
      return {};
    }
    if (key != "VECTORS" || line.size() != 3) return skipAttribute(parser, line, tuples, section);
    const std::string name = decodeName(line[1]);
    seen.names.push_back(name);
    seen.cellData.push_back(!inPointData);
    const bool wanted = !chosen && (arrayName.empty() || name == arrayName);
    if (wanted && inPointData) {
      VectorField field;
      field.dims = dims;
      field.geometry = geometry.grid;
      LIC3D_TRY(
          parser.readVectors(tuples, line[2], "VECTORS " + quoteForMessage(name), field.vectors));
      chosen = std::move(field);
      chosenName = name;
      return {};
    }
    if (wanted && !cellVectors) cellVectors = CellVectors{name, line[2], tuples, reader.position()};
    return skipAttribute(parser, line, tuples, section);
  };

  while (words) {
    Result<void> read = readSection(*words);
    if (read.ok()) {
      // Without `info` nothing after the chosen array matters; with it, the scan goes on only
      // to list the other arrays, so the result never depends on whether `info` was given.
      if (chosen && !info) break;
      Result<std::optional<Words>> next = parser.nextKeywordLine();
      if (next.ok()) {
        words = std::move(next).value();
        continue;
      }
      read = std::move(next).error();
    }
    if (chosen) break;
    return std::move(read).error();
  }

  VectorField field;
  if (chosen) {
    field = std::move(*chosen);
  } else if (cellVectors) {
    // Cell-centred vectors on an N-cell grid become a field of N voxels at the cell centres: the
    // origin moves by half a spacing (cellCentredGrid). Their data is read from where it starts.
    LIC3D_TRY_ASSIGN(FileReader again, FileReader::open(path));
    if (again.skip(cellVectors->offset) != cellVectors->offset)
      return fileError(path, "cannot read: " + again.failureReason());
    Parser cellParser(again);
    cellParser.setFormat(format);
    field.dims = cells.dims;
    field.geometry = cells.geometry;
    LIC3D_TRY(cellParser.readVectors(
        cellVectors->tuples, cellVectors->type,
        "VECTORS " + quoteForMessage(cellVectors->name) + " (cell data)", field.vectors));
    chosenName = cellVectors->name;
  } else {
    return vectorsNotFound(parser, arrayName, seen);
  }
  if (info) *info = FieldReadInfo{0, chosenName, seen.names};
  LIC3D_TRY(finishVectorField(path, field, info));
  return field;
}

}  // namespace lic3d
