// SPDX-License-Identifier: BSD-3-Clause
// The VTK legacy tokenizer: lines and words within length limits, and data blocks of any VTK type,
// ASCII or big-endian BINARY, refused when they cannot fit in what is left of the file.

#include "io/vtk_legacy_parser.h"

#include <algorithm>
#include <bit>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "core/text.h"
#include "io/file_util.h"
#include "io/volume_io.h"

namespace lic3d::vtk_legacy {

namespace {

constexpr std::size_t kMaxLineBytes = 4096;
constexpr std::size_t kMaxTokenBytes = 256;
// A multiple of every value size, so chunks never split a value.
// ASCII values are delivered in chunks of this many.
constexpr std::size_t kChunkValues = std::size_t{1} << 16;

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

std::string upperCase(std::string_view text) {
  std::string raised(text);
  for (char& c : raised)
    if (c >= 'a' && c <= 'z') c = static_cast<char>(c - 'a' + 'A');
  return raised;
}

std::string decodeName(std::string_view name) {
  std::string decoded;
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (name[i] == '%' && i + 2 < name.size() && hexDigit(name[i + 1]) >= 0 &&
        hexDigit(name[i + 2]) >= 0) {
      decoded += static_cast<char>(hexDigit(name[i + 1]) * 16 + hexDigit(name[i + 2]));
      i += 2;
    } else {
      decoded += name[i];
    }
  }
  return decoded;
}

Words wordsOf(std::string_view text) {
  const std::vector<std::string_view> views = splitWords(text);
  return Words(views.begin(), views.end());
}

Result<std::optional<std::string>> Parser::readLine() {
  int c = reader_.get();
  if (c < 0) return std::optional<std::string>();
  std::string line;
  for (; c >= 0 && c != '\n'; c = reader_.get()) {
    if (line.size() == kMaxLineBytes)
      return fail("a line near byte " + std::to_string(reader_.position()) + " is longer than " +
                  std::to_string(kMaxLineBytes) + " characters");
    line.push_back(static_cast<char>(c));
  }
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return std::optional<std::string>(std::move(line));
}

Result<std::optional<Words>> Parser::nextKeywordLine() {
  while (isAsciiSpace(reader_.peek())) reader_.get();
  LIC3D_TRY_ASSIGN(std::optional<std::string> line, readLine());
  if (!line) return std::optional<Words>();
  return std::optional<Words>(wordsOf(*line));
}

Result<std::string> Parser::readToken() {
  while (isAsciiSpace(reader_.peek())) reader_.get();
  std::string token;
  while (reader_.peek() >= 0 && !isAsciiSpace(reader_.peek())) {
    if (token.size() == kMaxTokenBytes)
      return fail("a value near byte " + std::to_string(reader_.position()) + " is longer than " +
                  std::to_string(kMaxTokenBytes) + " characters");
    token.push_back(static_cast<char>(reader_.get()));
  }
  return token;
}

Result<void> Parser::skipValues(std::uint64_t count, std::size_t binaryBytes,
                                const std::string& what) {
  if (format_ == Format::Binary) {
    std::uint64_t bytes = 0;
    if (__builtin_mul_overflow(count, binaryBytes, &bytes) || bytes > reader_.remaining())
      return truncated(what, count, binaryBytes);
    if (reader_.skip(bytes) != bytes)
      return fail(what + ": cannot read: " + reader_.failureReason());
    return {};
  }
  LIC3D_TRY(checkAsciiFits(count, what));
  for (std::uint64_t i = 0; i < count; ++i) {
    double value = 0.0;
    LIC3D_TRY(readAsciiNumber(value, count, i, what));
  }
  return {};
}

Result<void> Parser::skipTyped(std::uint64_t count, std::string_view typeName,
                               const std::string& what) {
  LIC3D_TRY_ASSIGN(const std::size_t bytes, binarySize(typeName, what));
  return skipValues(count, bytes, what);
}

Result<std::size_t> Parser::binarySize(std::string_view typeName, const std::string& what) const {
  LIC3D_TRY_ASSIGN(const NumberTypeInfo* type, dataType(typeName, what));
  return type->bytes;
}

Result<const NumberTypeInfo*> Parser::dataType(std::string_view typeName,
                                               const std::string& what) const {
  const std::string key = asciiLowerCase(typeName);
  if (key == "bit") return fail(what + ": bit arrays are not supported");
  if (key == "string" || key == "utf8_string" || key == "variant")
    return fail(what + ": " + quoteForMessage(typeName) + " arrays are not supported");
  if (const NumberTypeInfo* type = findVtkLegacyType(key)) return type;
  return fail(what + ": unknown data type " + quoteForMessage(typeName));
}

Result<std::vector<double>> Parser::readNumbers(std::uint64_t count, std::string_view typeName,
                                                const std::string& what) {
  LIC3D_TRY_ASSIGN(const NumberTypeInfo* type, dataType(typeName, what));
  std::vector<double> numbers;
  if (format_ == Format::Binary) {
    const std::uint64_t bytes = count * type->bytes;
    if (bytes > reader_.remaining()) return truncated(what, count, type->bytes);
    std::vector<char> data(static_cast<std::size_t>(bytes));
    if (reader_.read(data.data(), data.size()) != data.size())
      return fail(what + ": cannot read: " + reader_.failureReason());
    toNativeOrder(data.data(), static_cast<std::size_t>(count), type->bytes, std::endian::big);
    for (std::size_t i = 0; i < count; ++i)
      numbers.push_back(valueOf(
          reinterpret_cast<const unsigned char*>(data.data() + i * type->bytes), type->type));
    return numbers;
  }
  LIC3D_TRY(checkAsciiFits(count, what));
  for (std::uint64_t i = 0; i < count; ++i) {
    double value = 0.0;
    LIC3D_TRY(readAsciiNumber(value, count, i, what));
    numbers.push_back(value);
  }
  return numbers;
}

Result<void> Parser::readValues(std::uint64_t count, std::string_view typeName,
                                const std::string& what, const std::function<void()>& allocate,
                                const ValueSink& sink) {
  LIC3D_TRY_ASSIGN(const NumberTypeInfo* type, dataType(typeName, what));
  const std::size_t bytesPerValue = type->bytes;
  if (format_ == Format::Binary) {
    std::uint64_t bytes = 0;
    if (__builtin_mul_overflow(count, bytesPerValue, &bytes) || bytes > reader_.remaining())
      return truncated(what, count, bytesPerValue);
    allocate();
    std::vector<char> chunk(
        static_cast<std::size_t>(std::min<std::uint64_t>(kFileChunkBytes, bytes)));
    const std::size_t perChunk = chunk.size() / bytesPerValue;
    std::vector<double> values(perChunk);
    for (std::uint64_t done = 0; done < count;) {
      const std::size_t n =
          static_cast<std::size_t>(std::min<std::uint64_t>(perChunk, count - done));
      if (reader_.read(chunk.data(), n * bytesPerValue) != n * bytesPerValue)
        return fail(what + ": cannot read: " + reader_.failureReason());
      toNativeOrder(chunk.data(), n, bytesPerValue, std::endian::big);
      for (std::size_t i = 0; i < n; ++i)
        values[i] = valueOf(
            reinterpret_cast<const unsigned char*>(chunk.data() + i * bytesPerValue), type->type);
      sink(values.data(), n);
      done += n;
    }
    return {};
  }
  LIC3D_TRY(checkAsciiFits(count, what));
  allocate();
  const bool asFloat = type->type == NumberType::Float32;
  std::vector<double> values;
  values.reserve(static_cast<std::size_t>(std::min<std::uint64_t>(count, kChunkValues)));
  for (std::uint64_t i = 0; i < count; ++i) {
    double value = 0.0;
    LIC3D_TRY(readAsciiNumber(value, count, i, what, asFloat));
    values.push_back(value);
    if (values.size() == kChunkValues) {
      sink(values.data(), values.size());
      values.clear();
    }
  }
  if (!values.empty()) sink(values.data(), values.size());
  return {};
}

Result<void> Parser::readVectors(std::uint64_t count, std::string_view typeName,
                                 const std::string& what, std::vector<glm::vec3>& vectors) {
  const std::string key = asciiLowerCase(typeName);
  if (key != "float" && key != "double")
    return fail(what + ": type " + quoteForMessage(typeName) +
                " is not supported (expected float or double)");
  std::uint64_t next = 0;
  return readValues(
      3 * count, typeName, what,
      [&] { vectors.assign(static_cast<std::size_t>(count), glm::vec3(0.0f)); },
      [&](const double* values, std::size_t n) {
        for (std::size_t i = 0; i < n; ++i, ++next)
          vectors[static_cast<std::size_t>(next / 3)][static_cast<glm::length_t>(next % 3)] =
              vectorComponent(values[i]);
      });
}

Error Parser::truncated(const std::string& what, std::uint64_t count,
                        std::size_t bytesPerValue) const {
  return fail(what + ": the data is truncated: " + std::to_string(count) + " values of " +
              std::to_string(bytesPerValue) + " bytes do not fit in the " +
              std::to_string(reader_.remaining()) + " bytes left in the file");
}

Result<void> Parser::checkAsciiFits(std::uint64_t count, const std::string& what) const {
  if (count > reader_.remaining() / 2 + 1)
    return fail(what + ": the data is truncated: " + std::to_string(count) +
                " values do not fit in the " + std::to_string(reader_.remaining()) +
                " bytes left in the file");
  return {};
}

Result<void> Parser::readAsciiNumber(double& value, std::uint64_t count, std::uint64_t index,
                                     const std::string& what, bool asFloat) {
  LIC3D_TRY_ASSIGN(const std::string token, readToken());
  if (token.empty())
    return fail(what + ": the data is truncated: expected " + std::to_string(count) +
                " values, found " + std::to_string(index));
  bool parsed = false;
  if (asFloat) {
    float single = 0.0f;
    parsed = parseFloat(token, single);
    value = single;
    if (!parsed) parsed = parseDouble(token, value);
  } else {
    parsed = parseDouble(token, value);
  }
  if (!parsed)
    return fail(what + ": expected " + std::to_string(count) + " numbers, found " +
                quoteForMessage(token) + " after " + std::to_string(index));
  return {};
}

Result<std::uint64_t> parseCount(const Parser& parser, const std::string& word,
                                 const std::string& what) {
  std::uint64_t value = 0;
  if (!parseUnsigned(word, value))
    return parser.fail(what + ": " + quoteForMessage(word) + " is not a whole number");
  return value;
}

Result<void> checkWords(const Parser& parser, const Words& words, std::size_t minWords,
                        std::size_t maxWords, std::string_view form) {
  if (words.size() < minWords || words.size() > maxWords) {
    std::string found;
    for (const std::string& word : words) found += (found.empty() ? "" : " ") + word;
    return parser.fail("expected '" + std::string(form) + "', found " + quoteForMessage(found));
  }
  return {};
}

}  // namespace lic3d::vtk_legacy
