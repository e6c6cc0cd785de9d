// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to the VTK legacy reader (vtk_legacy_parser.cpp, vtk_legacy.cpp): the file's lines,
// words and data blocks, ASCII or big-endian BINARY, each checked against the bytes left in the
// file before it is read or skipped, so the structure above never reads past a bad count.

#include <cstddef>
#include <cstdint>
#include <functional>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "io/file_util.h"
#include "io/number_type.h"

namespace lic3d::vtk_legacy {

enum class Format { Ascii, Binary };

using Words = std::vector<std::string>;

// The words of `text` between ASCII whitespace.
Words wordsOf(std::string_view text);
// Keywords are compared in upper case, as VTK compares them.
std::string upperCase(std::string_view text);
// VTK writes array names with spaces and other unsafe bytes as %XX.
std::string decodeName(std::string_view name);

// Receives an array's values in order, in chunks.
using ValueSink = std::function<void(const double* values, std::size_t count)>;

class Parser {
 public:
  explicit Parser(FileReader& reader) : reader_(reader) {}

  Error fail(const std::string& problem) const { return fileError(reader_.path(), problem); }
  void setFormat(Format format) { format_ = format; }
  Format format() const { return format_; }
  std::uint64_t position() const { return reader_.position(); }

  // One line without its "\n" or "\r\n"; nullopt at the end of the file.
  Result<std::optional<std::string>> readLine();
  // The words of the next non-blank line; nullopt at the end of the file. Skipping whitespace
  // first also skips the newline VTK writes after each binary block.
  Result<std::optional<Words>> nextKeywordLine();
  // A whitespace-separated ASCII value; empty at the end of the file.
  Result<std::string> readToken();
  // Skips `count` values: `binaryBytes` each in BINARY files, numbers in ASCII files.
  Result<void> skipValues(std::uint64_t count, std::size_t binaryBytes, const std::string& what);
  // Skips `count` values of a VTK data type named in the file.
  Result<void> skipTyped(std::uint64_t count, std::string_view typeName, const std::string& what);
  // Reads `count` numbers of any VTK type as doubles; the caller bounds `count`.
  Result<std::vector<double>> readNumbers(std::uint64_t count, std::string_view typeName,
                                          const std::string& what);
  // Reads `count` numbers of any VTK type into `sink`, in chunks, calling `allocate` once the
  // count has been checked against the bytes left in the file and before any value is delivered.
  // Float values in ASCII parse as float, so they read exactly as they were written.
  Result<void> readValues(std::uint64_t count, std::string_view typeName, const std::string& what,
                          const std::function<void()>& allocate, const ValueSink& sink);
  // Reads `count` float or double vectors into `vectors`, checked against the file first.
  Result<void> readVectors(std::uint64_t count, std::string_view typeName, const std::string& what,
                           std::vector<glm::vec3>& vectors);

 private:
  Result<std::size_t> binarySize(std::string_view typeName, const std::string& what) const;
  Result<const NumberTypeInfo*> dataType(std::string_view typeName, const std::string& what) const;
  Error truncated(const std::string& what, std::uint64_t count, std::size_t bytesPerValue) const;
  // Each ASCII value takes at least one character and one separator.
  Result<void> checkAsciiFits(std::uint64_t count, const std::string& what) const;
  // Float arrays parse as float directly: going through double could round differently. A
  // number beyond the float range is still a number: it is read as a double, becomes infinity
  // and then a zero vector (finishVectorField), like NaN.
  Result<void> readAsciiNumber(double& value, std::uint64_t count, std::uint64_t index,
                               const std::string& what, bool asFloat = false);

  FileReader& reader_;
  Format format_ = Format::Ascii;
};

// A count from a keyword line, as a whole number.
Result<std::uint64_t> parseCount(const Parser& parser, const std::string& word,
                                 const std::string& what);
// Checks that a keyword line has `minWords`..`maxWords` words, for a message showing the form.
Result<void> checkWords(const Parser& parser, const Words& words, std::size_t minWords,
                        std::size_t maxWords, std::string_view form);

}  // namespace lic3d::vtk_legacy
