// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Where a run's time goes: wall-clock seconds per stage (reading or making the field, the noise,
// the mask, uploads, the LIC, frames, read-backs, encoding, writing), summed over a run's frames.
// The engine and the front ends add to one process-wide table; the CLI reports it in its summary
// (`"timings"`) and with --timings. Thread-safe: worker threads add their stages too.

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace lic3d {

// The stages in the order they were first recorded, with their summed seconds.
using StageTimings = std::vector<std::pair<std::string, double>>;

// Wall-clock seconds from `start` to now.
inline double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void addStageTime(std::string_view stage, double seconds);
StageTimings stageTimings();
// The bytes a stage moved (a volume written), summed like its seconds, so that --timings can
// give its rate; 0 for a stage without any.
void addStageBytes(std::string_view stage, std::uint64_t bytes);
std::uint64_t stageBytes(std::string_view stage);
// Clears the seconds and the bytes.
void clearStageTimings();

// Adds the time from its construction to its destruction (or to stop()) to `stage`.
class StageTimer {
 public:
  explicit StageTimer(std::string_view stage)
      : stage_(stage), start_(std::chrono::steady_clock::now()) {}
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;
  ~StageTimer() { stop(); }
  void stop() {
    if (stopped_) return;
    stopped_ = true;
    addStageTime(stage_, secondsSince(start_));
  }

 private:
  std::string stage_;
  std::chrono::steady_clock::time_point start_;
  bool stopped_ = false;
};

}  // namespace lic3d
