// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Text as files and messages write it and parsers read it: numbers, words, voxels and numbered
// file patterns, in the C locale and plain ASCII whatever the process's locale.

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <string>
#include <string_view>
#include <vector>

#include "core/volume.h"

namespace lic3d {

// The shortest text that reads back as the same double ("0.1", "1e-07", "nan"): for files.
std::string formatDouble(double value);
// Six significant digits ("%g": "0.1", "1.7", "4096"): for messages about parameters.
std::string formatNumber(double value);

// Untrusted text made safe for an error message: quoted, control and non-ASCII bytes escaped,
// long text cut.
std::string quoteForMessage(std::string_view text);
// A message cut to `limit` characters, saying how long it was (a parser's message that echoes
// a huge argument).
std::string cutMessage(std::string_view message, std::size_t limit = 300);

// The three numbers of `v` (formatDouble) between `separator`s: "1 2 3" for VTK XML, "1, 2, 3"
// inside a JSON list, "1,2,3" in the CLI's summary and NRRD's vectors.
std::string tripleText(const glm::dvec3& v, std::string_view separator);

// Whole-string numbers in the C locale; false for anything else (empty, trailing characters,
// out of range). Doubles accept a leading '+', "nan" and "inf".
bool parseUnsigned(std::string_view text, std::uint64_t& value);
bool parseInt(std::string_view text, int& value);
bool parseDouble(std::string_view text, double& value);
bool parseFloat(std::string_view text, float& value);

// ASCII text helpers for the parsers, independent of the locale.
bool isAsciiSpace(int c);
std::string asciiLowerCase(std::string_view text);
// The words of `text` between ASCII whitespace, as views into `text`.
std::vector<std::string_view> splitWords(std::string_view text);

// "(i,j,k)" for the voxel at `index` on a grid of `dims`, for error messages.
std::string voxelText(Dims dims, std::uint64_t index);

// A numbered file pattern's one %d or %0Nd (%% is a literal %), as ffmpeg takes them: output
// frames (`-o frame_%04d.png`) and input time steps (`--field step_%03d.vti`).
struct NumberConversion {
  std::size_t begin = 0, end = 0;  // [begin, end) is the conversion in the pattern
  int width = 0;                   // N of %0Nd, 0 for %d
};
struct NumberScan {
  enum class Problem { None, NotAConversion, MoreThanOne, NoConversion };
  Problem problem = Problem::None;
  NumberConversion conversion;  // when problem is None
  std::size_t at = 0;           // where a NotAConversion % stands
};
NumberScan scanNumberConversion(std::string_view pattern);
// %% becomes %.
std::string unescapePercent(std::string_view text);

}  // namespace lic3d
