#include "vtk_legacy.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "file_util.h"

namespace lic3d {
namespace {

constexpr std::size_t kMaxLineBytes = 4096;
constexpr std::size_t kMaxTokenBytes = 256;
// A multiple of every value size, so chunks never split a value.
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

enum class Format { Ascii, Binary };

struct DataType {
  std::string_view name;  // lower case, as VTK compares them
  std::size_t binaryBytes;
};

// The sizes in BINARY files. `long` is 8 bytes because VTK writes sizeof(long), and legacy files
// come from LP64 systems; vtkIdType is always written as a 32-bit int.
constexpr DataType kDataTypes[] = {
    {"unsigned_char", 1}, {"char", 1},          {"unsigned_short", 2}, {"short", 2},
    {"unsigned_int", 4},  {"int", 4},           {"unsigned_long", 8},  {"long", 8},
    {"vtktypeint64", 8},  {"vtktypeuint64", 8}, {"float", 4},          {"double", 8},
    {"vtkidtype", 4},
};

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

std::string joinQuoted(const std::vector<std::string>& names) {
  std::string joined;
  for (const std::string& name : names)
    joined += (joined.empty() ? "" : ", ") + quoteForMessage(name);
  return joined;
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
    const std::string key = asciiLowerCase(typeName);
    if (key == "bit") return fail(what + ": bit arrays are not supported");
    if (key == "string" || key == "utf8_string" || key == "variant")
      return fail(what + ": " + quoteForMessage(typeName) + " arrays are not supported");
    for (const DataType& type : kDataTypes)
      if (type.name == key) return type.binaryBytes;
    return fail(what + ": unknown data type " + quoteForMessage(typeName));
  }

  // Reads `count` float or double vectors into `vectors`, checked against the file first.
  Result<void> readVectors(std::uint64_t count, std::string_view typeName, const std::string& what,
                           Dims dims, std::vector<glm::vec3>& vectors) {
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

    std::optional<std::uint64_t> firstBad;
    std::uint64_t next = 0;
    const auto store = [&](double value) {
      float stored = 0.0f;
      if (std::isfinite(value) && std::abs(value) <= FLT_MAX) {
        stored = static_cast<float>(value);
      } else if (!firstBad) {
        firstBad = next;
      }
      vectors[static_cast<std::size_t>(next / 3)][static_cast<glm::length_t>(next % 3)] = stored;
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
    if (firstBad)
      return fail(what + ": component " + std::to_string(*firstBad % 3) +
                  " of the vector at point " + voxelText(dims, *firstBad / 3) +
                  " is NaN, infinite or outside the float range");
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

  // Float arrays parse as float directly: going through double could round differently.
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

// The lines between DATASET and the first POINT_DATA or CELL_DATA, which is returned.
Result<Words> readGeometry(Parser& parser, Geometry& geometry) {
  for (;;) {
    LIC3D_TRY_ASSIGN(const std::optional<Words> words, parser.nextKeywordLine());
    if (!words) return parser.fail("the file ends before POINT_DATA");
    const std::string key = upperCase(words->front());
    if (key == "POINT_DATA" || key == "CELL_DATA") {
      if (!geometry.dims) return parser.fail("missing DIMENSIONS before " + key);
      return *words;
    }
    if (key == "DIMENSIONS") {
      LIC3D_TRY(checkWords(parser, *words, 4, 4, "DIMENSIONS nx ny nz"));
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
    } else if (key == "SPACING" || key == "ASPECT_RATIO") {
      LIC3D_TRY(checkWords(parser, *words, 4, 4, key + " sx sy sz"));
      LIC3D_TRY_ASSIGN(geometry.grid.spacing, parseTriple(parser, *words, true));
    } else if (key == "ORIGIN") {
      LIC3D_TRY(checkWords(parser, *words, 4, 4, "ORIGIN x y z"));
      LIC3D_TRY_ASSIGN(geometry.grid.origin, parseTriple(parser, *words, false));
    } else if (key == "FIELD") {
      LIC3D_TRY(skipFieldData(parser, *words));
    } else if (key == "METADATA") {
      LIC3D_TRY(skipMetadata(parser));
    } else {
      return parser.fail("unexpected " + quoteForMessage(words->front()) +
                         " in the STRUCTURED_POINTS geometry (expected DIMENSIONS, SPACING, ORIGIN "
                         "or POINT_DATA)");
    }
  }
}

std::uint64_t cellCount(Dims dims) {
  std::uint64_t cells = 1;
  for (glm::length_t axis = 0; axis < 3; ++axis)
    cells *= static_cast<std::uint64_t>(std::max(dims[axis] - 1, 1));
  return cells;
}

// The first three lines and the DATASET line.
Result<void> readPreamble(Parser& parser) {
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
        "expected 'DATASET STRUCTURED_POINTS' after line 3, found " +
        (dataset ? quoteForMessage(dataset->front()) : std::string("the end of the file")));
  if (dataset->size() != 2 || upperCase(dataset->at(1)) != "STRUCTURED_POINTS")
    return parser.fail("dataset type " +
                       quoteForMessage(dataset->size() > 1 ? dataset->at(1) : "") +
                       " is not supported (expected STRUCTURED_POINTS)");
  return {};
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

// VECTORS arrays passed over while looking for the requested one.
struct VectorsSeen {
  Words pointData;
  Words cellData;
  bool anyPointData = false;
};

Error vectorsNotFound(const Parser& parser, std::string_view arrayName, const VectorsSeen& seen) {
  const std::string pointList = seen.pointData.empty() ? "none" : joinQuoted(seen.pointData);
  if (!arrayName.empty()) {
    const std::string wanted(arrayName);
    if (std::find(seen.cellData.begin(), seen.cellData.end(), wanted) != seen.cellData.end())
      return parser.fail("VECTORS " + quoteForMessage(wanted) +
                         " is cell data, which is not supported yet (lic3d needs point data); "
                         "point-data VECTORS found: " +
                         pointList);
    std::string message =
        "no point-data VECTORS named " + quoteForMessage(wanted) + "; found: " + pointList;
    if (!seen.cellData.empty())
      message += " (cell data, not supported yet: " + joinQuoted(seen.cellData) + ")";
    return parser.fail(message);
  }
  if (!seen.cellData.empty())
    return parser.fail("VECTORS " + joinQuoted(seen.cellData) +
                       " are cell data, which is not supported yet (lic3d needs point data)");
  if (!seen.anyPointData)
    return parser.fail("the file holds only CELL_DATA; cell data is not supported yet");
  return parser.fail("no VECTORS in POINT_DATA");
}

}  // namespace

Result<VectorField> readVectorFieldVtk(const std::filesystem::path& path,
                                       std::string_view arrayName) {
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  Parser parser(reader);
  LIC3D_TRY(readPreamble(parser));
  Geometry geometry;
  LIC3D_TRY_ASSIGN(std::optional<Words> words, readGeometry(parser, geometry));
  const Dims dims = *geometry.dims;

  bool inPointData = false;
  std::uint64_t tuples = 0;  // in the current POINT_DATA or CELL_DATA section
  VectorsSeen seen;
  while (words) {
    const Words& line = *words;
    const std::string key = upperCase(line.front());
    const std::string_view section = inPointData ? "POINT_DATA" : "CELL_DATA";
    if (key == "POINT_DATA" || key == "CELL_DATA") {
      LIC3D_TRY(checkWords(parser, line, 2, 2, key + " count"));
      LIC3D_TRY_ASSIGN(tuples, parseCount(parser, line[1], key));
      inPointData = key == "POINT_DATA";
      seen.anyPointData = seen.anyPointData || inPointData;
      const std::uint64_t expected = inPointData ? voxelCount(dims) : cellCount(dims);
      if (tuples != expected)
        return parser.fail(key + " " + line[1] + " does not match the " + std::to_string(expected) +
                           (inPointData ? " points" : " cells") + " of the " +
                           std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                           std::to_string(dims.z) + " grid");
    } else if (key == "VECTORS" && line.size() == 3) {
      const std::string name = decodeName(line[1]);
      (inPointData ? seen.pointData : seen.cellData).push_back(name);
      if (inPointData && (arrayName.empty() || name == arrayName)) {
        VectorField field;
        field.dims = dims;
        field.geometry = geometry.grid;
        LIC3D_TRY(parser.readVectors(tuples, line[2], "VECTORS " + quoteForMessage(name), dims,
                                     field.vectors));
        return field;
      }
      LIC3D_TRY(skipAttribute(parser, line, tuples, section));
    } else {
      LIC3D_TRY(skipAttribute(parser, line, tuples, section));
    }
    LIC3D_TRY_ASSIGN(words, parser.nextKeywordLine());
  }
  return vectorsNotFound(parser, arrayName, seen);
}

}  // namespace lic3d
