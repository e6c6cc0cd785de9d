#pragma once
// An 8-bit RGBA picture in memory (rows top to bottom) and its PNG files.

#include <cstdint>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include <glm/vec4.hpp>

#include "error.h"

namespace lic3d {

struct RgbaImage {
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> pixels;  // width * height * 4

  glm::u8vec4 at(int x, int y) const {
    const std::size_t i = 4 * (static_cast<std::size_t>(y) * width + x);
    return {pixels[i], pixels[i + 1], pixels[i + 2], pixels[i + 3]};
  }
};

// Key/value pairs stored in the PNG as text chunks (the parameters that made the picture): tEXt
// for ASCII values, iTXt (UTF-8) for others. Keys are PNG keywords: 1 to 79 printable ASCII
// characters, no leading, trailing or double spaces; values hold no NUL byte.
using PngText = std::vector<std::pair<std::string, std::string>>;

// 8-bit RGBA, encoded by libpng in memory and written through writeFileAtomically, so a failure
// never leaves a partial PNG. A bad image or text is InvalidInput; an encoder failure is Runtime.
Result<void> writePng(const std::filesystem::path& path, const RgbaImage& image,
                      const PngText& text = {});

// 16-bit grey (the LIC slice at full precision), `values` row by row from the top, stored big
// endian as PNG requires.
Result<void> writePngGray16(const std::filesystem::path& path, int width, int height,
                            const std::vector<std::uint16_t>& values, const PngText& text = {});

}  // namespace lic3d
