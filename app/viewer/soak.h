// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The desktop app's endurance run (--soak, tests/test_viewer.cpp, docs/RELIABILITY.md): a
// parameter change every kChangeEvery frames, a window resize now and then, memory samples at
// rest, and at the end the verdict whether memory grew.

#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "core/session.h"

namespace lic3d::viewer {

class Soak {
 public:
  // What the app recomputes asynchronously, counted for the report.
  struct Counts {
    std::uint64_t masks = 0;       // sparsity masks asked for
    std::uint64_t volumes = 0;     // LIC volumes finished and shown
    std::uint64_t fieldReads = 0;  // fields read on the loading thread
    std::uint64_t stepReads = 0;   // time steps read on a worker thread
  };
  // What a soak frame needs to know of the app.
  struct AppState {
    bool atRest = false;      // nothing is being read, masked or recomputed
    double seriesStep = 0.0;  // the time between two steps of the series shown, 0 without one
    std::uint64_t deviceBytes = 0;
  };

  // Frame `frame` of a run of `frames`: changes `session`, and the window's size through
  // `resize` (true: larger, false: back), and samples memory when due and at rest.
  void step(std::uint64_t frame, int frames, Session& session, const AppState& state,
            const std::function<void(bool larger)>& resize);
  // Prints the report; the exit status: 0, or 1 when memory grew after the warm-up (2 when the
  // run was too short to tell).
  int verdict(std::uint64_t frames, int swapchains, std::uint64_t masksBuilt) const;

  Counts counts;

 private:
  struct MemorySample {
    std::uint64_t frame;
    std::uint64_t rssBytes;
    std::uint64_t deviceBytes;
  };
  std::vector<MemorySample> samples_;
  std::optional<Session> base_;  // the session the changes are set from and undone to
  bool sampleDue_ = false;
};

}  // namespace lic3d::viewer
