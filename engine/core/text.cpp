// SPDX-License-Identifier: BSD-3-Clause
#include "core/text.h"

#include <array>
#include <charconv>
#include <cstdio>

namespace lic3d {

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

}  // namespace lic3d
