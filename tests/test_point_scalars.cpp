// SPDX-License-Identifier: BSD-3-Clause
// Scalars for colour and opacity (readPointScalars) from VTK legacy, VTK XML and NRRD files
// written here, the scalar names, units and validity mask the vector readers report, and the
// mask zeroing vectors.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "io/field_io.h"
#include "io/nrrd.h"
#include "io/vti.h"
#include "io/vtk_legacy.h"
#include "nrrd_test_support.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

using test::bytesOf;
using test::deflateBytes;
using test::expectInputError;

class PointScalarsTest : public test::TempFolderTest {};

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// Exactly equal, NaN matching NaN and the sign of zero kept.
void expectSameValues(const std::vector<float>& actual, const std::vector<float>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    if (std::isnan(expected[i])) {
      EXPECT_TRUE(std::isnan(actual[i])) << "value " << i << " is " << actual[i];
    } else {
      EXPECT_EQ(actual[i], expected[i]) << "value " << i;
      EXPECT_EQ(std::signbit(actual[i]), std::signbit(expected[i])) << "value " << i;
    }
  }
}

template <class T>
std::vector<float> asFloats(const std::vector<T>& values) {
  std::vector<float> floats;
  for (const T value : values) floats.push_back(static_cast<float>(value));
  return floats;
}

std::string text(const std::vector<double>& values, const char* format = "%.17g") {
  std::string line;
  for (const double value : values) {
    char number[40];
    std::snprintf(number, sizeof number, format, value);
    line += number;
    line += ' ';
  }
  return line + "\n";
}

std::vector<double> ramp(std::size_t count, double start, double step) {
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) values[i] = start + step * static_cast<double>(i);
  return values;
}

// --- VTK legacy ---------------------------------------------------------------------------------

constexpr char kLegacyGeometry[] =
    "DATASET STRUCTURED_POINTS\nDIMENSIONS 3 2 2\nSPACING 0.5 0.25 2\nORIGIN 1 2 -3.5\n";

// Float text that must parse as float directly, and the floats it means.
constexpr char kDensityText[] = "0.1 2.5e-3 -1E+2 3.4028234e38 1e-45 -0 nan 7 8 9 10 11\n";
const std::vector<float> kDensity = {0.1f, 2.5e-3f, -100.0f, 3.4028234e38f, 1e-45f, -0.0f,
                                     kNaN, 7.0f,    8.0f,    9.0f,          10.0f,  11.0f};

std::string asciiLegacy(const std::string& mask) {
  return std::string("# vtk DataFile Version 3.0\nscalars\nASCII\n") + kLegacyGeometry +
         "CELL_DATA 2\nSCALARS pressure double 1\nLOOKUP_TABLE default\n-1.5 2.25\n"
         "SCALARS density float\nLOOKUP_TABLE default\n5 6\n"
         "POINT_DATA 12\nSCALARS density float\nLOOKUP_TABLE default\n" +
         kDensityText + "SCALARS pair int 2\nLOOKUP_TABLE default\n" + text(ramp(24, -5, 1)) +
         "FIELD FieldData 3\ntemperature 1 12 double\n" + text(ramp(12, 0.1, 0.3)) +
         "flux 3 12 float\n" + text(ramp(36, 0, 2)) + "other 1 5 int\n1 2 3 4 5\n" +
         "VECTORS velocity float\n1 1 1\n2 2 2\nnan 3 3\n" + text(ramp(27, 1, 1)) + mask;
}

// VTK's legacy writer puts arrays that are no attribute, like the probe filter's mask, in a FIELD.
constexpr char kAsciiMask[] =
    "FIELD FieldData 1\nvtkValidPointMask 1 12 char\n1 1 0 1 1 1 1 1 1 1 0 1\n";

TEST_F(PointScalarsTest, VtkAsciiScalarsAndFieldArraysReadExactly) {
  const fs::path file = writeBytes("ascii.vtk", asciiLegacy(kAsciiMask));
  // Point data wins over the cell array of the same name that comes first.
  const Result<PointScalars> density = readPointScalars(file, "density");
  ASSERT_TRUE(density.ok()) << density.error().message;
  EXPECT_EQ(density->dims, Dims(3, 2, 2));
  EXPECT_EQ(density->geometry.spacing, glm::dvec3(0.5, 0.25, 2.0));
  EXPECT_EQ(density->geometry.origin, glm::dvec3(1.0, 2.0, -3.5));
  EXPECT_EQ(density->name, "density");
  EXPECT_EQ(density->unit, "");
  expectSameValues(density->values, kDensity);

  const Result<PointScalars> temperature = readPointScalarsVtk(file, "temperature");
  ASSERT_TRUE(temperature.ok()) << temperature.error().message;
  expectSameValues(temperature->values, asFloats(ramp(12, 0.1, 0.3)));

  // Without a name: the first point-data scalar array.
  const Result<PointScalars> first = readPointScalarsVtk(file, {});
  ASSERT_TRUE(first.ok()) << first.error().message;
  EXPECT_EQ(first->name, "density");

  // Cell data lies at the cell centres.
  const Result<PointScalars> pressure = readPointScalars(file, "pressure");
  ASSERT_TRUE(pressure.ok()) << pressure.error().message;
  EXPECT_EQ(pressure->dims, Dims(2, 1, 1));
  EXPECT_EQ(pressure->geometry.origin, glm::dvec3(1.25, 2.125, -2.5));
  expectSameValues(pressure->values, {-1.5f, 2.25f});

  // The mask is readable by name, but never offered.
  const Result<PointScalars> mask = readPointScalars(file, "vtkValidPointMask");
  ASSERT_TRUE(mask.ok()) << mask.error().message;
  expectSameValues(mask->values, {1, 1, 0, 1, 1, 1, 1, 1, 1, 1, 0, 1});
  expectInputError(readPointScalars(file, "nope"), file,
                   "named 'nope'; found: 'pressure' (cell data), 'density' (cell data), "
                   "'density', 'temperature'");
  expectInputError(readPointScalars(file, "pair"), file,
                   "SCALARS 'pair' has 2 components, a scalar has 1");
  expectInputError(readPointScalars(file, "flux"), file,
                   "FIELD array 'flux' has 3 components, a scalar has 1");
  expectInputError(readPointScalars(file, "velocity"), file, "VECTORS 'velocity' has 3");
  const fs::path none = writeBytes(
      "none.vtk", std::string("# vtk DataFile Version 3.0\nt\nASCII\n") + kLegacyGeometry +
                      "POINT_DATA 12\nVECTORS v float\n" + text(ramp(36, 1, 1)));
  expectInputError(readPointScalars(none, {}), none, "no scalar array");
}

TEST_F(PointScalarsTest, VtkValidPointMaskZeroesVectorsBeforeTheNonFiniteCheck) {
  const fs::path file = writeBytes("masked.vtk", asciiLegacy(kAsciiMask));
  FieldReadInfo info;
  const Result<VectorField> field = readVectorField(file, {}, &info);
  ASSERT_TRUE(field.ok()) << field.error().message;
  // Vector 2 holds a NaN, but the mask hides it first: masked, not non-finite.
  EXPECT_EQ(info.maskedVectors, 2u);
  EXPECT_EQ(info.nonFiniteVectors, 0u);
  EXPECT_EQ(info.scalarNames, (std::vector<std::string>{"density", "temperature"}));
  EXPECT_EQ(info.arrayNames, std::vector<std::string>{"velocity"});
  EXPECT_EQ(info.unit, "");
  EXPECT_EQ(field->vectors[1], glm::vec3(2.0f));
  EXPECT_EQ(field->vectors[2], glm::vec3(0.0f));
  EXPECT_EQ(field->vectors[9], glm::vec3(19.0f, 20.0f, 21.0f));
  EXPECT_EQ(field->vectors[10], glm::vec3(0.0f));
  EXPECT_EQ(field->vectors[11], glm::vec3(25.0f, 26.0f, 27.0f));
  // The mask comes after the vectors: it applies without `info` as well.
  const Result<VectorField> plain = readVectorFieldVtk(file);
  ASSERT_TRUE(plain.ok()) << plain.error().message;
  EXPECT_EQ(plain->vectors, field->vectors);

  // Without the mask the NaN vector is only non-finite.
  const fs::path unmasked = writeBytes("unmasked.vtk", asciiLegacy(""));
  ASSERT_TRUE(readVectorField(unmasked, {}, &info).ok());
  EXPECT_EQ(info.maskedVectors, 0u);
  EXPECT_EQ(info.nonFiniteVectors, 1u);

  // Every point masked: no flow at all.
  const fs::path all = writeBytes(
      "all masked.vtk",
      asciiLegacy("FIELD FieldData 1\nvtkValidPointMask 1 12 int\n0 0 0 0 0 0 0 0 0 0 0 0\n"));
  expectInputError(readVectorField(all), all, "every vector of the field is zero");
}

TEST_F(PointScalarsTest, VtkBinaryScalarsOfEveryTypeReadExactly) {
  const std::vector<std::uint8_t> u8 = {0, 1, 2, 127, 128, 200, 255, 3, 4, 5, 6, 7};
  const std::vector<std::int16_t> s16 = {-32768, -1, 0, 1, 32767, 5, 6, 7, 8, 9, 10, 11};
  const std::vector<std::int64_t> i64 = {-(std::int64_t{1} << 40), -3, 0, 1, 2, 3, 4, 5, 6, 7, 8,
                                         std::int64_t{1} << 53};
  const std::vector<float> f = {0.1f, kNaN, -kInf, 1e-45f, -0.0f, 6, 7, 8, 9, 10, 11, 12};
  const std::vector<double> d = {0.1, 1e300, -2.5, 1.0 / 3.0, 5, 6, 7, 8, 9, 10, 11, 12};
  const std::vector<std::uint32_t> u32 = {4000000000u, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11};
  const std::vector<std::uint8_t> mask = {1, 0, 1, 1, 1, 1, 1, 0, 1, 1, 1, 1};
  std::vector<double> vectors = ramp(36, 1, 0.5);
  const auto big = [](const auto& values) { return bytesOf(values, std::endian::big); };
  const std::string file =
      std::string("# vtk DataFile Version 3.0\nbinary\nBINARY\n") + kLegacyGeometry +
      "CELL_DATA 2\nSCALARS c float\nLOOKUP_TABLE default\n" + big(std::vector<float>{4, -4}) +
      "\nPOINT_DATA 12\nSCALARS vtkValidPointMask unsigned_char\nLOOKUP_TABLE default\n" +
      big(mask) + "\nSCALARS u8 unsigned_char 1\nLOOKUP_TABLE default\n" + big(u8) +
      "\nSCALARS s16 short\nLOOKUP_TABLE default\n" + big(s16) +
      "\nSCALARS i64 vtktypeint64\nLOOKUP_TABLE default\n" + big(i64) +
      "\nSCALARS f float\nLOOKUP_TABLE default\n" + big(f) +
      "\nSCALARS d double\nLOOKUP_TABLE default\n" + big(d) +
      "\nFIELD fd 1\nu32 1 12 unsigned_int\n" + big(u32) + "\nVECTORS v double\n" + big(vectors) +
      "\n";
  const fs::path path = writeBytes("binary.vtk", file);

  const auto read = [&](const char* name) {
    Result<PointScalars> scalars = readPointScalars(path, name);
    EXPECT_TRUE(scalars.ok()) << scalars.error().message;
    return scalars.ok() ? scalars->values : std::vector<float>{};
  };
  expectSameValues(read("u8"), asFloats(u8));
  expectSameValues(read("s16"), asFloats(s16));
  expectSameValues(read("i64"), asFloats(i64));
  expectSameValues(read("f"), f);
  // A double beyond the float range becomes infinity, never undefined behaviour.
  expectSameValues(read("d"),
                   {0.1f, kInf, -2.5f, static_cast<float>(1.0 / 3.0), 5, 6, 7, 8, 9, 10, 11, 12});
  expectSameValues(read("u32"), asFloats(u32));
  expectSameValues(read("c"), {4.0f, -4.0f});
  EXPECT_EQ(readPointScalars(path, {})->name, "u8");

  FieldReadInfo info;
  const Result<VectorField> field = readVectorField(path, {}, &info);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(info.scalarNames, (std::vector<std::string>{"u8", "s16", "i64", "f", "d", "u32"}));
  EXPECT_EQ(info.maskedVectors, 2u);
  for (std::size_t i = 0; i < 12; ++i) {
    const glm::vec3 expected = mask[i] ? glm::vec3(static_cast<float>(vectors[3 * i]),
                                                   static_cast<float>(vectors[3 * i + 1]),
                                                   static_cast<float>(vectors[3 * i + 2]))
                                       : glm::vec3(0.0f);
    EXPECT_EQ(field->vectors[i], expected) << i;
  }

  // An array cut before the chosen one: an error naming the cut array.
  const fs::path truncated =
      writeBytes("truncated.vtk", file.substr(0, file.find("\nSCALARS d") - 4));
  expectInputError(readPointScalars(truncated, "u32"), truncated,
                   "SCALARS 'f': the data is truncated");
  // The data of the chosen array itself is cut.
  const fs::path cut = writeBytes("cut.vtk", file.substr(0, file.find("\nSCALARS f") - 4));
  expectInputError(readPointScalars(cut, "i64"), cut, "SCALARS 'i64': the data is truncated");
}

// --- VTK XML ImageData --------------------------------------------------------------------------

struct VtiArray {
  std::string name;
  std::string type;
  int components = 1;  // 0: no NumberOfComponents attribute (one component)
  bool cellData = false;
  std::vector<double> values;
};

std::string littleEndianBytes(const VtiArray& array) {
  const auto le = [](const auto& values) { return bytesOf(values, std::endian::little); };
  std::vector<float> f32;
  std::vector<double> f64;
  std::vector<std::int16_t> i16;
  std::vector<std::int8_t> i8;
  std::vector<std::uint8_t> u8;
  for (const double v : array.values) {
    f32.push_back(static_cast<float>(v));
    f64.push_back(v);
    i16.push_back(static_cast<std::int16_t>(v));
    i8.push_back(static_cast<std::int8_t>(v));
    u8.push_back(static_cast<std::uint8_t>(v));
  }
  if (array.type == "Float32") return le(f32);
  if (array.type == "Float64") return le(f64);
  if (array.type == "Int16") return le(i16);
  if (array.type == "Int8") return le(i8);
  return le(u8);
}

std::string base64(const std::string& bytes) {
  constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string encoded;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t bits = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size())
      bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) bits |= static_cast<unsigned char>(bytes[i + 2]);
    encoded += kAlphabet[bits >> 18 & 63];
    encoded += kAlphabet[bits >> 12 & 63];
    encoded += i + 1 < bytes.size() ? kAlphabet[bits >> 6 & 63] : '=';
    encoded += i + 2 < bytes.size() ? kAlphabet[bits & 63] : '=';
  }
  return encoded;
}

// `format`: ascii, binary (base64), or zlib (base64 vtkZLibDataCompressor blocks of 16 bytes).
std::string makeVti(const std::vector<VtiArray>& arrays, const std::string& format) {
  const auto header = [](const std::vector<std::uint32_t>& numbers) {
    return bytesOf(numbers, std::endian::little);
  };
  const auto arrayXml = [&](const VtiArray& array) {
    std::string xml = "<DataArray type=\"" + array.type + "\" Name=\"" + array.name + "\"";
    if (array.components > 0)
      xml += " NumberOfComponents=\"" + std::to_string(array.components) + "\"";
    xml += std::string(" format=\"") + (format == "ascii" ? "ascii" : "binary") + "\">\n";
    const std::string bytes = littleEndianBytes(array);
    if (format == "ascii") {
      xml += text(array.values, array.type == "Float32" ? "%.9g" : "%.17g");
    } else if (format == "binary") {
      xml += base64(header({static_cast<std::uint32_t>(bytes.size())})) + base64(bytes);
    } else {
      constexpr std::size_t kBlock = 16;
      std::vector<std::uint32_t> numbers = {
          static_cast<std::uint32_t>((bytes.size() + kBlock - 1) / kBlock), kBlock,
          static_cast<std::uint32_t>(bytes.size() % kBlock)};
      std::string blocks;
      for (std::size_t at = 0; at < bytes.size(); at += kBlock) {
        const std::string block = deflateBytes(bytes.substr(at, kBlock), 15);
        numbers.push_back(static_cast<std::uint32_t>(block.size()));
        blocks += block;
      }
      xml += base64(header(numbers)) + base64(blocks);
    }
    return xml + "\n</DataArray>\n";
  };
  std::string points;
  std::string cells;
  for (const VtiArray& array : arrays) (array.cellData ? cells : points) += arrayXml(array);
  return std::string(
             "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
             "byte_order=\"LittleEndian\" header_type=\"UInt32\"") +
         (format == "zlib" ? " compressor=\"vtkZLibDataCompressor\"" : "") +
         ">\n<ImageData WholeExtent=\"0 2 0 1 0 1\" Origin=\"1 2 3\" Spacing=\"0.5 0.25 2\">\n"
         "<Piece Extent=\"0 2 0 1 0 1\">\n<PointData Scalars=\"i\" Vectors=\"velocity\">\n" +
         points + "</PointData>\n<CellData>\n" + cells +
         "</CellData>\n</Piece>\n</ImageData>\n</VTKFile>\n";
}

TEST_F(PointScalarsTest, VtiScalarsReadExactlyInEveryEncoding) {
  const std::vector<double> p = {
      0.1, -2.5, 1e-45, -0.0, static_cast<double>(kNaN), 3.4028234e38, 6, 7, 8, 9, 10, 11};
  const std::vector<double> i = {-32768, -1, 0, 1, 32767, 5, 6, 7, 8, 9, 10, 11};
  const std::vector<double> mask = {1, 1, 1, 0, 1, 1, 1, 1, 1, -1, 0, 0};
  std::vector<double> velocity = ramp(36, -3.25, 0.5);
  velocity[3 * 10] = static_cast<double>(kNaN);  // hidden by the mask
  const std::vector<VtiArray> arrays = {
      {"p", "Float32", 1, false, p},
      {"velocity", "Float32", 3, false, velocity},
      {"vtkValidPointMask", "Int8", 1, false, mask},
      {"i", "Int16", 0, false, i},
      {"c", "Float64", 1, true, {0.1, -7}},
  };
  for (const char* format : {"ascii", "binary", "zlib"}) {
    SCOPED_TRACE(format);
    const fs::path file = writeBytes("scalars.vti", makeVti(arrays, format));
    const Result<PointScalars> scalars = readPointScalars(file, "p");
    ASSERT_TRUE(scalars.ok()) << scalars.error().message;
    EXPECT_EQ(scalars->dims, Dims(3, 2, 2));
    EXPECT_EQ(scalars->geometry.origin, glm::dvec3(1.0, 2.0, 3.0));
    EXPECT_EQ(scalars->geometry.spacing, glm::dvec3(0.5, 0.25, 2.0));
    EXPECT_EQ(scalars->name, "p");
    EXPECT_EQ(scalars->unit, "");
    expectSameValues(scalars->values, asFloats(p));

    // Without a name: PointData's active Scalars, an array without NumberOfComponents.
    const Result<PointScalars> active = readPointScalarsVti(file, {});
    ASSERT_TRUE(active.ok()) << active.error().message;
    EXPECT_EQ(active->name, "i");
    expectSameValues(active->values, asFloats(i));

    const Result<PointScalars> cells = readPointScalars(file, "c");
    ASSERT_TRUE(cells.ok()) << cells.error().message;
    EXPECT_EQ(cells->dims, Dims(2, 1, 1));
    EXPECT_EQ(cells->geometry.origin, glm::dvec3(1.25, 2.125, 4.0));
    expectSameValues(cells->values, {0.1f, -7.0f});

    expectInputError(readPointScalars(file, "nope"), file,
                     "no 1-component DataArray named 'nope'; found: 'p', 'i', 'c' (cell data)");
    expectInputError(readPointScalars(file, "velocity"), file,
                     "DataArray 'velocity' has 3 components, expected 1");
    EXPECT_TRUE(readPointScalars(file, "vtkValidPointMask").ok());

    FieldReadInfo info;
    const Result<VectorField> field = readVectorField(file, {}, &info);
    ASSERT_TRUE(field.ok()) << field.error().message;
    EXPECT_EQ(info.scalarNames, (std::vector<std::string>{"p", "i"}));
    EXPECT_EQ(info.maskedVectors, 3u);
    EXPECT_EQ(info.nonFiniteVectors, 0u);
    for (std::size_t v = 0; v < 12; ++v) {
      const glm::vec3 expected = mask[v] != 0 ? glm::vec3(static_cast<float>(velocity[3 * v]),
                                                          static_cast<float>(velocity[3 * v + 1]),
                                                          static_cast<float>(velocity[3 * v + 2]))
                                              : glm::vec3(0.0f);
      EXPECT_EQ(field->vectors[v], expected) << v;
    }
  }
}

// --- NRRD ---------------------------------------------------------------------------------------

TEST_F(PointScalarsTest, NrrdScalarsOfAnyTypeWithSampleUnits) {
  const std::vector<std::int16_t> shorts = {-32768, -1, 0, 1, 32767, 5, 6, 7, 8, 9, 10, 11};
  const fs::path shortFile =
      writeBytes("pressure.nrrd",
                 "NRRD0004\ntype: short\ndimension: 3\nsizes: 3 2 2\nspacings: 0.5 0.25 2\n"
                 "space origin: (1,2,3)\nsample units: \"Pa\"\nendian: little\nencoding: raw\n\n" +
                     bytesOf(shorts, std::endian::little));
  const Result<PointScalars> pressure = readPointScalars(shortFile, {});
  ASSERT_TRUE(pressure.ok()) << pressure.error().message;
  EXPECT_EQ(pressure->dims, Dims(3, 2, 2));
  EXPECT_EQ(pressure->geometry.spacing, glm::dvec3(0.5, 0.25, 2.0));
  EXPECT_EQ(pressure->geometry.origin, glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(pressure->name, "pressure");
  EXPECT_EQ(pressure->unit, "Pa");
  expectSameValues(pressure->values, asFloats(shorts));

  // Big-endian gzip doubles, NaN kept, the unit unquoted and the field name without its space.
  const std::vector<double> doubles = {0.1, std::nan(""), -0.0, 1e300, -2.5, 1.0 / 3.0};
  const fs::path doubleFile =
      writeBytes("temperature.nrrd",
                 "NRRD0005\ntype: double\ndimension: 3\nsizes: 3 2 1\nsampleunits: deg C\n"
                 "endian: big\nencoding: gzip\n\n" +
                     deflateBytes(bytesOf(doubles, std::endian::big), 15 + 16));
  const Result<PointScalars> temperature = readPointScalars(doubleFile, {});
  ASSERT_TRUE(temperature.ok()) << temperature.error().message;
  EXPECT_EQ(temperature->name, "temperature");
  EXPECT_EQ(temperature->unit, "deg C");
  expectSameValues(temperature->values,
                   {0.1f, kNaN, -0.0f, kInf, -2.5f, static_cast<float>(1.0 / 3.0)});

  // A 2D grid: one layer along z. No units: an empty unit.
  const std::vector<std::uint8_t> bytes = {0, 1, 2, 3, 250, 255};
  const fs::path planar = writeBytes("plane.nrrd",
                                     "NRRD0004\ntype: uchar\ndimension: 2\nsizes: 3 2\n"
                                     "encoding: raw\n\n" +
                                         bytesOf(bytes, std::endian::little));
  const Result<PointScalars> plane = readPointScalarsNrrd(planar);
  ASSERT_TRUE(plane.ok()) << plane.error().message;
  EXPECT_EQ(plane->dims, Dims(3, 2, 1));
  EXPECT_EQ(plane->unit, "");
  expectSameValues(plane->values, asFloats(bytes));

  expectInputError(readPointScalars(shortFile, "pressure"), shortFile,
                   "applies only to .vtk and .vti files");
  const fs::path vectors =
      writeBytes("vectors.nrrd",
                 "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 3 2 2\nendian: little\n"
                 "sample units: \"m/s\"\nencoding: raw\n\n" +
                     bytesOf(asFloats(ramp(36, 1, 1)), std::endian::little));
  expectInputError(readPointScalars(vectors, {}), vectors, "dimension: expected 3");

  // The vector reader reports the unit of its vectors.
  FieldReadInfo info;
  ASSERT_TRUE(readVectorField(vectors, {}, &info).ok());
  EXPECT_EQ(info.unit, "m/s");
  EXPECT_TRUE(info.scalarNames.empty());
  EXPECT_EQ(info.maskedVectors, 0u);

  const fs::path raw = writeBytes("scalars.raw", std::string(12, '\0'));
  expectInputError(readPointScalars(raw, {}), raw, "cannot read scalars from a file with");
}

}  // namespace
}  // namespace lic3d
