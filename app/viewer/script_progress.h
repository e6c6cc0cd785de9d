// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The progress of a scripted run (--frames, --soak): "frame k of n" in the window, and for a long
// run on stderr as the CLI reports its work (options/progress.h): a line rewritten in place on a
// terminal, a line every tenth of the run in a log.

#include <cstdint>
#include <string>

namespace lic3d::viewer {

// Runs shorter than this report in the window only: they end before progress would help.
inline constexpr int kProgressMinFrames = 100;

class ScriptProgress {
 public:
  ScriptProgress() = default;
  // `frames`: the run's length (0: not scripted, nothing is reported). `terminal`: stderr is a
  // terminal. `quiet`: nothing on stderr (-q).
  ScriptProgress(int frames, bool terminal, bool quiet);

  // Frame `frame` (1-based) was drawn after `seconds` of the run; `waiting`: the frames are done
  // but the run waits for the picture it ends on. What to print on stderr now (empty: nothing).
  std::string update(std::uint64_t frame, double seconds, bool waiting);
  // What ends a live terminal line at the end of the run (empty: nothing).
  std::string finish();
  // The window's line, e.g. "scripted run: frame 40 of 500" (then "frame 500 of 500: waiting
  // for the picture").
  std::string windowText(std::uint64_t frame, bool waiting) const;
  // Of the frames, for the window's progress bar.
  float fraction(std::uint64_t frame) const;
  bool scripted() const { return frames_ > 0; }

 private:
  int frames_ = 0;
  bool terminal_ = false;
  bool quiet_ = true;
  int lastTenth_ = 0;           // of the log's lines
  double lastPrinted_ = -1e30;  // of the terminal's updates, in seconds
  bool saidWaiting_ = false;
  bool live_ = false;  // a terminal line is open
};

}  // namespace lic3d::viewer
