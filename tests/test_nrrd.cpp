// SPDX-License-Identifier: BSD-3-Clause
// NRRD round trips through the writers, the file helpers behind them, and readVectorField /
// readNoise dispatch; what the readers accept and refuse is in test_nrrd_read.cpp.

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <stdexcept>
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

// --- Round trips --------------------------------------------------------------------------------

// An output larger than the free space of its file system is refused before any work, with both
// numbers (exit status 3); one that fits passes.
TEST_F(NrrdTest, FreeSpaceIsCheckedAgainstTheOutputsSize) {
  EXPECT_TRUE(checkFreeSpace(path("small.nrrd"), 1).ok());
  const Result<void> huge = checkFreeSpace(path("huge.nrrd"), std::uint64_t{1} << 62);
  ASSERT_FALSE(huge.ok());
  EXPECT_EQ(huge.error().kind, ErrorKind::ResourceLimit);
  EXPECT_NE(huge.error().message.find("huge.nrrd: the output takes 4611686018427387904 bytes"),
            std::string::npos)
      << huge.error().message;
  EXPECT_NE(huge.error().message.find("bytes free"), std::string::npos);
  EXPECT_FALSE(fs::exists(path("huge.nrrd")));
}

// Outputs on one file system are summed: two that fit one by one may not fit together.
TEST_F(NrrdTest, FreeSpaceOfOutputsSharingAFileSystemIsSummed) {
  const std::uint64_t half = std::uint64_t{1} << 62;
  ASSERT_FALSE(checkFreeSpace(path("a.png"), half).ok());  // more than any disk holds
  const Result<void> both = checkFreeSpace({{path("a.png"), half}, {path("b.png"), half}});
  ASSERT_FALSE(both.ok());
  EXPECT_EQ(both.error().kind, ErrorKind::ResourceLimit);
  EXPECT_NE(both.error().message.find(
                "a.png and 1 other output(s) on its file system: they take 9223372036854775808 "
                "bytes"),
            std::string::npos)
      << both.error().message;
  EXPECT_TRUE(checkFreeSpace({{path("a.png"), 1}, {path("b.png"), 1}}).ok());
}

TEST_F(NrrdTest, VectorFieldRoundTripKeepsValuesAndGeometry) {
  // Spacings like 0.1 and 1/3 have no short decimal form: the header must still round-trip them.
  const VectorField field = makeField({5, 4, 3}, {{0.1, 1.0 / 3.0, 2.0}, {-1.5, 2.25, 1e-3}});
  const fs::path file = path("field.nrrd");
  ASSERT_TRUE(writeVectorFieldNrrd(file, field).ok());
  EXPECT_TRUE(readWhole(file).starts_with("NRRD0004\n# written by lic3d\n"));
  const Result<VectorField> read = readVectorFieldNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  expectSameField(*read, field);
}

TEST_F(NrrdTest, VectorFieldRoundTripOfOneVoxelAndOfLargeGrid) {
  for (const Dims dims : {Dims{1, 1, 1}, Dims{70, 60, 50}}) {
    const VectorField field = makeField(dims, {});
    const fs::path file = path("field.nrrd");
    ASSERT_TRUE(writeVectorFieldNrrd(file, field).ok());
    const Result<VectorField> read = readVectorFieldNrrd(file);
    ASSERT_TRUE(read.ok()) << read.error().message;
    expectSameField(*read, field);
  }
}

TEST_F(NrrdTest, ScalarVolumeIsWrittenAsDocumented) {
  ScalarVolume volume;
  volume.dims = {3, 2, 2};
  volume.geometry = {{0.5, 0.25, 2.0}, {-1.0, 0.0, 10.5}};
  for (int i = 0; i < 12; ++i) volume.values.push_back(static_cast<float>(i) / 11.0f);
  const fs::path file = path("lic.nrrd");
  ASSERT_TRUE(writeScalarNrrd(file, volume).ok());

  const std::string bytes = readWhole(file);
  const std::size_t end = bytes.find("\n\n");
  ASSERT_NE(end, std::string::npos);
  const std::string header = bytes.substr(0, end + 1);
  for (const char* line :
       {"NRRD0004\n", "# written by lic3d\n", "type: float\n", "dimension: 3\n",
        "space dimension: 3\n", "sizes: 3 2 2\n",
        "space directions: (0.5,0,0) (0,0.25,0) (0,0,2)\n", "endian: little\n",
        "labels: \"LIC\" \"y\" \"z\"\n", "encoding: raw\n", "space origin: (-1,0,10.5)\n"})
    EXPECT_NE(header.find(line), std::string::npos) << line << " not in:\n" << header;
  EXPECT_EQ(bytes.substr(end + 2), bytesOf(volume.values, std::endian::little));

  // The same file is valid float noise (values in [0,1] are kept exactly).
  const Result<NoiseVolume> noise = readNoiseNrrd(file);
  ASSERT_TRUE(noise.ok()) << noise.error().message;
  EXPECT_EQ(noise->dims, volume.dims);
  ASSERT_EQ(noise->type, NoiseType::Float32);
  for (std::size_t i = 0; i < volume.values.size(); ++i)
    EXPECT_EQ(noise->value(i), volume.values[i]);
}

TEST_F(NrrdTest, NoiseRoundTripKeepsType) {
  for (const NoiseType type : {NoiseType::UInt8, NoiseType::UInt16, NoiseType::Float32}) {
    NoiseVolume noise;
    noise.dims = {4, 3, 2};
    noise.type = type;
    noise.bytes.resize(voxelCount(noise.dims) * bytesPerValue(type));
    for (std::size_t i = 0; i < voxelCount(noise.dims); ++i) {
      if (type == NoiseType::UInt8) noise.bytes[i] = static_cast<std::uint8_t>(i * 37);
      if (type == NoiseType::UInt16) {
        const std::uint16_t v = static_cast<std::uint16_t>(i * 2731);
        std::memcpy(noise.bytes.data() + 2 * i, &v, 2);
      }
      if (type == NoiseType::Float32) {
        const float v = static_cast<float>(i) / 23.0f;
        std::memcpy(noise.bytes.data() + 4 * i, &v, 4);
      }
    }
    const fs::path file = path("noise.nrrd");
    ASSERT_TRUE(writeNoiseNrrd(file, noise).ok());
    const Result<NoiseVolume> read = readNoise(file);
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(read->dims, noise.dims);
    EXPECT_EQ(read->type, noise.type);
    EXPECT_EQ(read->bytes, noise.bytes);
  }
}

TEST_F(NrrdTest, WritersRefuseInconsistentVolumesAndLeaveNoFile) {
  VectorField field = makeField({2, 2, 2}, {});
  field.vectors.pop_back();
  const fs::path file = path("bad.nrrd");
  expectInputError(writeVectorFieldNrrd(file, field), file, "needs 8");
  ScalarVolume volume;
  volume.dims = {0, 1, 1};
  expectInputError(writeScalarNrrd(file, volume), file, "empty");
  field = makeField({2, 2, 2}, {{1.0, 0.0, 1.0}, {0.0, 0.0, 0.0}});
  expectInputError(writeVectorFieldNrrd(file, field), file, "spacing");
  EXPECT_TRUE(listFolder().empty());
}

// --- Scalar and RGBA volumes --------------------------------------------------------------------

TEST_F(NrrdTest, ScalarVolumeRoundTripKeepsNaN) {
  ScalarVolume volume;
  volume.dims = {4, 3, 2};
  volume.geometry = {{0.1, 0.2, 0.3}, {-5.0, 1.0 / 3.0, 7.0}};
  for (int i = 0; i < 24; ++i) volume.values.push_back(static_cast<float>(i) * 0.37f - 2.0f);
  volume.values[5] = std::numeric_limits<float>::quiet_NaN();
  const fs::path file = path("lic.nrrd");
  ASSERT_TRUE(writeScalarNrrd(file, volume).ok());
  const Result<ScalarVolume> read = readScalarNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->dims, volume.dims);
  EXPECT_EQ(read->geometry, volume.geometry);
  ASSERT_EQ(read->values.size(), volume.values.size());
  for (std::size_t i = 0; i < volume.values.size(); ++i) {
    if (i == 5) {
      EXPECT_TRUE(std::isnan(read->values[i]));
    } else {
      EXPECT_EQ(read->values[i], volume.values[i]) << i;
    }
  }
  // Double volumes are read too; vector fields are not scalar volumes.
  const fs::path doubles =
      writeBytes("d.nrrd",
                 "NRRD0004\ntype: double\ndimension: 3\nsizes: 2 1 1\nendian: big\n"
                 "encoding: raw\n\n" +
                     bytesOf(std::vector<double>{0.25, -8.5}, std::endian::big));
  const Result<ScalarVolume> doubleRead = readScalarNrrd(doubles);
  ASSERT_TRUE(doubleRead.ok()) << doubleRead.error().message;
  EXPECT_EQ(doubleRead->values, (std::vector<float>{0.25f, -8.5f}));
  ASSERT_TRUE(writeVectorFieldNrrd(path("v.nrrd"), makeField({2, 2, 2}, {})).ok());
  expectInputError(readScalarNrrd(path("v.nrrd")), path("v.nrrd"), "dimension: expected 3");
}

TEST_F(NrrdTest, RgbaVolumeRoundTripAndHeader) {
  RgbaVolume volume;
  volume.dims = {3, 2, 2};
  volume.geometry = {{0.5, 1.5, 2.5}, {1.0, 2.0, -3.0}};
  for (std::size_t i = 0; i < 48; ++i) volume.rgba.push_back(static_cast<std::uint8_t>(i * 5));
  const fs::path file = path("colour.nrrd");
  ASSERT_TRUE(writeRgbaNrrd(file, volume).ok());
  const std::string bytes = readWhole(file);
  for (const char* line :
       {"type: uchar\n", "dimension: 4\n", "sizes: 4 3 2 2\n",
        "kinds: RGBA-color domain domain domain\n", "labels: \"RGBA\" \"x\" \"y\" \"z\"\n",
        "space directions: none (0.5,0,0) (0,1.5,0) (0,0,2.5)\n", "space origin: (1,2,-3)\n"})
    EXPECT_NE(bytes.find(line), std::string::npos) << line;
  const Result<RgbaVolume> read = readRgbaNrrd(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->dims, volume.dims);
  EXPECT_EQ(read->geometry, volume.geometry);
  EXPECT_EQ(read->rgba, volume.rgba);
  volume.rgba.pop_back();
  expectInputError(writeRgbaNrrd(path("bad.nrrd"), volume), path("bad.nrrd"), "needs 48");
  EXPECT_FALSE(fs::exists(path("bad.nrrd")));
}

// --- File helpers -------------------------------------------------------------------------------

TEST_F(NrrdTest, WriteFileAtomicallyLeavesOnlyTheTarget) {
  const fs::path file = path("out.bin");
  const std::string content("bytes\0with a NUL", 16);
  ASSERT_TRUE(writeFileAtomically(file, content).ok());
  EXPECT_EQ(readWhole(file), content);
  EXPECT_EQ(listFolder(), std::vector<std::string>{"out.bin"});
  // Overwriting goes through the same temporary-then-rename path.
  ASSERT_TRUE(writeFileAtomically(file, [](std::ostream& out) {
                return static_cast<bool>(out << "second");
              }).ok());
  EXPECT_EQ(readWhole(file), "second");
  EXPECT_EQ(listFolder(), std::vector<std::string>{"out.bin"});
}

TEST_F(NrrdTest, FailedWriterLeavesNoTargetAndNoTemporaryFile) {
  const fs::path file = path("out.nrrd");
  const Result<void> result = writeFileAtomically(file, [](std::ostream& out) {
    out << "half of the content";
    return false;
  });
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find(file.string()), std::string::npos)
      << result.error().message;
  EXPECT_TRUE(listFolder().empty());

  // An existing file keeps its content when a later write fails.
  ASSERT_TRUE(writeFileAtomically(file, std::string_view("old")).ok());
  EXPECT_FALSE(writeFileAtomically(file, [](std::ostream&) { return false; }).ok());
  EXPECT_EQ(readWhole(file), "old");
  EXPECT_THROW((void)writeFileAtomically(file,
                                         [](std::ostream& out) -> bool {
                                           out << "partial";
                                           throw std::runtime_error("writer failed");
                                         }),
               std::runtime_error);
  EXPECT_EQ(readWhole(file), "old");
  EXPECT_EQ(listFolder(), std::vector<std::string>{"out.nrrd"});
}

// A signal during a write, a file-size limit and a name near the limit leave no temporary file
// behind and no half file under the real name (hardening, classes 8 and 9). Each case runs in a
// child process, which the signal ends.
TEST_F(NrrdTest, SignalsAndLimitsDuringAWriteLeaveNoTemporaryFile) {
  const auto inChild = [](const std::function<int()>& body) {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(body());
    int status = 0;
    ::waitpid(child, &status, 0);
    return status;
  };
  for (const int signal : {SIGTERM, SIGINT}) {
    const fs::path file = path("signalled.nrrd");
    const int status = inChild([&] {
      (void)writeFileAtomically(file, [&](std::ostream& out) {
        out << std::string(100000, 'x');
        out.flush();
        ::raise(signal);
        return true;
      });
      return 0;
    });
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal) << status;
    EXPECT_TRUE(listFolder().empty()) << signal;
  }
  // ulimit -f: the write fails (EFBIG) instead of SIGXFSZ killing the process.
  const int limited = inChild([&] {
    const struct rlimit limit { 4096, 4096 };
    ::setrlimit(RLIMIT_FSIZE, &limit);
    const Result<void> r = writeFileAtomically(path("big.nrrd"), std::string(1 << 20, 'x'));
    return r.ok() ? 0 : 7;
  });
  EXPECT_TRUE(WIFEXITED(limited) && WEXITSTATUS(limited) == 7) << limited;
  EXPECT_TRUE(listFolder().empty());
  // A 250-character name is written although ".name.tmp-PID-N" would be too long.
  const fs::path longName = path(std::string(246, 'n') + ".png");
  ASSERT_TRUE(writeFileAtomically(longName, std::string_view("content")).ok());
  EXPECT_EQ(readWhole(longName), "content");
  EXPECT_EQ(listFolder().size(), 1u);
}

TEST_F(NrrdTest, WriteFileAtomicallyReportsPathAndReason) {
  const fs::path missingFolder = path("no such folder") / "out.nrrd";
  Result<void> result = writeFileAtomically(missingFolder, std::string_view("x"));
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(result.error().message.find(missingFolder.string()), std::string::npos)
      << result.error().message;
  EXPECT_NE(result.error().message.find("No such file or directory"), std::string::npos)
      << result.error().message;

  // Renaming over a folder fails after the temporary file exists: it must be cleaned up.
  fs::create_directory(path("folder.nrrd"));
  result = writeFileAtomically(path("folder.nrrd"), std::string_view("x"));
  ASSERT_FALSE(result.ok());
  EXPECT_NE(result.error().message.find("folder.nrrd"), std::string::npos)
      << result.error().message;
  EXPECT_EQ(listFolder(), std::vector<std::string>{"folder.nrrd"});
  EXPECT_TRUE(fs::is_directory(path("folder.nrrd")));
}

TEST_F(NrrdTest, ReadFileHonoursTheLimitAndNamesTheFile) {
  const fs::path file = writeBytes("data.txt", "0123456789");
  Result<std::string> read = readFile(file, 10);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(*read, "0123456789");
  expectInputError(readFile(file, 9), file, "too large");
  expectInputError(readFile(path("missing.txt"), 100), path("missing.txt"),
                   "No such file or directory");
  fs::create_directory(path("folder"));
  expectInputError(readFile(path("folder"), 100), path("folder"), "not a regular file");
  // A FIFO without a writer must be refused, not waited on.
  ASSERT_EQ(::mkfifo(path("fifo.nrrd").c_str(), 0600), 0);
  expectInputError(readVectorFieldNrrd(path("fifo.nrrd")), path("fifo.nrrd"), "not a regular file");
  EXPECT_EQ(*readFile(writeBytes("empty.txt", ""), 0), "");
}

// --- Dispatch by extension ----------------------------------------------------------------------

TEST_F(NrrdTest, ReadVectorFieldDispatchesByExtension) {
  const VectorField field = makeField({2, 3, 4}, {});
  const fs::path file = path("FIELD.NRRD");
  ASSERT_TRUE(writeVectorFieldNrrd(file, field).ok());
  const Result<VectorField> read = readVectorField(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  expectSameField(*read, field);
  expectInputError(readVectorField(file, "velocity"), file, "applies only to .vtk and .vti files");

  const fs::path unknown = writeBytes("field.xyz", "whatever");
  expectInputError(
      readVectorField(unknown), unknown,
      "unsupported extension '.xyz' (supported: .vtk, .vti, .pvti, .nrrd, .nhdr, .raw)");
  const fs::path noExtension = writeBytes("field", "whatever");
  expectInputError(readVectorField(noExtension), noExtension, "no extension");
  expectInputError(readVectorField(path("missing.nrrd")), path("missing.nrrd"), "no such file");
  expectInputError(readVectorField(path("missing.vtk")), path("missing.vtk"), "no such file");
  fs::create_directory(path("folder.nrrd"));
  expectInputError(readVectorField(path("folder.nrrd")), path("folder.nrrd"), "directory");
  const fs::path detached = writeBytes("field.nhdr", "NRRD0004\n");
  expectInputError(readVectorField(detached), detached, "without the blank line");
}

TEST_F(NrrdTest, ReadNoiseTakesOnlyNrrd) {
  NoiseVolume noise;
  noise.dims = {2, 2, 2};
  noise.bytes.assign(8, 128);
  ASSERT_TRUE(writeNoiseNrrd(path("noise.nrrd"), noise).ok());
  const Result<NoiseVolume> read = readNoise(path("noise.nrrd"));
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->bytes, noise.bytes);
  const fs::path vtk = writeBytes("noise.vtk", "# vtk DataFile Version 3.0\n");
  expectInputError(readNoise(vtk), vtk, "supported: .nrrd");
  expectInputError(readNoise(path("missing.nrrd")), path("missing.nrrd"), "no such file");
}

}  // namespace
}  // namespace lic3d
