// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shared by the command-line tests (test_cli.cpp, test_cli_files.cpp, test_cli_time.cpp): one
// fixture that runs the lic3d executable in the test's folder, so gtest sees one CliTest suite,
// and what they read back from the PNGs it writes.

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>

#include "core/error.h"
#include "core/session.h"
#include "png_read.h"
#include "test_support.h"

namespace lic3d::test {

struct CommandRun {
  int status = -1;
  std::string output;  // stdout and stderr together, or the one stream asked for
};

// Which of lic3d's output streams a run captures.
enum class Streams { Both, StdoutOnly, StderrOnly };

class CliTest : public test::TempFolderTest {
 protected:
  CommandRun run(const std::string& args, const std::string& environment = "",
                 Streams streams = Streams::Both) const {
    const char* redirect = streams == Streams::Both         ? " 2>&1"
                           : streams == Streams::StdoutOnly ? " 2>/dev/null"
                                                            : " 2>&1 >/dev/null";
    return shell(environment + " '" + LIC3D_EXECUTABLE + "' " + args + redirect);
  }

  // A shell command line in the test's folder; what it prints, and its status.
  CommandRun shell(const std::string& line) const {
    const std::string command = "cd '" + folder().string() + "' && " + line;
    CommandRun result;
    FILE* pipe = popen(command.c_str(), "r");
    if (!pipe) return result;
    std::array<char, 4096> buffer;
    std::size_t n;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
      result.output.append(buffer.data(), n);
    const int raw = pclose(pipe);
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
    return result;
  }
};

// Width and height from a PNG's IHDR chunk.
inline std::pair<int, int> pngSize(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::array<unsigned char, 24> header{};
  in.read(reinterpret_cast<char*>(header.data()), header.size());
  if (!in || header[1] != 'P' || header[2] != 'N' || header[3] != 'G') return {0, 0};
  auto be32 = [&](int at) {
    return (header[at] << 24) | (header[at + 1] << 16) | (header[at + 2] << 8) | header[at + 3];
  };
  return {be32(16), be32(20)};
}

// The session stored in a PNG written by lic3d.
inline Result<Session> sessionInPng(const std::filesystem::path& file) {
  const test::DecodedPng png = test::decodePng(file);
  const auto text = png.text.find("lic3d-session");
  if (!png.ok || text == png.text.end()) return inputError(file.string() + ": no lic3d-session");
  return sessionFromJson(text->second, file.string());
}

}  // namespace lic3d::test
