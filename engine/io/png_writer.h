// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// PNG files: 8-bit RGBA pictures and 16-bit grey LIC slices, with text chunks that carry the
// parameters that made them.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/rgba_image.h"

namespace lic3d {

// Key/value pairs stored in the PNG as text chunks (the parameters that made the picture): tEXt
// for ASCII values, iTXt (UTF-8) for others, compressed (zTXt, compressed iTXt) from 1 KiB on. Keys
// are PNG keywords: 1 to 79 printable ASCII characters, no leading, trailing or double spaces;
// values hold no NUL byte.
using PngText = std::vector<std::pair<std::string, std::string>>;

// 8-bit RGBA, encoded by libpng in memory and written through writeFileAtomically, so a failure
// never leaves a partial PNG. A bad image or text is InvalidInput; an encoder failure is Runtime.
Result<void> writePng(const std::filesystem::path& path, const RgbaImage& image,
                      const PngText& text = {});

// 16-bit grey (the LIC slice at full precision), `values` row by row from the top, stored big
// endian as PNG requires.
Result<void> writePngGray16(const std::filesystem::path& path, int width, int height,
                            const std::vector<std::uint16_t>& values, const PngText& text = {});

// The most bytes writePng (4 bytes a pixel) or writePngGray16 (2) can write for an image of this
// size and text, whatever its pixels: zlib's deflateBound of the filtered rows (stored blocks,
// when the pixels do not compress), the chunks around them and the text as it is. LIC pictures
// take 12 to 92% of it (docs/RELIABILITY.md); the bound is what a free-space check can rely on.
std::uint64_t pngSizeBound(int width, int height, int bytesPerPixel, const PngText& text = {});

// Whether `path` is a whole PNG file: every row decodes, every chunk's CRC and the zlib stream
// check out, up to the IEND chunk. lic3d writes every file atomically, so one of its frames is
// whole or absent; this also tells a file cut short, zeroed in the middle or forged (a signature
// and an IEND chunk) by a copy or another program (`--skip-existing` redoes it). False when the
// path does not exist; InvalidInput naming it when it is not a regular file (a FIFO would hang).
Result<bool> isCompletePng(const std::filesystem::path& path);

// Whether the file is a regular file that starts with the PNG signature.
bool isPngFile(const std::filesystem::path& path);
// The value of the text chunk `key` (tEXt, zTXt or iTXt, compressed or not, before the image data,
// where lic3d writes them), or nothing when the PNG has none; InvalidInput naming the file when it
// is not a PNG, or when a text chunk holds or inflates to more than maxBytes (it is never inflated
// further: a zip bomb costs no memory).
Result<std::optional<std::string>> readPngText(const std::filesystem::path& path,
                                               const std::string& key, std::size_t maxBytes);

}  // namespace lic3d
