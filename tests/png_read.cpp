// SPDX-License-Identifier: BSD-3-Clause
#include "png_read.h"

#include <png.h>

#include <csetjmp>
#include <cstring>

#include "test_support.h"

namespace lic3d::test {
namespace {

struct ReadState {
  const std::string* data;
  std::size_t position;
};

void readBytes(png_structp png, png_bytep out, png_size_t length) {
  auto* state = static_cast<ReadState*>(png_get_io_ptr(png));
  if (state->position + length > state->data->size()) png_error(png, "read past the end");
  std::memcpy(out, state->data->data() + state->position, length);
  state->position += length;
}

// Out of line, so that the strings it makes live outside decodeInto's frame: a longjmp there
// must not skip their destructors (GCC's -Wclobbered).
[[gnu::noinline]] void copyTexts(png_structp png, png_infop info, DecodedPng& out) {
  png_textp texts = nullptr;
  const int count = png_get_text(png, info, &texts, nullptr);
  for (int i = 0; i < count; ++i) {
    out.text[texts[i].key] = std::string(
        texts[i].text, texts[i].itxt_length > 0 ? texts[i].itxt_length : texts[i].text_length);
    out.compression[texts[i].key] = texts[i].compression;
  }
}

// Plain C between setjmp and return, as libpng's longjmp requires.
bool decodeInto(const std::string& file, ReadState& state, DecodedPng& out) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  state.data = &file;
  state.position = 0;
  png_set_read_fn(png, &state, readBytes);
  png_read_info(png, info);
  int interlace = 0;
  png_get_IHDR(png, info, &out.width, &out.height, &out.bitDepth, &out.colorType, &interlace,
               nullptr, nullptr);
  const png_size_t rowBytes = png_get_rowbytes(png, info);
  out.bytes.resize(rowBytes * out.height);
  out.rows.resize(out.height);
  for (std::uint32_t y = 0; y < out.height; ++y) out.rows[y] = out.bytes.data() + y * rowBytes;
  png_read_image(png, out.rows.data());
  png_read_end(png, info);
  copyTexts(png, info, out);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

DecodedPng decodePng(const std::filesystem::path& path) {
  const std::string file = test::readWhole(path);
  DecodedPng decoded;
  ReadState state{};
  decoded.ok = decodeInto(file, state, decoded);
  return decoded;
}

RgbaPixels readRgbaPng(const std::filesystem::path& path) {
  const DecodedPng png = decodePng(path);
  RgbaPixels out;
  if (!png.ok || png.bitDepth != 8 || png.colorType != PNG_COLOR_TYPE_RGB_ALPHA) return out;
  out.width = static_cast<int>(png.width);
  out.height = static_cast<int>(png.height);
  out.rgba = png.bytes;
  return out;
}

}  // namespace lic3d::test
