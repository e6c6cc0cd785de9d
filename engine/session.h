#pragma once
// A session: everything that makes a picture (the field, the noise, LicParams, ViewParams) as a
// JSON file. The desktop app saves and loads it; `lic3d render --session` makes the same picture
// from it.

#include <cstdint>
#include <filesystem>
#include <string>

#include "error.h"
#include "lic_params.h"
#include "view_params.h"
#include "volume.h"
#include "volume_textures.h"

namespace lic3d {

struct FieldSource {
  std::string field = "tornado";  // an analytic field's name or a file path
  Dims grid{128};                 // the analytic field's grid
  std::string array;              // the vector array in a file with several ("" = the first)

  bool operator==(const FieldSource&) const = default;
};

struct NoiseSource {
  std::string file;        // a noise volume file, or "" for generated noise
  std::uint64_t seed = 1;  // of the white noise (and of the seed noise's spots)
  int seedSpots = 0;       // > 0: sparse seed noise with this many spots

  bool operator==(const NoiseSource&) const = default;
};

struct Session {
  FieldSource field;
  NoiseSource noise;
  FieldPrecision precision = FieldPrecision::Auto;
  LicParams lic;
  ViewParams view;

  bool operator==(const Session&) const = default;
};

inline constexpr int kSessionVersion = 1;

std::string sessionToJson(const Session& session);
// Missing keys keep their defaults; an unknown key, a wrong type or an unknown name is an
// InvalidInput error naming `source` and the key.
Result<Session> sessionFromJson(const std::string& text, const std::string& source);

Result<Session> readSession(const std::filesystem::path& path);
Result<void> writeSession(const std::filesystem::path& path, const Session& session);

}  // namespace lic3d
