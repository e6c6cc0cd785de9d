// SPDX-License-Identifier: BSD-3-Clause
#include "io/vtk_legacy.h"

#include <cmath>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/text.h"
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

// One array of a POINT_DATA or CELL_DATA section, as scanData meets it before its data.
struct DataArray {
  enum class Kind { Vectors, Scalars, Field };  // VECTORS, SCALARS, an array of a FIELD block
  Kind kind = Kind::Vectors;
  std::string name;  // after %XX decoding
  std::string type;
  std::uint64_t components = 1;
  std::uint64_t tuples = 0;
  bool pointData = true;
  std::uint64_t offset = 0;  // where its data starts in the file
};

// How every error names an array: "SCALARS 'p'", "VECTORS 'v' (cell data)".
std::string describe(const DataArray& array) {
  const char* kind = array.kind == DataArray::Kind::Vectors   ? "VECTORS "
                     : array.kind == DataArray::Kind::Scalars ? "SCALARS "
                                                              : "FIELD array ";
  return kind + quoteForMessage(array.name) + (array.pointData ? "" : " (cell data)");
}

// What a visitor did with an array: left its data to be skipped, read it, or read it and needs
// nothing after it.
enum class Visit { Skip, Read, Last };
using ArrayVisitor = std::function<Result<Visit>(Parser& parser, const DataArray& array)>;

// The POINT_DATA or CELL_DATA section being read.
struct Section {
  bool pointData = false;
  std::uint64_t tuples = 0;
};

// FIELD name numArrays, then per array "name numComponents numTuples type" and its values. In a
// POINT_DATA or CELL_DATA section (`section` given) an array of one tuple per point or cell is
// data on them and goes to `visit`; the rest, and every array of the dataset's own FIELD (before
// the sections), are skipped. `stop` is set when the visitor needs nothing more.
Result<void> readFieldData(Parser& parser, const Words& words, const Section* section = nullptr,
                           const ArrayVisitor* visit = nullptr, bool* stop = nullptr) {
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
    if (section && visit && tuples == section->tuples) {
      DataArray array;
      array.kind = DataArray::Kind::Field;
      array.name = decodeName(line->at(0));
      array.type = line->at(3);
      array.components = components;
      array.tuples = tuples;
      array.pointData = section->pointData;
      array.offset = parser.position();
      LIC3D_TRY_ASSIGN(const Visit done, (*visit)(parser, array));
      if (done == Visit::Last && stop) *stop = true;
      if (done == Visit::Last) return {};
      if (done == Visit::Read) continue;
    }
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
      LIC3D_TRY(readFieldData(parser, *words));
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

// Skips one attribute other than VECTORS, SCALARS and FIELD, whose data holds `tuples` tuples.
Result<void> skipAttribute(Parser& parser, const Words& line, std::uint64_t tuples,
                           std::string_view section) {
  const std::string key = upperCase(line.front());
  const std::string what = key + " " + quoteForMessage(line.size() > 1 ? decodeName(line[1]) : "");
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
  if (key == "NORMALS") {
    LIC3D_TRY(checkWords(parser, line, 3, 3, "NORMALS name type"));
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
  if (key == "METADATA") return skipMetadata(parser);
  return parser.fail("unexpected " + quoteForMessage(line.front()) + " in " + std::string(section) +
                     " (expected SCALARS, VECTORS, NORMALS, TENSORS, TEXTURE_COORDINATES, "
                     "COLOR_SCALARS, LOOKUP_TABLE, FIELD, POINT_DATA or CELL_DATA)");
}

// SCALARS name type [numComponents], then its LOOKUP_TABLE line.
Result<DataArray> readScalarsHeader(Parser& parser, const Words& line, const Section& section) {
  const std::string what = "SCALARS " + quoteForMessage(line.size() > 1 ? decodeName(line[1]) : "");
  LIC3D_TRY(checkWords(parser, line, 3, 4, "SCALARS name type [numComponents]"));
  DataArray array;
  array.kind = DataArray::Kind::Scalars;
  array.name = decodeName(line[1]);
  array.type = line[2];
  array.tuples = section.tuples;
  array.pointData = section.pointData;
  if (line.size() == 4) {
    LIC3D_TRY_ASSIGN(array.components, parseCount(parser, line[3], what));
    if (array.components < 1 || array.components > 4)
      return parser.fail(what + ": expected 1 to 4 components, found " + line[3]);
  }
  LIC3D_TRY_ASSIGN(const std::optional<Words> table, parser.nextKeywordLine());
  if (!table || upperCase(table->front()) != "LOOKUP_TABLE" || table->size() != 2)
    return parser.fail(what + ": expected a 'LOOKUP_TABLE name' line after SCALARS");
  array.offset = parser.position();
  return array;
}

// Walks the POINT_DATA and CELL_DATA sections from `line` (the one that opens the first) to the
// end of the file. Each VECTORS and SCALARS array, and each FIELD array of one tuple per point or
// cell, goes to `visit` before its data; the data it leaves is skipped. The walk stops at the
// first error, or when the visitor needs nothing more.
Result<void> scanData(Parser& parser, Dims dims, Words line, const ArrayVisitor& visit) {
  Section section;
  for (;;) {
    const std::string key = upperCase(line.front());
    if (key == "POINT_DATA" || key == "CELL_DATA") {
      LIC3D_TRY(checkWords(parser, line, 2, 2, key + " count"));
      LIC3D_TRY_ASSIGN(section.tuples, parseCount(parser, line[1], key));
      section.pointData = key == "POINT_DATA";
      const std::uint64_t expected = section.pointData ? voxelCount(dims) : cellCount(dims);
      if (section.tuples != expected)
        return parser.fail(key + " " + line[1] + " does not match the " + std::to_string(expected) +
                           (section.pointData ? " points" : " cells") + " of the " +
                           std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                           std::to_string(dims.z) + " grid");
    } else if (key == "VECTORS" || key == "SCALARS") {
      DataArray array;
      if (key == "SCALARS") {
        LIC3D_TRY_ASSIGN(array, readScalarsHeader(parser, line, section));
      } else {
        LIC3D_TRY(checkWords(parser, line, 3, 3, "VECTORS name type"));
        array.name = decodeName(line[1]);
        array.type = line[2];
        array.components = 3;
        array.tuples = section.tuples;
        array.pointData = section.pointData;
        array.offset = parser.position();
      }
      LIC3D_TRY_ASSIGN(const Visit done, visit(parser, array));
      if (done == Visit::Last) return {};
      if (done == Visit::Skip)
        LIC3D_TRY(parser.skipTyped(array.tuples * array.components, array.type,
                                   key + " " + quoteForMessage(array.name)));
    } else if (key == "FIELD") {
      bool stop = false;
      LIC3D_TRY(readFieldData(parser, line, &section, &visit, &stop));
      if (stop) return {};
    } else {
      LIC3D_TRY(skipAttribute(parser, line, section.tuples,
                              section.pointData ? "POINT_DATA" : "CELL_DATA"));
    }
    LIC3D_TRY_ASSIGN(std::optional<Words> next, parser.nextKeywordLine());
    if (!next) return {};
    line = std::move(*next);
  }
}

// The preamble and the geometry; the line that opens the first POINT_DATA or CELL_DATA.
Result<Words> readHead(Parser& parser, Geometry& geometry) {
  LIC3D_TRY_ASSIGN(const Dataset dataset, readPreamble(parser));
  return readGeometry(parser, dataset, geometry);
}

// Reads the data of an array the scan has passed (cell data, chosen only when no point data of
// its name follows), from where it starts.
Result<void> readAgain(const std::filesystem::path& path, Format format, const DataArray& array,
                       const std::function<Result<void>(Parser&)>& read) {
  LIC3D_TRY_ASSIGN(FileReader again, FileReader::open(path));
  if (again.skip(array.offset) != array.offset)
    return fileError(path, "cannot read: " + again.failureReason());
  Parser parser(again);
  parser.setFormat(format);
  return read(parser);
}

// The VECTORS arrays of a file, in file order.
struct VectorsSeen {
  std::vector<std::string> names;
  std::vector<bool> cellData;  // per name
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
  return parser.fail("no VECTORS in POINT_DATA or CELL_DATA");
}

// The scalar arrays met: 1-component SCALARS and FIELD arrays, point and cell data.
std::string listScalars(const std::vector<DataArray>& arrays) {
  std::string list;
  for (const DataArray& array : arrays)
    list += (list.empty() ? "" : ", ") + quoteForMessage(array.name) +
            (array.pointData ? "" : " (cell data)");
  return list.empty() ? "none" : list;
}

Result<void> readScalarValues(Parser& parser, const DataArray& array, std::vector<float>& values) {
  return parser.readValues(
      array.tuples, array.type, describe(array),
      [&] { values.reserve(static_cast<std::size_t>(array.tuples)); },
      [&](const double* read, std::size_t count) {
        for (std::size_t i = 0; i < count; ++i) values.push_back(vectorComponent(read[i]));
      });
}

}  // namespace

Result<VectorField> readVectorFieldVtk(const std::filesystem::path& path,
                                       std::string_view arrayName, FieldReadInfo* info) {
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  Parser parser(reader);
  Geometry geometry;
  LIC3D_TRY_ASSIGN(Words first, readHead(parser, geometry));
  const Dims dims = *geometry.dims;

  VectorsSeen seen;
  std::vector<std::string> scalarNames;
  std::optional<VectorField> chosen;  // point data is preferred: it is what lic3d samples
  std::string chosenName;
  std::optional<DataArray> cellVectors;
  std::vector<std::uint8_t> valid;  // kValidPointMaskName, when the file has it

  const auto visit = [&](Parser& p, const DataArray& array) -> Result<Visit> {
    if (array.kind != DataArray::Kind::Vectors) {
      if (!array.pointData || array.components != 1) return Visit::Skip;
      if (array.name != kValidPointMaskName) {
        scalarNames.push_back(array.name);
        return Visit::Skip;
      }
      if (!valid.empty()) return Visit::Skip;
      LIC3D_TRY(p.readValues(
          array.tuples, array.type, describe(array),
          [&] { valid.reserve(static_cast<std::size_t>(array.tuples)); },
          [&](const double* values, std::size_t count) {
            for (std::size_t i = 0; i < count; ++i) valid.push_back(values[i] != 0.0 ? 1 : 0);
          }));
      return Visit::Read;
    }
    seen.names.push_back(array.name);
    seen.cellData.push_back(!array.pointData);
    if (chosen || !(arrayName.empty() || array.name == arrayName)) return Visit::Skip;
    if (!array.pointData) {
      if (!cellVectors) cellVectors = array;
      return Visit::Skip;
    }
    VectorField field;
    field.dims = dims;
    field.geometry = geometry.grid;
    LIC3D_TRY(p.readVectors(array.tuples, array.type, describe(array), field.vectors));
    chosen = std::move(field);
    chosenName = array.name;
    return Visit::Read;
  };
  // The whole file is scanned even when the chosen array comes early: the mask may follow it,
  // and `info` lists every array (the result never depends on whether `info` was given).
  const Result<void> scanned = scanData(parser, dims, std::move(first), visit);
  // What follows the chosen array only adds names (and perhaps the mask): an error there does not
  // spoil the field.
  if (!scanned.ok() && !chosen) return scanned.error();

  VectorField field;
  std::size_t masked = 0;
  if (chosen) {
    field = std::move(*chosen);
    // The mask is on the points: it says nothing about cell-centred vectors.
    masked = maskVectors(valid, field.vectors);
  } else if (cellVectors) {
    // Cell-centred vectors on an N-cell grid become a field of N voxels at the cell centres: the
    // origin moves by half a spacing (cellCentredGrid).
    const CellCentredGrid cells = cellCentredGrid(dims, geometry.grid);
    field.dims = cells.dims;
    field.geometry = cells.geometry;
    LIC3D_TRY(readAgain(path, parser.format(), *cellVectors, [&](Parser& again) {
      return again.readVectors(cellVectors->tuples, cellVectors->type, describe(*cellVectors),
                               field.vectors);
    }));
    chosenName = cellVectors->name;
  } else {
    return vectorsNotFound(parser, arrayName, seen);
  }
  if (info) {
    *info = FieldReadInfo{};
    info->arrayName = chosenName;
    info->arrayNames = seen.names;
    info->scalarNames = std::move(scalarNames);
    info->maskedVectors = masked;
  }
  LIC3D_TRY(finishVectorField(path, field, info));
  return field;
}

Result<PointScalars> readPointScalarsVtk(const std::filesystem::path& path, std::string_view name) {
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  Parser parser(reader);
  Geometry geometry;
  LIC3D_TRY_ASSIGN(Words first, readHead(parser, geometry));
  const Dims dims = *geometry.dims;

  std::vector<DataArray> found;       // the scalar arrays, for the error when none fits
  std::optional<DataArray> misshape;  // an array of that name with other than 1 component
  std::optional<PointScalars> chosen;
  std::optional<DataArray> cellArray;
  const auto visit = [&](Parser& p, const DataArray& array) -> Result<Visit> {
    if (array.kind == DataArray::Kind::Vectors || array.components != 1) {
      if (!misshape && !name.empty() && array.name == name) misshape = array;
      return Visit::Skip;
    }
    // VTK's mask of valid points is no colour to offer: it is read only when named.
    const bool mask = array.pointData && array.name == kValidPointMaskName;
    if (!mask) found.push_back(array);
    if (name.empty() ? mask : array.name != name) return Visit::Skip;
    if (!array.pointData) {
      if (!cellArray) cellArray = array;
      return Visit::Skip;
    }
    PointScalars scalars;
    scalars.dims = dims;
    scalars.geometry = geometry.grid;
    scalars.name = array.name;
    LIC3D_TRY(readScalarValues(p, array, scalars.values));
    chosen = std::move(scalars);
    return Visit::Last;
  };
  const Result<void> scanned = scanData(parser, dims, std::move(first), visit);
  if (!scanned.ok()) return scanned.error();
  if (chosen) return std::move(*chosen);
  if (cellArray) {
    // Cell data is centred like cell vectors (cellCentredGrid).
    const CellCentredGrid cells = cellCentredGrid(dims, geometry.grid);
    PointScalars scalars;
    scalars.dims = cells.dims;
    scalars.geometry = cells.geometry;
    scalars.name = cellArray->name;
    LIC3D_TRY(readAgain(path, parser.format(), *cellArray, [&](Parser& again) {
      return readScalarValues(again, *cellArray, scalars.values);
    }));
    return scalars;
  }
  const std::string kinds = "(SCALARS or FIELD array of 1 component)";
  if (misshape)
    return parser.fail(describe(*misshape) + " has " + std::to_string(misshape->components) +
                       " components, a scalar has 1; scalar arrays " + kinds + ": " +
                       listScalars(found));
  if (!name.empty())
    return parser.fail("no scalar array " + kinds + " named " + quoteForMessage(name) +
                       "; found: " + listScalars(found));
  return parser.fail("no scalar array " + kinds + " in POINT_DATA or CELL_DATA");
}

}  // namespace lic3d
