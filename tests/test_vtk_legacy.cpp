// SPDX-License-Identifier: BSD-3-Clause
// VTK legacy reading: the two real data sets in assets/data, files written here in ASCII and
// BINARY, array selection, and malformed input.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/common.hpp>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/field_io.h"
#include "io/vtk_legacy.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;
using test::expectInputError;

using test::dataFolder;
using test::readWhole;

class VtkLegacyTest : public test::TempFolderTest {};

template <class T>
std::string bigEndian(const std::vector<T>& values) {
  std::string bytes(values.size() * sizeof(T), '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  if (std::endian::native == std::endian::little)
    for (std::size_t i = 0; i < values.size(); ++i)
      std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(i * sizeof(T)),
                   bytes.begin() + static_cast<std::ptrdiff_t>((i + 1) * sizeof(T)));
  return bytes;
}

// `count` numbers start, start + step, ... as ASCII, several per line like VTK writes them.
std::string asciiNumbers(std::size_t count, double start, double step) {
  std::string text;
  for (std::size_t i = 0; i < count; ++i) {
    char number[32];
    std::snprintf(number, sizeof number, "%.9g", start + step * static_cast<double>(i));
    text += number;
    text += (i % 9 == 8 || i + 1 == count) ? "\n" : " ";
  }
  return text;
}

struct Magnitudes {
  double min = std::numeric_limits<double>::infinity();
  double max = 0.0;
  double mean = 0.0;
  int zeros = 0;
  glm::dvec3 low{std::numeric_limits<double>::infinity()};
  glm::dvec3 high{-std::numeric_limits<double>::infinity()};
};

Magnitudes measure(const VectorField& field) {
  Magnitudes m;
  for (const glm::vec3& v : field.vectors) {
    const glm::dvec3 d(v);
    const double length = std::sqrt(d.x * d.x + d.y * d.y + d.z * d.z);
    m.min = std::min(m.min, length);
    m.max = std::max(m.max, length);
    m.mean += length;
    m.zeros += v == glm::vec3(0.0f) ? 1 : 0;
    m.low = glm::min(m.low, d);
    m.high = glm::max(m.high, d);
  }
  m.mean /= static_cast<double>(field.vectors.size());
  return m;
}

// --- The real data sets (values from assets/data/README.md) -------------------------------------

TEST_F(VtkLegacyTest, ReadsCarotidVelocityAfterItsScalars) {
  const fs::path file = dataFolder() / "carotid.vtk";
  const Result<VectorField> field = readVectorFieldVtk(file);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(76, 49, 45));
  EXPECT_EQ(field->geometry.spacing, glm::dvec3(1.0, 1.0, 1.0));
  EXPECT_EQ(field->geometry.origin, glm::dvec3(100.0, 80.0, 1.0));
  ASSERT_EQ(field->vectors.size(), 167580u);
  const Magnitudes m = measure(*field);
  EXPECT_NEAR(m.max, 22.695, 1e-3);
  EXPECT_EQ(m.min, 0.0);
  EXPECT_NEAR(m.mean, 0.1675, 1e-4);
  EXPECT_EQ(m.zeros, 19);
  EXPECT_NEAR(m.low.x, -11.56, 0.01);
  EXPECT_NEAR(m.high.x, 16.62, 0.01);
  EXPECT_NEAR(m.low.y, -22.63, 0.01);
  EXPECT_NEAR(m.high.y, 15.61, 0.01);
  EXPECT_NEAR(m.low.z, -17.47, 0.01);
  EXPECT_NEAR(m.high.z, 9.76, 0.01);

  // By name and through the dispatcher: the same array.
  const Result<VectorField> named = readVectorField(file, "vectors");
  ASSERT_TRUE(named.ok()) << named.error().message;
  EXPECT_EQ(named->vectors, field->vectors);
}

TEST_F(VtkLegacyTest, ReadsFemmMagneticFieldWithAnisotropicSpacing) {
  const fs::path file = dataFolder() / "example-femm-3d.vtk";
  const Result<VectorField> field = readVectorFieldVtk(file, "B");
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(47, 47, 47));
  EXPECT_EQ(field->geometry.spacing, glm::dvec3(0.05, 0.05, 0.125));
  EXPECT_EQ(field->geometry.origin, glm::dvec3(-1.15, -1.15, -0.375));
  const Magnitudes m = measure(*field);
  EXPECT_NEAR(m.max, 9.239e-3, 1e-6);
  EXPECT_NEAR(m.min, 1.242e-4, 1e-7);
  EXPECT_NEAR(m.mean, 3.453e-3, 1e-6);
  EXPECT_EQ(m.zeros, 0);
  EXPECT_NEAR(m.low.x, -5.217e-3, 1e-6);
  EXPECT_NEAR(m.high.y, 5.217e-3, 1e-6);
  EXPECT_NEAR(m.low.z, -2.136e-3, 1e-6);
  EXPECT_NEAR(m.high.z, 9.182e-3, 1e-6);
  // Bz is exactly mirror-symmetric in x: a wrong axis order or offset would break this.
  for (int k = 0; k < 47; ++k)
    for (int j = 0; j < 47; ++j)
      for (int i = 0; i < 47; ++i)
        ASSERT_EQ(field->at(i, j, k).z, field->at(46 - i, j, k).z) << i << "," << j << "," << k;
}

TEST_F(VtkLegacyTest, BothDataSetsReadThroughTheDispatcher) {
  FieldReadInfo info;
  const Result<VectorField> carotid = readVectorField(dataFolder() / "carotid.vtk", {}, &info);
  ASSERT_TRUE(carotid.ok()) << carotid.error().message;
  EXPECT_EQ(carotid->dims, Dims(76, 49, 45));
  EXPECT_EQ(info.nonFiniteVectors, 0u);
  EXPECT_EQ(info.arrayName, "vectors");
  EXPECT_EQ(info.arrayNames, std::vector<std::string>{"vectors"});
  const Result<VectorField> femm = readVectorField(dataFolder() / "example-femm-3d.vtk", {}, &info);
  ASSERT_TRUE(femm.ok()) << femm.error().message;
  EXPECT_EQ(femm->dims, Dims(47, 47, 47));
  EXPECT_EQ(femm->geometry.spacing, glm::dvec3(0.05, 0.05, 0.125));
  EXPECT_EQ(info.arrayName, "B");
  EXPECT_EQ(info.arrayNames, std::vector<std::string>{"B"});
}

TEST_F(VtkLegacyTest, MissingArrayNameListsTheNamesFound) {
  const fs::path file = dataFolder() / "carotid.vtk";
  expectInputError(readVectorFieldVtk(file, "velocity"), file,
                   "no VECTORS named 'velocity'; found: 'vectors'");
}

TEST_F(VtkLegacyTest, TruncatedCarotidIsAnErrorWhereverItIsCut) {
  const std::string whole = readWhole(dataFolder() / "carotid.vtk");
  ASSERT_EQ(whole.size(), 2681486u);
  const std::size_t scalarsStart = whole.find("LOOKUP_TABLE default\n") + 21;
  const std::size_t vectorsLine = whole.find("VECTORS vectors float\n");
  ASSERT_NE(vectorsLine, std::string::npos);
  for (const std::size_t cut :
       {std::size_t{0}, std::size_t{5}, std::size_t{40}, std::size_t{120}, scalarsStart - 3,
        scalarsStart, scalarsStart + 1000, vectorsLine - 1, vectorsLine + 10, vectorsLine + 22,
        vectorsLine + 22 + 1000000, whole.size() - 2}) {
    SCOPED_TRACE("cut at " + std::to_string(cut));
    const fs::path file = writeBytes("cut carotid.vtk", whole.substr(0, cut));
    const Result<VectorField> field = readVectorFieldVtk(file);
    ASSERT_FALSE(field.ok());
    EXPECT_EQ(field.error().kind, ErrorKind::InvalidInput) << field.error().message;
    EXPECT_NE(field.error().message.find("cut carotid.vtk"), std::string::npos)
        << field.error().message;
  }
  const fs::path file = writeBytes("cut carotid.vtk", whole.substr(0, whole.size() - 100));
  expectInputError(readVectorFieldVtk(file), file, "truncated");
}

// --- Files written here -------------------------------------------------------------------------

constexpr char kAsciiGeometry[] =
    "# vtk DataFile Version 3.0\nASCII file with every attribute kind\nASCII\n"
    "DATASET STRUCTURED_POINTS\nFIELD FieldData 1\nTIME 1 1 double\n0.5\n"
    "ORIGIN 1 2 -3.5\nDIMENSIONS 3 2 2\nASPECT_RATIO 0.5 0.25 2\n";

std::string asciiFile() {
  return std::string(kAsciiGeometry) + "POINT_DATA 12\n" +                           //
         "SCALARS density float\nLOOKUP_TABLE default\n" + asciiNumbers(12, 0, 1) +  //
         "SCALARS pair int 2\nLOOKUP_TABLE default\n" + asciiNumbers(24, -5, 1) +    //
         "LOOKUP_TABLE my_table 2\n0 0 0 1\n1 1 1 1\n" +                             //
         "COLOR_SCALARS colors 3\n" + asciiNumbers(36, 0, 0.01) +                    //
         "NORMALS normals float\n" + asciiNumbers(36, 1, 0) +                        //
         "TEXTURE_COORDINATES uv 2 float\n" + asciiNumbers(24, 0, 0.1) +             //
         "TENSORS stress double\n" + asciiNumbers(108, 0, 1e-3) +                    //
         "FIELD extra 2\nids 1 12 vtkIdType\n" + asciiNumbers(12, 0, 1) +            //
         "METADATA\nINFORMATION 0\n\nflux 3 12 float\n" + asciiNumbers(36, 0, 2) +   //
         "VECTORS first float\n" + asciiNumbers(36, -3, 0.5) +                       //
         "VECTORS second%20velocity double\n" + asciiNumbers(36, 1e-3, 1.5e-4) +     //
         "METADATA\nINFORMATION 1\nNAME L2_NORM_RANGE LOCATION vtkDataArray\nDATA 2 0 1\n\n";
}

void expectRamp(const VectorField& field, double start, double step) {
  ASSERT_EQ(field.vectors.size(), 12u);
  for (std::size_t i = 0; i < 36; ++i) {
    const double expected = start + step * static_cast<double>(i);
    ASSERT_FLOAT_EQ(field.vectors[i / 3][static_cast<glm::length_t>(i % 3)],
                    static_cast<float>(expected))
        << i;
  }
}

TEST_F(VtkLegacyTest, ReadsAsciiFileSkippingEveryOtherAttribute) {
  const fs::path file = writeBytes("ascii.vtk", asciiFile());
  const Result<VectorField> first = readVectorFieldVtk(file);
  ASSERT_TRUE(first.ok()) << first.error().message;
  EXPECT_EQ(first->dims, Dims(3, 2, 2));
  EXPECT_EQ(first->geometry.spacing, glm::dvec3(0.5, 0.25, 2.0));
  EXPECT_EQ(first->geometry.origin, glm::dvec3(1.0, 2.0, -3.5));
  expectRamp(*first, -3, 0.5);
  EXPECT_EQ(first->at(2, 1, 1), glm::vec3(13.5f, 14.0f, 14.5f));

  // Names are compared after VTK's %20 decoding.
  const Result<VectorField> second = readVectorFieldVtk(file, "second velocity");
  ASSERT_TRUE(second.ok()) << second.error().message;
  expectRamp(*second, 1e-3, 1.5e-4);

  expectInputError(readVectorFieldVtk(file, "normals"), file, "found: 'first', 'second velocity'");
}

TEST_F(VtkLegacyTest, AsciiFloatsParseExactlyLikeTheirDecimalText) {
  const fs::path file = writeBytes(
      "exact.vtk",
      "# vtk DataFile Version 2.0\nt\nascii\ndataset structured_points\ndimensions 1 1 2\n"
      "point_data 2\nvectors v float\n0.1 +2.5e-3 -1E+2\r\n3.4028234e38 1e-45 -0\n");
  const Result<VectorField> field = readVectorFieldVtk(file);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->geometry, GridGeometry{});  // VTK's defaults: spacing 1, origin 0
  EXPECT_EQ(field->vectors[0], glm::vec3(0.1f, 2.5e-3f, -100.0f));
  EXPECT_EQ(field->vectors[1], glm::vec3(3.4028234e38f, 1e-45f, 0.0f));
}

TEST_F(VtkLegacyTest, ReadsBinaryFileSkippingEveryOtherAttribute) {
  std::vector<double> vectors(36);
  for (std::size_t i = 0; i < vectors.size(); ++i) vectors[i] = 0.25 * static_cast<double>(i) - 2.0;
  // Binary blocks that start with whitespace bytes must not lose them.
  const std::string scalars = std::string("\n \t\r") + std::string(8, '\x07');
  const std::string file =
      "# vtk DataFile Version 3.0\nbinary\nBINARY\nDATASET STRUCTURED_POINTS\nDIMENSIONS 3 2 2\n"
      "SPACING 2 2 2\nORIGIN 0 0 0\nCELL_DATA 2\nVECTORS cellv float\n" +
      bigEndian(std::vector<float>(6, 1.0f)) +
      "\nPOINT_DATA 12\nSCALARS s unsigned_char\nLOOKUP_TABLE default\n" + scalars +
      "\nSCALARS l long 1\nLOOKUP_TABLE default\n" + bigEndian(std::vector<std::int64_t>(12, 10)) +
      "\nLOOKUP_TABLE t 2\n" + std::string(8, '\n') + "\nCOLOR_SCALARS c 4\n" +
      std::string(48, ' ') + "\nFIELD fd 3\nids 1 12 vtkIdType\n" +
      bigEndian(std::vector<std::int32_t>(12, 3)) + "\nNULL_ARRAY\nwide 2 3 vtktypeuint64\n" +
      bigEndian(std::vector<std::uint64_t>(6, 4)) + "\nTENSORS t short\n" +
      bigEndian(std::vector<std::int16_t>(108, 5)) + "\nNORMALS n float\n" +
      bigEndian(std::vector<float>(36, 0.5f)) + "\nTEXTURE_COORDINATES tc 3 unsigned_short\n" +
      bigEndian(std::vector<std::uint16_t>(36, 6)) + "\nVECTORS velocity double\n" +
      bigEndian(vectors) + "\n";
  const fs::path path = writeBytes("binary.vtk", file);
  const Result<VectorField> field = readVectorFieldVtk(path);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->geometry.spacing, glm::dvec3(2.0));
  for (std::size_t i = 0; i < vectors.size(); ++i)
    ASSERT_EQ(field->vectors[i / 3][static_cast<glm::length_t>(i % 3)],
              static_cast<float>(vectors[i]))
        << i;

  // The cell-data array comes first in the file, but point data is the default.
  const Result<VectorField> cells = readVectorFieldVtk(path, "cellv");
  ASSERT_TRUE(cells.ok()) << cells.error().message;
  EXPECT_EQ(cells->dims, Dims(2, 1, 1));
  EXPECT_EQ(cells->geometry.origin, glm::dvec3(1.0));
  EXPECT_EQ(cells->vectors, std::vector<glm::vec3>(2, glm::vec3(1.0f)));
  expectInputError(readVectorFieldVtk(path, "n"), path,
                   "no VECTORS named 'n'; found: 'cellv' (cell data), 'velocity'");

  // The file ends right after the vectors' data, without the usual newline: still fine.
  const fs::path noNewline = writeBytes("no newline.vtk", file.substr(0, file.size() - 1));
  EXPECT_TRUE(readVectorFieldVtk(noNewline).ok());
  const fs::path truncated = writeBytes("truncated.vtk", file.substr(0, file.size() - 9));
  expectInputError(readVectorFieldVtk(truncated), truncated, "truncated");
}

TEST_F(VtkLegacyTest, HugeDimensionsAreRefusedBeforeAllocating) {
  // 2^31 points of float vectors would be 24 GiB; the tiny payload must be refused first.
  for (const char* format : {"BINARY", "ASCII"}) {
    const fs::path file =
        writeBytes("huge.vtk", std::string("# vtk DataFile Version 3.0\nhuge\n") + format +
                                   "\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2048 2048 512\n"
                                   "POINT_DATA 2147483648\nVECTORS v float\n1 2 3 4 5 6\n");
    expectInputError(readVectorFieldVtk(file), file, "truncated");
  }
}

// --- Malformed files ----------------------------------------------------------------------------

struct MalformedCase {
  const char* label;
  std::string content;
  const char* fragment;
  const char* arrayName = "";
};

constexpr char kHead[] = "# vtk DataFile Version 3.0\ntitle\nASCII\nDATASET STRUCTURED_POINTS\n";
constexpr char kGeometry[] = "DIMENSIONS 2 1 1\nSPACING 1 1 1\nORIGIN 0 0 0\n";
constexpr char kVectors[] = "VECTORS v float\n1 2 3 4 5 6\n";

std::string vtk(const std::string& geometry, const std::string& data) {
  return std::string(kHead) + geometry + data;
}

std::string points(const std::string& attributes) {
  return vtk(kGeometry, "POINT_DATA 2\n" + attributes);
}

TEST_F(VtkLegacyTest, MalformedFilesAreInputErrorsNamingFileAndProblem) {
  const MalformedCase cases[] = {
      {"empty", "", "empty file"},
      {"not vtk", "P3\n2 2\n255\n", "not a VTK legacy file"},
      {"no title", "# vtk DataFile Version 3.0\n", "title line"},
      {"no format", "# vtk DataFile Version 3.0\ntitle\n", "expected ASCII or BINARY"},
      {"bad format", "# vtk DataFile Version 3.0\ntitle\nASCII2\n",
       "expected ASCII or BINARY, found 'ASCII2'"},
      {"no dataset", "# vtk DataFile Version 3.0\ntitle\nASCII\n", "found the end of the file"},
      {"point data first", "# vtk DataFile Version 3.0\ntitle\nASCII\nPOINT_DATA 2\n",
       "expected 'DATASET STRUCTURED_POINTS'"},
      {"polydata", "# vtk DataFile Version 3.0\ntitle\nASCII\nDATASET POLYDATA\n",
       "dataset type 'POLYDATA' is not supported"},
      {"missing dimensions", vtk("SPACING 1 1 1\n", "POINT_DATA 2\n" + std::string(kVectors)),
       "missing DIMENSIONS"},
      {"zero dimension", vtk("DIMENSIONS 2 0 1\n", ""),
       "DIMENSIONS: expected a whole number in [1, 16384]"},
      {"large dimension", vtk("DIMENSIONS 2 16385 1\n", ""), "found '16385'"},
      {"text dimension", vtk("DIMENSIONS 2 x 1\n", ""), "found 'x'"},
      {"two dimensions", vtk("DIMENSIONS 2 1\n", ""), "expected 'DIMENSIONS nx ny nz'"},
      {"too many points", vtk("DIMENSIONS 16384 16384 9\n", ""), "exceed the limit"},
      {"zero spacing", vtk("DIMENSIONS 2 1 1\nSPACING 1 0 1\n", ""),
       "SPACING: expected a positive number, found '0'"},
      {"nan aspect", vtk("DIMENSIONS 2 1 1\nASPECT_RATIO nan 1 1\n", ""),
       "ASPECT_RATIO: expected a positive number"},
      {"inf origin", vtk("DIMENSIONS 2 1 1\nORIGIN 0 inf 0\n", ""),
       "ORIGIN: expected a finite number"},
      {"unknown geometry", vtk("DIMENSIONS 2 1 1\nEXTENT 0 1 0 0 0 0\n", ""),
       "unexpected 'EXTENT'"},
      {"no point data", vtk(kGeometry, ""), "ends before POINT_DATA"},
      {"point count", vtk(kGeometry, "POINT_DATA 3\n" + std::string(kVectors)),
       "does not match the 2 points"},
      {"text count", vtk(kGeometry, "POINT_DATA two\n"), "'two' is not a whole number"},
      {"bit scalars", points("SCALARS s bit\nLOOKUP_TABLE default\n0 1\n"),
       "bit arrays are not supported"},
      {"unknown type", points("SCALARS s float16\nLOOKUP_TABLE default\n0 1\n"),
       "unknown data type 'float16'"},
      {"no lookup table", points("SCALARS s float\n0 1\n" + std::string(kVectors)), "LOOKUP_TABLE"},
      {"five components", points("SCALARS s float 5\nLOOKUP_TABLE default\n"), "1 to 4 components"},
      {"string field", points("FIELD f 1\nnames 1 2 string\na b\n"),
       "'string' arrays are not supported"},
      {"overflowing field", points("FIELD f 1\na 4294967296 4294967297 float\n"), "too many"},
      {"short field", points("FIELD f 2\na 1 2 float\n1 2\n"), "ends after 1 of 2 arrays"},
      {"field array line", points("FIELD f 1\na 1 2\n1 2\n"),
       "arrayName numComponents numTuples type"},
      {"huge lookup table", points("LOOKUP_TABLE t 99999999999\n"), "too many"},
      {"int vectors", points("VECTORS v int\n1 2 3 4 5 6\n"),
       "type 'int' is not supported (expected float or double)"},
      {"vectors without type", points("VECTORS v\n1 2 3 4 5 6\n"), "expected 'VECTORS name type'"},
      {"no vectors", points("SCALARS s float\nLOOKUP_TABLE default\n0 1\n"),
       "no VECTORS in POINT_DATA"},
      {"unknown attribute", points("BANANAS b float\n"), "unexpected 'BANANAS' in POINT_DATA"},
      {"bad number", points("VECTORS v float\n1 2 three 4 5 6\n"), "found 'three' after 2"},
      {"two exponents", points("VECTORS v float\n1 2 3 4 1e3e9 6\n"), "found '1e3e9'"},
      {"few numbers", points("VECTORS v float\n1 2 3 4\n"), "truncated"},
      {"skipped few numbers", points("NORMALS n float\n1 2 3 4\n"), "truncated"},
      {"zero vectors", points("VECTORS v float\n0 0 0 0 -0 0\n"),
       "every vector of the field is zero"},
      {"zero and nan vectors", points("VECTORS v double\n0 0 0 4 1e300 6\n"),
       "every vector of the field is zero (1 of the 2 were NaN, infinite or beyond a float's range "
       "of 3.4e38)"},
      {"long line", "# vtk DataFile Version 3.0\n" + std::string(5000, 't') + "\n",
       "longer than 4096"},
      {"long value", points("VECTORS v float\n" + std::string(300, '1') + " 2 3 4 5 6\n"),
       "longer than 256"},
      {"cell data without vectors",
       vtk(kGeometry, "CELL_DATA 1\nSCALARS s float\nLOOKUP_TABLE default\n1\n"),
       "no VECTORS in POINT_DATA or CELL_DATA"},
      {"cell vectors truncated", vtk(kGeometry, "CELL_DATA 1\nVECTORS cv float\n1 2\n"),
       "VECTORS 'cv': the data is truncated"},
      {"int cell vectors", vtk(kGeometry, "CELL_DATA 1\nVECTORS cv int\n1 2 3\n"),
       "type 'int' is not supported"},
      {"spacing in a rectilinear grid",
       "# vtk DataFile Version 3.0\nt\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 2 1 1\n"
       "SPACING 1 1 1\n",
       "unexpected 'SPACING' in the RECTILINEAR_GRID geometry"},
      {"coordinates in structured points", vtk(kGeometry, "X_COORDINATES 2 float\n0 1\n"),
       "unexpected 'X_COORDINATES' in the STRUCTURED_POINTS geometry"},
      {"cell count", vtk(kGeometry, "CELL_DATA 2\n"), "does not match the 1 cells"},
      {"missing name", points(kVectors), "no VECTORS named 'w'; found: 'v'", "w"},
      {"binary truncated",
       std::string("# vtk DataFile Version 3.0\nt\nBINARY\nDATASET STRUCTURED_POINTS\n") +
           kGeometry + "POINT_DATA 2\nVECTORS v float\n" + std::string(20, '\0'),
       "truncated"},
      {"binary skip truncated",
       std::string("# vtk DataFile Version 3.0\nt\nBINARY\nDATASET STRUCTURED_POINTS\n") +
           kGeometry + "POINT_DATA 2\nSCALARS s double\nLOOKUP_TABLE default\n" +
           std::string(15, '\0'),
       "truncated"},
  };
  for (const MalformedCase& c : cases) {
    SCOPED_TRACE(c.label);
    const fs::path file = writeBytes("bad field.vtk", c.content);
    expectInputError(readVectorFieldVtk(file, c.arrayName), file, c.fragment);
  }
}

TEST_F(VtkLegacyTest, CorruptedFilesNeverCrashTheReader) {
  // Random byte flips and cuts must give a field or an InvalidInput error; run under the
  // sanitizers this also checks that every read stays in bounds.
  const std::string binary =
      "# vtk DataFile Version 3.0\nb\nBINARY\nDATASET STRUCTURED_POINTS\nDIMENSIONS 3 2 2\nSPACING "
      "1 1 1\n"
      "ORIGIN 0 0 0\nPOINT_DATA 12\nSCALARS s short 2\nLOOKUP_TABLE default\n" +
      bigEndian(std::vector<std::int16_t>(24, 7)) + "\nFIELD f 1\na 2 3 double\n" +
      bigEndian(std::vector<double>(6, 1.0)) + "\nVECTORS v float\n" +
      bigEndian(std::vector<float>(36, 0.5f)) + "\n";
  std::mt19937 random(99);
  for (const std::string& original : {binary, asciiFile()}) {
    for (int trial = 0; trial < 400; ++trial) {
      std::string mutated = original;
      const int flips = 1 + static_cast<int>(random() % 4);
      for (int f = 0; f < flips; ++f) {
        const std::size_t at = random() % mutated.size();
        mutated[at] =
            random() % 2 ? static_cast<char>(random() % 256) : "0123456789 \n-.eE"[random() % 17];
      }
      if (trial % 5 == 0) mutated.resize(random() % mutated.size());
      const fs::path file = writeBytes("mutated.vtk", mutated);
      const Result<VectorField> read = readVectorFieldVtk(file);
      if (!read.ok()) {
        EXPECT_EQ(read.error().kind, ErrorKind::InvalidInput) << read.error().message;
      } else {
        EXPECT_EQ(read->vectors.size(), voxelCount(read->dims));
      }
    }
  }
}

TEST_F(VtkLegacyTest, ReadVectorFieldDispatchesVtkWithArrayName) {
  const fs::path file = writeBytes("Field.VTK", asciiFile());
  const Result<VectorField> field = readVectorField(file, "second velocity");
  ASSERT_TRUE(field.ok()) << field.error().message;
  expectRamp(*field, 1e-3, 1.5e-4);
  expectInputError(readVectorField(file, "nothing"), file, "found: 'first', 'second velocity'");
}

// --- Cell data, rectilinear grids, NaN
// ------------------------------------------------------------

TEST_F(VtkLegacyTest, CellDataBecomesAFieldAtTheCellCentres) {
  // 4x3x2 points are 3x2x1 cells; their centres start half a spacing after the origin.
  const std::string head =
      "# vtk DataFile Version 3.0\ncells\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 4 3 2\n"
      "SPACING 2 0.5 1\nORIGIN 10 20 30\n";
  const fs::path file =
      writeBytes("cells.vtk", head +
                                  "CELL_DATA 6\nSCALARS id int\nLOOKUP_TABLE default\n0 1 2 3 4 5\n"
                                  "VECTORS flow float\n" +
                                  asciiNumbers(18, 1, 1));
  FieldReadInfo info;
  const Result<VectorField> field = readVectorFieldVtk(file, {}, &info);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(3, 2, 1));
  EXPECT_EQ(field->geometry.spacing, glm::dvec3(2.0, 0.5, 1.0));
  EXPECT_EQ(field->geometry.origin, glm::dvec3(11.0, 20.25, 30.5));
  EXPECT_EQ(field->at(2, 1, 0), glm::vec3(16.0f, 17.0f, 18.0f));
  EXPECT_EQ(info.arrayName, "flow");
  EXPECT_EQ(info.arrayNames, std::vector<std::string>{"flow"});

  // An axis of one point has one flat cell at that point: no shift there.
  const fs::path flat =
      writeBytes("flat.vtk",
                 "# vtk DataFile Version 3.0\nflat\nBINARY\nDATASET STRUCTURED_POINTS\n"
                 "DIMENSIONS 3 1 2\nORIGIN 1 2 3\nCELL_DATA 2\nVECTORS v double\n" +
                     bigEndian(std::vector<double>{1, 2, 3, 4, 5, 6}) + "\n");
  const Result<VectorField> flatField = readVectorFieldVtk(flat);
  ASSERT_TRUE(flatField.ok()) << flatField.error().message;
  EXPECT_EQ(flatField->dims, Dims(2, 1, 1));
  EXPECT_EQ(flatField->geometry.origin, glm::dvec3(1.5, 2.0, 3.5));
  EXPECT_EQ(flatField->vectors[1], glm::vec3(4.0f, 5.0f, 6.0f));
}

TEST_F(VtkLegacyTest, PointDataIsPreferredAndNamesAreListed) {
  const std::string file =
      "# vtk DataFile Version 3.0\nboth\nASCII\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 2 2\n"
      "CELL_DATA 1\nVECTORS shared float\n9 9 9\nVECTORS onlycell float\n7 7 7\n"
      "POINT_DATA 8\nVECTORS shared float\n" +
      asciiNumbers(24, 1, 0) + "VECTORS other float\n" + asciiNumbers(24, 2, 0);
  const fs::path path = writeBytes("both.vtk", file);
  FieldReadInfo info;
  Result<VectorField> field = readVectorFieldVtk(path, {}, &info);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(2, 2, 2));
  EXPECT_EQ(field->vectors[0], glm::vec3(1.0f));
  EXPECT_EQ(info.arrayName, "shared");
  EXPECT_EQ(info.arrayNames, (std::vector<std::string>{"shared", "onlycell", "shared", "other"}));
  // The same name in both: point data wins. A cell-only name reads the cell data.
  field = readVectorFieldVtk(path, "shared");
  ASSERT_TRUE(field.ok());
  EXPECT_EQ(field->dims, Dims(2, 2, 2));
  field = readVectorFieldVtk(path, "onlycell", &info);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(1, 1, 1));
  EXPECT_EQ(field->vectors[0], glm::vec3(7.0f));
  EXPECT_EQ(info.arrayName, "onlycell");
  // A broken tail after the chosen array is not read without info, and not an error with it.
  const fs::path tail = writeBytes("tail.vtk", file + "BANANAS\n");
  EXPECT_TRUE(readVectorFieldVtk(tail, "shared").ok());
  EXPECT_TRUE(readVectorFieldVtk(tail, "shared", &info).ok());
  expectInputError(readVectorFieldVtk(tail, "missing"), tail, "unexpected 'BANANAS'");
}

TEST_F(VtkLegacyTest, ReadsUniformRectilinearGrids) {
  // ASCII float coordinates (rounded as float) and BINARY double and integer coordinates.
  const std::string ascii =
      "# vtk DataFile Version 3.0\nrect\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 3 2 1\n"
      "X_COORDINATES 3 float\n1000.1 1000.2 1000.3\nY_COORDINATES 2 double\n-1 1\n"
      "Z_COORDINATES 1 int\n7\nPOINT_DATA 6\nVECTORS v float\n" +
      asciiNumbers(18, 1, 1);
  fs::path file = writeBytes("rect.vtk", ascii);
  Result<VectorField> field = readVectorFieldVtk(file);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(3, 2, 1));
  EXPECT_NEAR(field->geometry.spacing.x, 0.1, 1e-4);
  EXPECT_EQ(field->geometry.spacing.y, 2.0);
  EXPECT_EQ(field->geometry.spacing.z, 1.0);
  EXPECT_NEAR(field->geometry.origin.x, 1000.1, 1e-4);
  EXPECT_EQ(field->geometry.origin.y, -1.0);
  EXPECT_EQ(field->geometry.origin.z, 7.0);

  const std::string binary =
      "# vtk DataFile Version 3.0\nrect\nBINARY\nDATASET RECTILINEAR_GRID\nDIMENSIONS 2 2 3\n"
      "Z_COORDINATES 3 double\n" +
      bigEndian(std::vector<double>{0.0, 0.1, 0.2}) + "\nX_COORDINATES 2 short\n" +
      bigEndian(std::vector<std::int16_t>{-4, 4}) + "\nY_COORDINATES 2 float\n" +
      bigEndian(std::vector<float>{0.5f, 0.75f}) + "\nPOINT_DATA 12\nVECTORS v float\n" +
      bigEndian(std::vector<float>(36, 0.5f)) + "\n";
  file = writeBytes("rect binary.vtk", binary);
  field = readVectorFieldVtk(file);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->geometry.spacing, glm::dvec3(8.0, 0.25, 0.1));
  EXPECT_EQ(field->geometry.origin, glm::dvec3(-4.0, 0.5, 0.0));
}

TEST_F(VtkLegacyTest, NonUniformRectilinearGridsAreErrorsNamingTheAxis) {
  const std::string head =
      "# vtk DataFile Version 3.0\nrect\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 3 2 1\n";
  const MalformedCase cases[] = {
      {"uniform but no data",
       head + "X_COORDINATES 3 double\n0 1 2\nY_COORDINATES 2 double\n0 1\n"
              "Z_COORDINATES 1 double\n0\n",
       "ends before POINT_DATA"},
      {"uneven x",
       head + "X_COORDINATES 3 double\n0 1 2.001\nY_COORDINATES 2 double\n0 1\n"
              "Z_COORDINATES 1 double\n0\nPOINT_DATA 6\n",
       "X_COORDINATES: the coordinates are not uniform: coordinate 1 is 1"},
      {"slightly uneven double z",
       "# vtk DataFile Version 3.0\nrect\nASCII\nDATASET RECTILINEAR_GRID\nDIMENSIONS 1 1 3\n"
       "X_COORDINATES 1 double\n0\nY_COORDINATES 1 double\n0\nZ_COORDINATES 3 double\n"
       "0 1.00001 2\nPOINT_DATA 3\n",
       "Z_COORDINATES: the coordinates are not uniform"},
      {"decreasing y", head + "X_COORDINATES 3 double\n0 1 2\nY_COORDINATES 2 double\n1 0\n",
       "Y_COORDINATES: the coordinates must increase"},
      {"nan x", head + "X_COORDINATES 3 double\n0 nan 2\n",
       "X_COORDINATES: the coordinates are not uniform"},
      {"wrong count", head + "X_COORDINATES 2 double\n0 1\n",
       "X_COORDINATES 2 does not match DIMENSIONS, which gives 3 points"},
      {"missing z",
       head + "X_COORDINATES 3 double\n0 1 2\nY_COORDINATES 2 double\n0 1\nPOINT_DATA 6\n",
       "Z_COORDINATES missing before POINT_DATA"},
      {"twice", head + "X_COORDINATES 3 double\n0 1 2\nX_COORDINATES 3 double\n0 1 2\n",
       "X_COORDINATES appears twice"},
      {"before dimensions",
       "# vtk DataFile Version 3.0\nrect\nASCII\nDATASET RECTILINEAR_GRID\n"
       "X_COORDINATES 3 double\n0 1 2\n",
       "missing DIMENSIONS before X_COORDINATES"},
      {"truncated binary",
       "# vtk DataFile Version 3.0\nrect\nBINARY\nDATASET RECTILINEAR_GRID\nDIMENSIONS 3 2 1\n"
       "X_COORDINATES 3 double\n" +
           std::string(20, '\0'),
       "X_COORDINATES: the data is truncated"},
  };
  for (const MalformedCase& c : cases) {
    SCOPED_TRACE(c.label);
    const fs::path file = writeBytes("bad rect.vtk", c.content);
    expectInputError(readVectorFieldVtk(file, c.arrayName), file, c.fragment);
  }
}

TEST_F(VtkLegacyTest, NonFiniteVectorsBecomeZeroAndAreCounted) {
  const fs::path file = writeBytes(
      "nan.vtk", vtk("DIMENSIONS 2 2 1\n",
                     "POINT_DATA 4\nVECTORS v float\n1 2 3\nnan 0 0\n0 -inf 0\n1 1e39 -1e-50\n"));
  FieldReadInfo info;
  const Result<VectorField> field = readVectorField(file, {}, &info);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(info.nonFiniteVectors, 3u);
  EXPECT_EQ(field->vectors,
            (std::vector<glm::vec3>{{1, 2, 3}, glm::vec3(0), glm::vec3(0), glm::vec3(0)}));
  const std::string binary =
      "# vtk DataFile Version 3.0\nb\nBINARY\nDATASET STRUCTURED_POINTS\nDIMENSIONS 2 1 1\n"
      "POINT_DATA 2\nVECTORS v double\n" +
      bigEndian(std::vector<double>{1e300, 0, 0, 0.5, 0.25, 0}) + "\n";
  const Result<VectorField> doubles = readVectorFieldVtk(writeBytes("d.vtk", binary), {}, &info);
  ASSERT_TRUE(doubles.ok()) << doubles.error().message;
  EXPECT_EQ(info.nonFiniteVectors, 1u);
  EXPECT_EQ(doubles->vectors[1], glm::vec3(0.5f, 0.25f, 0.0f));
}

}  // namespace
}  // namespace lic3d
