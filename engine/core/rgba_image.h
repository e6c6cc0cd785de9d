// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// An 8-bit RGBA picture in memory, rows top to bottom (io/png_writer.h writes it).

#include <cstdint>
#include <glm/vec4.hpp>
#include <vector>

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

}  // namespace lic3d
