// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Error messages name a parameter by its session key (Error::parameter, "lic.length"); each front
// end shows its own name for it instead (the CLI its flag, the app its widget). The rewriting is
// one function so that the front ends cannot drift apart; each supplies only its table.

#include <functional>
#include <map>
#include <string>

#include "core/error.h"

namespace lic3d {

// Session key → the name a front end shows ("lic.length" → "--length").
using KeyNames = std::map<std::string, std::string, std::less<>>;

// The error's message with the name of `names` in place of the key it starts with
// (Error::parameter), and of every other dotted key of `names` it mentions as a whole word:
// "--length must be in [0, 4096], got 5000".
std::string rewriteKeys(const Error& error, const KeyNames& names);

}  // namespace lic3d
