// SPDX-License-Identifier: BSD-3-Clause
#include "options/flags.h"

#include "core/text.h"

namespace lic3d::cli {
namespace {

// "--length" of "-L,--length".
std::string longName(const std::string& flags) {
  const std::size_t comma = flags.rfind(',');
  return comma == std::string::npos ? flags : flags.substr(comma + 1);
}

}  // namespace

std::vector<std::string_view> splitCommas(std::string_view text) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return parts;
}

KeyNames& flagNames() {
  static KeyNames names;
  return names;
}

void nameFlag(std::string_view key, const std::string& flags) {
  flagNames().emplace(std::string(key), longName(flags));
}

TextOption& addText(CLI::App& app, const std::string& flag, TextOption& option,
                    const std::string& help, const std::string& shownDefault,
                    std::string_view key) {
  option.option = app.add_option(flag, option.text, help);
  if (!shownDefault.empty()) option.option->default_str(shownDefault);
  if (!key.empty()) nameFlag(key, flag);
  return option;
}

CLI::Validator rangeCheck(const ParameterRange& range) {
  return CLI::Validator(
      [range](std::string& text) -> std::string {
        // CLI11 reads an empty value as the type's zero: refused here, or `--length ''` is 0.
        if (text.empty()) return "expected a number in " + range.text() + ", got ''";
        double value = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        const bool whole = end == text.data() + text.size();
        // Not a number: the conversion refuses it, in parseErrorMessage's words.
        if (!whole || (error != std::errc() && error != std::errc::result_out_of_range)) return {};
        if (error == std::errc() && range.contains(value)) return {};
        return "must be in " + range.text() + ", got '" + cutMessage(text, 60) + "'";
      },
      "in " + range.text(), "RANGE");
}

CLI::Validator rangeCheck(double min, double max) {
  return rangeCheck(ParameterRange{.min = min, .max = max});
}

}  // namespace lic3d::cli
