// SPDX-License-Identifier: BSD-3-Clause
// Streams: vector fields read piece by piece (each piece equal to the same box cut from the
// whole-file reader's field). Scalar volumes written piece by piece: test_volume_stream.cpp.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "core/parallel.h"
#include "io/field_io.h"
#include "io/field_stream.h"
#include "io/nrrd.h"
#include "lic/field_piece.h"
#include "test_support.h"
#include "vti_test_files.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;
using test::bytesOf;

constexpr Dims kDims{7, 5, 4};
const GridGeometry kGeometry{{0.5, 0.25, 2.0}, {-1.0, 3.0, 0.125}};

// A field with one NaN and one infinite vector, which both readers read as zero.
VectorField makeField(Dims dims = kDims) {
  VectorField field;
  field.dims = dims;
  field.geometry = kGeometry;
  for (std::size_t i = 0; i < voxelCount(dims); ++i) {
    const float t = static_cast<float>(i);
    field.vectors.push_back({std::sin(t), std::cos(0.5f * t) + 2.0f, 0.1f * t - 1.0f});
  }
  field.vectors[9].y = std::numeric_limits<float>::quiet_NaN();
  field.vectors[31].z = std::numeric_limits<float>::infinity();
  return field;
}

template <class T>
std::vector<T> valuesOf(const VectorField& field, bool planar) {
  std::vector<T> values;
  if (planar) {
    for (glm::length_t axis = 0; axis < 3; ++axis)
      for (const glm::vec3& v : field.vectors) values.push_back(T(v[axis]));
  } else {
    for (const glm::vec3& v : field.vectors) values.insert(values.end(), {T(v.x), T(v.y), T(v.z)});
  }
  return values;
}

// Boxes of every shape the stream reads differently: the whole grid, z slabs (one read), boxes
// spanning x (a read per layer), inner boxes (a read per row) and single voxels.
const std::vector<std::pair<Dims, Dims>> kBoxes = {
    {{0, 0, 0}, kDims},     {{0, 0, 1}, {7, 5, 2}}, {{0, 1, 0}, {7, 3, 4}}, {{2, 1, 1}, {3, 3, 2}},
    {{1, 0, 0}, {6, 5, 4}}, {{6, 4, 3}, {1, 1, 1}}, {{0, 2, 1}, {1, 1, 1}}};

// Every box read from the stream equals the box cut from the whole-file reader's field, bit for
// bit, with the geometry cutFieldPiece gives it (its `piece` aside).
void expectPiecesMatchWholeRead(const fs::path& path, std::string_view arrayName = {}) {
  SCOPED_TRACE(path.filename().string());
  FieldReadInfo info;
  const Result<VectorField> whole = readVectorField(path, arrayName, &info);
  ASSERT_TRUE(whole.ok()) << whole.error().message;
  Result<FieldStream> stream = FieldStream::open(path, arrayName);
  ASSERT_TRUE(stream.ok()) << stream.error().message;
  EXPECT_EQ(stream->dims(), whole->dims);
  EXPECT_EQ(stream->geometry(), whole->geometry);
  EXPECT_EQ(stream->unit(), info.unit);
  EXPECT_EQ(stream->arrayName(), info.arrayName);
  // Read in tasks of the default size (one for these small pieces), of one voxel, of a few voxels
  // (parts of a row) and of a few rows: the same vectors whichever thread read which part.
  for (const std::size_t chunk :
       {std::size_t{0}, std::size_t{1}, std::size_t{50}, std::size_t{400}})
    for (const auto& [offset, dims] : kBoxes) {
      bool inside = true;
      for (int a = 0; a < 3; ++a) inside = inside && offset[a] + dims[a] <= whole->dims[a];
      if (!inside) continue;
      stream->setChunkBytes(chunk > 0 ? chunk : std::size_t{4} << 20);
      SCOPED_TRACE(gridText(dims) + " at " + std::to_string(offset.x) + "," +
                   std::to_string(offset.y) + "," + std::to_string(offset.z) + " in tasks of " +
                   std::to_string(stream->chunkBytes()) + " bytes");
      const Result<VectorField> piece = stream->readPiece(offset, dims);
      ASSERT_TRUE(piece.ok()) << piece.error().message;
      const Result<VectorField> cut = cutFieldPiece(*whole, offset, dims);
      ASSERT_TRUE(cut.ok());
      EXPECT_EQ(piece->dims, cut->dims);
      EXPECT_EQ(piece->geometry, cut->geometry);
      EXPECT_FALSE(piece->piece.has_value());
      ASSERT_EQ(piece->vectors.size(), cut->vectors.size());
      EXPECT_EQ(std::memcmp(piece->vectors.data(), cut->vectors.data(),
                            piece->vectors.size() * sizeof(glm::vec3)),
                0);
    }
}

template <class T>
void expectUnsupported(const Result<T>& result, const fs::path& file, const std::string& why) {
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().kind, ErrorKind::Unsupported) << result.error().message;
  EXPECT_NE(result.error().message.find(file.string()), std::string::npos)
      << result.error().message;
  EXPECT_NE(result.error().message.find(why), std::string::npos) << result.error().message;
  EXPECT_NE(result.error().message.find("read whole"), std::string::npos) << result.error().message;
}

class FieldStreamTest : public test::TempFolderTest {
 protected:
  fs::path writeRaw(const std::string& name, const std::string& bytes,
                    const std::string& sidecar) const {
    writeBytes(fs::path(name).replace_extension(".json").string(), sidecar);
    return writeBytes(name, bytes);
  }
};

TEST_F(FieldStreamTest, RawPiecesEqualTheWholeReadInEveryLayout) {
  const VectorField field = makeField();
  const std::string dims =
      R"({"dims": [7, 5, 4], "spacing": [0.5, 0.25, 2], "origin": [-1, 3, 0.125])";
  for (const bool planar : {false, true}) {
    for (const std::endian order : {std::endian::little, std::endian::big}) {
      const std::string endian = order == std::endian::big ? "big" : "little";
      const std::string layout = std::string(", \"order\": \"") +
                                 (planar ? "planar" : "interleaved") + "\", \"endian\": \"" +
                                 endian + "\"";
      const std::string stem = std::string(planar ? "planar_" : "interleaved_") + endian;
      expectPiecesMatchWholeRead(writeRaw(
          stem + "_32.raw", bytesOf(valuesOf<float>(field, planar), order), dims + layout + "}"));
      expectPiecesMatchWholeRead(writeRaw(stem + "_64.raw",
                                          bytesOf(valuesOf<double>(field, planar), order),
                                          dims + layout + R"(, "type": "float64"})"));
    }
  }
}

TEST_F(FieldStreamTest, NonFiniteVectorsBecomeZeroAndAreCounted) {
  const VectorField field = makeField();
  const fs::path path =
      writeRaw("field.raw", bytesOf(valuesOf<float>(field, false), std::endian::little),
               R"({"dims": [7, 5, 4]})");
  const Result<FieldStream> stream = FieldStream::open(path);
  ASSERT_TRUE(stream.ok()) << stream.error().message;
  std::uint64_t nonFinite = 99;
  Result<VectorField> whole = stream->readPiece({0, 0, 0}, kDims, &nonFinite);
  ASSERT_TRUE(whole.ok());
  EXPECT_EQ(nonFinite, 2u);
  EXPECT_EQ(whole->vectors[9], glm::vec3(0.0f));
  EXPECT_EQ(whole->vectors[31], glm::vec3(0.0f));
  // Voxel 9 is (2,1,0): a row of y = 1 holds it, one of y = 2 does not.
  ASSERT_TRUE(stream->readPiece({0, 1, 0}, {7, 1, 1}, &nonFinite).ok());
  EXPECT_EQ(nonFinite, 1u);
  ASSERT_TRUE(stream->readPiece({0, 2, 0}, {7, 1, 1}, &nonFinite).ok());
  EXPECT_EQ(nonFinite, 0u);
}

// A piece read by threads in tasks of a few voxels: the same non-finite count, and each part handed
// to the visitor once, final; a field read into again keeps its memory when it is large enough.
TEST_F(FieldStreamTest, PiecesReadInPartsByThreadsAreVisitedOnceEach) {
  const VectorField field = makeField();
  const fs::path path =
      writeRaw("field.raw", bytesOf(valuesOf<float>(field, false), std::endian::little),
               R"({"dims": [7, 5, 4]})");
  Result<FieldStream> stream = FieldStream::open(path);
  ASSERT_TRUE(stream.ok()) << stream.error().message;
  const Result<VectorField> whole = stream->readPiece({0, 0, 0}, kDims);
  ASSERT_TRUE(whole.ok());
  for (const std::size_t chunk : {std::size_t{1}, std::size_t{30}, std::size_t{100}}) {
    SCOPED_TRACE(chunk);
    stream->setChunkBytes(chunk);
    VectorField into;
    std::mutex mutex;
    std::vector<int> seen(voxelCount(kDims), 0);
    std::vector<glm::vec3> visited(voxelCount(kDims));
    std::uint64_t nonFinite = 0;
    ASSERT_TRUE(stream
                    ->readPieceInto({0, 0, 0}, kDims, into, &nonFinite,
                                    [&](const glm::vec3* vectors, std::size_t count) {
                                      const std::lock_guard lock(mutex);
                                      const std::size_t at =
                                          static_cast<std::size_t>(vectors - into.vectors.data());
                                      for (std::size_t i = 0; i < count; ++i) {
                                        ++seen[at + i];
                                        visited[at + i] = vectors[i];
                                      }
                                    })
                    .ok());
    EXPECT_EQ(nonFinite, 2u);
    EXPECT_EQ(seen, std::vector<int>(voxelCount(kDims), 1));
    EXPECT_EQ(visited, whole->vectors);  // non-finite vectors already zero
    EXPECT_EQ(into.vectors, whole->vectors);
    // Read again into the same field, a smaller piece: its memory is kept.
    const glm::vec3* memory = into.vectors.data();
    ASSERT_TRUE(stream->readPieceInto({0, 1, 0}, {7, 4, 2}, into, &nonFinite).ok());
    EXPECT_EQ(into.vectors.data(), memory);
    EXPECT_EQ(into.dims, Dims(7, 4, 2));
    EXPECT_EQ(into.vectors, cutFieldPiece(*whole, {0, 1, 0}, {7, 4, 2})->vectors);
    EXPECT_EQ(nonFinite, 2u);  // voxels 9 (2,1,0) and 31 (3,4,0)
  }
}

TEST_F(FieldStreamTest, NrrdPiecesEqualTheWholeReadAttachedAndDetached) {
  VectorField field = makeField();
  ASSERT_TRUE(writeVectorFieldNrrd(path("written.nrrd"), field).ok());
  expectPiecesMatchWholeRead(path("written.nrrd"));

  // Doubles, big endian, a unit; and the same data detached after skipped lines and bytes.
  const std::string header =
      "NRRD0004\ntype: double\ndimension: 4\nsizes: 3 7 5 4\nspace dimension: 3\n"
      "space directions: none (0.5,0,0) (0,0.25,0) (0,0,2)\nspace origin: (-1,3,0.125)\n"
      "sample units: \"m/s\"\nendian: big\n";
  const std::string data = bytesOf(valuesOf<double>(field, false), std::endian::big);
  writeBytes("double.nrrd", header + "encoding: raw\n\n" + data);
  expectPiecesMatchWholeRead(path("double.nrrd"));
  EXPECT_EQ(FieldStream::open(path("double.nrrd"))->unit(), "m/s");
  writeBytes("double.data", "two lines\nto skip\n12345" + data);
  writeBytes("double.nhdr",
             header + "encoding: raw\ndata file: double.data\nline skip: 2\nbyte skip: 5\n\n");
  expectPiecesMatchWholeRead(path("double.nhdr"));

  // A 2D grid of 2D vectors (x, y, 0).
  std::vector<float> planarValues;
  for (std::size_t i = 0; i < 35; ++i)
    planarValues.insert(planarValues.end(), {0.5f * static_cast<float>(i), 1.0f});
  writeBytes("plane.nrrd",
             "NRRD0004\ntype: float\ndimension: 3\nsizes: 2 7 5\nendian: little\nencoding: "
             "raw\n\n" +
                 bytesOf(planarValues, std::endian::little));
  expectPiecesMatchWholeRead(path("plane.nrrd"));
}

TEST_F(FieldStreamTest, AppendedRawVtiPiecesEqualTheWholeRead) {
  const VectorField field = makeField();
  std::vector<double> vectors;
  for (const float value : valuesOf<float>(field, false)) vectors.push_back(value);
  test::Image image;
  // An extent that does not start at 0 moves the origin.
  image.wholeExtent = "2 8 -1 3 0 3";
  image.arrays.push_back({"density", "Float64", 1, false, test::ramp(140, 0, 1)});
  image.arrays.push_back({"velocity", "Float32", 3, false, vectors});
  image.arrays.push_back({"doubles", "Float64", 3, false, vectors});
  for (const bool header64 : {false, true}) {
    for (const bool bigEndian : {false, true}) {
      test::Encoding encoding;
      encoding.format = "appended";
      encoding.header64 = header64;
      encoding.bigEndian = bigEndian;
      const std::string name =
          std::string("field") + (header64 ? "64" : "32") + (bigEndian ? "be" : "le") + ".vti";
      expectPiecesMatchWholeRead(writeBytes(name, test::makeVti(image, encoding)));
      expectPiecesMatchWholeRead(path(name), "doubles");
      EXPECT_EQ(FieldStream::open(path(name))->arrayName(), "velocity");
    }
  }
}

TEST_F(FieldStreamTest, VtiMaskAndCellDataAsTheWholeReadHasThem) {
  const VectorField field = makeField();
  std::vector<double> vectors;
  for (const float value : valuesOf<float>(field, false)) vectors.push_back(value);
  std::vector<double> valid(140, 1.0);
  for (const std::size_t invalid : {0u, 9u, 17u, 100u}) valid[invalid] = 0.0;
  test::Encoding encoding;
  encoding.format = "appended";
  test::Image masked;
  masked.wholeExtent = "0 6 0 4 0 3";
  masked.arrays.push_back({"velocity", "Float32", 3, false, vectors});
  masked.arrays.push_back({"vtkValidPointMask", "UInt8", 1, false, valid});
  expectPiecesMatchWholeRead(writeBytes("masked.vti", test::makeVti(masked, encoding)));
  std::uint64_t nonFinite = 0;
  const Result<VectorField> all =
      FieldStream::open(path("masked.vti"))->readPiece({}, kDims, &nonFinite);
  ASSERT_TRUE(all.ok());
  EXPECT_EQ(all->vectors[17], glm::vec3(0.0f));
  EXPECT_EQ(nonFinite, 1u);  // voxel 9 is masked: only voxel 31 counts

  test::Image cells;
  cells.wholeExtent = "0 7 0 5 0 4";
  cells.arrays.push_back({"velocity", "Float32", 3, true, vectors});
  expectPiecesMatchWholeRead(writeBytes("cells.vti", test::makeVti(cells, encoding)));
}

TEST_F(FieldStreamTest, FormatsThatMustBeReadWholeAreUnsupported) {
  const VectorField field = makeField();
  const std::string data = bytesOf(valuesOf<float>(field, false), std::endian::little);
  const fs::path gzip =
      writeBytes("field.nrrd",
                 "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 7 5 4\nendian: little\n"
                 "encoding: gzip\n\n" +
                     test::deflateBytes(data, 15 + 16));
  ASSERT_TRUE(readVectorField(gzip).ok());
  expectUnsupported(FieldStream::open(gzip), gzip, "gzip");

  const test::Image image = test::testImage();
  for (const char* format : {"ascii", "binary", "appended"}) {
    for (const bool zlib : {false, true}) {
      for (const bool appendedBase64 : {false, true}) {
        test::Encoding encoding;
        encoding.format = format;
        encoding.zlib = zlib;
        encoding.appendedBase64 = appendedBase64;
        if (encoding.format == "appended" && !zlib && !appendedBase64) continue;  // streams
        if (encoding.format != "appended" && appendedBase64) continue;
        const fs::path file = writeBytes("image.vti", test::makeVti(image, encoding));
        SCOPED_TRACE(encoding.label());
        ASSERT_TRUE(readVectorField(file).ok());
        expectUnsupported(FieldStream::open(file), file,
                          zlib             ? "compressed"
                          : appendedBase64 ? "base64"
                                           : (encoding.format == "ascii" ? "ascii" : "base64"));
      }
    }
  }
  for (const char* name : {"field.vtk", "field.pvti"})
    expectUnsupported(FieldStream::open(writeBytes(name, "x")), path(name), "");
}

TEST_F(FieldStreamTest, TruncatedFilesAreRefusedBeforeReading) {
  const VectorField field = makeField();
  std::string data = bytesOf(valuesOf<float>(field, false), std::endian::little);
  data.resize(data.size() - 12);
  const fs::path raw = writeRaw("short.raw", data, R"({"dims": [7, 5, 4]})");
  const Result<FieldStream> stream = FieldStream::open(raw);
  ASSERT_FALSE(stream.ok());
  EXPECT_EQ(stream.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(stream.error().message.find(raw.string()), std::string::npos);
  EXPECT_NE(stream.error().message.find("holds 1668 bytes"), std::string::npos)
      << stream.error().message;
  EXPECT_NE(stream.error().message.find("needs 1680"), std::string::npos) << stream.error().message;

  test::Encoding encoding;
  encoding.format = "appended";
  std::string vti = test::makeVti(test::testImage(), encoding);
  vti.resize(vti.size() - 40);  // the closing tags and the last values
  const fs::path file = writeBytes("short.vti", vti);
  const Result<FieldStream> vtiStream = FieldStream::open(file);
  ASSERT_FALSE(vtiStream.ok());
  EXPECT_EQ(vtiStream.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(vtiStream.error().message.find("short.vti"), std::string::npos);
  EXPECT_NE(vtiStream.error().message.find("truncated"), std::string::npos)
      << vtiStream.error().message;
}

TEST_F(FieldStreamTest, GridsBeyondTheWholeFileLimitStream) {
  // 16384 x 16384 x 16 voxels (2^32, twice what a whole-file reader takes): a sparse 48 GiB file
  // in which one vector near the end is set.
  const fs::path raw = writeRaw("large.raw", "", R"({"dims": [16384, 16384, 16]})");
  const std::uint64_t voxels = std::uint64_t{16384} * 16384 * 16;
  std::error_code error;
  fs::resize_file(raw, voxels * 12, error);
  if (error) GTEST_SKIP() << "no sparse 48 GiB file here: " << error.message();
  const Dims voxel{16383, 16380, 15};
  const float vector[3] = {1.5f, -2.0f, 0.25f};
  {
    std::fstream out(raw, std::ios::in | std::ios::out | std::ios::binary);
    out.seekp(static_cast<std::streamoff>(
        voxelIndex({16384, 16384, 16}, voxel.x, voxel.y, voxel.z) * 12));
    out.write(reinterpret_cast<const char*>(vector), sizeof vector);
  }
  EXPECT_FALSE(readVectorField(raw).ok());
  const Result<FieldStream> stream = FieldStream::open(raw);
  ASSERT_TRUE(stream.ok()) << stream.error().message;
  EXPECT_EQ(stream->dims(), Dims(16384, 16384, 16));
  const Result<VectorField> piece = stream->readPiece({16380, 16379, 14}, {4, 3, 2});
  ASSERT_TRUE(piece.ok()) << piece.error().message;
  EXPECT_EQ(piece->at(3, 1, 1), glm::vec3(1.5f, -2.0f, 0.25f));
  EXPECT_EQ(piece->at(2, 1, 1), glm::vec3(0.0f));
  EXPECT_EQ(piece->geometry.origin, glm::dvec3(16380, 16379, 14));
  EXPECT_FALSE(stream->readPiece({16380, 0, 0}, {5, 1, 1}).ok());  // beyond the grid
}

TEST_F(FieldStreamTest, ThreadsReadPiecesAtOnce) {
  const VectorField field = makeField();
  const fs::path raw =
      writeRaw("field.raw", bytesOf(valuesOf<double>(field, true), std::endian::big),
               R"({"dims": [7, 5, 4], "type": "float64", "endian": "big", "order": "planar"})");
  const Result<FieldStream> stream = FieldStream::open(raw);
  ASSERT_TRUE(stream.ok()) << stream.error().message;
  const Result<VectorField> whole = readVectorField(raw);
  ASSERT_TRUE(whole.ok());
  std::vector<int> mismatches(8, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 50; ++round) {
        const auto& [offset, dims] = kBoxes[static_cast<std::size_t>(t + round) % kBoxes.size()];
        const Result<VectorField> piece = stream->readPiece(offset, dims);
        const Result<VectorField> cut = cutFieldPiece(*whole, offset, dims);
        if (!piece.ok() || piece->vectors != cut->vectors)
          ++mismatches[static_cast<std::size_t>(t)];
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  EXPECT_EQ(mismatches, std::vector<int>(8, 0));
}

}  // namespace
}  // namespace lic3d
