// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Reads PNG files back with libpng, for the tests that measure images.

#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace lic3d::test {

// What libpng reads back from a file.
struct DecodedPng {
  bool ok = false;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  int bitDepth = 0;
  int colorType = 0;
  std::vector<std::uint8_t> bytes;  // rows as stored: big-endian samples for 16 bits
  std::map<std::string, std::string> text;
  std::map<std::string, int> compression;  // per key: tEXt (-1) or iTXt (1)
  std::vector<unsigned char*> rows;  // here, not in decodeInto, so a longjmp skips no destructor
};

// ok is false when libpng cannot read the file.
DecodedPng decodePng(const std::filesystem::path& path);

// An 8-bit RGBA PNG's pixels (width * height * 4), or empty if the file is anything else.
struct RgbaPixels {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba;
};
RgbaPixels readRgbaPng(const std::filesystem::path& path);

}  // namespace lic3d::test
