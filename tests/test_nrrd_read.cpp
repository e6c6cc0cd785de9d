// SPDX-License-Identifier: BSD-3-Clause
// What the NRRD readers accept (every encoding, byte order, type spelling, header detail and
// detached data file) and how they refuse the rest: with an InvalidInput naming file and field.

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/field_io.h"
#include "io/file_util.h"
#include "io/nrrd.h"
#include "nrrd_test_support.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

using test::bytesOf;
using test::expectInputError;
using test::expectSameField;
using test::makeField;
using test::NrrdTest;
using test::readWhole;

// As teem writes gzip data.
std::string gzipCompress(const std::string& data) { return test::deflateBytes(data, 15 + 16); }

// The components of a field in file order, for hand-made payloads.
std::vector<float> componentsOf(const VectorField& field) {
  std::vector<float> values;
  for (const glm::vec3& v : field.vectors) values.insert(values.end(), {v.x, v.y, v.z});
  return values;
}

// --- Encodings, byte orders, types ---------------------------------------------------------------

TEST_F(NrrdTest, ReadsGzipVectorField) {
  const VectorField field = makeField({6, 5, 4}, {{0.5, 0.5, 1.0}, {1.0, 2.0, 3.0}});
  const std::string payload = bytesOf(componentsOf(field), std::endian::little);
  for (const char* encoding : {"gzip", "gz", "GZIP"}) {
    const fs::path file =
        writeBytes("field.nrrd", std::string("NRRD0005\ntype: float\ndimension: 4\nsizes: 3 6 5 4\n"
                                             "spacings: nan 0.5 0.5 1\nspace origin: (1,2,3)\n"
                                             "endian: little\nencoding: ") +
                                     encoding + "\n\n" + gzipCompress(payload));
    const Result<VectorField> read = readVectorFieldNrrd(file);
    ASSERT_TRUE(read.ok()) << encoding << ": " << read.error().message;
    expectSameField(*read, field);
  }
}

TEST_F(NrrdTest, ReadsGzipNoiseAndIgnoresBytesAfterTheStream) {
  std::vector<std::uint8_t> values(40 * 30 * 20);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = static_cast<std::uint8_t>(i % 7 * 30);
  const std::string payload(values.begin(), values.end());
  const fs::path file = writeBytes("noise.nrrd",
                                   "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 40 30 20\n"
                                   "encoding: gzip\n\n" +
                                       gzipCompress(payload) + "trailing garbage");
  const Result<NoiseVolume> read = readNoiseNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->type, NoiseType::UInt8);
  EXPECT_EQ(read->bytes, values);
}

// A small gzip file whose header promises a large grid costs memory only for the data that
// inflates (hardening, class 3): 800 KB of deflate that ends after 800 KB may claim 768 MB by
// the deflate ratio; the reader zero-filled all of it before inflating and peaked at ~770 MiB.
TEST_F(NrrdTest, GzipPromisingMoreThanItHoldsCostsOnlyWhatInflates) {
  std::mt19937 random(7);
  std::string incompressible(800'000, '\0');
  for (char& c : incompressible) c = static_cast<char>(random());
  const fs::path file =
      writeBytes("bomb.nrrd",
                 "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 400 400 400\nendian: little\n"
                 "encoding: gzip\n\n" +
                     gzipCompress(incompressible));
  const double grewMiB = test::peakMemoryGrowthMiB([&] {
    const Result<VectorField> field = readVectorField(file);
    if (field.ok() || field.error().message.find("gzip data holds only") == std::string::npos)
      ::_exit(1);
  });
  ASSERT_GE(grewMiB, 0.0) << "the read succeeded or failed for another reason";
  // Under AddressSanitizer the child's growth also holds the allocator's shadow and quarantine
  // and the pages of the forked test process it touches: 100.9 MiB with the streamed-I/O tests
  // in the binary, about 1 MiB more than before. The fault this guards against peaked at 770.
  EXPECT_LT(grewMiB, 150.0);
}

TEST_F(NrrdTest, GzipThatDoesNotMatchTheHeaderIsAnError) {
  const std::string payload = bytesOf(std::vector<float>(12, 0.5f), std::endian::little);
  const std::string compressed = gzipCompress(payload);
  const std::string header =
      "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 1\nendian: little\n"
      "encoding: gzip\n\n";
  fs::path file = writeBytes("half.nrrd", header + compressed.substr(0, compressed.size() / 2));
  expectInputError(readVectorFieldNrrd(file), file, "truncated");
  // All data present, but the gzip trailer (CRC and length) cut off.
  file = writeBytes("notrailer.nrrd", header + compressed.substr(0, compressed.size() - 8));
  expectInputError(readVectorFieldNrrd(file), file, "truncated");
  file = writeBytes("short.nrrd", header + gzipCompress(payload.substr(0, 40)));
  expectInputError(readVectorFieldNrrd(file), file, "holds only 40 bytes");
  file = writeBytes("long.nrrd", header + gzipCompress(payload + payload));
  expectInputError(readVectorFieldNrrd(file), file, "more than the 48 bytes");
  std::string corrupt = compressed;
  for (std::size_t i = 10; i < corrupt.size(); ++i)
    corrupt[i] = static_cast<char>(corrupt[i] ^ 0x5a);
  file = writeBytes("corrupt.nrrd", header + corrupt);
  expectInputError(readVectorFieldNrrd(file), file, "gzip data");
  file = writeBytes("missing.nrrd", header);
  expectInputError(readVectorFieldNrrd(file), file, "gzip data is missing");
}

TEST_F(NrrdTest, ReadsBigEndianAndDoubleVectorFields) {
  const VectorField field = makeField({3, 2, 2}, {});
  const std::vector<float> floats = componentsOf(field);
  const std::vector<double> doubles(floats.begin(), floats.end());
  struct Case {
    const char* type;
    const char* endian;
    std::string payload;
  };
  const Case cases[] = {
      {"float", "big", bytesOf(floats, std::endian::big)},
      {"double", "little", bytesOf(doubles, std::endian::little)},
      {"double", "big", bytesOf(doubles, std::endian::big)},
  };
  for (const Case& c : cases) {
    const fs::path file =
        writeBytes("field.nrrd", std::string("NRRD0004\ntype: ") + c.type +
                                     "\ndimension: 4\nsizes: 3 3 2 2\nendian: " + c.endian +
                                     "\nencoding: raw\n\n" + c.payload);
    const Result<VectorField> read = readVectorFieldNrrd(file);
    ASSERT_TRUE(read.ok()) << c.type << " " << c.endian << ": " << read.error().message;
    expectSameField(*read, field);
  }
}

TEST_F(NrrdTest, ReadsBigEndianUShortAndFloatNoise) {
  const std::vector<std::uint16_t> shorts = {0, 1, 256, 65535, 4660, 9};
  fs::path file = writeBytes("u16.nrrd",
                             "NRRD0004\ntype: ushort\ndimension: 3\nsizes: 3 2 1\nendian: big\n"
                             "encoding: raw\n\n" +
                                 bytesOf(shorts, std::endian::big));
  Result<NoiseVolume> read = readNoiseNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->type, NoiseType::UInt16);
  for (std::size_t i = 0; i < shorts.size(); ++i) EXPECT_EQ(read->value(i), shorts[i] / 65535.0f);

  const std::vector<float> floats = {0.0f, 0.25f, 1.0f, 0.5f, 0.125f, 0.75f};
  file = writeBytes("f32.nrrd",
                    "NRRD0004\ntype: float\ndimension: 3\nsizes: 3 2 1\nendian: big\n"
                    "encoding: raw\n\n" +
                        bytesOf(floats, std::endian::big));
  read = readNoiseNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  for (std::size_t i = 0; i < floats.size(); ++i) EXPECT_EQ(read->value(i), floats[i]);
}

TEST_F(NrrdTest, AcceptsEveryNrrdSpellingOfTheNoiseTypes) {
  const std::vector<std::uint16_t> shorts = {1, 2, 3, 4};
  const std::vector<std::uint8_t> bytes = {1, 2, 3, 4};
  struct Case {
    const char* spelling;
    NoiseType type;
  };
  const Case cases[] = {
      {"uchar", NoiseType::UInt8},           {"unsigned char", NoiseType::UInt8},
      {"uint8", NoiseType::UInt8},           {"uint8_t", NoiseType::UInt8},
      {"UNSIGNED  CHAR", NoiseType::UInt8},  {"ushort", NoiseType::UInt16},
      {"unsigned short", NoiseType::UInt16}, {"unsigned short int", NoiseType::UInt16},
      {"uint16", NoiseType::UInt16},         {"uint16_t", NoiseType::UInt16},
      {"float", NoiseType::Float32},
  };
  for (const Case& c : cases) {
    std::string payload;
    if (c.type == NoiseType::UInt8) payload.assign(bytes.begin(), bytes.end());
    if (c.type == NoiseType::UInt16) payload = bytesOf(shorts, std::endian::little);
    if (c.type == NoiseType::Float32)
      payload = bytesOf(std::vector<float>{0.0f, 0.5f, 0.25f, 1.0f}, std::endian::little);
    const fs::path file =
        writeBytes("noise.nrrd", std::string("NRRD0004\ntype: ") + c.spelling +
                                     "\ndimension: 3\nsizes: 2 2 1\nendian: little\n"
                                     "encoding: raw\n\n" +
                                     payload);
    const Result<NoiseVolume> read = readNoiseNrrd(file);
    ASSERT_TRUE(read.ok()) << c.spelling << ": " << read.error().message;
    EXPECT_EQ(read->type, c.type) << c.spelling;
  }
}

TEST_F(NrrdTest, FloatNoiseOutsideTheUnitRangeIsRescaledByItsMinAndMax) {
  const std::vector<float> values = {2.0f, 4.0f, 6.0f, 10.0f};
  const fs::path file = writeBytes("noise.nrrd",
                                   "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 1\n"
                                   "endian: little\nencoding: raw\n\n" +
                                       bytesOf(values, std::endian::little));
  const Result<NoiseVolume> read = readNoiseNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->value(0), 0.0f);
  EXPECT_EQ(read->value(1), 0.25f);
  EXPECT_EQ(read->value(2), 0.5f);
  EXPECT_EQ(read->value(3), 1.0f);
}

TEST_F(NrrdTest, FloatNoiseMustBeFiniteAndRescalable) {
  const std::string header =
      "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 2 1\nendian: little\nencoding: raw\n\n";
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  fs::path file = writeBytes(
      "nan.nrrd", header + bytesOf(std::vector<float>{0.0f, nan, 0.5f, 1.0f}, std::endian::little));
  expectInputError(readNoiseNrrd(file), file, "voxel (1,0,0) is NaN or infinite");
  file = writeBytes(
      "inf.nrrd", header + bytesOf(std::vector<float>{0.0f, 0.5f, 1.0f, inf}, std::endian::little));
  expectInputError(readNoiseNrrd(file), file, "voxel (1,1,0) is NaN or infinite");
  file =
      writeBytes("const.nrrd", header + bytesOf(std::vector<float>(4, 7.0f), std::endian::little));
  expectInputError(readNoiseNrrd(file), file, "constant");
  // A constant inside [0,1] needs no rescaling and is fine.
  file =
      writeBytes("half.nrrd", header + bytesOf(std::vector<float>(4, 0.5f), std::endian::little));
  EXPECT_TRUE(readNoiseNrrd(file).ok());
}

// --- Header details -----------------------------------------------------------------------------

TEST_F(NrrdTest, AcceptsCommentsKeyValuesUnknownFieldsAndCrlf) {
  const VectorField field = makeField({2, 2, 1}, {{0.5, 0.75, 2.0}, {-1.0, 0.5, 4.0}});
  const std::string header =
      "NRRD0001\r\n# a comment\r\ncontent: test field\r\nmy key:=my: value\r\ntype: float\r\n"
      "dimension: 4\r\nspace: right-anterior-superior\r\nsizes: 3 2 2 1\r\nunknown field: "
      "whatever\r\n"
      "kinds: 3-vector domain domain domain\r\nspacings: NaN 0.5 0.75 2\r\n"
      "space origin: ( -1 , 0.5 , 4 )\r\nendian: little\r\nencoding: raw\r\n\r\n";
  const fs::path file =
      writeBytes("field.nrrd", header + bytesOf(componentsOf(field), std::endian::little) + "junk");
  const Result<VectorField> read = readVectorFieldNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  expectSameField(*read, field);
}

TEST_F(NrrdTest, SpaceDirectionsGiveTheSpacingEvenWhenRotated) {
  const VectorField field = makeField({2, 2, 1}, {});
  // A frame rotated about z: each axis keeps its length (0.5, 2, 3); the rotation is dropped.
  const fs::path file =
      writeBytes("field.nrrd",
                 "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 1\nspace dimension: 3\n"
                 "space directions: none (0.3,0.4,0) (-1.2, 1.6, 0) (0,0,3)\n"
                 "spacings: nan 9 9 9\nendian: little\nencoding: raw\n\n" +
                     bytesOf(componentsOf(field), std::endian::little));
  const Result<VectorField> read = readVectorFieldNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_DOUBLE_EQ(read->geometry.spacing.x, 0.5);
  EXPECT_DOUBLE_EQ(read->geometry.spacing.y, 2.0);
  EXPECT_DOUBLE_EQ(read->geometry.spacing.z, 3.0);
  EXPECT_EQ(read->geometry.origin, glm::dvec3(0.0));
}

struct MalformedCase {
  const char* label;
  std::string content;
  const char* fragment;
};

std::string fieldFile(const std::string& fields,
                      const std::string& payload = std::string(48, '\0')) {
  return "NRRD0004\n" + fields + "\n" + payload;
}

const std::string kGoodFields =
    "type: float\ndimension: 4\nsizes: 3 2 2 1\nendian: little\nencoding: raw\n";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  text.replace(text.find(from), from.size(), to);
  return text;
}

TEST_F(NrrdTest, MalformedVectorFieldFilesAreInputErrorsNamingFileAndProblem) {
  const std::string nanBytes = bytesOf(
      std::vector<float>{0, 0, 0, 0, std::numeric_limits<float>::quiet_NaN(), 0, 0, 0, 0, 0, 0, 0},
      std::endian::little);
  const std::string hugeDouble =
      bytesOf(std::vector<double>{0, 0, 0, 0, 0, 0, 1e300, 0, 0, 0, 0, 0}, std::endian::little);
  const MalformedCase cases[] = {
      {"empty", "", "empty file"},
      {"bad magic", "NRRX0004\n" + kGoodFields + "\n", "not a NRRD file"},
      {"binary garbage", std::string("\x89PNG\r\n\x1a\n\0\0", 10), "not a NRRD file"},
      {"no newline", std::string(200, 'N'), "not a NRRD file"},
      {"future version", "NRRD0006\n" + kGoodFields + "\n", "unsupported NRRD version"},
      {"version zero", "NRRD0000\n" + kGoodFields + "\n", "unsupported NRRD version"},
      {"missing sizes", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1\n", "")),
       "missing field 'sizes'"},
      {"missing type", fieldFile(replaced(kGoodFields, "type: float\n", "")),
       "missing field 'type'"},
      {"missing dimension", fieldFile(replaced(kGoodFields, "dimension: 4\n", "")),
       "missing field 'dimension'"},
      {"missing encoding", fieldFile(replaced(kGoodFields, "encoding: raw\n", "")),
       "missing field 'encoding'"},
      {"missing endian", fieldFile(replaced(kGoodFields, "endian: little\n", "")),
       "missing field 'endian'"},
      {"wrong dimension", fieldFile(replaced(kGoodFields, "dimension: 4", "dimension: 5")),
       "dimension: expected 4"},
      {"non-numeric dimension", fieldFile(replaced(kGoodFields, "dimension: 4", "dimension: four")),
       "not a whole number"},
      {"sizes count", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 2 2")),
       "sizes: expected 4 numbers"},
      {"two components", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 2 2 2 1")),
       "must have size 3"},
      {"size too large", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 16385 2 1")),
       "outside [1, 16384]"},
      {"size zero", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 2 0 1")),
       "outside [1, 16384]"},
      {"too many voxels",
       fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 16384 16384 9")),
       "exceed the limit"},
      {"non-numeric size", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 2 x 1")),
       "'x' is not a whole number"},
      {"negative size", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 -2 2 1")),
       "'-2' is not a whole number"},
      {"fractional size", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 2.0 2 1")),
       "'2.0' is not a whole number"},
      {"overflowing size",
       fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 99999999999999999999999 2 1")),
       "not a whole number"},
      {"unknown type", fieldFile(replaced(kGoodFields, "type: float", "type: quaternion")),
       "unknown type 'quaternion'"},
      {"integer type", fieldFile(replaced(kGoodFields, "type: float", "type: short")),
       "'short' is not supported"},
      {"block type", fieldFile(replaced(kGoodFields, "type: float", "type: block")),
       "'block' is not supported"},
      {"ascii encoding", fieldFile(replaced(kGoodFields, "encoding: raw", "encoding: ascii")),
       "'ascii' is not supported"},
      {"bzip2 encoding", fieldFile(replaced(kGoodFields, "encoding: raw", "encoding: bzip2")),
       "'bzip2' is not supported"},
      {"unknown encoding", fieldFile(replaced(kGoodFields, "encoding: raw", "encoding: lz4")),
       "unknown encoding"},
      {"bad endian", fieldFile(replaced(kGoodFields, "endian: little", "endian: middle")),
       "expected little or big, found 'middle'"},
      {"truncated payload", fieldFile(kGoodFields, std::string(47, '\0')), "truncated"},
      {"no payload", fieldFile(kGoodFields, ""), "truncated"},
      {"no blank line", "NRRD0004\n" + kGoodFields, "blank line"},
      {"huge header", "NRRD0004\n" + std::string(70000, '#') + "\n" + kGoodFields + "\n", "64 KiB"},
      {"missing data file", fieldFile(kGoodFields + "data file: field.raw\n"),
       "data file " /* then the data file's path */},
      {"missing data file, old spelling", fieldFile(kGoodFields + "datafile: field.raw\n"),
       "field.raw: cannot open"},
      {"data file list", fieldFile(kGoodFields + "data file: LIST\n"), "names several files"},
      {"data file pattern", fieldFile(kGoodFields + "data file: slice%03d.raw 1 10 1\n"),
       "names several files"},
      {"empty data file", fieldFile(kGoodFields + "data file:\n"), "data file: no file name"},
      {"duplicate field", fieldFile(kGoodFields + "type: double\n"), "appears twice"},
      {"no colon", fieldFile(kGoodFields + "what is this\n"), "expected 'field: value'"},
      {"line skip past the end", fieldFile(kGoodFields + "line skip: 2\n"),
       "line skip: the data ends after 0 of the 2 lines"},
      {"negative line skip", fieldFile(kGoodFields + "line skip: -1\n"),
       "line skip: expected a whole number"},
      {"byte skip", fieldFile(kGoodFields + "byte skip: -2\n"),
       "byte skip: expected -1 or a whole number, found '-2'"},
      {"byte skip past the end", fieldFile(kGoodFields + "byte skip: 40\n"), "truncated"},
      {"byte skip beyond the file", fieldFile(kGoodFields + "byte skip: 4000\n"),
       "byte skip: 4000 bytes to skip"},
      {"byte skip -1 with gzip",
       fieldFile(replaced(kGoodFields, "encoding: raw", "encoding: gzip") + "byte skip: -1\n"),
       "needs raw encoding"},
      {"nan spacing", fieldFile(kGoodFields + "spacings: nan nan 1 1\n"), "spacings: axis 1"},
      {"zero spacing", fieldFile(kGoodFields + "spacings: nan 1 0 1\n"), "spacings: axis 2"},
      {"spacings count", fieldFile(kGoodFields + "spacings: 1 1 1\n"),
       "spacings: expected 4 numbers"},
      {"short direction", fieldFile(kGoodFields + "space directions: none (1,0) (0,1,0) (0,0,1)\n"),
       "space directions: axis 1"},
      {"zero direction",
       fieldFile(kGoodFields + "space directions: none (0,0,0) (0,1,0) (0,0,1)\n"), "zero length"},
      // Its square overflows a double; the length itself does not, and is refused by range.
      {"direction of 1e200",
       fieldFile(kGoodFields + "space directions: none (1e200,0,0) (0,1,0) (0,0,1)\n"),
       "spacing along x is 1e+200"},
      {"direction for components",
       fieldFile(kGoodFields + "space directions: (1,0,0) (1,0,0) (0,1,0) (0,0,1)\n"),
       "must be 'none'"},
      {"directions count", fieldFile(kGoodFields + "space directions: none (1,0,0) (0,1,0)\n"),
       "expected 4 entries"},
      {"unclosed direction",
       fieldFile(kGoodFields + "space directions: none (1,0,0 (0,1,0) (0,0,1)\n"),
       "space directions"},
      {"bad origin", fieldFile(kGoodFields + "space origin: (1,2)\n"), "space origin"},
      {"nan origin", fieldFile(kGoodFields + "space origin: (nan,0,0)\n"), "space origin"},
      {"origin without parentheses", fieldFile(kGoodFields + "space origin: 1,2,3\n"),
       "space origin"},
      {"space dimension", fieldFile(kGoodFields + "space dimension: 2\n"),
       "space dimension: expected 3"},
      {"spacing beyond float", fieldFile(kGoodFields + "spacings: nan 1e308 1 1\n"),
       "spacing along x"},
      {"spacings 1e60 apart", fieldFile(kGoodFields + "spacings: nan 1e-30 1 1e30\n"),
       "differ by a factor"},
      {"only zero vectors", fieldFile(kGoodFields), "every vector of the field is zero"},
      {"nan and zero vectors", fieldFile(kGoodFields, nanBytes),
       "every vector of the field is zero (1 of the 4 were NaN, infinite or beyond a float's "
       "range of 3.4e38)"},
      {"double beyond float and zero vectors",
       fieldFile(replaced(kGoodFields, "type: float", "type: double"), hugeDouble),
       "(1 of the 4 were NaN, infinite or beyond a float's range of 3.4e38)"},
      {"gzip cannot hold",
       fieldFile(replaced(replaced(kGoodFields, "encoding: raw", "encoding: gzip"),
                          "sizes: 3 2 2 1", "sizes: 3 512 512 512"),
                 std::string(10, 'x')),
       "cannot inflate"},
  };
  for (const MalformedCase& c : cases) {
    SCOPED_TRACE(c.label);
    const fs::path file = writeBytes("bad field.nrrd", c.content);
    expectInputError(readVectorFieldNrrd(file), file, c.fragment);
  }
  // A detached header whose data file is itself, padded so that its own text would pass for
  // the data (hardening, class 11: it was read as float data).
  const fs::path self =
      writeBytes("self.nhdr",
                 "NRRD0004\n" + kGoodFields + "data file: self.nhdr\n\n" + std::string(4096, '\1'));
  expectInputError(readVectorFieldNrrd(self), self, "the header itself");
}

TEST_F(NrrdTest, MalformedNoiseFilesAreInputErrors) {
  const std::string good = "type: uchar\ndimension: 3\nsizes: 2 2 1\nencoding: raw\n";
  const MalformedCase cases[] = {
      {"vector dimension",
       fieldFile(replaced(good, "dimension: 3\nsizes: 2 2 1", "dimension: 4\nsizes: 3 2 2 1"), ""),
       "dimension: expected 3"},
      {"double noise",
       fieldFile(replaced(good, "uchar", "double") + "endian: little\n", std::string(32, '\0')),
       "'double' is not supported here (expected uchar, ushort or float)"},
      {"signed noise", fieldFile(replaced(good, "uchar", "signed char"), "abcd"),
       "'signed char' is not supported"},
      {"ushort without endian", fieldFile(replaced(good, "uchar", "ushort"), std::string(8, '\0')),
       "missing field 'endian'"},
      {"truncated", fieldFile(good, "abc"), "truncated"},
      {"sizes count", fieldFile(replaced(good, "sizes: 2 2 1", "sizes: 2 2"), "abcd"),
       "expected 3 numbers"},
  };
  for (const MalformedCase& c : cases) {
    SCOPED_TRACE(c.label);
    const fs::path file = writeBytes("bad-noise.nrrd", c.content);
    expectInputError(readNoiseNrrd(file), file, c.fragment);
  }
}

TEST_F(NrrdTest, HugeHeaderSizesAreRefusedBeforeAllocating) {
  // 2^31 voxels of float vectors would be 24 GiB; the 48-byte payload must be refused first.
  const fs::path file = writeBytes(
      "huge.nrrd", fieldFile(replaced(kGoodFields, "sizes: 3 2 2 1", "sizes: 3 16384 16384 8")));
  expectInputError(readVectorFieldNrrd(file), file, "truncated");
}

TEST_F(NrrdTest, CorruptedFilesNeverCrashTheReaders) {
  // Random byte flips and cuts of valid files must give a value or an InvalidInput error; run
  // under the sanitizers this also checks every read stays in bounds.
  const VectorField field = makeField({3, 2, 2}, {{0.5, 1.0, 2.0}, {1.0, 2.0, 3.0}});
  const fs::path source = path("source.nrrd");
  ASSERT_TRUE(writeVectorFieldNrrd(source, field).ok());
  const std::string raw = readWhole(source);
  const std::string gzipped =
      replaced(raw.substr(0, raw.find("\n\n") + 2), "encoding: raw", "encoding: gzip") +
      gzipCompress(raw.substr(raw.find("\n\n") + 2));
  std::mt19937 random(1234);
  for (const std::string& original : {raw, gzipped}) {
    for (int trial = 0; trial < 400; ++trial) {
      std::string mutated = original;
      const int flips = 1 + static_cast<int>(random() % 4);
      for (int f = 0; f < flips; ++f) {
        const std::size_t at = random() % mutated.size();
        mutated[at] =
            static_cast<char>(random() % 2 ? random() % 256 : "0123456789 :\n(),-"[random() % 17]);
      }
      if (trial % 5 == 0) mutated.resize(random() % mutated.size());
      const fs::path file = writeBytes("mutated.nrrd", mutated);
      const Result<VectorField> read = readVectorFieldNrrd(file);
      if (!read.ok()) {
        EXPECT_EQ(read.error().kind, ErrorKind::InvalidInput) << read.error().message;
      } else {
        EXPECT_EQ(read->vectors.size(), voxelCount(read->dims));
      }
      const Result<NoiseVolume> noise = readNoiseNrrd(file);
      if (!noise.ok()) {
        EXPECT_EQ(noise.error().kind, ErrorKind::InvalidInput) << noise.error().message;
      }
    }
  }
}

// --- Detached headers ----------------------------------------------------------------------------

TEST_F(NrrdTest, ReadsDetachedHeaderWithRelativeDataFile) {
  const VectorField field = makeField({4, 3, 2}, {{0.5, 0.25, 2.0}, {1.0, -2.0, 3.0}});
  fs::create_directory(path("data"));
  writeBytes("data/field.raw", bytesOf(componentsOf(field), std::endian::big));
  // No blank line at the end: a detached header may end with its file.
  const fs::path header =
      writeBytes("field.nhdr",
                 "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 4 3 2\nspace dimension: 3\n"
                 "space directions: none (0.5,0,0) (0,0.25,0) (0,0,2)\nspace origin: (1,-2,3)\n"
                 "endian: big\nencoding: raw\ndata file: data/field.raw");
  const Result<VectorField> read = readVectorFieldNrrd(header);
  ASSERT_TRUE(read.ok()) << read.error().message;
  expectSameField(*read, field);
  // The dispatcher takes .nhdr, and the same header with an absolute data-file path.
  const Result<VectorField> dispatched = readVectorField(header);
  ASSERT_TRUE(dispatched.ok()) << dispatched.error().message;
  expectSameField(*dispatched, field);
  const fs::path absolute =
      writeBytes("absolute.nhdr",
                 "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 4 3 2\nendian: big\n"
                 "encoding: raw\nspacings: nan 0.5 0.25 2\nspace origin: (1,-2,3)\n"
                 "data file: " +
                     path("data/field.raw").string() + "\n\n");
  const Result<VectorField> fromAbsolute = readVectorFieldNrrd(absolute);
  ASSERT_TRUE(fromAbsolute.ok()) << fromAbsolute.error().message;
  expectSameField(*fromAbsolute, field);
}

TEST_F(NrrdTest, ReadsDetachedGzipDataAndSkips) {
  const VectorField field = makeField({3, 3, 3}, {});
  const std::string payload = bytesOf(componentsOf(field), std::endian::little);
  const std::string fields =
      "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 3 3 3\n"
      "endian: little\n";
  struct Case {
    const char* label;
    std::string headerFields;
    std::string data;
  };
  const Case cases[] = {
      {"gzip", "encoding: gzip\n", gzipCompress(payload)},
      {"gzip with a decompressed byte skip", "encoding: gzip\nbyte skip: 5\n",
       gzipCompress("12345" + payload)},
      {"line skip", "encoding: raw\nline skip: 2\n", "a text header\nsecond line\n" + payload},
      {"byte skip", "encoding: raw\nbyte skip: 7\n", "skipped" + payload},
      {"byte skip -1", "encoding: raw\nbyte skip: -1\n", std::string(100, 'x') + payload},
      {"line and byte skip", "encoding: raw\nline skip: 1\nbyte skip: 3\n", "line\nabc" + payload},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.label);
    writeBytes("field.data", c.data);
    const fs::path header =
        writeBytes("field.nhdr", fields + c.headerFields + "data file: ./field.data\n");
    const Result<VectorField> read = readVectorFieldNrrd(header);
    ASSERT_TRUE(read.ok()) << read.error().message;
    expectSameField(*read, field);
  }
  // Skips work in attached files too.
  const fs::path attached = writeBytes(
      "attached.nrrd", fields + "encoding: raw\nline skip: 1\n\nskipped line\n" + payload);
  const Result<VectorField> read = readVectorFieldNrrd(attached);
  ASSERT_TRUE(read.ok()) << read.error().message;
  expectSameField(*read, field);
}

TEST_F(NrrdTest, DetachedDataErrorsNameHeaderAndDataFile) {
  const std::string fields =
      "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 1\n"
      "endian: little\n";
  fs::path header = writeBytes("field.nhdr", fields + "encoding: raw\ndata file: missing.raw\n");
  expectInputError(readVectorFieldNrrd(header), header, "missing.raw: cannot open");
  writeBytes("short.raw", std::string(47, '\1'));
  header = writeBytes("field.nhdr", fields + "encoding: raw\ndata file: short.raw\n");
  Result<VectorField> read = readVectorFieldNrrd(header);
  expectInputError(read, header, "short.raw: data is truncated");
  writeBytes("bad.gz", "not gzip at all, not at all");
  header = writeBytes("field.nhdr", fields + "encoding: gzip\ndata file: bad.gz\n");
  read = readVectorFieldNrrd(header);
  expectInputError(read, header, "bad.gz: gzip data is corrupt");
  fs::create_directory(path("folder.raw"));
  header = writeBytes("field.nhdr", fields + "encoding: raw\ndata file: folder.raw\n");
  expectInputError(readVectorFieldNrrd(header), header, "not a regular file");
  // Without a data file, a header must end with a blank line and hold its data.
  header = writeBytes("field.nhdr", fields + "encoding: raw\n");
  expectInputError(readVectorFieldNrrd(header), header, "without the blank line");
}

TEST_F(NrrdTest, ReadsDetachedNoise) {
  NoiseVolume noise;
  noise.dims = {3, 2, 2};
  noise.bytes = {0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 100, 110};
  writeBytes("noise.bin", std::string(noise.bytes.begin(), noise.bytes.end()));
  const fs::path header =
      writeBytes("noise.nhdr",
                 "NRRD0004\ntype: uchar\ndimension: 3\nsizes: 3 2 2\nencoding: raw\n"
                 "data file: noise.bin\n");
  const Result<NoiseVolume> read = readNoise(header);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->bytes, noise.bytes);
}

// --- NaN and Inf, all-zero fields
// ------------------------------------------------------------------

TEST_F(NrrdTest, NonFiniteVectorsBecomeZeroAndAreCounted) {
  VectorField field = makeField({3, 2, 1}, {});
  std::vector<float> values = componentsOf(field);
  values[1] = std::numeric_limits<float>::quiet_NaN();          // voxel 0
  values[3 * 2 + 2] = std::numeric_limits<float>::infinity();   // voxel 2
  values[3 * 4 + 0] = -std::numeric_limits<float>::infinity();  // voxel 4
  values[3 * 4 + 1] = std::numeric_limits<float>::quiet_NaN();  // voxel 4 again: one vector
  const fs::path file = writeBytes("nan.nrrd",
                                   "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 3 2 1\n"
                                   "endian: little\nencoding: raw\n\n" +
                                       bytesOf(values, std::endian::little));
  FieldReadInfo info;
  info.arrayName = "stale";
  const Result<VectorField> read = readVectorField(file, {}, &info);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(info.nonFiniteVectors, 3u);
  EXPECT_TRUE(info.arrayName.empty());
  EXPECT_TRUE(info.arrayNames.empty());
  for (const std::size_t voxel : {0u, 2u, 4u}) EXPECT_EQ(read->vectors[voxel], glm::vec3(0.0f));
  for (const std::size_t voxel : {1u, 3u, 5u})
    EXPECT_EQ(read->vectors[voxel], field.vectors[voxel]);

  // Doubles beyond the float range count the same way; the call without info gives the same field.
  std::vector<double> doubles(values.begin(), values.end());
  doubles[3 * 5] = 1e300;
  const fs::path doubleFile = writeBytes("big.nrrd",
                                         "NRRD0004\ntype: double\ndimension: 4\nsizes: 3 3 2 1\n"
                                         "endian: little\nencoding: raw\n\n" +
                                             bytesOf(doubles, std::endian::little));
  ASSERT_TRUE(readVectorFieldNrrd(doubleFile, &info).ok());
  EXPECT_EQ(info.nonFiniteVectors, 4u);
  const Result<VectorField> again = readVectorFieldNrrd(doubleFile);
  ASSERT_TRUE(again.ok());
  EXPECT_EQ(again->vectors[5], glm::vec3(0.0f));
}

}  // namespace
}  // namespace lic3d
