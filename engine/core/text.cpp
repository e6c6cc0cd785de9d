// SPDX-License-Identifier: BSD-3-Clause
#include "core/text.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>

namespace lic3d {
namespace {

// from_chars takes no leading '+', which some writers put before positive numbers.
template <class T>
bool parseReal(std::string_view text, T& value) {
  if (!text.empty() && text.front() == '+') {
    text.remove_prefix(1);
    if (!text.empty() && (text.front() == '+' || text.front() == '-')) return false;
  }
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return !text.empty() && error == std::errc() && stop == end;
}

}  // namespace

std::string formatDouble(double value) {
  std::array<char, 32> text{};
  const auto [end, error] = std::to_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() ? std::string(text.data(), end) : std::string("nan");
}

std::string formatNumber(double value) {
  std::array<char, 32> text{};
  std::snprintf(text.data(), text.size(), "%g", value);
  return text.data();
}

std::string quoteForMessage(std::string_view text) {
  constexpr std::size_t kMaxShown = 60;
  std::string quoted = "'";
  for (std::size_t i = 0; i < text.size() && i < kMaxShown; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c >= 0x20 && c < 0x7f) {
      quoted += static_cast<char>(c);
    } else {
      constexpr char kHex[] = "0123456789abcdef";
      quoted += "\\x";
      quoted += kHex[c >> 4];
      quoted += kHex[c & 15];
    }
  }
  quoted += text.size() > kMaxShown ? "'..." : "'";
  return quoted;
}

std::string cutMessage(std::string_view message, std::size_t limit) {
  if (message.size() <= limit) return std::string(message);
  return std::string(message.substr(0, limit)) + "... (" + std::to_string(message.size()) +
         " characters)";
}

std::string tripleText(const glm::dvec3& v, std::string_view separator) {
  std::string text = formatDouble(v.x);
  text += separator;
  text += formatDouble(v.y);
  text += separator;
  text += formatDouble(v.z);
  return text;
}

bool parseUnsigned(std::string_view text, std::uint64_t& value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return !text.empty() && error == std::errc() && stop == end;
}

bool parseInt(std::string_view text, int& value) {
  const char* end = text.data() + text.size();
  const auto [stop, error] = std::from_chars(text.data(), end, value);
  return !text.empty() && error == std::errc() && stop == end;
}

bool parseDouble(std::string_view text, double& value) { return parseReal(text, value); }
bool parseFloat(std::string_view text, float& value) { return parseReal(text, value); }

bool isAsciiSpace(int c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

std::string asciiLowerCase(std::string_view text) {
  std::string lowered(text);
  for (char& c : lowered)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return lowered;
}

std::vector<std::string_view> splitWords(std::string_view text) {
  std::vector<std::string_view> words;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && isAsciiSpace(text[i])) ++i;
    const std::size_t start = i;
    while (i < text.size() && !isAsciiSpace(text[i])) ++i;
    if (i > start) words.push_back(text.substr(start, i - start));
  }
  return words;
}

std::string voxelText(Dims dims, std::uint64_t index) {
  const std::uint64_t nx = static_cast<std::uint64_t>(std::max(dims.x, 1));
  const std::uint64_t ny = static_cast<std::uint64_t>(std::max(dims.y, 1));
  // Appends rather than "(" + ...: GCC 12 at -O3 gives a false -Wrestrict on prepending a literal.
  std::string text = "(";
  text += std::to_string(index % nx);
  text += ',';
  text += std::to_string(index / nx % ny);
  text += ',';
  text += std::to_string(index / (nx * ny));
  text += ')';
  return text;
}

NumberScan scanNumberConversion(std::string_view pattern) {
  NumberScan scan;
  bool found = false;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%') continue;
    if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
      ++i;
      continue;
    }
    NumberConversion c;
    c.begin = i;
    std::size_t j = i + 1;
    if (j + 1 < pattern.size() && pattern[j] == '0' && pattern[j + 1] >= '1' &&
        pattern[j + 1] <= '9') {
      c.width = pattern[j + 1] - '0';
      j += 2;
    }
    if (j >= pattern.size() || pattern[j] != 'd') {
      scan.problem = NumberScan::Problem::NotAConversion;
      scan.at = i;
      return scan;
    }
    if (found) {
      scan.problem = NumberScan::Problem::MoreThanOne;
      return scan;
    }
    c.end = j + 1;
    scan.conversion = c;
    found = true;
    i = j;
  }
  if (!found) scan.problem = NumberScan::Problem::NoConversion;
  return scan;
}

std::string unescapePercent(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    out += text[i];
    if (text[i] == '%' && i + 1 < text.size() && text[i + 1] == '%') ++i;
  }
  return out;
}

}  // namespace lic3d
