// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A session: everything that makes a picture (the field, the noise, LicParams, ViewParams) as a
// JSON file. The desktop app saves and loads it; `lic3d render --session` makes the same picture
// from it.

#include <cstdint>
#include <string>

#include "core/error.h"
#include "core/field_precision.h"
#include "core/lic_params.h"
#include "core/look.h"
#include "core/view_params.h"
#include "core/volume.h"

namespace lic3d {

struct FieldSource {
  std::string field = "tornado";  // an analytic field's name or a file path
  Dims grid{128};                 // the analytic field's grid
  std::string array;              // the vector array in a file with several ("" = the first)
  // The LIC grid of a file's field, finer (or coarser) than the file's: "N", "NX,NY,NZ" or a
  // factor "Fx" (core/resolution.h); the field is sampled trilinearly on it and the noise made
  // at it. Empty: the file's own grid.
  std::string resolution;

  bool operator==(const FieldSource&) const = default;
};

struct NoiseSource {
  std::string file;           // a noise volume file, or "" for generated noise
  std::uint64_t seed = 1;     // of the white noise (and of the seed noise's spots)
  int seedSpots = 0;          // > 0: sparse seed noise with this many spots
  float seedFraction = 0.0f;  // > 0 (and no seedSpots): seed noise with this fraction of voxels

  bool operator==(const NoiseSource&) const = default;
};

// 2D LIC (`lic3d render2d`, the app's 2D mode; thesis chapter 3): which plane of a 3D field, and
// the size of the LIC image.
struct PlaneParams {
  int axis = 2;    // a 3D field is cut across this axis (0, 1, 2: x, y, z)
  int index = -1;  // at this voxel layer; -1: the middle one
  int width = 0;   // the LIC image; 0: the field's grid (the other side given: keeping its aspect)
  int height = 0;
  // A plane at any orientation instead of a voxel layer: through `point` (fractions of the box)
  // with `normal` (box axes), sampled at width x height (0: the field's finest spacing).
  bool oblique = false;
  glm::vec3 point{0.5f};
  glm::vec3 normal{0.0f, 0.0f, 1.0f};

  bool operator==(const PlaneParams&) const = default;
};

struct Session {
  Look look = Look::Dense;  // the look the parameters came from (core/look.h)
  FieldSource field;
  NoiseSource noise;
  FieldPrecision precision = FieldPrecision::Auto;
  LicParams lic;
  ViewParams view;
  bool twoD = false;  // 2D LIC of a plane instead of the 3D volume
  PlaneParams plane;
  // An analytic field's time, or a file series' position in steps (docs/TIME.md).
  double time = 0.0;
  // > 0: a time-dependent analytic field is a series of this many steps over its period, blended
  // on the GPU like files; 0: it is sampled at each time exactly.
  int timeSteps = 0;

  bool operator==(const Session&) const = default;
};

inline constexpr int kSessionVersion = 1;

// The most bytes of session text lic3d reads (a session file, or the text chunk of a PNG), derived
// from what it can save, so that every session it saves reads back: 1 MiB for everything but the
// transfer function (paths, names and numbers take a few KiB), and 100 bytes for each control point
// a preset file can hold (sessionToJson writes a point on a line of four numbers, each at most 23
// characters, their separators and the indentation: 81 bytes at most). A preset's name shares its
// file with the points and is written no longer than it was read.
inline constexpr std::size_t kMaxSessionBytes = (std::size_t{1} << 20) + 100 * kMaxPresetPoints;

// The ranges of core/parameter_ranges.h (validate(LicParams), validate(ViewParams) and the
// session's own: grid, noise, time, plane); InvalidInput naming the parameter by its key. A
// session whose text would exceed kMaxSessionBytes (a transfer function of more points than a
// preset file holds) is refused too: it could be saved but not read back.
Result<void> validate(const Session& session);

// Two-space indentation, an array of numbers four to a line (a control point, a vector), floats
// in the fewest digits that read back as the same float.
std::string sessionToJson(const Session& session);
// Missing keys keep their defaults; an unknown key, a wrong type or an unknown name is an
// InvalidInput error naming `source` and the key.
Result<Session> sessionFromJson(const std::string& text, const std::string& source);

}  // namespace lic3d
