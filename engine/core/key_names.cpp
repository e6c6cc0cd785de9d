// SPDX-License-Identifier: BSD-3-Clause
#include "core/key_names.h"

namespace lic3d {
namespace {

bool isKeyCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.';
}

}  // namespace

std::string rewriteKeys(const Error& error, const KeyNames& names) {
  std::string text = error.message;
  if (error.parameter.empty()) return text;
  const auto named = names.find(error.parameter);
  if (named != names.end() && text.starts_with(error.parameter))
    text.replace(0, error.parameter.size(), named->second);
  // Keys without a dot ("seed") are ordinary words elsewhere in a message.
  for (const auto& [key, name] : names) {
    if (key.find('.') == std::string::npos) continue;
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
      const std::size_t end = at + key.size();
      const bool whole = (at == 0 || !isKeyCharacter(text[at - 1])) &&
                         (end == text.size() || !isKeyCharacter(text[end]));
      if (!whole) {
        at = end;
        continue;
      }
      text.replace(at, key.size(), name);
      at += name.size();
    }
  }
  return text;
}

}  // namespace lic3d
