// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Batch work of `lic3d render` and `lic3d compute`: animations (turntable, bias cycle) and the
// frame ranges that split them over job arrays, outputs chosen by file extension (LIC and RGBA
// volumes, a LIC slice as 16-bit PNG), video through ffmpeg, and the one-line JSON summary
// scripts read. The session every PNG carries is pngText (options/session_options.h).
// docs/BATCH.md is the user's side of this file.

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "core/rgba_image.h"
#include "core/volume.h"
#include "io/file_util.h"
#include "io/png_writer.h"
#include "io/volume_io.h"
#include "jobs/bricks.h"
#include "options/batch_options.h"
#include "options/session_options.h"
#include "passes/slice_pass.h"

namespace lic3d::cli {

enum class Animation { None, Turntable, Bias, Time };

// Which frames one run renders and where they go.
struct FramePlan {
  Animation animation = Animation::None;
  int count = 1;  // N: frames of the whole animation
  int first = 0;  // this run renders first..end-1; numbering is the animation's
  int end = 1;
  std::string output;  // the PNG, or for an animation a pattern with one %d or %0Nd
  // Time animations: frame f is at timeStart + (timeEnd - timeStart) * f / N when the range
  // loops (frame N would be frame 0), else * f / (N - 1) (both ends are frames). With
  // --animate-bias as well, the bias cycles every biasCycle frames.
  double timeStart = 0.0;
  double timeEnd = 0.0;
  bool timeLoops = true;
  int biasCycle = 0;

  int rendered() const { return end - first; }
  bool complete() const { return first == 0 && end == count; }
  double timeOf(int frame) const;
};

// Checks the batch flags and the output (before any work: InvalidInput naming the flag). An
// animation without -o writes lic3d_%04d.png (`defaultPattern`); one with -o needs a pattern
// there. `domain` is the field's (a time animation needs a time-dependent field).
Result<FramePlan> planFrames(const BatchOptions& options, const ComputeOptions& compute,
                             const TimeDomain& domain = {},
                             const char* defaultPattern = "lic3d_%04d.png");
// --rgba-volume and --video: extensions, folders and ffmpeg on PATH.
Result<void> checkRenderOutputs(const BatchOptions& options, const FramePlan& plan,
                                const Session& session);
// Once the inputs are read and before any work: no output of the run (the picture or every
// frame, the RGBA volume, the video) is one of them (checkNotAnInput, io/file_util.h).
Result<void> checkOutputsAreNotInputs(const BatchOptions& options, const FramePlan& plan);

// The most bytes each picture of `plan` takes, for checkFreeSpace before any work: pngSizeBound of
// a width x height RGBA picture with the session's text, and 1 KiB for what differs per frame (its
// angle, bias or time, a reduced copy's note). With --skip-existing, a frame that is a PNG file
// already is not counted (it is most likely kept). The video is not counted: its size is the
// encoder's, and the frames are kept when it fails.
Result<std::vector<OutputBytes>> pictureOutputBytes(const BatchOptions& options,
                                                    const FramePlan& plan, const Session& session,
                                                    int width, int height);
// A volume file of `grid` (.nrrd, .vti, .raw and its sidecar), `bytesPerVoxel` a voxel: the data
// as it is written (raw, uncompressed) and 64 KiB for the header or sidecar.
std::uint64_t volumeFileBytes(Dims grid, int bytesPerVoxel);

// The parameters of frame `frame`: a turntable turns the azimuth by 360/N per frame from the
// given one; a bias cycle runs the bias from -L up to L and back down, so that frame N would be
// frame 0 again; a time animation sets the time (and cycles the bias with --animate-bias).
Session frameSession(const Session& base, const FramePlan& plan, int frame);
int cycledBias(int length, int frame, int count);

// `pattern` with its frame-number conversion replaced (checked by planFrames).
std::string framePath(const std::string& pattern, int frame);

// --skip-existing: the frames of `plan` whose PNG is whole already (isCompletePng), left as they
// are; none without the flag. A note on stderr says how many unless `quiet`.
struct FrameSkips {
  std::vector<bool> whole;  // per frame from plan.first
  int count = 0;
  bool has(const FramePlan& plan, int frame) const {
    return whole[static_cast<std::size_t>(frame - plan.first)];
  }
};
// InvalidInput naming a frame's path that is not a regular file (a FIFO would hang the run).
Result<FrameSkips> findWholeFrames(const FramePlan& plan, bool skipExisting, bool quiet);

// ffmpeg from PATH; InvalidInput saying so when there is none.
Result<std::filesystem::path> findFfmpeg();
// Encodes the frames of `plan` (all of them) into `video` (H.264 in .mp4, VP9 in .webm) at
// `fps`, through a temporary file renamed when ffmpeg succeeded. A failing ffmpeg is Runtime.
Result<void> encodeVideo(const std::filesystem::path& ffmpeg, const FramePlan& plan, double fps,
                         const std::string& video);

// compute's -o: .nrrd, .vti or .raw (the LIC volume, float32, with spacing and origin; voxels that
// sparsity hides are NaN), or a slice PNG (checkComputeOutput below). Written by every thread at
// once, straight from the volume (writeScalarVolumeFile).
Result<void> writeLicVolumeFile(const std::string& path, const ScalarVolume& volume);

// A slice through the LIC volume: axis 0, 1, 2 for x, y, z; index -1 means the middle one.
struct LicSlice {
  int axis = 2;
  int index = -1;
};
Result<LicSlice> parseSlice(const std::string& text);
// Checks compute's output before any work: a volume (.nrrd, .vti, .raw, .vdb; nothing returned)
// or a slice PNG, whose slice is --slice or, with a session (a slice PNG remaking itself), the
// slice the session records (its plane's axis and index). .vdb is refused in a build without
// OpenVDB, and --color-by (a grid of the .vdb) with any other output.
Result<std::optional<LicSlice>> checkComputeOutput(const std::string& path,
                                                   const BatchOptions& options,
                                                   const SessionOptions& inputs);
// The slice as a 16-bit grey PNG: LIC value v in [0,1] as round(65535 v), hidden voxels 0. Rows
// run along the slice's second axis from its top (highest index) down, columns along its first
// (z: x right, y up; y: x right, z up; x: y right, z up). An index outside the grid is
// InvalidInput naming --slice.
Result<void> writeLicSlicePng(const std::string& path, const ScalarVolume& volume, LicSlice slice,
                              const Session& session);

Result<void> writeRgbaVolumeFile(const std::string& path, const RgbaVolume& volume);

// The machine-readable last line of render and compute on stdout:
// `lic3d-summary {"command":...,"frames":...,"seconds":...,"outputs":[...],"device":...,
// "field":{...}}`.
// Beside the session in a picture drawn from a reduced copy of its LIC (docs/SCALE.md): what
// was drawn, e.g. "LIC 2048x2048x2048 made in 12 bricks, drawn as every 2nd voxel: 1024x1024x1024".
inline constexpr char kPngReducedKey[] = "lic3d-reduced";

struct RunSummary {
  std::string command;
  int frames = 0;  // PNG frames rendered (0 for compute)
  double seconds = 0.0;
  std::vector<std::string> outputs;
  std::string device;
  std::string field;  // the field's name or file
  std::string array;  // the array read from a file; empty otherwise
  Dims grid{0};
  GridGeometry geometry;
  std::size_t nonFiniteVectors = 0;
  // With a sparsity mask: the fraction of the LIC voxels it hid (the last frame's volume).
  std::optional<double> hiddenFraction;
  // compute on a device: the bricks the LIC was made in (1: the grid in one piece).
  std::optional<int> bricks;
  // ... and each device's share of that work (jobs/bricks.h).
  std::vector<DeviceShare> shares;
  // render of a LIC too large to draw whole: every `reduction`-th voxel of it (reduced_volume.h).
  int reduction = 0;
  Dims reducedGrid{0};
  bool readByBricks = false;  // the field file was read brick by brick (io/field_stream.h)
  // Seconds per stage (core/stage_times.h), in the order the stages first ran.
  std::vector<std::pair<std::string, double>> timings;
};
std::string summaryLine(const RunSummary& summary);

}  // namespace lic3d::cli
