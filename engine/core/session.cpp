// SPDX-License-Identifier: BSD-3-Clause
#include "core/session.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <glm/geometric.hpp>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <type_traits>
#include <utility>
#include <vector>

#include "core/enum_names.h"
#include "core/parameter_ranges.h"
#include "core/resolution.h"
#include "core/strict_json.h"
#include "core/text.h"

namespace lic3d {
namespace {

using Json = nlohmann::ordered_json;

// Every key of a session file, in file order, once: sessionToJson runs it with a Writer over a
// const Session, sessionFromJson with a Reader over a Session to fill. Fields::value takes
// numbers, booleans, strings, enums (by their names) and glm vectors (as arrays); pair, axis and
// mode store two members as one array, an axis as "x"/"y"/"z" and the 2D flag as "2d"/"3d".
template <class Fields, class S>
void visitSession(Fields& f, S& s) {
  f.version("lic3d_session");
  f.value("look", s.look);
  f.object("field", [&](Fields& o) {
    o.value("source", s.field.field);
    o.value("grid", s.field.grid);
    o.value("array", s.field.array);
    o.value("resolution", s.field.resolution);
  });
  f.object("noise", [&](Fields& o) {
    o.value("file", s.noise.file);
    o.value("seed", s.noise.seed);
    o.value("seed_spots", s.noise.seedSpots);
    o.value("seed_fraction", s.noise.seedFraction);
  });
  f.value("precision", s.precision);
  f.mode("mode", s.twoD);
  f.value("time", s.time);
  f.value("time_steps", s.timeSteps);
  f.object("plane", [&](Fields& o) {
    o.axis("axis", s.plane.axis);
    o.value("index", s.plane.index);
    o.value("width", s.plane.width);
    o.value("height", s.plane.height);
    o.value("oblique", s.plane.oblique);
    o.value("point", s.plane.point);
    o.value("normal", s.plane.normal);
  });
  auto& l = s.lic;
  f.object("lic", [&](Fields& o) {
    o.value("length", l.length);
    o.value("step", l.step);
    o.value("bias", l.bias);
    o.value("integrator", l.integrator);
    o.value("kernel", l.kernel);
    o.value("noise_filter", l.noiseFilter);
    o.value("direction", l.direction);
    o.value("scheme", l.scheme);
    o.object("sparsity", [&](Fields& p) {
      p.value("distribution", l.sparsity.distribution);
      p.value("points", l.sparsity.points);
      p.value("radius", l.sparsity.radius);
      p.value("ratio", l.sparsity.ratio);
      p.value("seed", l.sparsity.seed);
      p.value("amount", l.sparsity.amount);
    });
  });
  auto& v = s.view;
  f.object("view", [&](Fields& o) {
    o.value("width", v.width);
    o.value("height", v.height);
    o.value("slicing", v.slicing);
    o.value("slices", v.slices);
    o.object("camera", [&](Fields& c) {
      c.value("azimuth", v.camera.azimuth);
      c.value("elevation", v.camera.elevation);
      c.value("distance", v.camera.distance);
      c.value("fov", v.camera.fovY);
      c.value("orthographic", v.camera.orthographic);
      c.value("target", v.camera.target);
    });
    o.value("background", v.background);
    o.value("alpha", v.alpha);
    o.value("optical_depth", v.opticalDepth);
    o.value("opacity", v.opacityMode);
    o.value("filter", v.filter);
    o.value("contrast", v.contrast);
    o.value("percentile_window", v.percentileWindow);
    o.value("window_percentiles", v.windowPercentiles);
    o.value("manual_window", v.manualWindow);
    o.pair("window", v.windowLow, v.windowHigh);
    o.value("gain", v.gain);
    o.value("brightness", v.brightness);
    o.value("color", v.color);
    o.value("colormap", v.colormap);
    o.value("diverging_when_signed", v.divergingWhenSigned);
    o.value("color_by", v.colorBy);
    o.value("opacity_by", v.opacityBy);
    o.value("range_tail", v.rangeTail);
    o.transfer("transfer_function", v.transfer);
    o.value("auto_color_range", v.autoColorRange);
    o.pair("color_range", v.colorLow, v.colorHigh);
    o.value("legend", v.legend);
    o.value("axes", v.axes);
    o.value("title", v.title);
    o.value("legend_title", v.legendTitle);
    o.value("font_size", v.fontSize);
    o.value("magnitude_opacity", v.magnitudeOpacity);
    o.value("magnitude_threshold", v.magnitudeThreshold);
    o.value("opacity_floor", v.opacityFloor);
    o.value("clip_min", v.clipMin);
    o.value("clip_max", v.clipMax);
    o.value("clip_plane", v.clipPlane);
    o.value("clip_plane_point", v.clipPlanePoint);
    o.value("clip_plane_normal", v.clipPlaneNormal);
    o.value("roi", v.roi);
    o.value("roi_center", v.roiCenter);
    o.value("roi_size", v.roiSize);
    o.value("roi_rotation", v.roiRotation);
    o.value("roi_outside", v.roiOutside);
    o.value("fog", v.fog);
    o.pair("fog_range", v.fogStart, v.fogEnd);
    o.value("fog_color_from_background", v.fogColorFromBackground);
    o.value("fog_color", v.fogColor);
    o.value("stereo", v.stereo);
    o.value("eye_separation", v.eyeSeparation);
    o.value("zero_parallax", v.zeroParallax);
    o.value("lighting", v.lighting);
    o.object("light", [&](Fields& t) {
      t.value("ambient", v.light.ambient);
      t.value("diffuse", v.light.diffuse);
      t.value("specular", v.light.specular);
      t.value("shininess", v.light.shininess);
    });
    o.value("halo", v.halo);
    o.value("halo_radius", v.haloRadius);
    o.value("occlusion", v.occlusion);
    o.value("jitter", v.jitter);
  });
}

// A JSON number as T: integers only from whole numbers within T's range (no wrapping, no
// truncation of 4.7, no -1 as an unsigned seed); floats as parsed (validate() checks ranges).
// False with what was expected in `expected`.
template <class T>
bool numberAs(const Json& j, T& out, std::string& expected) {
  if constexpr (std::is_integral_v<T>) {
    const bool whole = j.is_number_integer() || (j.is_number_float() && [&] {
                         const double d = j.get<double>();
                         return std::isfinite(d) && std::floor(d) == d;
                       }());
    expected = "a whole number from " + std::to_string(std::numeric_limits<T>::min()) + " to " +
               std::to_string(std::numeric_limits<T>::max());
    if (!whole) return false;
    if (j.is_number_unsigned()) {
      const auto u = j.get<std::uint64_t>();
      if (u > static_cast<std::uint64_t>(std::numeric_limits<T>::max())) return false;
      out = static_cast<T>(u);
      return true;
    }
    if (j.is_number_integer()) {
      const auto i = j.get<std::int64_t>();
      if (i < 0 && std::is_unsigned_v<T>) return false;
      if (i < static_cast<std::int64_t>(std::numeric_limits<T>::min()) ||
          (i > 0 && static_cast<std::uint64_t>(i) >
                        static_cast<std::uint64_t>(std::numeric_limits<T>::max())))
        return false;
      out = static_cast<T>(i);
      return true;
    }
    const double d = j.get<double>();  // a whole float such as 20.0
    // T's maximum is 2^digits - 1, which a double may round up to 2^digits: compare with that.
    if (d < static_cast<double>(std::numeric_limits<T>::min()) ||
        d >= std::ldexp(1.0, std::numeric_limits<T>::digits))
      return false;
    out = static_cast<T>(d);
    return true;
  } else {
    expected = "a number";
    if (!j.is_number()) return false;
    out = j.get<T>();
    return true;
  }
}

template <class T>
struct IsGlmVector : std::false_type {};
template <glm::length_t N, class T, glm::qualifier Q>
struct IsGlmVector<glm::vec<N, T, Q>> : std::true_type {};

// The double nearest to the shortest decimal that reads back as `value`: JSON then holds 0.2 for
// 0.2f, not the float's exact 0.20000000298023224. The Reader takes it as a double and narrows it
// to `value` again: a double carries more than twice a float's digits, so the two roundings agree.
double shortestDouble(float value) {
  char text[32];
  const char* end = std::to_chars(text, text + sizeof text, value).ptr;
  double result = 0.0;
  std::from_chars(text, end, result);
  return result;
}

template <class T>
auto jsonNumber(T value) {
  if constexpr (std::is_same_v<T, float>)
    return shortestDouble(value);
  else
    return value;
}

// Writes the keys visitSession names into a JSON object.
class Writer {
 public:
  explicit Writer(Json& object) : object_(object) {}

  void version(const char* key) { object_[key] = kSessionVersion; }
  template <class T>
  void value(const char* key, const T& value) {
    if constexpr (std::is_enum_v<T>) {
      object_[key] = enumName(value);
    } else if constexpr (IsGlmVector<T>::value) {
      Json array = Json::array();
      for (int i = 0; i < T::length(); ++i) array.push_back(jsonNumber(value[i]));
      object_[key] = std::move(array);
    } else {
      object_[key] = jsonNumber(value);
    }
  }
  void pair(const char* key, float first, float second) {
    object_[key] = Json::array({shortestDouble(first), shortestDouble(second)});
  }
  void transfer(const char* key, const TransferFunction& tf) {
    Json rgb = Json::array(), points = Json::array();
    for (const ColorPoint& p : tf.colors)
      for (const double x :
           {p.x, shortestDouble(p.rgb.r), shortestDouble(p.rgb.g), shortestDouble(p.rgb.b)})
        rgb.push_back(x);
    for (const OpacityPoint& p : tf.opacities)
      for (const double x : {p.x, p.alpha, 0.5, 0.0}) points.push_back(x);
    object_[key] = {{"Name", tf.name}, {"RGBPoints", rgb}, {"Points", points}};
  }
  void axis(const char* key, int axis) {
    object_[key] = std::string(1, static_cast<char>('x' + axis));
  }
  void mode(const char* key, bool twoD) { object_[key] = twoD ? "2d" : "3d"; }
  template <class Nested>
  void object(const char* key, const Nested& write) {
    Json nested = Json::object();
    Writer writer(nested);
    write(writer);
    object_[key] = std::move(nested);
  }

 private:
  Json& object_;
};

// Fills C++ values from a JSON object, remembering the first problem and refusing keys it was
// never asked about (a misspelt key would otherwise be silently ignored).
class Reader {
 public:
  Reader(const Json& object, std::string path, std::string* error)
      : object_(object), path_(std::move(path)), error_(error) {
    if (!object_.is_object()) fail(path_, "an object");
  }
  ~Reader() {
    if (!error_->empty() || !object_.is_object()) return;
    for (const auto& [key, value] : object_.items())
      if (!seen_.count(key)) {
        *error_ = "unknown key " + join(key);
        return;
      }
  }

  void version(const char* key) {
    int version = kSessionVersion;
    value(key, version);
    if (error_->empty() && version != kSessionVersion)
      *error_ = std::string(key) + " is " + std::to_string(version) +
                ", this lic3d reads version " + std::to_string(kSessionVersion);
  }
  template <class T>
  void value(const char* key, T& value) {
    const Json* j = find(key);
    if (!j) return;
    if constexpr (std::is_same_v<T, bool>) {
      if (!j->is_boolean()) return fail(join(key), "true or false");
      value = j->get<bool>();
    } else if constexpr (std::is_same_v<T, std::string>) {
      if (!j->is_string()) return fail(join(key), "a string");
      value = j->get<std::string>();
    } else if constexpr (std::is_enum_v<T>) {
      const auto parsed = j->is_string() ? parseEnum<T>(j->get<std::string>()) : std::nullopt;
      if (!parsed) return fail(join(key), "one of " + enumChoices<T>());
      value = *parsed;
    } else if constexpr (IsGlmVector<T>::value) {
      if (!j->is_array() || j->size() != static_cast<std::size_t>(T::length()))
        return fail(join(key), "an array of " + std::to_string(T::length()) + " numbers");
      for (int i = 0; i < T::length(); ++i) {
        std::string expected;
        if (!numberAs((*j)[static_cast<std::size_t>(i)], value[i], expected))
          return fail(join(key),
                      "an array of " + std::to_string(T::length()) + " numbers, each " + expected);
      }
    } else {
      std::string expected;
      if (!numberAs(*j, value, expected)) {
        // Reported with the parameter's range, which is what the user can give, not int's.
        if (const ParameterRange* range = findParameterRange(join(key)))
          expected = "a whole number in " + range->text();
        return fail(join(key), expected + ", got " + quoteForMessage(j->dump()));
      }
    }
  }
  void numbers(const char* key, std::vector<double>& values, std::size_t stride) {
    const Json* j = find(key);
    if (!j) return;
    if (!j->is_array() || j->size() % stride != 0)
      return fail(join(key), "an array of " + std::to_string(stride) + "-tuples of numbers");
    values.clear();
    for (const Json& v : *j) {
      if (!v.is_number()) return fail(join(key), "an array of numbers");
      values.push_back(v.get<double>());
    }
  }
  // A transfer function as the Writer stores it: relative x, ParaView's RGBPoints and Points.
  void transfer(const char* key, TransferFunction& tf) {
    object(key, [&](Reader& r) {
      r.value("Name", tf.name);
      std::vector<double> rgb, points;
      r.numbers("RGBPoints", rgb, 4);
      r.numbers("Points", points, 4);
      tf.colors.clear();
      tf.opacities.clear();
      for (std::size_t i = 0; i < rgb.size(); i += 4)
        tf.colors.push_back(
            {rgb[i], glm::vec3(static_cast<float>(rgb[i + 1]), static_cast<float>(rgb[i + 2]),
                               static_cast<float>(rgb[i + 3]))});
      for (std::size_t i = 0; i < points.size(); i += 4)
        tf.opacities.push_back({points[i], points[i + 1]});
    });
  }
  void pair(const char* key, float& first, float& second) {
    glm::vec2 both(first, second);
    value(key, both);
    first = both.x;
    second = both.y;
  }
  void axis(const char* key, int& axis) {
    std::string name(1, static_cast<char>('x' + axis));
    value(key, name);
    if (error_->empty() && name != "x" && name != "y" && name != "z")
      fail(join(key), "x, y or z");
    else if (error_->empty())
      axis = name[0] - 'x';
  }
  void mode(const char* key, bool& twoD) {
    std::string name = twoD ? "2d" : "3d";
    value(key, name);
    if (error_->empty() && name != "2d" && name != "3d") fail(join(key), "2d or 3d");
    twoD = name == "2d";
  }
  template <class Nested>
  void object(const char* key, const Nested& read) {
    if (const Json* j = find(key)) {
      Reader nested(*j, join(key), error_);
      if (error_->empty()) read(nested);
    }
  }

 private:
  const Json* find(const char* key) {
    seen_[key] = true;
    if (!error_->empty() || !object_.is_object()) return nullptr;
    const auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
  }
  std::string join(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }
  void fail(const std::string& where, const std::string& expected) {
    if (error_->empty())
      *error_ = (where.empty() ? "the top level" : where) + " must be " + expected;
  }

  const Json& object_;
  std::string path_;
  std::string* error_;
  std::map<std::string, bool> seen_;
};

}  // namespace

Result<void> validate(const Session& s) {
  for (int a = 0; a < 3; ++a) {
    LIC3D_TRY(checkRange(ranges::kGrid, s.field.grid[a]));
    LIC3D_TRY(checkRange(ranges::kPlanePoint, s.plane.point[a]));
    LIC3D_TRY(checkRange(ranges::kPlaneNormal, s.plane.normal[a]));
  }
  LIC3D_TRY(parseResolution(s.field.resolution));
  if (s.plane.oblique && !(glm::length(s.plane.normal) > 1e-6f))
    return parameterError(ranges::kPlaneNormal.key,
                          "must not be zero: the normal given is (" +
                              tripleText(glm::dvec3(s.plane.normal), ", ") +
                              "), its length must exceed 1e-6");
  LIC3D_TRY(checkRange(ranges::kSeedSpots, s.noise.seedSpots));
  LIC3D_TRY(checkRange(ranges::kSeedFraction, s.noise.seedFraction));
  LIC3D_TRY(checkRange(ranges::kTime, s.time));
  LIC3D_TRY(checkRange(ranges::kTimeSteps, s.timeSteps));
  if (s.timeSteps == 1) return parameterError(ranges::kTimeSteps.key, "must be 0 or at least 2");
  LIC3D_TRY(checkRange(ranges::kPlaneIndex, s.plane.index));
  LIC3D_TRY(checkRange(ranges::kPlaneWidth, s.plane.width));
  LIC3D_TRY(checkRange(ranges::kPlaneHeight, s.plane.height));
  LIC3D_TRY(validate(s.lic));
  LIC3D_TRY(validate(s.view));
  // A session travels as JSON text (session files, PNG metadata): text that is not UTF-8, such
  // as a file name in another encoding, could not be recorded, so it is refused before any work.
  std::size_t bytes = 0;
  try {
    bytes = sessionToJson(s).size();
  } catch (const Json::exception& e) {
    return inputError(std::string("the session holds text that is not UTF-8 (") + e.what() +
                      "); lic3d records its parameters as JSON text: rename the file");
  }
  if (bytes > kMaxSessionBytes)
    return inputError(
        "the session takes " + std::to_string(bytes) + " bytes as JSON text, beyond the " +
        std::to_string(kMaxSessionBytes) + " bytes lic3d reads back (its transfer function has " +
        std::to_string(s.view.transfer.colors.size()) + " colour and " +
        std::to_string(s.view.transfer.opacities.size()) +
        " opacity points; a preset file holds at most " + std::to_string(kMaxPresetPoints) + ")");
  return {};
}

namespace {

bool isScalar(const Json& json) { return json.is_primitive(); }

// Like Json::dump(2), but an array of scalars four to a line: dump(2) gave every number of a
// transfer function a line of its own, and a 243 KB preset 1.1 MB of session (446 KB now).
void appendJson(std::string& out, const Json& json, int depth) {
  const std::string inner(2 * static_cast<std::size_t>(depth + 1), ' ');
  const std::string outer(2 * static_cast<std::size_t>(depth), ' ');
  const bool array = json.is_array();
  if (!json.is_structured()) {
    out += json.dump();
  } else if (json.empty()) {
    out += array ? "[]" : "{}";
  } else if (array && std::all_of(json.begin(), json.end(), isScalar)) {
    const bool oneLine = json.size() <= 4;
    out += oneLine ? "[" : "[\n" + inner;
    for (std::size_t i = 0; i < json.size(); ++i) {
      if (i > 0) out += i % 4 == 0 ? ",\n" + inner : ", ";
      out += json[i].dump();
    }
    out += oneLine ? "]" : "\n" + outer + "]";
  } else {
    out += array ? "[\n" : "{\n";
    bool first = true;
    for (const auto& item : json.items()) {
      if (!first) out += ",\n";
      first = false;
      out += inner;
      if (!array) out += Json(item.key()).dump() + ": ";
      appendJson(out, item.value(), depth + 1);
    }
    out += "\n" + outer + (array ? "]" : "}");
  }
}

}  // namespace

std::string sessionToJson(const Session& session) {
  Json json = Json::object();
  Writer writer(json);
  visitSession(writer, session);
  std::string text;
  appendJson(text, json, 0);
  return text + "\n";
}

Result<Session> sessionFromJson(const std::string& text, const std::string& source) {
  LIC3D_TRY_ASSIGN(const Json json, parseJsonStrictly(text, source));
  Session session;
  std::string error;
  {
    Reader reader(json, "", &error);
    visitSession(reader, session);
  }
  if (!error.empty()) return inputError(source + ": " + error);
  // Named by the file and the key: the flags of a front end have no part in it.
  if (Result<void> valid = validate(session); !valid)
    return inputError(source + ": " + valid.error().message);
  return session;
}

}  // namespace lic3d
