// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/script_progress.h"

#include <algorithm>
#include <cstdio>

namespace lic3d::viewer {
namespace {

// A terminal line is rewritten at most this often: printing every frame would slow the run.
constexpr double kTerminalInterval = 0.25;

std::string progressLine(std::uint64_t frame, int frames, double seconds) {
  const double done = static_cast<double>(std::min<std::uint64_t>(frame, frames));
  const double left = done > 0 ? seconds / done * (frames - done) : 0.0;
  char text[160];
  std::snprintf(
      text, sizeof text, "lic3d-view: frame %llu of %d (%.0f %%), %.1f s elapsed, ETA %.1f s",
      static_cast<unsigned long long>(frame), frames, 100.0 * done / frames, seconds, left);
  return text;
}

}  // namespace

ScriptProgress::ScriptProgress(int frames, bool terminal, bool quiet)
    : frames_(std::max(frames, 0)), terminal_(terminal), quiet_(quiet) {}

std::string ScriptProgress::update(std::uint64_t frame, double seconds, bool waiting) {
  if (quiet_ || frames_ < kProgressMinFrames) return {};
  if (waiting) {
    if (saidWaiting_) return {};
    saidWaiting_ = true;
    const std::string line = "lic3d-view: " + std::to_string(frames_) +
                             " frames drawn, waiting for the picture to finish";
    if (!terminal_) return line + "\n";
    live_ = false;
    return "\r" + line + "\033[K\n";
  }
  if (terminal_) {
    if (seconds - lastPrinted_ < kTerminalInterval && frame < static_cast<std::uint64_t>(frames_))
      return {};
    lastPrinted_ = seconds;
    live_ = true;
    // "\033[K" clears what a longer earlier line left.
    return "\r" + progressLine(frame, frames_, seconds) + "\033[K";
  }
  const int tenth = static_cast<int>(10 * std::min<std::uint64_t>(frame, frames_) / frames_);
  if (tenth <= lastTenth_) return {};
  lastTenth_ = tenth;
  return progressLine(frame, frames_, seconds) + "\n";
}

std::string ScriptProgress::finish() {
  if (!live_) return {};
  live_ = false;
  return "\n";  // keep the live line
}

std::string ScriptProgress::windowText(std::uint64_t frame, bool waiting) const {
  // Short enough for the panel's progress bar, which centres it.
  if (waiting)
    return "frame " + std::to_string(frames_) + " of " + std::to_string(frames_) +
           ": waiting for the picture";
  return "scripted run: frame " + std::to_string(frame) + " of " + std::to_string(frames_);
}

float ScriptProgress::fraction(std::uint64_t frame) const {
  return frames_ > 0 ? static_cast<float>(std::min<std::uint64_t>(frame, frames_)) /
                           static_cast<float>(frames_)
                     : 0.0f;
}

}  // namespace lic3d::viewer
