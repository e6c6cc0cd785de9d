#include "io/vtk_legacy.h"

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "io/file_util.h"
#include "io/volume_io.h"
#include "io/vtk_legacy_parser.h"

namespace lic3d {
namespace {

using vtk_legacy::checkWords;
using vtk_legacy::decodeName;
using vtk_legacy::Format;
using vtk_legacy::parseCount;
using vtk_legacy::Parser;
using vtk_legacy::upperCase;
using vtk_legacy::Words;
using vtk_legacy::wordsOf;

enum class Dataset { StructuredPoints, RectilinearGrid };

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
