// SPDX-License-Identifier: BSD-3-Clause
#include "lic/font.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#define STB_TRUETYPE_IMPLEMENTATION
// Its functions file-local: Dear ImGui (the app) links its own copy of stb_truetype.
#define STBTT_STATIC
#include <stb_truetype.h>
#pragma GCC diagnostic pop

namespace lic3d {

// The bytes of the font file, made by cmake/EmbedFile.cmake.
extern const unsigned char kEmbeddedFont[];
extern const std::size_t kEmbeddedFontSize;

namespace {

const stbtt_fontinfo& font() {
  static const stbtt_fontinfo info = [] {
    stbtt_fontinfo f{};
    // The font is part of the program: one that does not load is a broken build.
    if (kEmbeddedFontSize == 0 ||
        !stbtt_InitFont(&f, kEmbeddedFont, stbtt_GetFontOffsetForIndex(kEmbeddedFont, 0))) {
      std::fprintf(stderr, "lic3d: the embedded font does not load (%zu bytes)\n",
                   kEmbeddedFontSize);
      std::abort();
    }
    return f;
  }();
  return info;
}

// The code points of UTF-8 text; a malformed sequence is U+FFFD.
std::vector<int> codePoints(std::string_view text) {
  std::vector<int> points;
  for (std::size_t i = 0; i < text.size();) {
    const auto byte = static_cast<unsigned char>(text[i]);
    const int length = byte < 0x80           ? 1
                       : (byte >> 5) == 0x6  ? 2
                       : (byte >> 4) == 0xE  ? 3
                       : (byte >> 3) == 0x1E ? 4
                                             : 0;
    int point = length == 1   ? byte
                : length == 2 ? byte & 0x1F
                : length == 3 ? byte & 0x0F
                              : byte & 0x07;
    bool valid = length > 0 && i + static_cast<std::size_t>(length) <= text.size();
    for (int k = 1; valid && k < length; ++k) {
      const auto next = static_cast<unsigned char>(text[i + static_cast<std::size_t>(k)]);
      valid = (next >> 6) == 0x2;
      point = (point << 6) | (next & 0x3F);
    }
    points.push_back(valid ? point : 0xFFFD);
    i += valid ? static_cast<std::size_t>(length) : 1;
  }
  return points;
}

struct Scaled {
  float scale = 0.0f;  // font units to pixels
  int ascent = 0;
  int descent = 0;
};

Scaled scaled(float size) {
  Scaled s;
  s.scale = stbtt_ScaleForMappingEmToPixels(&font(), std::max(size, 1.0f));
  int ascent = 0, descent = 0, gap = 0;
  stbtt_GetFontVMetrics(&font(), &ascent, &descent, &gap);
  s.ascent = static_cast<int>(std::ceil(static_cast<float>(ascent) * s.scale));
  s.descent = static_cast<int>(std::ceil(static_cast<float>(-descent) * s.scale));
  return s;
}

// Calls visit(glyph, pen x) for each glyph, the pen advanced with kerning; the pen's end.
template <class Visit>
float layOut(const std::vector<int>& points, float scale, Visit&& visit) {
  float pen = 0.0f;
  int previous = 0;
  for (const int point : points) {
    const int glyph = stbtt_FindGlyphIndex(&font(), point);
    if (previous != 0)
      pen += scale * static_cast<float>(stbtt_GetGlyphKernAdvance(&font(), previous, glyph));
    visit(glyph, pen);
    int advance = 0, bearing = 0;
    stbtt_GetGlyphHMetrics(&font(), glyph, &advance, &bearing);
    pen += scale * static_cast<float>(advance);
    previous = glyph;
  }
  return pen;
}

}  // namespace

TextExtent measureText(std::string_view text, float size) {
  const Scaled s = scaled(size);
  const float pen = layOut(codePoints(text), s.scale, [](int, float) {});
  return {static_cast<int>(std::ceil(pen)), s.ascent + s.descent, s.ascent};
}

void drawText(RgbaImage& image, int x, int y, std::string_view text, glm::u8vec4 color,
              float size) {
  const Scaled s = scaled(size);
  const int baseline = y + s.ascent;
  std::vector<unsigned char> coverage;
  layOut(codePoints(text), s.scale, [&](int glyph, float pen) {
    // The glyph at the pen's fraction of a pixel, so that spacing does not round to whole pixels.
    const float left = static_cast<float>(x) + pen;
    const float whole = std::floor(left);
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    stbtt_GetGlyphBitmapBoxSubpixel(&font(), glyph, s.scale, s.scale, left - whole, 0.0f, &x0, &y0,
                                    &x1, &y1);
    const int w = x1 - x0, h = y1 - y0;
    if (w <= 0 || h <= 0) return;
    coverage.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
    stbtt_MakeGlyphBitmapSubpixel(&font(), coverage.data(), w, h, w, s.scale, s.scale, left - whole,
                                  0.0f, glyph);
    const int ox = static_cast<int>(whole) + x0, oy = baseline + y0;
    for (int j = std::max(0, -oy); j < h && oy + j < image.height; ++j)
      for (int i = std::max(0, -ox); i < w && ox + i < image.width; ++i) {
        const float a = static_cast<float>(coverage[static_cast<std::size_t>(j * w + i)]) *
                        static_cast<float>(color.a) / (255.0f * 255.0f);
        if (a <= 0.0f) continue;
        std::uint8_t* p = &image.pixels[4 * (static_cast<std::size_t>(oy + j) * image.width +
                                             static_cast<std::size_t>(ox + i))];
        for (int k = 0; k < 3; ++k)
          p[k] = static_cast<std::uint8_t>(static_cast<float>(color[k]) * a +
                                           static_cast<float>(p[k]) * (1.0f - a) + 0.5f);
        p[3] = static_cast<std::uint8_t>(255.0f * a + static_cast<float>(p[3]) * (1.0f - a) + 0.5f);
      }
  });
}

}  // namespace lic3d
