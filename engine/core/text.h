// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Numbers as messages and files print them.

#include <string>
#include <string_view>

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

}  // namespace lic3d
