// SPDX-License-Identifier: BSD-3-Clause
#include "test_support.h"

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>

namespace lic3d::test {

namespace fs = std::filesystem;

fs::path dataFolder() {
  if (const char* folder = std::getenv("LIC3D_TEST_DATA"); folder && *folder) return folder;
  return fs::path(__FILE__).parent_path().parent_path() / "assets" / "data";
}

std::string readWhole(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string deflateBytes(const std::string& data, int windowBits) {
  z_stream zs{};
  EXPECT_EQ(deflateInit2(&zs, 6, Z_DEFLATED, windowBits, 8, Z_DEFAULT_STRATEGY), Z_OK);
  std::string out(deflateBound(&zs, static_cast<uLong>(data.size())) + 32, '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data.data()));
  zs.avail_in = static_cast<uInt>(data.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(deflate(&zs, Z_FINISH), Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

std::string shortNumberPreset(int points) {
  std::mt19937 random(11);
  const auto digit = [&] { return "0." + std::to_string(random() % 10); };
  std::string colours, opacities;
  for (int i = 0; i < points; ++i) {
    char x[32];
    std::snprintf(x, sizeof x, "%.4g", i / static_cast<double>(points - 1));
    const std::string comma = i + 1 < points ? "," : "";
    colours += std::string(x) + "," + digit() + "," + digit() + "," + digit() + comma;
    opacities += std::string(x) + "," + digit() + ",0.5,0" + comma;
  }
  return R"([{"Name":"script","RGBPoints":[)" + colours + R"(],"Points":[)" + opacities + "]}]";
}

std::string deflateZeros(std::uint64_t count) {
  z_stream zs{};
  EXPECT_EQ(deflateInit(&zs, Z_BEST_SPEED), Z_OK);
  const std::string zeros(1 << 20, '\0');
  std::string out, buffer(1 << 16, '\0');
  int status = Z_OK;
  while (status != Z_STREAM_END) {
    if (zs.avail_in == 0 && count > 0) {
      const std::uint64_t take = std::min<std::uint64_t>(count, zeros.size());
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(zeros.data()));
      zs.avail_in = static_cast<uInt>(take);
      count -= take;
    }
    zs.next_out = reinterpret_cast<Bytef*>(buffer.data());
    zs.avail_out = static_cast<uInt>(buffer.size());
    status = deflate(&zs, count == 0 ? Z_FINISH : Z_NO_FLUSH);
    EXPECT_TRUE(status == Z_OK || status == Z_STREAM_END || status == Z_BUF_ERROR) << status;
    out.append(buffer.data(), buffer.size() - zs.avail_out);
  }
  deflateEnd(&zs);
  return out;
}

std::string withPngChunk(const std::string& png, const std::string& type, const std::string& data) {
  const auto bigEndian = [](std::uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  const std::string body = type + data;
  const auto crc = static_cast<std::uint32_t>(
      crc32(0, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size())));
  const std::size_t afterHeader = 8 + 4 + 4 + 13 + 4;  // signature, IHDR's length, type, data, CRC
  return png.substr(0, afterHeader) + bigEndian(static_cast<std::uint32_t>(data.size())) + body +
         bigEndian(crc) + png.substr(afterHeader);
}

double peakMemoryGrowthMiB(const std::function<void()>& body) {
  // The child reports its resident set at the start through a pipe; wait4 gives its peak.
  int fds[2];
  if (::pipe(fds) != 0) return -1.0;
  const pid_t child = ::fork();
  if (child == 0) {
    long pages = 0;
    std::ifstream("/proc/self/statm") >> pages >> pages;
    const long startKiB = pages * (::sysconf(_SC_PAGESIZE) / 1024);
    (void)!::write(fds[1], &startKiB, sizeof startKiB);
    body();
    ::_exit(0);
  }
  ::close(fds[1]);
  long startKiB = 0;
  const bool reported = ::read(fds[0], &startKiB, sizeof startKiB) == sizeof startKiB;
  ::close(fds[0]);
  int status = 0;
  struct rusage usage {};
  ::wait4(child, &status, 0, &usage);
  if (!reported || !WIFEXITED(status) || WEXITSTATUS(status) != 0) return -1.0;
  return static_cast<double>(usage.ru_maxrss - startKiB) / 1024.0;
}

void TempFolderTest::SetUp() {
  const ::testing::TestInfo* info = ::testing::UnitTest::GetInstance()->current_test_info();
  std::string name = std::string("lic3d_") + info->test_suite_name() + "_" + info->name();
  for (char& c : name)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  dir_ = fs::temp_directory_path() / (name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir_);
  fs::create_directories(dir_);
}

void TempFolderTest::TearDown() {
  std::error_code ignored;
  fs::remove_all(dir_, ignored);
}

fs::path TempFolderTest::writeBytes(const std::string& name, const std::string& bytes) const {
  const fs::path target = path(name);
  std::ofstream out(target, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  return target;
}

std::vector<std::string> TempFolderTest::listFolder() const {
  std::vector<std::string> names;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_))
    names.push_back(entry.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace lic3d::test
