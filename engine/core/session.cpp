#include "core/session.h"

#include <cmath>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "core/enum_names.h"

namespace lic3d {
namespace {

using Json = nlohmann::ordered_json;

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

  template <class T>
  void number(const char* key, T& value) {
    if (const Json* j = find(key)) {
      if (!j->is_number()) return fail(join(key), "a number");
      value = j->get<T>();
    }
  }
  void boolean(const char* key, bool& value) {
    if (const Json* j = find(key)) {
      if (!j->is_boolean()) return fail(join(key), "true or false");
      value = j->get<bool>();
    }
  }
  void string(const char* key, std::string& value) {
    if (const Json* j = find(key)) {
      if (!j->is_string()) return fail(join(key), "a string");
      value = j->get<std::string>();
    }
  }
  template <class E>
  void name(const char* key, E& value) {
    if (const Json* j = find(key)) {
      const auto parsed = j->is_string() ? parseEnum<E>(j->get<std::string>()) : std::nullopt;
      if (!parsed) return fail(join(key), "one of " + enumChoices<E>());
      value = *parsed;
    }
  }
  template <class V>
  void vector(const char* key, V& value) {
    if (const Json* j = find(key)) {
      if (!j->is_array() || j->size() != static_cast<std::size_t>(V::length()))
        return fail(join(key), "an array of " + std::to_string(V::length()) + " numbers");
      for (int i = 0; i < V::length(); ++i) {
        if (!(*j)[static_cast<std::size_t>(i)].is_number())
          return fail(join(key), "an array of numbers");
        value[i] = (*j)[static_cast<std::size_t>(i)].get<typename V::value_type>();
      }
    }
  }
  void object(const char* key, const std::function<void(Reader&)>& read) {
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

Json toArray(glm::vec3 v) { return Json::array({v.x, v.y, v.z}); }
Json toArray(glm::vec2 v) { return Json::array({v.x, v.y}); }

}  // namespace

std::string sessionToJson(const Session& s) {
  const LicParams& l = s.lic;
  const ViewParams& v = s.view;
  Json j;
  j["lic3d_session"] = kSessionVersion;
  j["field"] = {{"source", s.field.field},
                {"grid", Json::array({s.field.grid.x, s.field.grid.y, s.field.grid.z})},
                {"array", s.field.array}};
  j["noise"] = {{"file", s.noise.file}, {"seed", s.noise.seed}, {"seed_spots", s.noise.seedSpots}};
  j["precision"] = enumName(s.precision);
  j["mode"] = s.twoD ? "2d" : "3d";
  j["time"] = s.time;
  j["time_steps"] = s.timeSteps;
  j["plane"] = {{"axis", std::string(1, static_cast<char>('x' + s.plane.axis))},
                {"index", s.plane.index},
                {"width", s.plane.width},
                {"height", s.plane.height}};
  j["lic"] = {{"length", l.length},
              {"step", l.step},
              {"bias", l.bias},
              {"integrator", enumName(l.integrator)},
              {"kernel", enumName(l.kernel)},
              {"noise_filter", enumName(l.noiseFilter)},
              {"direction", enumName(l.direction)},
              {"scheme", enumName(l.scheme)},
              {"sparsity",
               {{"distribution", enumName(l.sparsity.distribution)},
                {"points", l.sparsity.points},
                {"radius", l.sparsity.radius},
                {"ratio", l.sparsity.ratio},
                {"seed", l.sparsity.seed}}}};
  const CameraParams& c = v.camera;
  j["view"] = {{"width", v.width},
               {"height", v.height},
               {"slicing", enumName(v.slicing)},
               {"slices", v.slices},
               {"camera",
                {{"azimuth", c.azimuth},
                 {"elevation", c.elevation},
                 {"distance", c.distance},
                 {"fov", c.fovY},
                 {"orthographic", c.orthographic},
                 {"target", toArray(c.target)}}},
               {"background", toArray(v.background)},
               {"alpha", v.alpha},
               {"opacity", enumName(v.opacityMode)},
               {"filter", enumName(v.filter)},
               {"contrast", v.contrast},
               {"manual_window", v.manualWindow},
               {"window", toArray(glm::vec2(v.windowLow, v.windowHigh))},
               {"gain", v.gain},
               {"brightness", v.brightness},
               {"color", enumName(v.color)},
               {"colormap", enumName(v.colormap)},
               {"auto_color_range", v.autoColorRange},
               {"color_range", toArray(glm::vec2(v.colorLow, v.colorHigh))},
               {"legend", v.legend},
               {"axes", v.axes},
               {"magnitude_opacity", v.magnitudeOpacity},
               {"magnitude_threshold", v.magnitudeThreshold},
               {"clip_min", toArray(v.clipMin)},
               {"clip_max", toArray(v.clipMax)},
               {"roi", enumName(v.roi)},
               {"roi_center", toArray(v.roiCenter)},
               {"roi_size", v.roiSize},
               {"roi_rotation", toArray(v.roiRotation)},
               {"roi_outside", v.roiOutside},
               {"fog", v.fog},
               {"fog_range", toArray(glm::vec2(v.fogStart, v.fogEnd))},
               {"fog_color_from_background", v.fogColorFromBackground},
               {"fog_color", toArray(v.fogColor)},
               {"stereo", enumName(v.stereo)},
               {"eye_separation", v.eyeSeparation},
               {"zero_parallax", v.zeroParallax},
               {"lighting", enumName(v.lighting)},
               {"light",
                {{"ambient", v.light.ambient},
                 {"diffuse", v.light.diffuse},
                 {"specular", v.light.specular},
                 {"shininess", v.light.shininess}}}};
  return j.dump(2) + "\n";
}

Result<Session> sessionFromJson(const std::string& text, const std::string& source) {
  Json json;
  try {
    json = Json::parse(text);
  } catch (const Json::parse_error& e) {
    return inputError(source + ": not valid JSON: " + e.what());
  }
  Session s;
  std::string error;
  {
    Reader top(json, "", &error);
    int version = kSessionVersion;
    top.number("lic3d_session", version);
    if (error.empty() && version != kSessionVersion)
      error = "lic3d_session is " + std::to_string(version) + ", this lic3d reads version " +
              std::to_string(kSessionVersion);
    top.object("field", [&](Reader& r) {
      r.string("source", s.field.field);
      r.vector("grid", s.field.grid);
      r.string("array", s.field.array);
    });
    top.object("noise", [&](Reader& r) {
      r.string("file", s.noise.file);
      r.number("seed", s.noise.seed);
      r.number("seed_spots", s.noise.seedSpots);
    });
    top.name("precision", s.precision);
    std::string mode = s.twoD ? "2d" : "3d";
    top.string("mode", mode);
    if (error.empty() && mode != "2d" && mode != "3d") error = "mode must be 2d or 3d";
    s.twoD = mode == "2d";
    top.number("time", s.time);
    top.number("time_steps", s.timeSteps);
    top.object("plane", [&](Reader& r) {
      std::string axis(1, static_cast<char>('x' + s.plane.axis));
      r.string("axis", axis);
      if (error.empty() && axis != "x" && axis != "y" && axis != "z")
        error = "plane.axis must be x, y or z";
      else if (error.empty())
        s.plane.axis = axis[0] - 'x';
      r.number("index", s.plane.index);
      r.number("width", s.plane.width);
      r.number("height", s.plane.height);
    });
    top.object("lic", [&](Reader& r) {
      LicParams& l = s.lic;
      r.number("length", l.length);
      r.number("step", l.step);
      r.number("bias", l.bias);
      r.name("integrator", l.integrator);
      r.name("kernel", l.kernel);
      r.name("noise_filter", l.noiseFilter);
      r.name("direction", l.direction);
      r.name("scheme", l.scheme);
      r.object("sparsity", [&](Reader& sp) {
        sp.name("distribution", l.sparsity.distribution);
        sp.number("points", l.sparsity.points);
        sp.number("radius", l.sparsity.radius);
        sp.number("ratio", l.sparsity.ratio);
        sp.number("seed", l.sparsity.seed);
      });
    });
    top.object("view", [&](Reader& r) {
      ViewParams& v = s.view;
      r.number("width", v.width);
      r.number("height", v.height);
      r.name("slicing", v.slicing);
      r.number("slices", v.slices);
      r.object("camera", [&](Reader& c) {
        c.number("azimuth", v.camera.azimuth);
        c.number("elevation", v.camera.elevation);
        c.number("distance", v.camera.distance);
        c.number("fov", v.camera.fovY);
        c.boolean("orthographic", v.camera.orthographic);
        c.vector("target", v.camera.target);
      });
      r.vector("background", v.background);
      r.number("alpha", v.alpha);
      r.name("opacity", v.opacityMode);
      r.name("filter", v.filter);
      r.boolean("contrast", v.contrast);
      r.boolean("manual_window", v.manualWindow);
      glm::vec2 window(v.windowLow, v.windowHigh);
      r.vector("window", window);
      v.windowLow = window.x;
      v.windowHigh = window.y;
      r.number("gain", v.gain);
      r.number("brightness", v.brightness);
      r.name("color", v.color);
      r.name("colormap", v.colormap);
      r.boolean("auto_color_range", v.autoColorRange);
      glm::vec2 range(v.colorLow, v.colorHigh);
      r.vector("color_range", range);
      v.colorLow = range.x;
      v.colorHigh = range.y;
      r.boolean("legend", v.legend);
      r.boolean("axes", v.axes);
      r.number("magnitude_opacity", v.magnitudeOpacity);
      r.number("magnitude_threshold", v.magnitudeThreshold);
      r.vector("clip_min", v.clipMin);
      r.vector("clip_max", v.clipMax);
      r.name("roi", v.roi);
      r.vector("roi_center", v.roiCenter);
      r.number("roi_size", v.roiSize);
      r.vector("roi_rotation", v.roiRotation);
      r.boolean("roi_outside", v.roiOutside);
      r.boolean("fog", v.fog);
      glm::vec2 fog(v.fogStart, v.fogEnd);
      r.vector("fog_range", fog);
      v.fogStart = fog.x;
      v.fogEnd = fog.y;
      r.boolean("fog_color_from_background", v.fogColorFromBackground);
      r.vector("fog_color", v.fogColor);
      r.name("stereo", v.stereo);
      r.number("eye_separation", v.eyeSeparation);
      r.number("zero_parallax", v.zeroParallax);
      r.name("lighting", v.lighting);
      r.object("light", [&](Reader& lr) {
        lr.number("ambient", v.light.ambient);
        lr.number("diffuse", v.light.diffuse);
        lr.number("specular", v.light.specular);
        lr.number("shininess", v.light.shininess);
      });
    });
  }
  if (!error.empty()) return inputError(source + ": " + error);
  for (int a = 0; a < 3; ++a)
    if (s.field.grid[a] < 1 || s.field.grid[a] > 2048)
      return inputError(source + ": field.grid sizes must be in 1..2048");
  if (!std::isfinite(s.time)) return inputError(source + ": time must be a finite number");
  if (s.timeSteps < 0 || s.timeSteps == 1 || s.timeSteps > 100000)
    return inputError(source + ": time_steps must be 0 or 2..100000");
  if (s.plane.index < -1 || s.plane.width < 0 || s.plane.width > 16384 || s.plane.height < 0 ||
      s.plane.height > 16384)
    return inputError(source +
                      ": plane.index must be -1 or more, plane.width and plane.height "
                      "0..16384");
  if (auto r = validate(s.lic); !r) return inputError(source + ": " + r.error().message);
  if (auto r = validate(s.view); !r) return inputError(source + ": " + r.error().message);
  return s;
}

}  // namespace lic3d
