// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shared by the test suites: the real-data folder and a fixture with a private scratch folder.

#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace lic3d::test {

// assets/data: LIC3D_TEST_DATA (set by test_environment.cpp), else relative to this source file.
std::filesystem::path dataFolder();

std::string readWhole(const std::filesystem::path& file);

// `data` as one zlib stream (windowBits 15) or gzip stream (15 + 16), as VTK and teem write them.
std::string deflateBytes(const std::string& data, int windowBits);

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
