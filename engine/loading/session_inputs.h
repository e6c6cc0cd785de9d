// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A session's inputs, made or read in one place for every front end (the CLI, the desktop app,
// the ParaView plugin, the tests): the field (an analytic field, a file, or a time series of
// either), the noise, whether they fit in memory, and the field at a time (docs/TIME.md):
// sampled again, or two resident steps of a series blended on the GPU.

#include <map>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/session.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"
#include "io/volume_io.h"
#include "lic/analytic_fields.h"
#include "lic/time_series.h"
#include "passes/analytic_field_pass.h"
#include "render/lic_renderer.h"

namespace lic3d {

// The times a field has: a periodic one (an analytic field) repeats after `end`, a series of
// files runs from step 0 to its last step.
struct TimeDomain {
  double start = 0.0;
  double end = 0.0;
  bool periodic = false;
  bool timeDependent = false;  // false: the field is steady, a time animation is refused
};
// The time domain of the session's field, before it is loaded (a series' files are listed).
Result<TimeDomain> timeDomainOf(const Session& session);

// Refuses grids whose host-side arrays would not fit this machine's memory (before a field of
// `dims` is made or read).
Result<void> checkHostMemory(Dims dims);

// What a front end keeps resident besides the field, the noise and one LIC volume.
struct RequestShape {
  bool doubleBuffered = false;  // the app's second LIC volume
  bool volumeReadback = false;  // `compute` reads the volume back
  bool licOnHost = false;       // the LIC is gathered from bricks on the host to be drawn
  bool frame = false;           // a frame of the session's size (or frameWidth x frameHeight)
  int frameWidth = 0;
  int frameHeight = 0;
  bool timeSeries = false;      // two resident time steps blended on the GPU (docs/TIME.md)
  std::uint64_t deviceCap = 0;  // > 0: at most this many bytes of device memory (--memory-budget)
};
// ResourceLimit error (exit status 3) if the request does not fit the device and the host:
// checked before anything of it is allocated on the device.
Result<void> checkRequestMemory(const Context& context, const Session& session, Dims dims,
                                const RequestShape& shape);

// One field: an analytic field sampled at `time` (the tornado's time parameter; steady fields
// ignore it), or a file (`info`, when given, gets the array read, the file's vector arrays and
// the vectors read as zero). `gridGiven`: the grid was asked for explicitly, which a file
// refuses. A series of files is not one field: InvalidInput.
Result<VectorField> loadField(const FieldSource& source, bool gridGiven,
                              FieldReadInfo* info = nullptr, double time = 0.0);

// A file's field on the LIC grid of source.resolution (core/resolution.h): resampled, or as it
// is when none is given. Checks the host memory first.
Result<VectorField> atResolution(VectorField field, const FieldSource& source);

// Noise on a grid of `dims`: a noise file (which must have that grid), sparse seed noise, or
// seeded white noise.
Result<NoiseVolume> loadNoise(const NoiseSource& source, Dims dims);
// The noise of `field`: for a piece of a larger field (FieldPiece, the ParaView plugin under
// MPI), the whole grid's white noise cut to the piece, so the pieces agree with the whole.
Result<NoiseVolume> loadNoise(const NoiseSource& source, const VectorField& field);

// Whether the noise is the seeded white noise (no file, no seed noise).
bool isWhiteNoise(const NoiseSource& source);

struct InputOptions {
  bool gridGiven = false;     // the grid was given explicitly (a file field refuses it)
  int analyticTimeSteps = 0;  // > 0: a time-dependent analytic field is a series of this many
                              // steps (the session's time_steps, or the app's default)
  // An analytic field with white noise is made on the device (SessionInputs::device) rather
  // than on the host: for front ends that need no host copy of the field (no CPU LIC, no derived
  // scalars, no RGBA volume).
  bool fieldOnDevice = false;
  bool operator==(const InputOptions&) const = default;
};

// What the frames' fields come from: one steady field; a time-dependent analytic field sampled
// exactly at each time; or a time series whose steps are blended, two resident at a time.
struct SessionInputs {
  VectorField field;  // steady or sampled: the field at `time`; a series: a step read
  NoiseVolume noise;
  FieldReadInfo info;  // of a file field (a series: non-finite vectors of every step read)
  bool fromFile = false;
  std::optional<AnalyticField> sampled;
  // Made on the device (InputOptions::fieldOnDevice): `field` and `noise` then hold the grid and
  // geometry but no vectors or bytes; hostFieldAt still makes the field on the host.
  std::optional<AnalyticInputs> device;
  std::optional<TimeSeries> series;
  std::optional<int> fieldStep;  // the step of the series `field` is, until it is replaced
  double time = 0.0;
  std::map<int, VectorField> hostSteps;  // blended on the host: at most the two in use
  int stepsRead = 0;                     // of the series, for the closing report
  std::vector<double> blendMs;           // GPU time of each blend
  // Scalar arrays a front end holds in memory (the Python module's), on the field's grid before
  // its resolution: colour and opacity name them as a file's arrays, and find them first.
  std::vector<PointScalars> arrays;
};

// The field and noise of `session` at session.time (a series: the first step of the bracket
// around it, and its grid's noise). Validates the sparsity parameters against the grid.
Result<SessionInputs> loadSessionInputs(const Session& session, const InputOptions& options = {});

// Inputs a front end holds in memory (the Python module's arrays): `field`, finished as a file's
// (non-finite vectors read as zero, counted in info; InvalidInput naming `what` when no vector
// flows) and brought to the session's resolution; `noise` when given (it must have the LIC grid),
// else the session's noise.
Result<SessionInputs> sessionInputsOf(const Session& session, VectorField field,
                                      std::optional<NoiseVolume> noise, const std::string& what);

// Step `k` of `series`, checked against the grid, spacing and origin of the steps read before
// (`dims`, `geometry`); its non-finite vectors are counted in `info` when given. Thread-safe.
Result<VectorField> loadSeriesStep(const TimeSeries& series, std::string_view array, int k,
                                   Dims dims, const GridGeometry& geometry,
                                   FieldReadInfo* info = nullptr);

// The steps of the bracket around a time that the renderer does not hold.
std::vector<int> missingSteps(const LicRenderer& renderer, const TimeBracket& bracket);
// Uploads the `loaded` steps that `bracket` still needs (steps for a time already left behind
// would evict the ones in use).
Result<void> uploadSteps(LicRenderer& renderer, const TimeBracket& bracket,
                         std::span<const std::pair<int, VectorField>> loaded);

// The field at `time` on the host: sampled, or the series' two steps blended (the CPU
// reference of the GPU blend; --cpu and the RGBA volume's colours).
Result<VectorField> hostFieldAt(SessionInputs& inputs, const Session& session, double time);

// Brings the renderer's field to `time`: a steady field is set once (`first`), a sampled field
// is made again when the time changed, a series uploads the steps around `time` that are not
// resident and blends them on the GPU. With `onHost` the field is made on the host (--cpu).
Result<void> moveToTime(SessionInputs& inputs, const Session& session, double time,
                        LicRenderer& renderer, bool first, bool onHost = false);

}  // namespace lic3d
