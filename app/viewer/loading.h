// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The desktop app's field (docs/TIME.md): read or made on a worker thread so the window stays
// responsive; for a time series, the steps around the session's time read on a worker thread
// and blended on the GPU, two resident at a time. The engine's inputs module
// (loading/session_inputs.h) does the reading; this class does it off the drawing thread.

#include <future>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/session.h"
#include "loading/session_inputs.h"
#include "render/lic_renderer.h"

namespace lic3d::viewer {

class FieldLoader {
 public:
  struct Loaded {
    SessionInputs inputs;
    TimeBracket bracket;                             // a series: the steps around its time
    std::vector<std::pair<int, VectorField>> steps;  // ... read
  };

  // Starts reading the field and noise of `session` (its sparsity is not checked: the app turns
  // it off instead). A time-dependent analytic field becomes a series of session.timeSteps steps,
  // or `defaultTimeSteps`. `gridGiven`: the grid was given on the command line.
  void start(const Session& session, bool gridGiven, int defaultTimeSteps);
  bool loading() const { return loading_.valid(); }
  // The field read, once it is (nothing while it is still being read).
  std::optional<Result<Loaded>> finished();

  // Makes `loaded` the renderer's field: a steady field's texture, or a series' noise and the
  // steps read. The series' other steps are read from now on by updateTime.
  Result<void> show(const Loaded& loaded, LicRenderer& renderer);

  // Blends the field at `time` from the two steps around it, reading steps that are not
  // resident on a worker thread; true when a new blend was made. A step that cannot be read
  // sets `message` and is not read again every frame. `stepReads` counts the steps read.
  Result<bool> updateTime(LicRenderer& renderer, const Session& session, std::string& message,
                          std::uint64_t& stepReads);
  // A step is being read, or the blend shown is not the one of `time`.
  bool timePending(double time) const;
  const std::optional<TimeSeries>& series() const { return series_; }
  // After a lost device: the steps being read are waited for and dropped with the series.
  void dropSeries();

 private:
  using Steps = std::vector<std::pair<int, VectorField>>;
  std::future<Result<Loaded>> loading_;
  std::optional<TimeSeries> series_;
  Dims grid_{0};
  GridGeometry geometry_;
  std::optional<TimeBracket> blended_;  // what the field texture was blended from
  std::future<Result<Steps>> stepLoading_;
  std::vector<int> stepsLoading_;  // what stepLoading_ reads
  std::vector<int> failedSteps_;   // steps that could not be read: not read again every frame
};

}  // namespace lic3d::viewer
