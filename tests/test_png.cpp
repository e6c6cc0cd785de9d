// SPDX-License-Identifier: BSD-3-Clause
// PNG writing: 8-bit RGBA and 16-bit grey, text chunks, and refusals; read back with libpng.

#include <gtest/gtest.h>
#include <png.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/rgba_image.h"
#include "io/png_writer.h"
#include "png_read.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

class PngTest : public test::TempFolderTest {};

using test::DecodedPng;
using test::decodePng;

TEST_F(PngTest, WritesRgbaWithTextChunks) {
  RgbaImage image;
  image.width = 5;
  image.height = 3;
  for (int i = 0; i < 5 * 3 * 4; ++i) image.pixels.push_back(static_cast<std::uint8_t>(i * 4 + 1));
  const PngText text = {{"Software", "lic3d"},
                        {"lic3d parameters", "--length 20 --step 0.5 --kernel box"},
                        {"Comment", "flow \xc3\xbc\xe2\x86\x92 streaks"}};
  const fs::path file = path("image.png");
  ASSERT_TRUE(writePng(file, image, text).ok());
  const DecodedPng png = decodePng(file);
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.width, 5u);
  EXPECT_EQ(png.height, 3u);
  EXPECT_EQ(png.bitDepth, 8);
  EXPECT_EQ(png.colorType, PNG_COLOR_TYPE_RGBA);
  EXPECT_EQ(png.bytes, image.pixels);
  EXPECT_EQ(png.text.at("Software"), "lic3d");
  EXPECT_EQ(png.text.at("lic3d parameters"), "--length 20 --step 0.5 --kernel box");
  EXPECT_EQ(png.compression.at("Software"), PNG_TEXT_COMPRESSION_NONE);
  // Non-ASCII text goes into an iTXt chunk as UTF-8.
  EXPECT_EQ(png.text.at("Comment"), "flow \xc3\xbc\xe2\x86\x92 streaks");
  EXPECT_EQ(png.compression.at("Comment"), PNG_ITXT_COMPRESSION_NONE);
  const std::string bytes = test::readWhole(file);
  EXPECT_NE(bytes.find("tEXtSoftware"), std::string::npos);
  EXPECT_NE(bytes.find("iTXtComment"), std::string::npos);

  // The two-argument form still works and writes no text.
  ASSERT_TRUE(writePng(path("plain.png"), image).ok());
  const DecodedPng plain = decodePng(path("plain.png"));
  ASSERT_TRUE(plain.ok);
  EXPECT_TRUE(plain.text.empty());
  EXPECT_EQ(plain.bytes, image.pixels);
}

// pngSizeBound holds for pixels that do not compress (random bytes) and those that do, in both
// formats, text included (long text is stored compressed): the free-space checks of render and
// compute rely on it.
TEST_F(PngTest, SizeBoundHoldsForIncompressiblePixels) {
  std::uint32_t state = 12345;
  const auto next = [&] { return state = state * 1664525u + 1013904223u; };
  std::string noise;
  for (int i = 0; i < 3000; ++i) noise.push_back(static_cast<char>(' ' + (next() >> 24) % 95));
  const PngText shortText = {{"lic3d session", "{}"}, {"Comment", "\xc3\xbc"}};
  const PngText longText = {{"lic3d session", noise}, {"Comment", std::string(5000, 'x')}};
  for (const int size : {1, 7, 300}) {
    RgbaImage noisy;
    noisy.width = size;
    noisy.height = size + 3;
    for (int i = 0; i < noisy.width * noisy.height * 4; ++i)
      noisy.pixels.push_back(static_cast<std::uint8_t>(next() >> 24));
    for (const PngText* text : {&shortText, &longText}) {
      const fs::path rgba = path("rgba.png");
      ASSERT_TRUE(writePng(rgba, noisy, *text).ok());
      const std::uint64_t bound = pngSizeBound(noisy.width, noisy.height, 4, *text);
      EXPECT_LE(fs::file_size(rgba), bound) << size;
      // Not a loose bound: within 2% and 200 bytes of what incompressible pixels take.
      if (text == &shortText) {
        EXPECT_GE(fs::file_size(rgba) * 102 / 100 + 200, bound) << size;
      }

      std::vector<std::uint16_t> grey;
      for (int i = 0; i < size * (size + 3); ++i)
        grey.push_back(static_cast<std::uint16_t>(next() >> 16));
      ASSERT_TRUE(writePngGray16(path("grey.png"), size, size + 3, grey, *text).ok());
      EXPECT_LE(fs::file_size(path("grey.png")), pngSizeBound(size, size + 3, 2, *text)) << size;
    }
  }
}

TEST_F(PngTest, WritesSixteenBitGreyBigEndian) {
  const int width = 4;
  const int height = 2;
  const std::vector<std::uint16_t> values = {0, 1, 255, 256, 4660, 32768, 65534, 65535};
  const fs::path file = path("slice.png");
  ASSERT_TRUE(writePngGray16(file, width, height, values, {{"Title", "LIC slice z=10"}}).ok());
  const DecodedPng png = decodePng(file);
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.width, 4u);
  EXPECT_EQ(png.height, 2u);
  EXPECT_EQ(png.bitDepth, 16);
  EXPECT_EQ(png.colorType, PNG_COLOR_TYPE_GRAY);
  ASSERT_EQ(png.bytes.size(), 16u);
  for (std::size_t i = 0; i < values.size(); ++i)
    EXPECT_EQ(png.bytes[2 * i] << 8 | png.bytes[2 * i + 1], values[i]) << i;
  EXPECT_EQ(png.text.at("Title"), "LIC slice z=10");
}

TEST_F(PngTest, RefusesBadImagesAndTextsAndLeavesNoFile) {
  RgbaImage image;
  image.width = 2;
  image.height = 2;
  image.pixels.assign(15, 0);
  const fs::path file = path("bad.png");
  const auto expectRefused = [&](const Result<void>& result, const std::string& fragment) {
    ASSERT_FALSE(result.ok());
    EXPECT_EQ(result.error().kind, ErrorKind::InvalidInput) << result.error().message;
    EXPECT_NE(result.error().message.find("bad.png"), std::string::npos) << result.error().message;
    EXPECT_NE(result.error().message.find(fragment), std::string::npos) << result.error().message;
  };
  expectRefused(writePng(file, image), "holds 15 values instead of 4 per pixel");
  image.pixels.assign(16, 0);
  image.width = 0;
  expectRefused(writePng(file, image), "empty");
  image.width = 2;
  expectRefused(writePng(file, image, {{"", "x"}}), "is not a PNG keyword");
  expectRefused(writePng(file, image, {{" lead", "x"}}), "is not a PNG keyword");
  expectRefused(writePng(file, image, {{"two  spaces", "x"}}), "is not a PNG keyword");
  expectRefused(writePng(file, image, {{std::string(80, 'k'), "x"}}), "is not a PNG keyword");
  expectRefused(writePng(file, image, {{"k\xe9y", "x"}}), "is not a PNG keyword");
  expectRefused(writePng(file, image, {{"key", std::string("a\0b", 3)}}), "NUL byte");
  expectRefused(writePng(file, image, {{"key", "\xff\xfe"}}), "not UTF-8");
  expectRefused(writePngGray16(file, 3, 3, std::vector<std::uint16_t>(8), {}),
                "holds 8 values instead of 1 per pixel");
  EXPECT_TRUE(listFolder().empty());
  // An unwritable path is an input error naming it, and leaves nothing.
  const Result<void> missing = writePng(path("no folder") / "x.png", RgbaImage{1, 1, {1, 2, 3, 4}});
  ASSERT_FALSE(missing.ok());
  EXPECT_NE(missing.error().message.find("no folder"), std::string::npos);
  EXPECT_TRUE(listFolder().empty());
}

TEST_F(PngTest, LibpngLimitsAreErrorsNotCrashes) {
  // Wider than libpng's default limit of 1,000,000 columns: libpng's own error, as a Result.
  const std::vector<std::uint16_t> values(1000001, 7);
  const Result<void> result = writePngGray16(path("wide.png"), 1000001, 1, values);
  ASSERT_FALSE(result.ok());
  EXPECT_EQ(result.error().kind, ErrorKind::Runtime);
  EXPECT_NE(result.error().message.find("wide.png"), std::string::npos) << result.error().message;
  EXPECT_TRUE(listFolder().empty());
}

RgbaImage smallImage() { return RgbaImage{2, 1, {1, 2, 3, 255, 4, 5, 6, 255}}; }

// Long text (a session with a large transfer function) is compressed: zTXt when ASCII, compressed
// iTXt when UTF-8; short text stays tEXt, and every kind reads back.
TEST_F(PngTest, LongTextIsCompressed) {
  std::string ascii;
  for (int i = 0; ascii.size() < 200'000; ++i) ascii += std::to_string(i % 977) + ", 0.5,\n";
  const std::string utf8 = "fl\xc3\xbc" + ascii;
  ASSERT_TRUE(writePng(path("long.png"), smallImage(),
                       {{"ascii", ascii}, {"utf8", utf8}, {"short", "lic3d"}})
                  .ok());
  const DecodedPng png = decodePng(path("long.png"));
  ASSERT_TRUE(png.ok);
  EXPECT_EQ(png.compression.at("ascii"), PNG_TEXT_COMPRESSION_zTXt);
  EXPECT_EQ(png.compression.at("utf8"), PNG_ITXT_COMPRESSION_zTXt);
  EXPECT_EQ(png.compression.at("short"), PNG_TEXT_COMPRESSION_NONE);
  EXPECT_LT(fs::file_size(path("long.png")), ascii.size() / 4);
  EXPECT_EQ(readPngText(path("long.png"), "ascii", 1 << 20).value(), ascii);
  EXPECT_EQ(readPngText(path("long.png"), "utf8", 1 << 20).value(), utf8);
  EXPECT_EQ(readPngText(path("long.png"), "short", 1 << 20).value(), "lic3d");
}

// Text chunks as older lic3d (and other programs) wrote them, uncompressed, still read.
TEST_F(PngTest, UncompressedTextStillReads) {
  ASSERT_TRUE(writePng(path("plain.png"), smallImage()).ok());
  const std::string plain = test::readWhole(path("plain.png"));
  const std::string text(5000, 'a');
  writeBytes("tEXt.png", test::withPngChunk(plain, "tEXt", std::string("key\0", 4) + text));
  writeBytes("iTXt.png", test::withPngChunk(plain, "iTXt", std::string("key\0\0\0\0\0", 8) + text));
  for (const char* file : {"tEXt.png", "iTXt.png"}) {
    const Result<std::optional<std::string>> read = readPngText(path(file), "key", 1 << 20);
    ASSERT_TRUE(read) << file << ": " << read.error().message;
    EXPECT_EQ(read->value_or(""), text) << file;
  }
}

// Text beyond the reader's limit is refused, naming the file and the limit; a compressed chunk
// that inflates without end (a zip bomb) costs no memory: it is counted, never held.
TEST_F(PngTest, TextBeyondTheLimitIsRefusedWithoutInflatingIt) {
  ASSERT_TRUE(writePng(path("plain.png"), smallImage()).ok());
  const std::string plain = test::readWhole(path("plain.png"));
  writeBytes("bomb.png", test::withPngChunk(plain, "zTXt",
                                            std::string("key\0\0", 5) +
                                                test::deflateZeros(std::uint64_t{512} << 20)));
  writeBytes("long.png",
             test::withPngChunk(plain, "tEXt", std::string("key\0", 4) + std::string(5000, 'a')));
  for (const auto& [file, limit] :
       {std::pair("bomb.png", std::size_t{64} << 20), std::pair("long.png", std::size_t{1000})}) {
    const Result<std::optional<std::string>> read = readPngText(path(file), "key", limit);
    ASSERT_FALSE(read) << file;
    EXPECT_NE(read.error().message.find(file), std::string::npos) << read.error().message;
    EXPECT_NE(read.error().message.find(std::to_string(limit)), std::string::npos)
        << read.error().message;
  }
  const double growth = test::peakMemoryGrowthMiB(
      [&] { (void)readPngText(path("bomb.png"), "key", std::size_t{64} << 20); });
  EXPECT_LT(growth, 32.0) << "MiB for a bomb of 512 MiB";
}

// isCompletePng decodes the whole picture: a file cut short, zeroed in the middle or forged from a
// signature and an IEND chunk is not whole; a FIFO is an error at once, not a wait for a writer.
TEST_F(PngTest, CompleteMeansEveryRowDecodes) {
  RgbaImage image;
  image.width = 16;
  image.height = 16;
  for (unsigned i = 0; i < 16 * 16 * 4; ++i)
    image.pixels.push_back(static_cast<std::uint8_t>(i * i * 31 + i / 7));
  ASSERT_TRUE(writePng(path("whole.png"), image).ok());
  const std::string whole = test::readWhole(path("whole.png"));
  EXPECT_TRUE(isCompletePng(path("whole.png")).value());
  EXPECT_FALSE(isCompletePng(path("missing.png")).value());
  writeBytes("forged.png",
             std::string("\x89PNG\r\n\x1a\n", 8) + std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12));
  EXPECT_FALSE(isCompletePng(path("forged.png")).value());
  std::string zeroed = whole;
  std::fill(zeroed.begin() + 60, zeroed.end() - 20, '\0');
  writeBytes("zeroed.png", zeroed);
  EXPECT_FALSE(isCompletePng(path("zeroed.png")).value());
  writeBytes("cut.png", whole.substr(0, whole.size() - 20));
  EXPECT_FALSE(isCompletePng(path("cut.png")).value());
  ASSERT_EQ(::mkfifo(path("fifo.png").c_str(), 0600), 0);
  const Result<bool> fifo = isCompletePng(path("fifo.png"));
  ASSERT_FALSE(fifo);
  EXPECT_NE(fifo.error().message.find("not a regular file"), std::string::npos);
  EXPECT_FALSE(isPngFile(path("fifo.png")));
}

}  // namespace
}  // namespace lic3d
