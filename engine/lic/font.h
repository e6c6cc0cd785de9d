// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The text of pictures (legends, titles, axes): DejaVu Sans, embedded in the binary at build time
// (cmake/EmbedFile.cmake), rasterized with stb_truetype and blended into RGBA images by its
// coverage, so edges are anti-aliased at any size. Sizes are the em in pixels.

#include <glm/vec4.hpp>
#include <string_view>

#include "core/rgba_image.h"

namespace lic3d {

// A line of text at a size: its line box is `width` (the pen's advance) by `height` (ascent plus
// descent), the baseline `ascent` below the box's top. Ink stays inside the box but for accents
// above capitals and the side bearings of italic-like glyphs, which DejaVu Sans's digits and
// Latin letters do not have.
struct TextExtent {
  int width = 0;
  int height = 0;
  int ascent = 0;
};
TextExtent measureText(std::string_view text, float size);

// Draws UTF-8 `text` with its line box's top-left at (x, y), each pixel blended with `color` by
// the glyph's coverage times color.a; what falls outside the image is cut off.
void drawText(RgbaImage& image, int x, int y, std::string_view text, glm::u8vec4 color, float size);

}  // namespace lic3d
