#pragma once
// Progress of long work on stderr: a live percentage on a terminal, a few lines in a log.

#include <chrono>
#include <string>

namespace lic3d::cli {

class Progress {
 public:
  Progress(std::string what, bool quiet);
  ~Progress();
  void update(double fraction);
  void finish();

 private:
  std::string what_;
  bool quiet_;
  bool terminal_;
  bool finished_ = false;
  int lastReported_ = -1;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace lic3d::cli
