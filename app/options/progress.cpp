// SPDX-License-Identifier: BSD-3-Clause
#include "options/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "core/stage_times.h"

namespace lic3d::cli {
Progress::Progress(std::string what, bool quiet)
    : what_(std::move(what)),
      quiet_(quiet),
      terminal_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

Progress::~Progress() { finish(); }

void Progress::update(double fraction) {
  if (quiet_ || finished_) return;
  const int percent = static_cast<int>(fraction * 100.0);
  current_ = std::clamp(percent, 0, 99);
  // A terminal gets every percent in place; a log gets one line per quarter.
  const int step = terminal_ ? 1 : 25;
  if (percent / step == lastReported_ / step || percent >= 100) return;
  lastReported_ = percent;
  if (terminal_)
    std::fprintf(stderr, "\rlic3d: %s %3d%%%s%s\033[K", what_.c_str(), percent,
                 stage_.empty() ? "" : ": ", stage_.c_str());
  else
    std::fprintf(stderr, "lic3d: %s %d%%\n", what_.c_str(), percent);
}

void Progress::stage(const std::string& stage) {
  if (quiet_ || finished_) return;
  stage_ = stage;
  if (terminal_)
    std::fprintf(stderr, "\rlic3d: %s %3d%%: %s\033[K", what_.c_str(), current_, stage.c_str());
  else
    std::fprintf(stderr, "lic3d: %s %d%%: %s\n", what_.c_str(), current_, stage.c_str());
  std::fflush(stderr);
}

void Progress::cancel() {
  if (finished_) return;
  finished_ = true;
  if (!quiet_ && terminal_ && lastReported_ >= 0) std::fputc('\n', stderr);
}

void Progress::finish() {
  if (quiet_ || finished_) return;
  finished_ = true;
  std::fprintf(stderr, "%slic3d: %s done in %.2f s%s\n", terminal_ ? "\r" : "", what_.c_str(),
               secondsSince(start_), terminal_ ? "\033[K" : "");
}

FrameProgress::FrameProgress(int total, bool quiet)
    : total_(total),
      quiet_(quiet),
      terminal_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()) {}

FrameProgress::~FrameProgress() { finish(); }

void FrameProgress::frameDone(int frame) {
  ++done_;
  if (quiet_) return;
  const double elapsed = secondsSince(start_);
  const double left = elapsed / done_ * (total_ - done_);
  // "\033[K" clears what a longer earlier line left on the terminal.
  std::fprintf(stderr, "%slic3d: frame %d: %d/%d done, %.1f s elapsed, ETA %.1f s%s",
               terminal_ ? "\r" : "", frame, done_, total_, elapsed, left,
               terminal_ ? "\033[K" : "\n");
  std::fflush(stderr);
}

void FrameProgress::finish() {
  if (finished_) return;
  finished_ = true;
  if (quiet_ || !terminal_ || done_ == 0) return;
  std::fputc('\n', stderr);  // keep the live line
}

}  // namespace lic3d::cli
