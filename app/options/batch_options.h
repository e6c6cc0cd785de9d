// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The batch flags of `lic3d render`, `compute` and `render2d` (animations, frame ranges, video,
// extra outputs) as the command line declares them; batch.h does the work they ask for.

#include <string>

#include "options/session_options.h"

namespace lic3d::cli {

// The options beyond a single picture.
struct BatchOptions {
  int turntable = 0;     // frames of one full turn of the camera; 0: no turntable
  int animateBias = 0;   // frames of one bias cycle -L..L..-L; 0: none
  int animateTime = 0;   // frames of a time animation (docs/TIME.md); 0: none
  TextOption timeRange;  // T0,T1 of the time animation
  TextOption frames;     // A:B, frames A..B-1 of the animation
  std::string video;     // .mp4 or .webm made by ffmpeg from the frames
  double fps = 30.0;
  bool skipExisting = false;       // frames whose PNG is whole already are left as they are
  std::string rgbaVolume;          // render: the colour-mapped volume, .vti or .nrrd
  std::string visibleWork = "on";  // render: on, LIC of the bricks the pictures show; off, all
  TextOption slice;                // compute: AXIS[:INDEX], the LIC slice written as PNG
};

// --turntable, --animate-bias, --animate-time, --time-range, --frames, --video, --fps,
// --rgba-volume, --visible-work.
void addRenderBatchOptions(CLI::App& app, BatchOptions& options);
// render2d's: --animate-bias, --animate-time, --time-range, --frames, --video, --fps.
void addImageBatchOptions(CLI::App& app, BatchOptions& options);
// --slice.
void addComputeBatchOptions(CLI::App& app, BatchOptions& options);

}  // namespace lic3d::cli
