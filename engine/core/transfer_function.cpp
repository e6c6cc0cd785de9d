// SPDX-License-Identifier: BSD-3-Clause
#include "core/transfer_function.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <type_traits>

#include "core/strict_json.h"
#include "core/text.h"

namespace lic3d {
namespace {

using Json = nlohmann::ordered_json;

template <class Point, class Value>
Value interpolate(const std::vector<Point>& points, double t, Value Point::*value) {
  t = std::clamp(t, 0.0, 1.0);
  if (t <= points.front().x) return points.front().*value;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (t <= points[i].x) {
      const double span = points[i].x - points[i - 1].x;
      const double w = span > 0.0 ? (t - points[i - 1].x) / span : 1.0;
      using Weight = std::conditional_t<std::is_same_v<Value, double>, double, float>;
      return points[i - 1].*value +
             static_cast<Weight>(w) * (points[i].*value - points[i - 1].*value);
    }
  return points.back().*value;
}

bool inUnit(double v) { return v >= 0.0 && v <= 1.0; }

// The numbers of key `key` of `preset`, a multiple of `stride` of them.
Result<std::vector<double>> numbers(const Json& preset, const char* key, std::size_t stride,
                                    const std::string& source) {
  std::vector<double> values;
  const auto it = preset.find(key);
  if (it == preset.end()) return values;
  if (!it->is_array() || it->size() % stride != 0)
    return inputError(source + ": " + key + " must be an array of " + std::to_string(stride) +
                      "-tuples of numbers");
  for (const Json& v : *it) {
    if (!v.is_number()) return inputError(source + ": " + key + " must hold numbers only");
    values.push_back(v.get<double>());
  }
  return values;
}

}  // namespace

glm::vec3 TransferFunction::color(double t) const {
  return colors.empty() ? glm::vec3(static_cast<float>(std::clamp(t, 0.0, 1.0)))
                        : interpolate(colors, t, &ColorPoint::rgb);
}

double TransferFunction::opacity(double t) const {
  return opacities.empty() ? 1.0 : interpolate(opacities, t, &OpacityPoint::alpha);
}

Result<void> validate(const TransferFunction& tf, const std::string& what) {
  for (std::size_t i = 0; i < tf.colors.size(); ++i) {
    const ColorPoint& p = tf.colors[i];
    if (!inUnit(p.x) || (i > 0 && p.x < tf.colors[i - 1].x))
      return inputError(what + ": colour points must have x in [0, 1], in increasing order");
    for (int c = 0; c < 3; ++c)
      if (!inUnit(p.rgb[c])) return inputError(what + ": colour components must be in [0, 1]");
  }
  for (std::size_t i = 0; i < tf.opacities.size(); ++i) {
    const OpacityPoint& p = tf.opacities[i];
    if (!inUnit(p.x) || (i > 0 && p.x < tf.opacities[i - 1].x))
      return inputError(what + ": opacity points must have x in [0, 1], in increasing order");
    if (!inUnit(p.alpha)) return inputError(what + ": opacities must be in [0, 1]");
  }
  return {};
}

Result<TransferFunction> transferFunctionFromJson(const std::string& text,
                                                  const std::string& source) {
  LIC3D_TRY_ASSIGN(Json json, parseJsonStrictly(text, source));
  if (json.is_array()) {
    if (json.empty()) return inputError(source + ": an empty list of presets");
    json = json.front();
  }
  if (!json.is_object()) return inputError(source + ": expected a ParaView colour-map preset");
  TransferFunction tf;
  if (const auto name = json.find("Name"); name != json.end() && name->is_string())
    tf.name = name->get<std::string>();
  LIC3D_TRY_ASSIGN(const std::vector<double> rgb, numbers(json, "RGBPoints", 4, source));
  LIC3D_TRY_ASSIGN(const std::vector<double> points, numbers(json, "Points", 4, source));
  if (rgb.empty() && points.empty())
    return inputError(source + ": the preset has neither RGBPoints nor Points");
  // ParaView applies a preset rescaled to the data: x runs over the colour points' span.
  const std::vector<double>& span = rgb.empty() ? points : rgb;
  double first = span[0], last = span[0];
  for (std::size_t i = 0; i < span.size(); i += 4) {
    first = std::min(first, span[i]);
    last = std::max(last, span[i]);
  }
  auto relative = [&](double x) {
    return last > first ? std::clamp((x - first) / (last - first), 0.0, 1.0) : 0.0;
  };
  for (std::size_t i = 0; i < rgb.size(); i += 4)
    tf.colors.push_back(
        {relative(rgb[i]), glm::vec3(static_cast<float>(rgb[i + 1]), static_cast<float>(rgb[i + 2]),
                                     static_cast<float>(rgb[i + 3]))});
  for (std::size_t i = 0; i < points.size(); i += 4)
    tf.opacities.push_back({relative(points[i]), points[i + 1]});
  auto byX = [](const auto& a, const auto& b) { return a.x < b.x; };
  std::stable_sort(tf.colors.begin(), tf.colors.end(), byX);
  std::stable_sort(tf.opacities.begin(), tf.opacities.end(), byX);
  LIC3D_TRY(validate(tf, source));
  return tf;
}

std::string transferFunctionToJson(const TransferFunction& tf) {
  Json preset = Json::object();
  preset["Name"] = tf.name.empty() ? "lic3d" : tf.name;
  preset["ColorSpace"] = "RGB";
  if (!tf.colors.empty()) {
    Json rgb = Json::array();
    for (const ColorPoint& p : tf.colors)
      for (const double v : {p.x, double(p.rgb.r), double(p.rgb.g), double(p.rgb.b)})
        rgb.push_back(v);
    preset["RGBPoints"] = rgb;
  }
  if (!tf.opacities.empty()) {
    Json points = Json::array();
    for (const OpacityPoint& p : tf.opacities)
      for (const double v : {p.x, p.alpha, 0.5, 0.0}) points.push_back(v);
    preset["Points"] = points;
  }
  return Json::array({preset}).dump(2) + "\n";
}

}  // namespace lic3d
