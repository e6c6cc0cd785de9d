// SPDX-License-Identifier: BSD-3-Clause
// Scalar volumes written piece by piece (ScalarVolumeStream), in blocks and runs from several
// threads: byte for byte the whole-volume writers' files (which write through it, by runs from
// every thread), or no file at all; hidden voxels NaN.

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "io/nrrd.h"
#include "io/volume_stream.h"
#include "io/vti.h"
#include "lic/field_piece.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;
using test::bytesOf;

const GridGeometry kGeometry{{0.5, 0.25, 2.0}, {-1.0, 3.0, 0.125}};

// A volume of 9x7x5 values, NaN among them (as sparsity writes hidden voxels).
ScalarVolume makeVolume() {
  ScalarVolume volume;
  volume.dims = {9, 7, 5};
  volume.geometry = kGeometry;
  for (std::size_t i = 0; i < voxelCount(volume.dims); ++i)
    volume.values.push_back(std::sin(0.37f * static_cast<float>(i)));
  volume.values[40] = std::numeric_limits<float>::quiet_NaN();
  return volume;
}

// Disjoint blocks covering the 9x7x5 grid, in every shape the stream writes differently: a slab
// of two layers spanning x and y (one run), blocks spanning x (a run per layer) and smaller ones
// (a run per row).
const std::vector<std::pair<Dims, Dims>> kBlocks = {
    {{0, 0, 0}, {9, 7, 2}}, {{0, 0, 2}, {9, 4, 2}}, {{0, 4, 2}, {5, 3, 2}}, {{5, 4, 2}, {4, 3, 2}},
    {{0, 0, 4}, {2, 3, 1}}, {{2, 0, 4}, {7, 3, 1}}, {{0, 3, 4}, {2, 4, 1}}, {{2, 3, 4}, {7, 4, 1}}};

Result<void> writeBlock(ScalarVolumeStream& stream, const ScalarVolume& volume, Dims offset,
                        Dims dims) {
  const Result<ScalarVolume> block = cutVolume(volume, offset, dims);
  if (!block.ok()) return block.error();
  return stream.write(offset, dims, block->values.data());
}

class ScalarVolumeStreamTest : public test::TempFolderTest {};

// The block's rows, each one run written straight from the whole volume.
Result<void> writeBlockAsRuns(ScalarVolumeStream& stream, const ScalarVolume& volume, Dims offset,
                              Dims dims) {
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j) {
      const std::size_t first = voxelIndex(volume.dims, offset.x, offset.y + j, offset.z + k);
      LIC3D_TRY(
          stream.writeRun(first, volume.values.data() + first, static_cast<std::size_t>(dims.x)));
    }
  return {};
}

struct Format {
  const char* extension;
  ScalarFileFormat format;
};
const Format kFormats[] = {{".nrrd", ScalarFileFormat::Nrrd},
                           {".vti", ScalarFileFormat::Vti},
                           {".raw", ScalarFileFormat::Raw}};

// The whole writer of each format: writeScalarNrrd, writeScalarVti, and for .raw the one writer
// of whole volumes they share.
Result<void> writeWhole(const Format& format, const fs::path& file, const ScalarVolume& volume,
                        std::string_view name) {
  switch (format.format) {
    case ScalarFileFormat::Nrrd: return writeScalarNrrd(file, volume, name);
    case ScalarFileFormat::Vti: return writeScalarVti(file, volume, name);
    case ScalarFileFormat::Raw: break;
  }
  return writeScalarVolumeFile(file, format.format, volume, {.name = name});
}

TEST_F(ScalarVolumeStreamTest, EveryFormatWrittenInBlocksAndRunsFromThreadsIsTheWholeWritersFile) {
  const ScalarVolume volume = makeVolume();
  for (const Format& format : kFormats) {
    SCOPED_TRACE(format.extension);
    const fs::path whole = path(std::string("whole") + format.extension);
    const fs::path blocks = path(std::string("blocks") + format.extension);
    ASSERT_TRUE(writeWhole(format, whole, volume, "speed").ok());
    Result<ScalarVolumeStream> stream =
        ScalarVolumeStream::create(blocks, volume.dims, volume.geometry, "speed");
    ASSERT_TRUE(stream.ok()) << stream.error().message;
    // Three threads, each writing every third block: as a block, or row by row as runs.
    std::vector<int> failures(3, 0);
    std::vector<std::thread> threads;
    for (std::size_t t = 0; t < failures.size(); ++t) {
      threads.emplace_back([&, t] {
        for (std::size_t b = t; b < kBlocks.size(); b += failures.size()) {
          const auto& [offset, dims] = kBlocks[b];
          const Result<void> written = b % 2 == 0 ? writeBlock(*stream, volume, offset, dims)
                                                  : writeBlockAsRuns(*stream, volume, offset, dims);
          if (!written.ok()) ++failures[t];
        }
      });
    }
    for (std::thread& thread : threads) thread.join();
    EXPECT_EQ(failures, std::vector<int>(3, 0));
    EXPECT_FALSE(fs::exists(blocks));  // not before finish()
    const Result<void> finished = stream->finish();
    ASSERT_TRUE(finished.ok()) << finished.error().message;
    EXPECT_EQ(test::readWhole(blocks), test::readWhole(whole));
    if (format.format == ScalarFileFormat::Raw) {
      EXPECT_EQ(test::readWhole(path("blocks.json")), test::readWhole(path("whole.json")));
    }
  }
  EXPECT_EQ(listFolder(),
            (std::vector<std::string>{"blocks.json", "blocks.nrrd", "blocks.raw", "blocks.vti",
                                      "whole.json", "whole.nrrd", "whole.raw", "whole.vti"}));
}

// What writeScalarVti wrote before it wrote through the stream, byte for byte: ParaView's and
// VTK's readers, and lic3d's, read this layout.
TEST_F(ScalarVolumeStreamTest, VtiIsTheDocumentedAppendedRawFile) {
  const ScalarVolume volume = makeVolume();
  ASSERT_TRUE(writeScalarVti(path("whole.vti"), volume, "speed").ok());
  const std::uint64_t size = voxelCount(volume.dims) * sizeof(float);
  std::string expected =
      std::string(
          "<?xml version=\"1.0\"?>\n<!-- written by lic3d -->\n"
          "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"") +
      (std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian") +
      "\" header_type=\"UInt64\">\n"
      "  <ImageData WholeExtent=\"0 8 0 6 0 4\" Origin=\"-1 3 0.125\" Spacing=\"0.5 0.25 2\" "
      "Direction=\"1 0 0 0 1 0 0 0 1\">\n"
      "    <Piece Extent=\"0 8 0 6 0 4\">\n"
      "      <PointData Scalars=\"speed\">\n"
      "        <DataArray type=\"Float32\" Name=\"speed\" NumberOfComponents=\"1\" "
      "format=\"appended\" offset=\"0\"/>\n"
      "      </PointData>\n      <CellData>\n      </CellData>\n    </Piece>\n  </ImageData>\n"
      "  <AppendedData encoding=\"raw\">\n   _";
  expected.append(reinterpret_cast<const char*>(&size), sizeof size);
  expected += bytesOf(volume.values, std::endian::native);
  expected += "\n  </AppendedData>\n</VTKFile>\n";
  EXPECT_EQ(test::readWhole(path("whole.vti")), expected);
}

TEST_F(ScalarVolumeStreamTest, AStreamNotFinishedLeavesNoFile) {
  const ScalarVolume volume = makeVolume();
  {
    Result<ScalarVolumeStream> stream =
        ScalarVolumeStream::create(path("lic.nrrd"), volume.dims, volume.geometry);
    ASSERT_TRUE(stream.ok()) << stream.error().message;
    ASSERT_TRUE(writeBlock(*stream, volume, kBlocks[0].first, kBlocks[0].second).ok());
    EXPECT_EQ(listFolder().size(), 1u);  // the temporary file
  }
  EXPECT_TRUE(listFolder().empty());
  {
    // Every block but one: finish() refuses, and nothing appears.
    Result<ScalarVolumeStream> stream =
        ScalarVolumeStream::create(path("lic.raw"), volume.dims, volume.geometry);
    ASSERT_TRUE(stream.ok()) << stream.error().message;
    for (std::size_t b = 1; b < kBlocks.size(); ++b)
      ASSERT_TRUE(writeBlock(*stream, volume, kBlocks[b].first, kBlocks[b].second).ok());
    const Result<void> finished = stream->finish();
    ASSERT_FALSE(finished.ok());
    EXPECT_NE(finished.error().message.find(path("lic.raw").string()), std::string::npos);
    EXPECT_NE(finished.error().message.find("a block is missing"), std::string::npos)
        << finished.error().message;
  }
  EXPECT_TRUE(listFolder().empty());
}

TEST_F(ScalarVolumeStreamTest, RawReadsBackWithItsSidecar) {
  const ScalarVolume volume = makeVolume();
  Result<ScalarVolumeStream> stream =
      ScalarVolumeStream::create(path("lic.raw"), volume.dims, volume.geometry);
  ASSERT_TRUE(stream.ok()) << stream.error().message;
  for (auto it = kBlocks.rbegin(); it != kBlocks.rend(); ++it)
    ASSERT_TRUE(writeBlock(*stream, volume, it->first, it->second).ok());
  ASSERT_TRUE(stream->finish().ok());
  EXPECT_EQ(listFolder(), (std::vector<std::string>{"lic.json", "lic.raw"}));
  EXPECT_EQ(test::readWhole(path("lic.raw")), bytesOf(volume.values, std::endian::little));
  EXPECT_EQ(test::readWhole(path("lic.json")),
            "{\"dims\": [9, 7, 5], \"spacing\": [0.5, 0.25, 2], \"origin\": [-1, 3, 0.125], "
            "\"components\": 1, \"type\": \"float32\", \"endian\": \"little\", "
            "\"bytes\": 1260}\n");
}

// The sidecar's name may hold only an older sidecar: any other file there is refused before
// anything is written, and kept.
TEST_F(ScalarVolumeStreamTest, RawRefusesToReplaceAJsonThatIsNotItsSidecar) {
  const ScalarVolume volume = makeVolume();
  writeBytes("lic.json", "{\"lic\": {\"length\": 5}}");
  const Result<ScalarVolumeStream> refused =
      ScalarVolumeStream::create(path("lic.raw"), volume.dims, volume.geometry);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(refused.error().message.find("lic.json: exists and is not the JSON sidecar"),
            std::string::npos)
      << refused.error().message;
  EXPECT_EQ(test::readWhole(path("lic.json")), "{\"lic\": {\"length\": 5}}");
  EXPECT_EQ(listFolder(), (std::vector<std::string>{"lic.json"}));
  // An older sidecar is replaced.
  writeBytes("lic.json", "{\"dims\": [1, 1, 1], \"components\": 1, \"bytes\": 4}\n");
  Result<ScalarVolumeStream> stream =
      ScalarVolumeStream::create(path("lic.raw"), volume.dims, volume.geometry);
  ASSERT_TRUE(stream.ok()) << stream.error().message;
  ASSERT_TRUE(stream->write(Dims(0), volume.dims, volume.values.data()).ok());
  ASSERT_TRUE(stream->finish().ok());
  EXPECT_NE(test::readWhole(path("lic.json")).find("\"bytes\": 1260"), std::string::npos);
}

TEST_F(ScalarVolumeStreamTest, BadPathsAndBlocksAreErrorsNamingTheFile) {
  const ScalarVolume volume = makeVolume();
  writeBytes("file", "not a folder");
  for (const fs::path& target : {path("file") / "lic.nrrd", path("missing") / "lic.raw"}) {
    const Result<ScalarVolumeStream> stream =
        ScalarVolumeStream::create(target, volume.dims, volume.geometry);
    ASSERT_FALSE(stream.ok());
    EXPECT_EQ(stream.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(stream.error().message.find(target.string()), std::string::npos)
        << stream.error().message;
  }
  const Result<ScalarVolumeStream> png =
      ScalarVolumeStream::create(path("lic.png"), volume.dims, volume.geometry);
  ASSERT_FALSE(png.ok());
  EXPECT_EQ(png.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(png.error().message.find("lic.png"), std::string::npos);
  EXPECT_NE(png.error().message.find("only as .nrrd, .vti or .raw"), std::string::npos);

  Result<ScalarVolumeStream> stream =
      ScalarVolumeStream::create(path("lic.nrrd"), volume.dims, volume.geometry);
  ASSERT_TRUE(stream.ok());
  const std::vector<float> values(8, 1.0f);
  const Result<void> outside = stream->write({8, 0, 0}, {2, 2, 2}, values.data());
  ASSERT_FALSE(outside.ok());
  EXPECT_NE(outside.error().message.find("lic.nrrd"), std::string::npos);
  EXPECT_NE(outside.error().message.find("does not lie inside"), std::string::npos);
  const Result<void> past = stream->writeRun(voxelCount(volume.dims) - 4, values.data(), 8);
  ASSERT_FALSE(past.ok());
  EXPECT_NE(past.error().message.find("lic.nrrd"), std::string::npos);
  EXPECT_NE(past.error().message.find("does not lie inside"), std::string::npos)
      << past.error().message;
  // Nothing outside was counted: the grid written whole finishes, and nothing comes after.
  ASSERT_TRUE(stream->writeRun(0, volume.values.data(), volume.values.size()).ok());
  ASSERT_TRUE(stream->finish().ok());
  EXPECT_FALSE(stream->writeRun(0, values.data(), 1).ok());

  // A mask that is not the grid's.
  ScalarVolume masked = makeVolume();
  masked.drawn.assign(masked.values.size() - 1, 1);
  const Result<void> mask = writeScalarVolumeFile(path("masked.nrrd"), ScalarFileFormat::Nrrd,
                                                  masked, {.hidden = HiddenVoxels::AsNaN});
  ASSERT_FALSE(mask.ok());
  EXPECT_NE(mask.error().message.find("its mask has 314 flags for its 315 voxels"),
            std::string::npos)
      << mask.error().message;
  EXPECT_FALSE(fs::exists(path("masked.nrrd")));
}

// The tests below read files back: readers note their files as inputs of the run (by inode,
// which a later file may reuse), so they come after those above that check the input guard.

TEST_F(ScalarVolumeStreamTest, VtiWrittenInBlocksReadsBackThroughTheVtiReaders) {
  const ScalarVolume volume = makeVolume();
  Result<ScalarVolumeStream> stream =
      ScalarVolumeStream::create(path("lic.vti"), volume.dims, volume.geometry, "speed");
  ASSERT_TRUE(stream.ok()) << stream.error().message;
  for (auto it = kBlocks.rbegin(); it != kBlocks.rend(); ++it)
    ASSERT_TRUE(writeBlockAsRuns(*stream, volume, it->first, it->second).ok());
  ASSERT_TRUE(stream->finish().ok());
  const auto expectValues = [&](const std::vector<float>& values) {
    ASSERT_EQ(values.size(), volume.values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i == 40) {
        EXPECT_TRUE(std::isnan(values[i]));
      } else {
        EXPECT_EQ(values[i], volume.values[i]) << i;
      }
    }
  };
  const Result<ScalarVolume> read = readScalarVti(path("lic.vti"));
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->dims, volume.dims);
  EXPECT_EQ(read->geometry, volume.geometry);
  expectValues(read->values);
  const Result<PointScalars> scalars = readPointScalarsVti(path("lic.vti"), "speed");
  ASSERT_TRUE(scalars.ok()) << scalars.error().message;
  EXPECT_EQ(scalars->dims, volume.dims);
  expectValues(scalars->values);
}

// Sparsity's hidden voxels are NaN in every format, whichever thread wrote their run, and only
// they: runs of 16 voxels, some with hidden voxels and some without.
TEST_F(ScalarVolumeStreamTest, HiddenVoxelsAreNaNInEveryFormat) {
  ScalarVolume volume = makeVolume();
  volume.values[40] = 0.5f;
  volume.drawn.assign(volume.values.size(), 1);
  for (const std::size_t i : {0, 17, 18, 40, 99, 200, 314}) volume.drawn[i] = 0;
  const ScalarVolume kept = volume;
  for (const Format& format : kFormats) {
    SCOPED_TRACE(format.extension);
    const fs::path file = path(std::string("lic") + format.extension);
    const Result<void> written = writeScalarVolumeFile(
        file, format.format, volume, {.hidden = HiddenVoxels::AsNaN, .runBytes = 64});
    ASSERT_TRUE(written.ok()) << written.error().message;
    std::vector<float> values;
    if (format.format == ScalarFileFormat::Nrrd) {
      const Result<ScalarVolume> read = readScalarNrrd(file);
      ASSERT_TRUE(read.ok()) << read.error().message;
      values = read->values;
    } else if (format.format == ScalarFileFormat::Vti) {
      const Result<ScalarVolume> read = readScalarVti(file);
      ASSERT_TRUE(read.ok()) << read.error().message;
      values = read->values;
    } else {
      const std::string bytes = test::readWhole(file);
      ASSERT_EQ(bytes.size(), volume.values.size() * sizeof(float));
      values.resize(volume.values.size());
      std::memcpy(values.data(), bytes.data(), bytes.size());  // little endian, as the host
    }
    ASSERT_EQ(values.size(), volume.values.size());
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (volume.drawn[i] == 0) {
        EXPECT_TRUE(std::isnan(values[i])) << i;
      } else {
        EXPECT_EQ(values[i], volume.values[i]) << i;
      }
    }
    // In runs of the default size (one here), the same file.
    const fs::path once = path(std::string("once") + format.extension);
    ASSERT_TRUE(
        writeScalarVolumeFile(once, format.format, volume, {.hidden = HiddenVoxels::AsNaN}).ok());
    EXPECT_EQ(test::readWhole(once), test::readWhole(file));
  }
  // The volume itself is untouched, and without AsNaN its values are written as they are.
  EXPECT_EQ(bytesOf(volume.values, std::endian::native), bytesOf(kept.values, std::endian::native));
  ASSERT_TRUE(
      writeScalarVolumeFile(path("computed.raw"), ScalarFileFormat::Raw, volume, {.runBytes = 64})
          .ok());
  EXPECT_EQ(test::readWhole(path("computed.raw")), bytesOf(volume.values, std::endian::little));
}

}  // namespace
}  // namespace lic3d
