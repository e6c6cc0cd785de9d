// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Unsteady fields (docs/TIME.md): a time series of 3D vector fields, either numbered files
// (`step_%03d.vti`, or a glob such as `step_*.vti`) or an analytic field sampled at its own
// times. Steps are read one at a time, when they are needed: only the two around the current
// time are kept (on the device, time_blend_pass.h), so a series may exceed device memory.

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/volume.h"
#include "io/volume_io.h"
#include "lic/analytic_fields.h"

namespace lic3d {

// Whether `field` names a series of files rather than one: it holds a frame-number conversion
// (%d or %0Nd) or a glob character (*, ?, [).
bool isFieldSeriesPattern(std::string_view field);

// The steps around a time, and the weight of the second: the field there is
// (1 - weight) step `first` + weight step `second`.
struct TimeBracket {
  int first = 0;
  int second = 0;
  double weight = 0.0;
  bool operator==(const TimeBracket&) const = default;
};

struct TimeSeries {
  // Files: step k is files[k] and lies at time k (time counts steps), clamped to [0, K-1].
  // Analytic: step k is the field at time k * period / K, and time wraps around the period, so
  // the last step blends into the first (the series loops as the field does).
  std::vector<std::filesystem::path> files;
  std::optional<AnalyticField> analytic;
  Dims grid{0};       // analytic only
  int steps = 0;      // K >= 2
  double period = 0;  // analytic only

  bool periodic() const { return analytic.has_value(); }
  // The time of step k.
  double stepTime(int k) const;
  // The time range a time animation covers by default: [0, K-1] for files, [0, period) else.
  double endTime() const;
  TimeBracket bracket(double time) const;
  // Step k: read from its file (`arrayName` and `info` as readVectorField takes them) or sampled.
  Result<VectorField> loadStep(int k, std::string_view arrayName = {},
                               FieldReadInfo* info = nullptr) const;
  std::string describe() const;  // "12 files step_000.vti .. step_011.vti", for messages
};

// The files of a pattern, in step order: for %d / %0Nd the files whose name has a number there,
// by number (gaps allowed: step k is the k-th file); for a glob the matches in name order. At
// least two files are needed; InvalidInput names the pattern otherwise.
Result<TimeSeries> fileSeries(const std::string& pattern);

// `steps` samples of a time-dependent analytic field over one period of it (timePeriod); an
// InvalidInput error for a field that does not change with time or fewer than 2 steps.
Result<TimeSeries> analyticSeries(AnalyticField field, Dims grid, int steps);

// The field between two steps, and the CPU reference of the GPU blend
// (passes/time_blend_pass.h): (1 - w) a + w b per voxel, in double, rounded to float. The
// steps must share grid and geometry (InvalidInput otherwise); w is clamped to [0, 1].
Result<VectorField> interpolateFields(const VectorField& a, const VectorField& b, double weight);

}  // namespace lic3d
