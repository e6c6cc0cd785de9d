// SPDX-License-Identifier: BSD-3-Clause
#include "options/batch_options.h"

#include "options/flags.h"

namespace lic3d::cli {
namespace {

void addTimeAnimationOptions(CLI::App& app, BatchOptions& options) {
  app.add_option("--animate-time", options.animateTime,
                 "Render N frames of the field's time (docs/TIME.md): over one period of an "
                 "analytic field (a loop: frame N would be frame 0), or over a series of files "
                 "from the first to the last step (N = the number of files: one frame per step); "
                 "with --animate-bias too, the bias cycles as well")
      ->check(rangeCheck(1, 1000000));
  options.timeRange.option = app.add_option(
      "--time-range", options.timeRange.text,
      "T0,T1: the times --animate-time covers instead (a loop when T1 - T0 is the field's "
      "period)");
}

// --frames (a piece of an animation) and --video, for every command that renders frames.
void addFrameRangeAndVideoOptions(CLI::App& app, BatchOptions& options) {
  options.frames.option = app.add_option(
      "--frames", options.frames.text,
      "A:B renders only frames A..B-1 of the animation (0 <= A < B <= N), numbered as in the "
      "whole animation: one piece of a job array");
  app.add_option("--video", options.video,
                 "After the frames, encode them with ffmpeg (from PATH) into this .mp4 (H.264), "
                 ".webm (VP9) or .gif; needs every frame of the animation");
  app.add_flag("--skip-existing", options.skipExisting,
               "Leave every frame (or the picture) whose PNG is already whole and render only "
               "the rest: a requeued task of a job array redoes only what is missing");
  app.add_option("--fps", options.fps, "Frames per second of --video")
      ->check(rangeCheck(0.1, 1000.0))
      ->capture_default_str();
}
}  // namespace

void addRenderBatchOptions(CLI::App& app, BatchOptions& options) {
  app.add_option("--turntable", options.turntable,
                 "Render N frames of a full turn: the azimuth advances 360/N per frame from "
                 "--azimuth; -o is a pattern with %d or %04d (default lic3d_%04d.png)")
      ->check(rangeCheck(1, 1000000));
  app.add_option("--animate-bias", options.animateBias,
                 "Render N frames of the bias cycle -L..L..-L (the texture flows along the "
                 "field, frame N would be frame 0 again); the LIC volume is recomputed per frame")
      ->check(rangeCheck(1, 1000000));
  addTimeAnimationOptions(app, options);
  addFrameRangeAndVideoOptions(app, options);
  app.add_option("--rgba-volume", options.rgbaVolume,
                 "Also write the colour-mapped volume as 8-bit RGBA (.vti or .nrrd): grey or "
                 "colour and the opacity per voxel, as the slices draw it (docs/BATCH.md)");
  app.add_option("--visible-work", options.visibleWork,
                 "on: the LIC makes only the 8^3-voxel bricks the pictures can show (not "
                 "transparent by speed, not clipped, inside the region of interest) and the "
                 "contrast stretch follows their voxels; off: every voxel and the whole grid's "
                 "statistics (docs/VISIBLE_WORK.md); off with --rgba-volume")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
}

void addImageBatchOptions(CLI::App& app, BatchOptions& options) {
  app.add_option("--animate-bias", options.animateBias,
                 "Render N frames of the bias cycle -L..L..-L (the texture flows along the "
                 "field, frame N would be frame 0 again); with --animate-time, one bias cycle "
                 "lasts N frames")
      ->check(rangeCheck(1, 1000000));
  addTimeAnimationOptions(app, options);
  addFrameRangeAndVideoOptions(app, options);
}

void addComputeBatchOptions(CLI::App& app, BatchOptions& options) {
  options.slice.option = app.add_option(
      "--slice", options.slice.text,
      "With -o FILE.png: write the LIC slice AXIS:INDEX (x, y or z; INDEX defaults to the "
      "middle) as a 16-bit grey PNG");
}

}  // namespace lic3d::cli
