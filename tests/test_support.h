// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shared by the test suites: the real-data folder and a fixture with a private scratch folder.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/volume.h"

namespace lic3d::test {

// assets/data: LIC3D_TEST_DATA (set by test_environment.cpp), else relative to this source file.
std::filesystem::path dataFolder();

std::string readWhole(const std::filesystem::path& file);

// Values as bytes in the given byte order.
template <class T>
std::string bytesOf(const std::vector<T>& values, std::endian order) {
  std::string bytes(values.size() * sizeof(T), '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  if (order != std::endian::native)
    for (std::size_t i = 0; i < values.size(); ++i)
      std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(i * sizeof(T)),
                   bytes.begin() + static_cast<std::ptrdiff_t>((i + 1) * sizeof(T)));
  return bytes;
}

// The same grid, geometry and vectors, bit for bit.
inline void expectSameField(const VectorField& actual, const VectorField& expected) {
  EXPECT_EQ(actual.dims, expected.dims);
  EXPECT_EQ(actual.geometry, expected.geometry);
  ASSERT_EQ(actual.vectors.size(), expected.vectors.size());
  for (std::size_t i = 0; i < expected.vectors.size(); ++i)
    ASSERT_EQ(actual.vectors[i], expected.vectors[i]) << "voxel " << i;
}

// `result` is an input error whose message names `file` and contains `fragment`.
template <class T>
void expectInputError(const Result<T>& result, const std::filesystem::path& file,
                      const std::string& fragment) {
  ASSERT_FALSE(result.ok()) << "expected an error containing '" << fragment << "'";
  const std::string& message = result.error().message;
  EXPECT_EQ(result.error().kind, ErrorKind::InvalidInput) << message;
  EXPECT_NE(message.find(file.filename().string()), std::string::npos) << message;
  EXPECT_NE(message.find(fragment), std::string::npos)
      << "'" << fragment << "' not in: " << message;
}

// `data` as one zlib stream (windowBits 15) or gzip stream (15 + 16), as VTK and teem write them.
std::string deflateBytes(const std::string& data, int windowBits);
// A ParaView colour-map preset of `points` colour and opacity points with short numbers
// ("0.1234,0.3,0.5,0.9"), as a script writes one: about 36 bytes a point.
std::string shortNumberPreset(int points);

// A zlib stream of `count` zero bytes, deflated a MiB at a time: a bomb of any size in little
// memory.
std::string deflateZeros(std::uint64_t count);
// The PNG file `png` with one more chunk, of `type` and `data`, after its header chunk (IHDR): a
// text chunk as another program (or an older lic3d) writes it.
std::string withPngChunk(const std::string& png, const std::string& type, const std::string& data);

// Runs `body` in a forked child and returns by how much the child's peak resident set grew over
// what it had when it started, in MiB: what one call costs in memory, apart from the test process.
double peakMemoryGrowthMiB(const std::function<void()>& body);

// Each test gets its own folder, removed afterwards, so a failure leaves nothing that could
// confuse another test.
class TempFolderTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;

  const std::filesystem::path& folder() const { return dir_; }
  std::filesystem::path path(const std::string& name) const { return dir_ / name; }
  std::filesystem::path writeBytes(const std::string& name, const std::string& bytes) const;
  // The names in the folder, sorted: a failed write must leave nothing, not even a temporary.
  std::vector<std::string> listFolder() const;

 private:
  std::filesystem::path dir_;
};

}  // namespace lic3d::test
