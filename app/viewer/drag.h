// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A LIC parameter dragged at the frame rate: while a LIC slider is held the app asks for a coarse
// LIC volume (render/lic_volume_job.h), whose stride fits the drag's LIC budget, and for the full
// one when the slider is let go; the speed the panel shows (frame and LIC times); and the scripted
// drag of --drag-lic that tests and measures it.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "core/lic_params.h"
#include "core/volume.h"

namespace lic3d::viewer {

// The median of the last kCapacity values added: the panel's frame times.
class RecentMedian {
 public:
  static constexpr std::size_t kCapacity = 60;
  void add(double value);
  double median() const;  // 0 when none was added
  std::size_t size() const { return values_.size(); }

 private:
  std::vector<double> values_;
  std::size_t next_ = 0;
};

// The panel's lines, e.g. "frame 16.7 ms CPU, 9.12 ms GPU (median of 60)" and
// "LIC 2.91 ms GPU, coarse 256x256x256" or "LIC 23.1 ms GPU, full 512x512x512".
std::string frameTimeText(double cpuMs, double gpuMs, std::size_t frames);
std::string licTimeText(double licMs, int stride, Dims grid);

// Which LIC volume to ask for each frame.
class LicDrag {
 public:
  // `forcedStride`: 0 chooses the stride from the GPU time of the last full LIC
  // (coarseLicStride); 1 always the full LIC; 2, 4 or 8 that stride.
  explicit LicDrag(int forcedStride = 0) : forcedStride_(forcedStride) {}
  // The stride to request the current parameters at this frame, if anything is to be requested:
  // `changed` when the LIC parameters changed, `dragging` while a LIC slider is held. A change
  // while dragging asks for the coarse volume; the end of a drag that asked for one asks for the
  // full volume; any other change for the full volume.
  std::optional<int> request(bool changed, bool dragging, double fullLicMs);
  // A coarse job at `stride` took `ms` of GPU time: while that is over the budget, later drags
  // ask for at least the next stride (nextCoarseStride).
  void noteCoarse(int stride, double ms);

 private:
  int forcedStride_ = 0;
  int floor_ = 1;      // the least stride a drag asks for, from the coarse jobs measured
  int requested_ = 1;  // the stride last requested
};

// --drag-lic N: once the first volume is shown, the LIC length slider is held for N frames, one
// step longer each frame, and then let go.
class ScriptedDrag {
 public:
  ScriptedDrag() = default;
  explicit ScriptedDrag(int frames) : frames_(frames) {}
  bool scripted() const { return frames_ > 0; }
  // Frame by frame: `ready` once the first volume is shown. Sets `lic`'s length while held;
  // returns whether the slider is held this frame.
  bool step(bool ready, LicParams& lic);
  // The drag is over (or none was asked for).
  bool done() const { return frames_ <= 0 || held_ >= frames_; }

 private:
  int frames_ = 0;
  int held_ = 0;  // frames the slider was held so far
};

}  // namespace lic3d::viewer
