// SPDX-License-Identifier: BSD-3-Clause
// VTK XML ImageData: files in every encoding VTK writes (made here), cell data, array choice,
// malformed input, and the LIC and RGBA writers read back.

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/field_io.h"
#include "io/vti.h"
#include "test_support.h"
#include "vti_test_files.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

using test::readWhole;
using namespace test;  // the VTI files of vti_test_files.h

class VtiTest : public test::TempFolderTest {};

void expectRamp(const VectorField& field, double start, double step) {
  ASSERT_EQ(field.vectors.size() * 3, 36u);
  for (std::size_t i = 0; i < 36; ++i)
    ASSERT_EQ(field.vectors[i / 3][static_cast<glm::length_t>(i % 3)],
              static_cast<float>(start + step * static_cast<double>(i)))
        << i;
}

TEST_F(VtiTest, ReadsEveryEncoding) {
  for (const std::string type : {"Float32", "Float64"}) {
    for (const Encoding& encoding : everyEncoding()) {
      SCOPED_TRACE(type + " " + encoding.label());
      const fs::path file = writeBytes("field.vti", makeVti(testImage(type), encoding));
      FieldReadInfo info;
      const Result<VectorField> field = readVectorFieldVti(file, {}, &info);
      ASSERT_TRUE(field.ok()) << field.error().message;
      EXPECT_EQ(field->dims, Dims(3, 2, 2));
      EXPECT_EQ(field->geometry.origin, glm::dvec3(1.0, 2.0, 3.0));
      EXPECT_EQ(field->geometry.spacing, glm::dvec3(0.5, 0.25, 2.0));
      expectRamp(*field, -3.25, 0.5);
      EXPECT_EQ(info.nonFiniteVectors, 0u);
      EXPECT_EQ(info.arrayName, "velocity");
      EXPECT_EQ(info.arrayNames, std::vector<std::string>{"velocity"});
    }
  }
}

TEST_F(VtiTest, ReadsIntegerVectorsAndLargeCompressedArrays) {
  Image image;
  image.wholeExtent = "0 39 0 29 0 19";
  image.arrays.push_back({"v", "Float32", 3, false, ramp(3 * 40 * 30 * 20, 0.5, 0.25)});
  Encoding encoding;
  encoding.format = "appended";
  encoding.zlib = true;
  encoding.blockSize = 32768;
  const fs::path file = writeBytes("large.vti", makeVti(image, encoding));
  const Result<VectorField> field = readVectorField(file);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(40, 30, 20));
  EXPECT_EQ(field->vectors.back().z, static_cast<float>(0.5 + 0.25 * (3 * 24000 - 1)));

  image = Image{};
  image.arrays.push_back({"ints", "Int16", 3, false, ramp(36, -18, 1)});
  encoding.blockSize = 5;
  const fs::path ints = writeBytes("ints.vti", makeVti(image, encoding));
  const Result<VectorField> intField = readVectorFieldVti(ints);
  ASSERT_TRUE(intField.ok()) << intField.error().message;
  expectRamp(*intField, -18, 1);
}

// Files larger than the reader's head (64 KiB) with appended data are streamed from the file
// into the arrays rather than read whole: every encoding of it reads the same, a second array's
// offset is honoured, and a file cut short is refused without reading past its end.
// zlib blocks whose table promises a large array cost memory only for the blocks that inflate
// (hardening, class 3): 23,438 blocks of 36 corrupt bytes may claim 768 MB by the deflate ratio;
// the reader zero-filled the array before inflating the first and peaked at ~770 MiB.
TEST_F(VtiTest, BlocksPromisingMoreThanTheyHoldCostOnlyWhatInflates) {
  constexpr std::uint64_t kBytes = std::uint64_t{400} * 400 * 400 * 3 * 4;
  constexpr std::uint64_t kBlock = 32768;
  const std::uint64_t blocks = (kBytes + kBlock - 1) / kBlock;
  std::vector<std::uint64_t> table{blocks, kBlock, kBytes % kBlock};
  table.insert(table.end(), blocks, 36);
  Encoding encoding;
  std::string data = headerNumbers(table, encoding);
  std::mt19937 random(3);
  for (std::uint64_t i = 0; i < blocks * 36; ++i) data += static_cast<char>(random());
  const std::string extent = "0 399 0 399 0 399";
  const fs::path file = writeBytes(
      "bomb.vti",
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
      "byte_order=\"LittleEndian\" header_type=\"UInt32\" compressor=\"vtkZLibDataCompressor\">"
      "<ImageData WholeExtent=\"" +
          extent +
          "\" Origin=\"0 0 0\" Spacing=\"1 1 1\"><Piece "
          "Extent=\"" +
          extent +
          "\"><PointData><DataArray type=\"Float32\" Name=\"v\" "
          "NumberOfComponents=\"3\" format=\"appended\" offset=\"0\"/></PointData></Piece>"
          "</ImageData><AppendedData encoding=\"raw\">_" +
          data + "</AppendedData></VTKFile>\n");
  const double grewMiB = test::peakMemoryGrowthMiB([&] {
    const Result<VectorField> field = readVectorField(file);
    if (field.ok() || field.error().message.find("block 0") == std::string::npos) ::_exit(1);
  });
  ASSERT_GE(grewMiB, 0.0) << "the read succeeded or failed for another reason";
  EXPECT_LT(grewMiB, 100.0);
}

TEST_F(VtiTest, LargeAppendedDataIsStreamedAndReadsAsTheWholeFile) {
  Image image;
  image.wholeExtent = "0 63 0 47 0 23";  // 73,728 points: 864 KiB of Float32 vectors
  const std::size_t points = 64 * 48 * 24;
  image.arrays.push_back({"density", "Float64", 1, false, ramp(points, 0.0, 1.0)});
  image.arrays.push_back({"velocity", "Float32", 3, false, ramp(3 * points, -7.5, 0.125)});
  for (const bool zlib : {false, true})
    for (const bool bigEndian : {false, true})
      for (const bool appendedBase64 : {false, true}) {
        Encoding encoding;
        encoding.format = "appended";
        encoding.zlib = zlib;
        encoding.bigEndian = bigEndian;
        encoding.appendedBase64 = appendedBase64;
        encoding.header64 = true;
        encoding.blockSize = 20000;  // not a multiple of 12: values span blocks
        SCOPED_TRACE(encoding.label());
        const std::string bytes = makeVti(image, encoding);
        ASSERT_GT(bytes.size(), std::size_t{64} << 10);
        const fs::path file = writeBytes("streamed.vti", bytes);
        const Result<VectorField> field = readVectorFieldVti(file, "velocity");
        ASSERT_TRUE(field.ok()) << field.error().message;
        ASSERT_EQ(field->vectors.size(), points);
        for (std::size_t i = 0; i < 3 * points; i += 997)
          ASSERT_EQ(field->vectors[i / 3][static_cast<glm::length_t>(i % 3)],
                    static_cast<float>(-7.5 + 0.125 * static_cast<double>(i)))
              << i;
        EXPECT_EQ(field->vectors.back().z,
                  static_cast<float>(-7.5 + 0.125 * static_cast<double>(3 * points - 1)));
        const Result<PointScalars> density = readPointScalarsVti(file, "density");
        ASSERT_TRUE(density.ok()) << density.error().message;
        EXPECT_EQ(density->values[points - 1], static_cast<float>(points - 1));

        // Cut inside the vectors' data: an error naming the file, no crash.
        const fs::path cut = writeBytes("cut.vti", bytes.substr(0, bytes.size() - 40000));
        const Result<VectorField> truncated = readVectorFieldVti(cut, "velocity");
        ASSERT_FALSE(truncated.ok());
        EXPECT_NE(truncated.error().message.find("cut.vti"), std::string::npos)
            << truncated.error().message;
      }
}

TEST_F(VtiTest, WholeExtentOffsetMovesTheOrigin) {
  Image image = testImage();
  image.wholeExtent = "-2 0 4 5 10 11";
  const fs::path file = writeBytes("offset.vti", makeVti(image, Encoding{}));
  const Result<VectorField> field = readVectorFieldVti(file);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->geometry.origin, glm::dvec3(1.0 - 1.0, 2.0 + 1.0, 3.0 + 20.0));
}

TEST_F(VtiTest, CellDataBecomesAFieldAtTheCellCentres) {
  // 4x3x2 points hold 3x2x1 cells.
  Image image;
  image.wholeExtent = "0 3 0 2 0 1";
  image.arrays.push_back({"cells", "Float32", 3, true, ramp(18, 1, 1)});
  for (const Encoding& encoding : everyEncoding()) {
    SCOPED_TRACE(encoding.label());
    const fs::path file = writeBytes("cells.vti", makeVti(image, encoding));
    const Result<VectorField> field = readVectorFieldVti(file);
    ASSERT_TRUE(field.ok()) << field.error().message;
    EXPECT_EQ(field->dims, Dims(3, 2, 1));
    EXPECT_EQ(field->geometry.origin, glm::dvec3(1.25, 2.125, 4.0));
    EXPECT_EQ(field->geometry.spacing, glm::dvec3(0.5, 0.25, 2.0));
    EXPECT_EQ(field->at(2, 1, 0), glm::vec3(16.0f, 17.0f, 18.0f));
  }
}

TEST_F(VtiTest, ChoosesArraysByNameAndListsThemWhenMissing) {
  Image image;
  image.pointAttributes = "Vectors=\"b\"";
  image.arrays.push_back({"scalar", "Float32", 1, false, ramp(12, 0, 1)});
  image.arrays.push_back({"a", "Float32", 3, false, ramp(36, 1, 0)});
  image.arrays.push_back({"b", "Float32", 3, false, ramp(36, 2, 0)});
  image.arrays.push_back({"b", "Float32", 3, true, ramp(6, 5, 0)});
  image.arrays.push_back({"c", "Float64", 3, true, ramp(6, 3, 0)});
  for (const Encoding& encoding : everyEncoding()) {
    SCOPED_TRACE(encoding.label());
    const fs::path file = writeBytes("arrays.vti", makeVti(image, encoding));
    FieldReadInfo info;
    // The active Vectors attribute is the default.
    Result<VectorField> field = readVectorFieldVti(file, {}, &info);
    ASSERT_TRUE(field.ok()) << field.error().message;
    EXPECT_EQ(field->vectors[0], glm::vec3(2.0f));
    EXPECT_EQ(info.arrayName, "b");
    EXPECT_EQ(info.arrayNames, (std::vector<std::string>{"a", "b", "b", "c"}));
    field = readVectorField(file, "a");
    ASSERT_TRUE(field.ok()) << field.error().message;
    EXPECT_EQ(field->vectors[11], glm::vec3(1.0f));
    field = readVectorFieldVti(file, "c");
    ASSERT_TRUE(field.ok()) << field.error().message;
    EXPECT_EQ(field->dims, Dims(2, 1, 1));
    EXPECT_EQ(field->vectors[1], glm::vec3(3.0f));
    expectInputError(readVectorField(file, "d"), file,
                     "no 3-component DataArray named 'd'; found: 'a', 'b', 'b' (cell data), "
                     "'c' (cell data)");
    expectInputError(readVectorFieldVti(file, "scalar"), file,
                     "DataArray 'scalar' has 1 components, expected 3");
  }
}

TEST_F(VtiTest, NonFiniteVectorsBecomeZeroAndAllZeroIsAnError) {
  Image image;
  std::vector<double> values = ramp(36, 1, 1);
  values[4] = std::numeric_limits<double>::quiet_NaN();
  values[9] = -std::numeric_limits<double>::infinity();
  values[35] = 1e300;  // beyond float
  image.arrays.push_back({"v", "Float64", 3, false, values});
  for (const Encoding& encoding : everyEncoding()) {
    SCOPED_TRACE(encoding.label());
    const fs::path file = writeBytes("nan.vti", makeVti(image, encoding));
    FieldReadInfo info;
    const Result<VectorField> field = readVectorFieldVti(file, {}, &info);
    ASSERT_TRUE(field.ok()) << field.error().message;
    EXPECT_EQ(info.nonFiniteVectors, 3u);
    EXPECT_EQ(field->vectors[1], glm::vec3(0.0f));
    EXPECT_EQ(field->vectors[3], glm::vec3(0.0f));
    EXPECT_EQ(field->vectors[11], glm::vec3(0.0f));
    EXPECT_EQ(field->vectors[2], glm::vec3(7.0f, 8.0f, 9.0f));
  }
  image.arrays[0].values.assign(36, 0.0);
  image.arrays[0].values[0] = std::numeric_limits<double>::quiet_NaN();
  const fs::path file = writeBytes("zero.vti", makeVti(image, Encoding{}));
  expectInputError(readVectorFieldVti(file), file,
                   "every vector of the field is zero (1 of the 12 were NaN, infinite or beyond a "
                   "float's range of 3.4e38)");
}

// --- Malformed files ----------------------------------------------------------------------------

struct MalformedCase {
  const char* label;
  std::string content;
  const char* fragment;
};

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

TEST_F(VtiTest, MalformedFilesAreInputErrorsNamingFileAndProblem) {
  Encoding binary;
  binary.format = "binary";
  Encoding zlib = binary;
  zlib.zlib = true;
  Encoding appended;
  appended.format = "appended";
  Encoding appendedZlib = appended;
  appendedZlib.zlib = true;
  const std::string ascii = makeVti(testImage(), Encoding{});
  const std::string plain = makeVti(testImage(), binary);
  const std::string compressed = makeVti(testImage(), zlib);
  const std::string raw = makeVti(testImage(), appended);
  const std::string rawZlib = makeVti(testImage(), appendedZlib);
  // The velocity block of the appended raw file: after density's 4 + 96 bytes.
  const std::size_t velocity = raw.find("\n   _") + 5 + 100;
  const std::size_t rawZlibData = rawZlib.find("\n   _") + 5;

  const auto withVelocityHeader = [&](std::uint32_t size) {
    std::string file = raw;
    std::memcpy(file.data() + velocity, &size, 4);
    return file;
  };
  // The zlib header of "density" (the first array) in the appended zlib file, replaced.
  const auto withZlibHeader = [&](std::vector<std::uint32_t> numbers) {
    std::string file = rawZlib;
    std::memcpy(file.data() + rawZlibData, numbers.data(), 4 * numbers.size());
    return file;
  };
  const std::string velocityBase64 =
      base64(headerNumbers({144}, binary)) + base64(valueBytes(testImage().arrays[1], false));

  const MalformedCase cases[] = {
      {"empty", "", "empty file"},
      {"legacy vtk", "# vtk DataFile Version 3.0\n", "not an XML file"},
      {"bad xml", "<VTKFile type=\"ImageData\"><ImageData>", "invalid XML at byte"},
      {"mismatched tags", "<VTKFile></ImageData>", "invalid XML"},
      {"not vtk", "<svg/>", "root element is not VTKFile"},
      {"polydata", replaced(ascii, "type=\"ImageData\"", "type=\"PolyData\""),
       "VTKFile type 'PolyData' is not supported (expected ImageData)"},
      {"byte order", replaced(ascii, "LittleEndian", "MiddleEndian"),
       "byte_order: expected LittleEndian or BigEndian"},
      {"header type", replaced(ascii, "header_type=\"UInt32\"", "header_type=\"UInt16\""),
       "header_type: expected UInt32 or UInt64"},
      {"lz4", replaced(compressed, "vtkZLibDataCompressor", "vtkLZ4DataCompressor"),
       "compressor 'vtkLZ4DataCompressor' is not supported"},
      {"no image data", "<VTKFile type=\"ImageData\"></VTKFile>", "no ImageData element"},
      {"no extent", replaced(ascii, "WholeExtent=", "Whole="), "ImageData: missing WholeExtent"},
      {"reversed extent", replaced(ascii, "WholeExtent=\"0 2", "WholeExtent=\"2 0"),
       "WholeExtent: expected 6 whole numbers"},
      {"short extent", replaced(ascii, "WholeExtent=\"0 2 0 1 0 1", "WholeExtent=\"0 2 0 1 0"),
       "WholeExtent: expected 6 whole numbers"},
      {"huge extent",
       replaced(ascii, "WholeExtent=\"0 2 0 1 0 1", "WholeExtent=\"0 16383 0 16383 0 8"),
       "more than the limit"},
      {"long axis", replaced(ascii, "WholeExtent=\"0 2", "WholeExtent=\"0 16384"),
       "outside [1, 16384]"},
      {"enormous extent",
       replaced(ascii, "WholeExtent=\"0 2", "WholeExtent=\"0 99999999999999999999"),
       "WholeExtent: expected 6 whole numbers"},
      {"zero spacing", replaced(ascii, "Spacing=\"0.5", "Spacing=\"0"),
       "ImageData Spacing: expected 3 positive numbers"},
      {"nan origin", replaced(ascii, "Origin=\"1", "Origin=\"nan"),
       "ImageData Origin: expected 3 finite numbers"},
      {"two pieces",
       replaced(ascii, "  </ImageData>", "<Piece Extent=\"0 2 0 1 0 1\"/></ImageData>"),
       "ImageData holds 2 Piece elements"},
      {"piece extent", replaced(ascii, "<Piece Extent=\"0 2", "<Piece Extent=\"0 1"),
       "differs from WholeExtent"},
      {"no vectors", replaced(ascii, "NumberOfComponents=\"3\"", "NumberOfComponents=\"4\""),
       "no 3-component DataArray in PointData or CellData"},
      {"2D vectors on a 3D grid",
       replaced(ascii, "NumberOfComponents=\"3\"", "NumberOfComponents=\"2\""),
       "they need a 2D grid"},
      {"zero components", replaced(ascii, "NumberOfComponents=\"3\"", "NumberOfComponents=\"0\""),
       "NumberOfComponents: expected 1 to 64"},
      {"string array", replaced(ascii, "type=\"Float32\"", "type=\"String\""),
       "DataArray 'velocity': type 'String' is not supported"},
      {"tuples", replaced(ascii, "Name=\"velocity\"", "Name=\"velocity\" NumberOfTuples=\"13\""),
       "NumberOfTuples '13' does not match the 12 points"},
      {"few ascii numbers", replaced(ascii, "-3.25 ", ""), "holds 35 numbers, expected 36"},
      {"many ascii numbers", replaced(ascii, "-3.25 ", "-3.25 1 "),
       "holds more than the 36 numbers expected"},
      {"ascii word", replaced(ascii, "-3.25 ", "minus "), "expected a number, found 'minus'"},
      {"ascii too short",
       replaced(replaced(ascii, "WholeExtent=\"0 2 0 1 0 1", "WholeExtent=\"0 999 0 999 0 9"),
                "Extent=\"0 2 0 1 0 1", "Extent=\"0 999 0 999 0 9"),
       "the text holds at most"},
      {"format", replaced(ascii, "\"3\" format=\"ascii\"", "\"3\" format=\"hex\""),
       "format: expected ascii, binary or appended, found 'hex'"},
      {"bad base64", replaced(plain, velocityBase64.substr(0, 12), "AAAAA=AAAAAA"),
       "invalid base64 data"},
      {"block size",
       replaced(plain, velocityBase64.substr(0, 8),
                base64(headerNumbers({140}, binary)).substr(0, 8)),
       "the data block holds 140 bytes, expected 144 (12 tuples of 3 Float32)"},
      {"base64 cut", replaced(plain, velocityBase64, velocityBase64.substr(0, 100)), "truncated"},
      {"no appended data", replaced(raw, "<AppendedData encoding=\"raw\">", "<Other>"),
       "invalid XML"},
      {"unclosed appended tag", raw.substr(0, raw.find("<AppendedData") + 20),
       "the AppendedData tag is not closed"},
      {"no underscore", replaced(raw, "\n   _", "\n   #"),
       "AppendedData: expected '_' before the data"},
      {"appended encoding", replaced(raw, "encoding=\"raw\"", "encoding=\"hex\""),
       "AppendedData encoding: expected raw or base64"},
      {"offset beyond", replaced(raw, "offset=\"100\"", "offset=\"100000\""),
       "offset 100000 is beyond the"},
      {"offset text", replaced(raw, "offset=\"100\"", "offset=\"-1\""),
       "an appended array needs a whole-number offset"},
      {"appended missing",
       replaced(ascii, "Name=\"velocity\" NumberOfComponents=\"3\" format=\"ascii\">",
                "Name=\"velocity\" NumberOfComponents=\"3\" format=\"appended\" offset=\"0\">"),
       "format is appended, but the file has no AppendedData"},
      {"appended header", withVelocityHeader(0xfffffff0u), "the data block holds 4294967280 bytes"},
      {"appended truncated", raw.substr(0, velocity + 100), "truncated"},
      {"appended header cut", raw.substr(0, velocity + 2), "the data ends inside its header"},
      {"zlib zero blocks", withZlibHeader({0, 32768, 96}), "compression header"},
      {"zlib last larger", withZlibHeader({1, 32, 96}), "compression header"},
      {"zlib many blocks", withZlibHeader({0x7fffffff, 1, 0}),
       "2147483647 blocks, more than the data can hold"},
      {"zlib wrong total", withZlibHeader({1, 32768, 95}), "the compressed blocks hold 1 x 32768"},
      {"zlib huge block", withZlibHeader({1, 32768, 96, 0x7fffffff}), "truncated"},
      {"zlib ratio", withZlibHeader({1, 96, 0, 0}), "0 compressed bytes cannot inflate to 96"},
      {"zlib corrupt",
       [&] {
         std::string file = rawZlib;
         for (std::size_t i = rawZlibData + 16 + 2; i < rawZlibData + 16 + 10; ++i) file[i] ^= 0x55;
         return file;
       }(),
       "DataArray 'density' block 0: compressed data"},
  };
  for (const MalformedCase& c : cases) {
    SCOPED_TRACE(c.label);
    const fs::path file = writeBytes("bad field.vti", c.content);
    const Result<VectorField> field = readVectorFieldVti(file);
    if (std::string(c.label).starts_with("zlib")) {
      // The zlib cases corrupt "density", which the scalar reader reads.
      expectInputError(readScalarVti(file), file, c.fragment);
    } else {
      expectInputError(field, file, c.fragment);
    }
  }
}

TEST_F(VtiTest, CorruptedFilesNeverCrashTheReader) {
  // Random byte flips and cuts of files in several encodings give a field or an InvalidInput
  // error; under the sanitizers this also checks every read stays in bounds.
  std::vector<std::string> originals;
  for (const Encoding& encoding : everyEncoding())
    originals.push_back(makeVti(testImage(), encoding));
  std::mt19937 random(7);
  for (const std::string& original : originals) {
    for (int trial = 0; trial < 60; ++trial) {
      std::string mutated = original;
      const int flips = 1 + static_cast<int>(random() % 4);
      for (int f = 0; f < flips; ++f) {
        const std::size_t at = random() % mutated.size();
        mutated[at] = random() % 2 ? static_cast<char>(random() % 256)
                                   : "0123456789 \"<>/=_AZaz+"[random() % 23];
      }
      if (trial % 5 == 0) mutated.resize(random() % mutated.size());
      const fs::path file = writeBytes("mutated.vti", mutated);
      for (const Result<VectorField>& read :
           {readVectorFieldVti(file), readVectorFieldVti(file, "x")}) {
        if (!read.ok()) {
          EXPECT_EQ(read.error().kind, ErrorKind::InvalidInput) << read.error().message;
        } else {
          EXPECT_EQ(read->vectors.size(), voxelCount(read->dims));
        }
      }
      const Result<ScalarVolume> scalars = readScalarVti(file);
      if (!scalars.ok()) {
        EXPECT_EQ(scalars.error().kind, ErrorKind::InvalidInput) << scalars.error().message;
      }
    }
  }
}

// --- Writers ------------------------------------------------------------------------------------

TEST_F(VtiTest, ScalarVolumeRoundTripKeepsValuesNaNAndGeometry) {
  ScalarVolume volume;
  volume.dims = {5, 4, 3};
  volume.geometry = {{0.1, 1.0 / 3.0, 2.0}, {-1.5, 2.25, 1e-3}};
  for (int i = 0; i < 60; ++i) volume.values.push_back(std::sin(static_cast<float>(i)));
  volume.values[7] = std::numeric_limits<float>::quiet_NaN();
  const fs::path file = path("lic.vti");
  ASSERT_TRUE(writeScalarVti(file, volume).ok());
  const std::string bytes = readWhole(file);
  for (const char* text : {"<VTKFile type=\"ImageData\"", "header_type=\"UInt64\"",
                           "WholeExtent=\"0 4 0 3 0 2\"", "Spacing=\"0.1 0.3333333333333333 2\"",
                           "<PointData Scalars=\"LIC\">", "type=\"Float32\" Name=\"LIC\"",
                           "format=\"appended\" offset=\"0\"", "<AppendedData encoding=\"raw\">"})
    EXPECT_NE(bytes.find(text), std::string::npos) << text;
  const Result<ScalarVolume> read = readScalarVti(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->dims, volume.dims);
  EXPECT_EQ(read->geometry, volume.geometry);
  ASSERT_EQ(read->values.size(), volume.values.size());
  for (std::size_t i = 0; i < volume.values.size(); ++i) {
    if (i == 7) {
      EXPECT_TRUE(std::isnan(read->values[i]));
    } else {
      EXPECT_EQ(read->values[i], volume.values[i]) << i;
    }
  }
  // Any name, escaped for XML, reads back.
  ASSERT_TRUE(writeScalarVti(path("named.vti"), volume, "LIC <\"&'> value").ok());
  EXPECT_NE(readWhole(path("named.vti")).find("Name=\"LIC &lt;&quot;&amp;&apos;&gt; value\""),
            std::string::npos);
  ASSERT_TRUE(readScalarVti(path("named.vti")).ok());
}

TEST_F(VtiTest, RgbaVolumeRoundTrip) {
  RgbaVolume volume;
  volume.dims = {3, 2, 4};
  volume.geometry = {{2.0, 0.5, 0.25}, {10.0, -20.0, 0.5}};
  for (std::size_t i = 0; i < 96; ++i) volume.rgba.push_back(static_cast<std::uint8_t>(i * 7 + 3));
  const fs::path file = path("colour.vti");
  ASSERT_TRUE(writeRgbaVti(file, volume).ok());
  EXPECT_NE(readWhole(file).find("type=\"UInt8\" Name=\"rgba\" NumberOfComponents=\"4\""),
            std::string::npos);
  const Result<RgbaVolume> read = readRgbaVti(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->dims, volume.dims);
  EXPECT_EQ(read->geometry, volume.geometry);
  EXPECT_EQ(read->rgba, volume.rgba);
  // An RGBA volume is not a scalar or vector volume.
  expectInputError(readScalarVti(file), file, "no 1-component DataArray");
  expectInputError(readVectorFieldVti(file), file, "no 3-component DataArray");
}

TEST_F(VtiTest, WritersRefuseBadVolumesAndLeaveNoFile) {
  ScalarVolume volume;
  volume.dims = {2, 2, 2};
  volume.values.assign(7, 0.5f);
  const fs::path file = path("bad.vti");
  expectInputError(writeScalarVti(file, volume), file, "needs 8");
  volume.values.assign(8, 0.5f);
  expectInputError(writeScalarVti(file, volume, ""), file, "the array name is empty");
  expectInputError(writeScalarVti(file, volume, "tab\tname"), file, "control character");
  volume.geometry.spacing.y = 0.0;
  expectInputError(writeScalarVti(file, volume), file, "spacing");
  RgbaVolume rgba;
  rgba.dims = {0, 1, 1};
  expectInputError(writeRgbaVti(file, rgba), file, "empty");
  EXPECT_TRUE(listFolder().empty());
}

// A .pvti's pieces (what ParaView writes under MPI) make the whole field by their extents; they
// may share points, and must cover the whole extent.
TEST_F(VtiTest, PvtiAssemblesItsPiecesByTheirExtents) {
  const auto piece = [&](const std::string& name, int x0, int x1) {
    Image image;
    image.wholeExtent = std::to_string(x0) + " " + std::to_string(x1) + " 0 1 0 1";
    image.pointAttributes = "Vectors=\"v\"";
    Array v{.name = "v"};
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = x0; i <= x1; ++i)
          v.values.insert(v.values.end(), {i + 10.0 * j + 100.0 * k, 1.0, -1.0});
    image.arrays.push_back(v);
    fs::create_directories(path("p"));
    writeBytes("p/" + name, makeVti(image, Encoding{.format = "appended"}));
  };
  piece("a.vti", 0, 2);
  piece("b.vti", 2, 3);
  const auto pvti = [&](const std::string& name, const std::string& pieces) {
    return writeBytes(
        name,
        "<VTKFile type=\"PImageData\" version=\"0.1\"><PImageData WholeExtent=\"0 3 0 "
        "1 0 1\" GhostLevel=\"0\" Origin=\"1 2 3\" Spacing=\"0.5 0.25 2\"><PPointData "
        "Vectors=\"v\"><PDataArray type=\"Float32\" Name=\"v\" "
        "NumberOfComponents=\"3\"/></PPointData>" +
            pieces + "</PImageData></VTKFile>");
  };
  const std::string a = "<Piece Extent=\"0 2 0 1 0 1\" Source=\"p/a.vti\"/>";
  const std::string b = "<Piece Extent=\"2 3 0 1 0 1\" Source=\"p/b.vti\"/>";
  FieldReadInfo info;
  const Result<VectorField> field = readVectorField(pvti("whole.pvti", a + b), "", &info);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(4, 2, 2));
  EXPECT_EQ(field->geometry.spacing, glm::dvec3(0.5, 0.25, 2.0));
  EXPECT_EQ(field->geometry.origin, glm::dvec3(1.0, 2.0, 3.0));
  EXPECT_EQ(info.arrayName, "v");
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i < 4; ++i)
        EXPECT_EQ(field->at(i, j, k),
                  glm::vec3(static_cast<float>(i + 10 * j + 100 * k), 1.0f, -1.0f))
            << i << " " << j << " " << k;

  // A missing piece, a piece whose file does not match its extent, a piece outside the whole.
  const Result<VectorField> missing = readVectorField(pvti("missing.pvti", a));
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("without data"), std::string::npos)
      << missing.error().message;
  const Result<VectorField> wrong =
      readVectorField(pvti("wrong.pvti", a + "<Piece Extent=\"1 3 0 1 0 1\" Source=\"p/b.vti\"/>"));
  ASSERT_FALSE(wrong.ok());
  EXPECT_NE(wrong.error().message.find("b.vti: holds a grid of 2x2x2"), std::string::npos)
      << wrong.error().message;
  const Result<VectorField> outside = readVectorField(
      pvti("outside.pvti", a + "<Piece Extent=\"2 4 0 1 0 1\" Source=\"p/b.vti\"/>"));
  ASSERT_FALSE(outside.ok());
  EXPECT_EQ(outside.error().kind, ErrorKind::InvalidInput);
}

// What a .pvti may not make the reader do: take an extent beyond int as a small one, allocate the
// grid of a whole extent its pieces do not fill, let the last of two disagreeing pieces win, or
// ignore a piece placed elsewhere than the whole's Origin and Spacing say.
TEST_F(VtiTest, PvtiRefusesExtentsAndPiecesThatDisagree) {
  const auto piece = [&](const std::string& name, int x0, int x1, double bump,
                         const std::string& origin = "1 2 3",
                         const std::string& spacing = "0.5 0.25 2") {
    Image image;
    image.wholeExtent = std::to_string(x0) + " " + std::to_string(x1) + " 0 1 0 1";
    image.origin = origin;
    image.spacing = spacing;
    Array v{.name = "v"};
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 2; ++j)
        for (int i = x0; i <= x1; ++i) v.values.insert(v.values.end(), {i + bump, 1.0, -1.0});
    image.arrays.push_back(v);
    fs::create_directories(path("p"));
    writeBytes("p/" + name, makeVti(image, Encoding{.format = "appended"}));
  };
  const auto pvti = [&](const std::string& name, const std::string& whole,
                        const std::string& pieces) {
    return writeBytes(
        name, "<VTKFile type=\"PImageData\" version=\"0.1\"><PImageData WholeExtent=\"" + whole +
                  "\" Origin=\"1 2 3\" Spacing=\"0.5 0.25 2\">" + pieces +
                  "</PImageData></VTKFile>");
  };
  const auto refused = [&](const fs::path& file, const fs::path& named, const std::string& text) {
    const Result<VectorField> field = readVectorField(file);
    ASSERT_FALSE(field.ok()) << file;
    EXPECT_EQ(field.error().kind, ErrorKind::InvalidInput) << field.error().message;
    EXPECT_NE(field.error().message.find(named.string()), std::string::npos)
        << field.error().message;
    EXPECT_NE(field.error().message.find(text), std::string::npos) << field.error().message;
  };
  piece("a.vti", 0, 2, 0.0);
  piece("b.vti", 2, 3, 0.0);
  piece("b_differs.vti", 2, 3, 0.5);
  piece("b_spacing.vti", 2, 3, 0.0, "1 2 3", "1 1 1");
  piece("b_origin.vti", 2, 3, 0.0, "5 2 3");
  const std::string a = "<Piece Extent=\"0 2 0 1 0 1\" Source=\"p/a.vti\"/>";
  const auto b = [](const std::string& source) {
    return "<Piece Extent=\"2 3 0 1 0 1\" Source=\"p/" + source + "\"/>";
  };
  ASSERT_TRUE(readVectorField(pvti("good.pvti", "0 3 0 1 0 1", a + b("b.vti"))).ok());
  // 4294967311 is 15 modulo 2^32: read as 64 bits, it is refused, by its file and attribute.
  refused(pvti("wraps.pvti", "0 4294967311 0 0 0 0", a), path("wraps.pvti"),
          "PImageData WholeExtent '0 4294967311 0 0 0 0'");
  refused(pvti("piece_wraps.pvti", "0 3 0 1 0 1", "<Piece Extent=\"0 4294967298 0 1 0 1\"/>"),
          path("piece_wraps.pvti"), "Piece Extent '0 4294967298 0 1 0 1' leaves the WholeExtent");
  // A whole extent its pieces do not fill is refused before any piece is read (the piece's file
  // does not exist) or the grid of 2^26 points allocated.
  refused(pvti("claims.pvti", "0 1023 0 1023 0 63",
               "<Piece Extent=\"0 1 0 0 0 0\" Source=\"p/none.vti\"/>"),
          path("claims.pvti"), "without data");
  refused(pvti("gap.pvti", "0 3 0 1 0 1",
               "<Piece Extent=\"0 1 0 1 0 1\" Source=\"p/none.vti\"/>"
               "<Piece Extent=\"3 3 0 1 0 1\" Source=\"p/none.vti\"/>"
               "<Piece Extent=\"2 2 0 0 0 1\" Source=\"p/none.vti\"/>"
               "<Piece Extent=\"2 2 1 1 0 0\" Source=\"p/none.vti\"/>"),
          path("gap.pvti"), "without data");
  // Pieces share the points of x = 2: b_differs holds other vectors there.
  refused(pvti("differs.pvti", "0 3 0 1 0 1", a + b("b_differs.vti")), path("p/b_differs.vti"),
          "overlaps an earlier piece at point (2, 0, 0)");
  refused(pvti("spacing.pvti", "0 3 0 1 0 1", a + b("b_spacing.vti")), path("p/b_spacing.vti"),
          "Spacing");
  refused(pvti("origin.pvti", "0 3 0 1 0 1", a + b("b_origin.vti")), path("p/b_origin.vti"),
          "Origin");
  refused(pvti("origin_first.pvti", "0 3 0 1 0 1",
               "<Piece Extent=\"2 3 0 1 0 1\" Source=\"p/b_origin.vti\"/>" + a),
          path("p/b_origin.vti"), "Origin");
}

}  // namespace
}  // namespace lic3d
