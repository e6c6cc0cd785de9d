// SPDX-License-Identifier: BSD-3-Clause
#include "io/png_writer.h"

#include <png.h>

#include <algorithm>
#include <cerrno>
#include <csetjmp>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <string>

#include "core/stage_times.h"
#include "core/text.h"
#include "io/file_util.h"

// libpng is linked statically (like zlib) so the binary needs nothing beyond libvulkan, libstdc++
// and libc. libpng reports errors by longjmp; the encoder below holds no C++ object across
// setjmp, so no destructor is ever skipped.

namespace lic3d {

namespace {
constexpr int kPngCompressionLevel = 2;
// Text from this length on is compressed (zTXt, or compressed iTXt): a session with a large
// transfer function shrinks several times, and short values stay plain tEXt.
constexpr std::size_t kCompressedTextBytes = 1024;
}  // namespace
namespace {

struct EncodeState {
  std::string* output = nullptr;
  char error[200] = {};
  char warning[200] = {};  // the first about a text chunk, which tells why libpng left it out
};

void onError(png_structp png, png_const_charp message) {
  auto* state = static_cast<EncodeState*>(png_get_error_ptr(png));
  std::strncpy(state->error, message ? message : "unknown error", sizeof state->error - 1);
  png_longjmp(png, 1);
}

void onWarning(png_structp png, png_const_charp message) {
  auto* state = static_cast<EncodeState*>(png_get_error_ptr(png));
  // libpng names the chunk first ("zTXt: ...").
  const bool text =
      message && (std::strncmp(message, "tEXt", 4) == 0 || std::strncmp(message, "zTXt", 4) == 0 ||
                  std::strncmp(message, "iTXt", 4) == 0);
  if (text && state->warning[0] == '\0')
    std::strncpy(state->warning, message, sizeof state->warning - 1);
}

void onWrite(png_structp png, png_bytep data, png_size_t length) {
  auto* state = static_cast<EncodeState*>(png_get_io_ptr(png));
  bool failed = false;
  try {
    state->output->append(reinterpret_cast<const char*>(data), length);
  } catch (const std::bad_alloc&) {
    failed = true;
  }
  // Outside the catch block: png_error longjmps, and must not leave a live exception behind.
  if (failed) png_error(png, "out of memory");
}

void onFlush(png_structp) {}

struct PngFormat {
  int width;
  int height;
  int bitDepth;
  int colorType;
};

// Encodes into *state.output; false with state.error set on failure. Plain C data only between
// setjmp and the end (see the note at the top).
bool encode(EncodeState& state, const PngFormat& format, png_bytepp rows, png_textp texts,
            int textCount) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &state, onError, onWarning);
  if (!png) {
    std::strncpy(state.error, "cannot create the PNG encoder", sizeof state.error - 1);
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info) {
    png_destroy_write_struct(&png, nullptr);
    std::strncpy(state.error, "cannot create the PNG header", sizeof state.error - 1);
    return false;
  }
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_write_struct(&png, &info);
    return false;
  }
  png_set_write_fn(png, &state, onWrite, onFlush);
  png_set_IHDR(png, info, static_cast<png_uint_32>(format.width),
               static_cast<png_uint_32>(format.height), format.bitDepth, format.colorType,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // zlib level 2: a 1024² LIC picture took 92 ms and 501 KiB against 320 ms and 397 KiB at the
  // default level 6 (level 1: 86 ms, 525 KiB; 9: 3.3 s, 367 KiB), measured on the build machine.
  png_set_compression_level(png, kPngCompressionLevel);
  if (textCount > 0) png_set_text(png, info, texts, textCount);
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

bool isValidUtf8(const std::string& text) {
  std::size_t i = 0;
  while (i < text.size()) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    const std::size_t length = c < 0x80         ? 1
                               : (c >> 5) == 6  ? 2
                               : (c >> 4) == 14 ? 3
                               : (c >> 3) == 30 ? 4
                                                : 0;
    if (length == 0 || i + length > text.size()) return false;
    for (std::size_t k = 1; k < length; ++k)
      if ((static_cast<unsigned char>(text[i + k]) >> 6) != 2) return false;
    i += length;
  }
  return true;
}

// PNG keywords (PNG spec 11.3.4.2): 1-79 Latin-1 characters without leading, trailing or
// consecutive spaces; lic3d keeps to printable ASCII.
bool isValidKeyword(const std::string& key) {
  if (key.empty() || key.size() > 79 || key.front() == ' ' || key.back() == ' ') return false;
  for (std::size_t i = 0; i < key.size(); ++i) {
    if (key[i] < 0x20 || key[i] > 0x7e) return false;
    if (key[i] == ' ' && key[i + 1] == ' ') return false;
  }
  return true;
}

Result<std::vector<png_text>> makeTexts(const std::filesystem::path& path, const PngText& text) {
  std::vector<png_text> texts;
  for (const auto& [key, value] : text) {
    if (!isValidKeyword(key))
      return inputError("cannot write '" + path.string() + "': the text key " +
                        quoteForMessage(key) +
                        " is not a PNG keyword (1 to 79 printable ASCII characters, no leading, "
                        "trailing or double spaces)");
    if (value.find('\0') != std::string::npos || !isValidUtf8(value))
      return inputError("cannot write '" + path.string() + "': the text of " +
                        quoteForMessage(key) + " holds a NUL byte or is not UTF-8");
    const bool ascii = std::all_of(value.begin(), value.end(),
                                   [](char c) { return static_cast<unsigned char>(c) < 0x80; });
    const bool compress = value.size() >= kCompressedTextBytes;
    png_text entry{};
    // tEXt and zTXt are Latin-1, so anything beyond ASCII goes into an iTXt chunk (UTF-8).
    entry.compression = ascii ? (compress ? PNG_TEXT_COMPRESSION_zTXt : PNG_TEXT_COMPRESSION_NONE)
                              : (compress ? PNG_ITXT_COMPRESSION_zTXt : PNG_ITXT_COMPRESSION_NONE);
    entry.key = const_cast<png_charp>(key.c_str());
    entry.text = const_cast<png_charp>(value.c_str());
    entry.text_length = value.size();
    texts.push_back(entry);
  }
  return texts;
}

Result<void> encodeAndWrite(const std::filesystem::path& path, const PngFormat& format,
                            const std::uint8_t* pixels, std::size_t rowBytes, const PngText& text) {
  LIC3D_TRY_ASSIGN(std::vector<png_text> texts, makeTexts(path, text));
  std::vector<png_bytep> rows(static_cast<std::size_t>(format.height));
  for (std::size_t y = 0; y < rows.size(); ++y)
    rows[y] = const_cast<png_bytep>(pixels + y * rowBytes);
  std::string encoded;
  EncodeState state;
  state.output = &encoded;
  if (!encode(state, format, rows.data(), texts.data(), static_cast<int>(texts.size())))
    return runtimeError("cannot encode '" + path.string() + "' as PNG: " + state.error);
  return writeFileAtomically(path, encoded);
}

Result<void> checkSize(const std::filesystem::path& path, int width, int height, std::size_t values,
                       std::size_t valuesPerPixel) {
  if (width <= 0 || height <= 0 ||
      values != static_cast<std::size_t>(width) * static_cast<std::size_t>(height) * valuesPerPixel)
    return inputError("cannot write '" + path.string() + "': the " + std::to_string(width) + "x" +
                      std::to_string(height) + " image is empty or holds " +
                      std::to_string(values) + " values instead of " +
                      std::to_string(valuesPerPixel) + " per pixel");
  return {};
}

}  // namespace

std::uint64_t pngSizeBound(int width, int height, int bytesPerPixel, const PngText& text) {
  // A filter byte before each row.
  const std::uint64_t filtered = static_cast<std::uint64_t>(std::max(height, 0)) *
                                 (1 + static_cast<std::uint64_t>(std::max(width, 0)) *
                                          static_cast<std::uint64_t>(bytesPerPixel));
  // zlib's deflateBound for the default window and memory level, with its header and checksum.
  const std::uint64_t deflated =
      filtered + (filtered >> 12) + (filtered >> 14) + (filtered >> 25) + 13 + 6;
  // libpng cuts the stream into IDAT chunks of its 8 KiB buffer, 12 bytes of frame each.
  const std::uint64_t idat = deflated + 12 * (deflated / 8192 + 1);
  // tEXt: key, NUL, value; iTXt adds 4 bytes (flags, method, empty language and translation).
  // A compressed value (from kCompressedTextBytes on) takes at most deflateBound of it.
  std::uint64_t texts = 0;
  for (const auto& [key, value] : text) {
    const std::uint64_t n = value.size();
    const std::uint64_t stored =
        n >= kCompressedTextBytes ? n + (n >> 12) + (n >> 14) + (n >> 25) + 13 + 6 : n;
    texts += 12 + key.size() + 5 + stored;
  }
  // Signature, IHDR, IEND.
  return 8 + 25 + 12 + idat + texts;
}

Result<void> writePng(const std::filesystem::path& path, const RgbaImage& image,
                      const PngText& text) {
  LIC3D_TRY(checkSize(path, image.width, image.height, image.pixels.size(), 4));
  const StageTimer timer("png encode and write");
  return encodeAndWrite(path, {image.width, image.height, 8, PNG_COLOR_TYPE_RGBA},
                        image.pixels.data(), 4 * static_cast<std::size_t>(image.width), text);
}

Result<void> writePngGray16(const std::filesystem::path& path, int width, int height,
                            const std::vector<std::uint16_t>& values, const PngText& text) {
  LIC3D_TRY(checkSize(path, width, height, values.size(), 1));
  const StageTimer timer("png encode and write");
  std::vector<std::uint8_t> bigEndian(2 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    bigEndian[2 * i] = static_cast<std::uint8_t>(values[i] >> 8);
    bigEndian[2 * i + 1] = static_cast<std::uint8_t>(values[i] & 0xff);
  }
  return encodeAndWrite(path, {width, height, 16, PNG_COLOR_TYPE_GRAY}, bigEndian.data(),
                        2 * static_cast<std::size_t>(width), text);
}

namespace {

constexpr unsigned char kPngSignature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};

// libpng reads through a FileReader, which refused FIFOs and devices when it opened the file.
void onRead(png_structp png, png_bytep data, png_size_t length) {
  auto* reader = static_cast<FileReader*>(png_get_io_ptr(png));
  if (reader->read(data, length) != length) png_error(png, "the file ends early");
}

// Decodes every row and the chunks after them (CRCs and the zlib stream checked): true when the
// whole picture decodes. Plain C data only between setjmp and the end.
bool decodes(FileReader& reader, EncodeState& state) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  png_bytep volatile row = nullptr;
  if (!info || setjmp(png_jmpbuf(png))) {
    std::free(row);
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, &reader, onRead);
  png_set_sig_bytes(png, sizeof kPngSignature);  // the caller read and checked it
  png_read_info(png, info);
  const int passes = png_set_interlace_handling(png);
  png_read_update_info(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  row = static_cast<png_bytep>(std::malloc(png_get_rowbytes(png, info)));
  if (!row) png_error(png, "out of memory");
  for (int pass = 0; pass < passes; ++pass)
    for (png_uint_32 y = 0; y < height; ++y) png_read_row(png, row, nullptr);
  png_read_end(png, nullptr);
  std::free(row);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

// libpng's text chunks of the file into `found` (when one has `key`); false with state.error set
// when it is not a readable PNG. A text chunk that holds (or inflates to) more than maxBytes is
// left out with state.warning set: libpng counts a compressed chunk's bytes before it allocates
// them, so a zip bomb costs no memory. Plain C data only between setjmp and the end.
bool readText(FileReader& reader, const char* key, std::size_t maxBytes, EncodeState& state,
              std::string& found, bool& has) {
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &state, onError, onWarning);
  if (!png) return false;
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, info ? &info : nullptr, nullptr);
    return false;
  }
  png_set_read_fn(png, &reader, onRead);
  png_set_sig_bytes(png, sizeof kPngSignature);  // the caller read and checked it
  // The keyword and a terminating NUL come on top of the text.
  png_set_chunk_malloc_max(png, maxBytes + 81);
  png_read_info(png, info);
  png_textp texts = nullptr;
  const int count = png_get_text(png, info, &texts, nullptr);
  for (int i = 0; i < count; ++i)
    if (std::strcmp(texts[i].key, key) == 0) {
      has = true;
      found.assign(texts[i].text,
                   texts[i].itxt_length > 0 ? texts[i].itxt_length : texts[i].text_length);
    }
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace

Result<bool> isCompletePng(const std::filesystem::path& path) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) return false;
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path, false));
  unsigned char start[8];
  if (reader.read(start, sizeof start) != sizeof start ||
      std::memcmp(start, kPngSignature, sizeof start) != 0)
    return false;
  EncodeState state;
  return decodes(reader, state);
}

bool isPngFile(const std::filesystem::path& path) {
  Result<FileReader> reader = FileReader::open(path, false);
  unsigned char start[8];
  return reader && reader->read(start, sizeof start) == sizeof start &&
         std::memcmp(start, kPngSignature, sizeof start) == 0;
}

Result<std::optional<std::string>> readPngText(const std::filesystem::path& path,
                                               const std::string& key, std::size_t maxBytes) {
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  unsigned char start[8];
  if (reader.read(start, sizeof start) != sizeof start ||
      std::memcmp(start, kPngSignature, sizeof start) != 0)
    return fileError(path, "not a PNG file");
  EncodeState state;
  std::string found;
  bool has = false;
  if (!readText(reader, key.c_str(), maxBytes, state, found, has))
    return fileError(path, std::string("not a readable PNG: ") + state.error);
  if (!has && state.warning[0] != '\0')
    return fileError(path, "no text chunk " + key + " could be read: a text chunk is damaged, " +
                               "or holds or inflates to more than the limit of " +
                               std::to_string(maxBytes) + " bytes (" + state.warning + ")");
  if (has && found.size() > maxBytes)
    return fileError(path, "the text chunk " + key + " holds " + std::to_string(found.size()) +
                               " bytes, beyond the limit of " + std::to_string(maxBytes));
  if (!has) return std::optional<std::string>();
  return std::optional<std::string>(std::move(found));
}

}  // namespace lic3d
