#include "progress.h"

#include <cstdio>
#include <unistd.h>

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
  // A terminal gets every percent in place; a log gets one line per quarter.
  const int step = terminal_ ? 1 : 25;
  if (percent / step == lastReported_ / step || percent >= 100) return;
  lastReported_ = percent;
  if (terminal_)
    std::fprintf(stderr, "\rlic3d: %s %3d%%", what_.c_str(), percent);
  else
    std::fprintf(stderr, "lic3d: %s %d%%\n", what_.c_str(), percent);
}

void Progress::finish() {
  if (quiet_ || finished_) return;
  finished_ = true;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::fprintf(stderr, "%slic3d: %s done in %.2f s\n", terminal_ ? "\r" : "", what_.c_str(),
               seconds);
}

}  // namespace lic3d::cli
