// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Internal to the command-line options (options/*.cpp): how a flag is added with its range and its
// session key, and the small parsers the text flags share. The one header of the options that
// includes CLI11, so that the programs' own files need not compile it.

#include <CLI/CLI.hpp>
#include <charconv>
#include <map>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include "core/enum_names.h"
#include "core/error.h"
#include "core/key_names.h"
#include "core/parameter_ranges.h"
#include "options/session_options.h"

namespace lic3d::cli {

template <class T>
Result<T> parseNumber(std::string_view text, const char* flag) {
  T value{};
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end)
    return inputError(std::string(flag) + ": expected " +
                      (std::is_integral_v<T> ? "a whole number" : "a number") + ", got '" +
                      std::string(text) + "'");
  return value;
}

std::vector<std::string_view> splitCommas(std::string_view text);

// The session keys the engine names parameters by (Error::parameter), and the flags that set
// them: reportError shows the flag where the message has the key. Filled as the options are
// added.
KeyNames& flagNames();
// Records that `flags` ("-L,--length") sets the session key `key`.
void nameFlag(std::string_view key, const std::string& flags);

TextOption& addText(CLI::App& app, const std::string& flag, TextOption& option,
                    const std::string& help, const std::string& shownDefault = "",
                    std::string_view key = {});

// CLI11's check of a value against its range of core/parameter_ranges.h: "must be in [0, 4096],
// got '5000'". Text that is no number is left to the conversion, whose message
// parseArguments and parseCommandLine put in the same words.
CLI::Validator rangeCheck(const ParameterRange& range);
// The same for a front end's own setting (threads, frames, benchmark sizes) in [min, max].
CLI::Validator rangeCheck(double min, double max);

// A numeric option with its range, whose key error messages name.
template <class T>
CLI::Option* addRanged(CLI::App& app, const std::string& flags, T& value,
                       const ParameterRange& range, const std::string& help) {
  nameFlag(range.key, flags);
  return app.add_option(flags, value, help)->check(rangeCheck(range))->capture_default_str();
}

// An option taking one of the names of E (enum_names.h); any other value is refused with the
// names in table order ("must be one of box, hann, gauss; got 'foo'"), not CLI11's map dump.
template <class E>
CLI::Option* addEnumOption(CLI::App& app, const std::string& flag, E& value,
                           const std::string& help) {
  return app.add_option(flag, value, help + ": " + enumChoices<E>())
      ->transform(CLI::Validator(
          [](std::string& text) -> std::string {
            std::string list;
            for (const EnumName<E>& n : enumNames<E>()) {
              if (text == n.name) {
                text = std::to_string(static_cast<long long>(n.value));
                return {};
              }
              list += (list.empty() ? "" : ", ") + std::string(n.name);
            }
            return "must be one of " + list + "; got '" + text + "'";
          },
          ""))
      ->default_str(std::string(enumName(value)));
}

// Accepts only the digits of a whole number >= 0 (seeds: "-1" would otherwise wrap to 2^64 - 1).
CLI::Validator wholeNumberText();

// The view flags whose text needs parsing, into the session (checked with it afterwards).
Result<void> applyViewOptions(SessionOptions& options);

}  // namespace lic3d::cli
