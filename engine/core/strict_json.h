// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// JSON text as lic3d reads every JSON file (sessions, colour-map presets, raw sidecars): malformed
// text, a
// number beyond a double (1e400), nesting deeper than a file of lic3d can be and a key given twice
// in one object are InvalidInput errors naming the source, never exceptions or a silent choice.
// `source` ends the message's prefix ("session.json: ..."); `maxDepth` is the deepest nesting the
// file's format can have.

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "core/error.h"

namespace lic3d {

inline constexpr int kMaxJsonDepth = 64;

template <class Json = nlohmann::ordered_json>
Result<Json> parseJsonStrictly(const std::string& text, const std::string& source,
                               int maxDepth = kMaxJsonDepth) {
  struct TooDeep {};
  std::vector<std::set<std::string>> keys;  // of the objects open at each depth
  std::string duplicate;
  const auto check = [&](int depth, typename Json::parse_event_t event, Json& parsed) {
    if (depth > maxDepth) throw TooDeep{};
    if (event == Json::parse_event_t::object_start) keys.emplace_back();
    if (event == Json::parse_event_t::object_end && !keys.empty()) keys.pop_back();
    if (event == Json::parse_event_t::key && !keys.empty() &&
        !keys.back().insert(parsed.template get<std::string>()).second && duplicate.empty())
      duplicate = parsed.template get<std::string>();
    return true;
  };
  Json json;
  try {
    json = Json::parse(text, check);
  } catch (const TooDeep&) {
    return inputError(source + ": nested deeper than " + std::to_string(maxDepth) + " levels");
  } catch (const typename Json::exception& e) {
    return inputError(source + ": not valid JSON: " + e.what());
  }
  if (!duplicate.empty())
    return inputError(source + ": the key '" + duplicate +
                      "' appears twice in one object (which one was meant?)");
  return json;
}

}  // namespace lic3d
