// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Progress of long work on stderr: a live line on a terminal, a few plain lines in a log.

#include <chrono>
#include <string>

namespace lic3d::cli {

// One computation, as a percentage.
class Progress {
 public:
  Progress(std::string what, bool quiet);
  ~Progress();
  void update(double fraction);
  // Names what the work does now, at once: "lic3d: <what> <percent>%: <stage>" (a line in a log;
  // on a terminal the live line).
  void stage(const std::string& stage);
  void finish();
  // Ends without the "done" line (the work failed; the error says why).
  void cancel();

 private:
  std::string what_;
  bool quiet_;
  bool terminal_;
  bool finished_ = false;
  int lastReported_ = -1;
  int current_ = 0;    // the last fraction given, reported or not
  std::string stage_;  // shown after the percentage on a terminal
  std::chrono::steady_clock::time_point start_;
};

// The frames of a batch render: frames done of the total, the time so far and the estimated time
// left (the mean time per frame so far times the frames left). A log gets one line per frame, a
// terminal one line rewritten in place.
class FrameProgress {
 public:
  FrameProgress(int total, bool quiet);
  ~FrameProgress();
  // Frame `frame` (its number in the whole animation) is written.
  void frameDone(int frame);
  void finish();

 private:
  int total_;
  int done_ = 0;
  bool quiet_;
  bool terminal_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace lic3d::cli
