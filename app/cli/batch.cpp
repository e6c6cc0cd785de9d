// SPDX-License-Identifier: BSD-3-Clause
#include "cli/batch.h"

#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <initializer_list>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <system_error>

#include "core/colormap.h"
#include "core/session.h"
#include "core/text.h"
#include "io/file_util.h"
#include "io/nrrd.h"
#include "io/session_file.h"
#include "io/vdb_write.h"
#include "io/volume_stream.h"
#include "io/vti.h"

namespace lic3d::cli {
namespace {

namespace fs = std::filesystem;

std::string extensionOf(const std::string& path) { return fs::path(path).extension().string(); }

// checkOutputPath for one of several extensions, the message naming the flag.
Result<void> checkOutputPathOneOf(const std::string& path, const std::string& flag,
                                  std::initializer_list<const char*> extensions) {
  const std::string extension = extensionOf(path);
  std::string list;
  for (const char* e : extensions) {
    if (extension == e) {
      if (auto r = checkOutputPath(path, e); !r) return inputError(flag + ": " + r.error().message);
      return {};
    }
    list += (list.empty() ? "" : ", ") + std::string(e);
  }
  return inputError(flag + " " + path + ": expected a file name ending in " + list);
}

// The one frame-number conversion of a pattern: where it starts and ends and its zero-padded
// width (0 for plain %d). Only %d and %0Nd (N = 1..9) are frame numbers, as ffmpeg's image2
// reader takes them; %% is a literal '%'. Anything else is refused, so a pattern never reaches a
// printf-like formatter with a conversion that could misread its arguments.
using Conversion = NumberConversion;

Result<Conversion> findConversion(const std::string& pattern) {
  const std::string problem = "-o " + pattern +
                              ": an animation writes one PNG per frame, so -o "
                              "needs a pattern with one %d or %0Nd for the frame number (e.g. "
                              "frame_%04d.png)";
  const NumberScan scan = scanNumberConversion(pattern);
  switch (scan.problem) {
    case NumberScan::Problem::None: return scan.conversion;
    case NumberScan::Problem::NotAConversion:
      return inputError(
          problem + "; '" +
          pattern.substr(scan.at, std::min<std::size_t>(4, pattern.size() - scan.at)) +
          "...' is not one (write %% for a literal %)");
    case NumberScan::Problem::MoreThanOne: return inputError(problem + "; it has more than one");
    case NumberScan::Problem::NoConversion: break;
  }
  return inputError(problem);
}

bool isExecutableFile(const fs::path& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode) &&
         ::access(path.c_str(), X_OK) == 0;
}

// Runs `args` (args[0] a path) and waits; the exit status, or -1 when it could not start, or 128
// + the signal that ended it.
int runProgram(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t child = fork();
  if (child < 0) return -1;
  if (child == 0) {
    // ffmpeg's own output (errors only, with -loglevel error) goes to lic3d's stderr; stdout
    // stays free for the summary line.
    dup2(STDERR_FILENO, STDOUT_FILENO);
    execv(argv[0], argv.data());
    _exit(127);
  }
  int status = 0;
  while (waitpid(child, &status, 0) < 0)
    if (errno != EINTR) return -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

}  // namespace

double FramePlan::timeOf(int frame) const {
  const int steps = timeLoops ? count : count - 1;
  if (steps <= 0) return timeStart;
  return timeStart + (timeEnd - timeStart) * static_cast<double>(frame) / steps;
}

Result<FramePlan> planFrames(const BatchOptions& options, const ComputeOptions& compute,
                             const TimeDomain& domain, const char* defaultPattern) {
  FramePlan plan;
  if (options.turntable > 0 && options.animateBias > 0)
    return inputError("--turntable and --animate-bias: give one animation per run");
  if (options.turntable > 0 && options.animateTime > 0)
    return inputError("--turntable and --animate-time: give one animation per run");
  if (options.timeRange.given() && options.animateTime == 0)
    return inputError("--time-range sets the times of --animate-time N: add it");
  if (options.animateTime > 0) {
    const std::string& field = compute.inputs.session.field.field;
    if (!domain.timeDependent)
      return inputError("--animate-time: " + field +
                        " does not change with time (the tornado, the 2D wave and series of "
                        "files do)");
    plan.animation = Animation::Time;
    plan.count = options.animateTime;
    plan.timeStart = domain.start;
    plan.timeEnd = domain.end;
    plan.timeLoops = domain.periodic;
    if (options.timeRange.given()) {
      const std::string& text = options.timeRange.text;
      LIC3D_TRY_ASSIGN(const std::vector<float> range, parseFloatList(text, "--time-range", 2));
      if (!(range[0] < range[1]))
        return inputError("--time-range: need T0 < T1, got '" + text + "'");
      plan.timeStart = range[0];
      plan.timeEnd = range[1];
    }
    if (!plan.timeLoops && plan.count < 2)
      return inputError(
          "--animate-time over a series of files needs 2 frames or more (its "
          "first and last step)");
    if (options.animateBias > 0) {
      if (compute.inputs.session.lic.length == 0)
        return inputError("--animate-bias cycles the bias through -L..L: it needs --length > 0");
      plan.biasCycle = options.animateBias;
    }
  } else if (options.turntable > 0) {
    plan.animation = Animation::Turntable;
    plan.count = options.turntable;
  } else if (options.animateBias > 0) {
    plan.animation = Animation::Bias;
    plan.count = options.animateBias;
    if (compute.inputs.session.lic.length == 0)
      return inputError("--animate-bias cycles the bias through -L..L: it needs --length > 0");
  }
  plan.first = 0;
  plan.end = plan.count;

  if (options.frames.given()) {
    const std::string& text = options.frames.text;
    if (plan.animation == Animation::None)
      return inputError("--frames " + text +
                        ": picks frames of an animation; use it with --turntable N, "
                        "--animate-bias N or --animate-time N");
    const std::size_t colon = text.find(':');
    int a = 0, b = 0;
    if (colon == std::string::npos || !parseInt(std::string_view(text).substr(0, colon), a) ||
        !parseInt(std::string_view(text).substr(colon + 1), b))
      return inputError("--frames: expected A:B (two whole numbers), got '" + text + "'");
    if (!(0 <= a && a < b && b <= plan.count))
      return inputError("--frames " + text + ": need 0 <= A < B <= " + std::to_string(plan.count) +
                        " (the animation has " + std::to_string(plan.count) + " frames)");
    plan.first = a;
    plan.end = b;
  }

  if (plan.animation == Animation::None) {
    plan.output = compute.output;
    LIC3D_TRY(checkOutputPath(plan.output, ".png"));
    return plan;
  }
  const bool outputGiven = given(compute.outputOption);
  plan.output = outputGiven ? compute.output : defaultPattern;
  LIC3D_TRY(findConversion(plan.output));
  LIC3D_TRY(checkOutputPath(framePath(plan.output, plan.first), ".png"));
  return plan;
}

Result<void> checkRenderOutputs(const BatchOptions& options, const FramePlan& plan,
                                const Session& session) {
  LIC3D_TRY(pngText(session, plan.output));
  if (!options.rgbaVolume.empty()) {
    if (plan.animation == Animation::Bias || plan.animation == Animation::Time)
      return inputError(
          "--rgba-volume writes one volume, but --animate-bias and --animate-time change it "
          "every frame: render a single --bias or --time instead");
    LIC3D_TRY(checkOutputPathOneOf(options.rgbaVolume, "--rgba-volume", {".vti", ".nrrd"}));
  }
  if (!options.video.empty()) {
    if (plan.animation == Animation::None)
      return inputError("--video " + options.video +
                        ": encodes the frames of an animation; add --turntable N, "
                        "--animate-bias N or --animate-time N");
    if (!plan.complete())
      return inputError("--video needs every frame, but --frames renders " +
                        std::to_string(plan.first) + ".." + std::to_string(plan.end - 1) + " of " +
                        std::to_string(plan.count) +
                        ": encode the frames with ffmpeg once all jobs are done (docs/BATCH.md)");
    LIC3D_TRY(checkOutputPathOneOf(options.video, "--video", {".mp4", ".webm", ".gif"}));
    LIC3D_TRY(findFfmpeg());
  }
  return {};
}

Result<void> checkOutputsAreNotInputs(const BatchOptions& options, const FramePlan& plan) {
  if (plan.animation == Animation::None) {
    LIC3D_TRY(checkNotAnInput(plan.output));
  } else {
    for (int frame = plan.first; frame < plan.end; ++frame)
      LIC3D_TRY(checkNotAnInput(framePath(plan.output, frame)));
  }
  if (!options.rgbaVolume.empty()) LIC3D_TRY(checkNotAnInput(options.rgbaVolume));
  if (!options.video.empty()) LIC3D_TRY(checkNotAnInput(options.video));
  return {};
}

Result<std::vector<OutputBytes>> pictureOutputBytes(const BatchOptions& options,
                                                    const FramePlan& plan, const Session& session,
                                                    int width, int height) {
  LIC3D_TRY_ASSIGN(const PngText text, pngText(session, plan.output));
  const std::uint64_t perFrame = pngSizeBound(width, height, 4, text) + 1024;
  std::vector<OutputBytes> outputs;
  if (plan.animation == Animation::None) {
    outputs.push_back({plan.output, perFrame, true});
    return outputs;
  }
  for (int frame = plan.first; frame < plan.end; ++frame) {
    const std::string path = framePath(plan.output, frame);
    if (!options.skipExisting || !isPngFile(path)) outputs.push_back({path, perFrame, true});
  }
  return outputs;
}

std::uint64_t volumeFileBytes(Dims grid, int bytesPerVoxel) {
  return std::uint64_t{voxelCount(grid)} * static_cast<std::uint64_t>(bytesPerVoxel) +
         std::uint64_t{64} * 1024;
}

// Frame `frame` of an animation whose bias cycles every `count` frames.
int cycledBias(int length, int frame, int count) {
  return biasInCycle(length, static_cast<double>(((frame % count) + count) % count) / count);
}

Session frameSession(const Session& base, const FramePlan& plan, int frame) {
  Session s = base;
  if (plan.animation == Animation::Turntable)
    s.view.camera.azimuth =
        static_cast<float>(static_cast<double>(base.view.camera.azimuth) +
                           360.0 * static_cast<double>(frame) / static_cast<double>(plan.count));
  else if (plan.animation == Animation::Bias)
    s.lic.bias = cycledBias(base.lic.length, frame, plan.count);
  else if (plan.animation == Animation::Time) {
    s.time = plan.timeOf(frame);
    if (plan.biasCycle > 0) s.lic.bias = cycledBias(base.lic.length, frame, plan.biasCycle);
  }
  return s;
}

std::string framePath(const std::string& pattern, int frame) {
  const Result<Conversion> c = findConversion(pattern);
  if (!c) return pattern;
  std::string number = std::to_string(frame);
  if (static_cast<int>(number.size()) < c->width)
    number.insert(0, static_cast<std::size_t>(c->width) - number.size(), '0');
  return unescapePercent(std::string_view(pattern).substr(0, c->begin)) + number +
         unescapePercent(std::string_view(pattern).substr(c->end));
}

Result<FrameSkips> findWholeFrames(const FramePlan& plan, bool skipExisting, bool quiet) {
  FrameSkips skips;
  skips.whole.assign(static_cast<std::size_t>(plan.rendered()), false);
  const bool animated = plan.animation != Animation::None;
  for (int frame = plan.first; skipExisting && frame < plan.end; ++frame) {
    const std::string path = animated ? framePath(plan.output, frame) : plan.output;
    LIC3D_TRY_ASSIGN(const bool whole, isCompletePng(path));
    if (whole) {
      // Kept as it is: an input of the run from now on, which no other output may replace.
      noteInput(path);
      skips.whole[static_cast<std::size_t>(frame - plan.first)] = true;
      ++skips.count;
    }
  }
  if (skips.count > 0 && !quiet)
    std::fprintf(stderr,
                 "lic3d: --skip-existing: %d of %d frame(s) already whole, left as they are\n",
                 skips.count, plan.rendered());
  return skips;
}

Result<fs::path> findFfmpeg() {
  const char* path = std::getenv("PATH");
  std::string_view folders = path ? path : "";
  while (true) {
    const std::size_t colon = folders.find(':');
    const std::string_view folder = folders.substr(0, colon);
    const fs::path candidate = fs::path(folder.empty() ? "." : std::string(folder)) / "ffmpeg";
    if (isExecutableFile(candidate)) return candidate;
    if (colon == std::string_view::npos) break;
    folders.remove_prefix(colon + 1);
  }
  return inputError(
      "--video: ffmpeg is not on PATH; install it (Debian: apt-get install "
      "ffmpeg) or leave out --video and encode the frames later");
}

Result<void> encodeVideo(const fs::path& ffmpeg, const FramePlan& plan, double fps,
                         const std::string& video) {
  const fs::path target(video);
  const bool webm = target.extension() == ".webm";
  const bool gif = target.extension() == ".gif";
  // ffmpeg writes beside the target under a temporary name (the format is given, since the name
  // does not end in it), which is renamed when it succeeded: no partial video is ever left.
  const fs::path temporary = target.parent_path() / ("." + target.filename().string() + ".tmp-" +
                                                     std::to_string(getpid()));
  // "./" keeps ffmpeg from reading a relative name with a colon ("take:2_%d.png") as a protocol.
  auto forFfmpeg = [](const fs::path& p) {
    return p.is_absolute() ? p.string() : "./" + p.string();
  };
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", fps);
  std::vector<std::string> args = {
      ffmpeg.string(), "-hide_banner", "-loglevel", "error", "-nostdin", "-y", "-framerate", rate,
      "-start_number", std::to_string(plan.first), "-i", forFfmpeg(plan.output), "-frames:v",
      std::to_string(plan.rendered()),
      // H.264 and VP9 in 4:2:0 need even sizes; frames are opaque, so alpha is dropped.
      "-vf",
      gif ? "split[a][b];[a]palettegen=max_colors=256[p];[b][p]paletteuse=dither=none"
          : "pad=ceil(iw/2)*2:ceil(ih/2)*2,format=yuv420p"};
  if (gif) {
    // One palette made from all frames; GIF loops forever, as the animations are made to.
    for (const char* a : {"-loop", "0", "-f", "gif"}) args.emplace_back(a);
  } else if (webm) {
    for (const char* a : {"-c:v", "libvpx-vp9", "-crf", "30", "-b:v", "0", "-f", "webm"})
      args.emplace_back(a);
  } else {
    for (const char* a : {"-c:v", "libx264", "-crf", "18", "-movflags", "+faststart", "-f", "mp4"})
      args.emplace_back(a);
  }
  args.push_back(forFfmpeg(temporary));
  const int status = runProgram(args);
  std::error_code ec;
  if (status != 0) {
    fs::remove(temporary, ec);
    return runtimeError("--video " + video + ": ffmpeg (" + ffmpeg.string() + ") " +
                        (status < 0 ? std::string("could not be started")
                                    : "failed with exit status " + std::to_string(status)) +
                        "; the frames are kept");
  }
  fs::rename(temporary, target, ec);
  if (ec) {
    // The reason first: removing the temporary file reuses (and clears) the error code.
    const std::string reason = ec.message();
    fs::remove(temporary, ec);
    return runtimeError("--video " + video +
                        ": cannot rename ffmpeg's output into place: " + reason);
  }
  return {};
}

Result<std::optional<LicSlice>> checkComputeOutput(const std::string& path,
                                                   const BatchOptions& options,
                                                   const SessionOptions& inputs) {
  const std::string extension = extensionOf(path);
  if (given(inputs.colorBy) && extension != ".vdb")
    return inputError("--color-by " + inputs.session.view.colorBy +
                      ": compute writes the scalar as a grid of a .vdb; use -o FILE.vdb");
  if (options.slice.given()) {
    LIC3D_TRY_ASSIGN(const LicSlice slice, parseSlice(options.slice.text));
    if (extension != ".png")
      return inputError("--slice " + options.slice.text + " writes a PNG: use -o FILE.png, not " +
                        path);
    LIC3D_TRY(checkOutputPath(path, ".png"));
    return std::optional<LicSlice>(slice);
  }
  if (extension == ".png" && !inputs.sessionFile.empty() && !inputs.session.twoD) {
    LIC3D_TRY(checkOutputPath(path, ".png"));
    return std::optional<LicSlice>(LicSlice{inputs.session.plane.axis, inputs.session.plane.index});
  }
  if (extension == ".png")
    return inputError(
        "-o " + path +
        ": compute writes the LIC volume (.nrrd, .vti, .raw or .vdb); for a 16-bit PNG of one "
        "slice add --slice AXIS[:INDEX], e.g. --slice z:64");
  LIC3D_TRY(checkOutputPathOneOf(path, "-o", {".nrrd", ".vti", ".raw", ".vdb"}));
  if (extension == ".vdb" && !openVdbAvailable())
    return inputError("-o " + path +
                      ": this lic3d was built without OpenVDB (LIC3D_OPENVDB), so it cannot write "
                      ".vdb; write .nrrd, .vti or .raw");
  return std::optional<LicSlice>();
}

Result<void> writeLicVolumeFile(const std::string& path, const ScalarVolume& volume) {
  // Every thread writes runs straight from the volume; voxels that sparsity hides are NaN ("no
  // value" to ParaView and VisIt), copied with them only in the runs that have any.
  const std::string extension = extensionOf(path);
  const ScalarFileFormat format = extension == ".vti"   ? ScalarFileFormat::Vti
                                  : extension == ".raw" ? ScalarFileFormat::Raw
                                                        : ScalarFileFormat::Nrrd;
  return writeScalarVolumeFile(path, format, volume, {.hidden = HiddenVoxels::AsNaN});
}

Result<LicSlice> parseSlice(const std::string& text) {
  LicSlice slice;
  const std::size_t colon = text.find(':');
  const std::string axis = text.substr(0, colon);
  if (axis != "x" && axis != "y" && axis != "z")
    return inputError("--slice: expected AXIS or AXIS:INDEX with AXIS x, y or z, got '" + text +
                      "'");
  slice.axis = axis[0] - 'x';
  if (colon != std::string::npos &&
      (!parseInt(std::string_view(text).substr(colon + 1), slice.index) || slice.index < 0))
    return inputError("--slice: the index of '" + text + "' is not a whole number >= 0");
  return slice;
}

Result<void> writeLicSlicePng(const std::string& path, const ScalarVolume& volume, LicSlice slice,
                              const Session& session) {
  const Dims d = volume.dims;
  const int size = d[slice.axis];
  const int index = slice.index < 0 ? size / 2 : slice.index;
  if (index >= size)
    return inputError("--slice " + std::string(1, static_cast<char>('x' + slice.axis)) + ":" +
                      std::to_string(index) + ": the grid has " + std::to_string(size) +
                      " slices along that axis (0.." + std::to_string(size - 1) + ")");
  // The image's columns and rows run along the two other axes, in order.
  const int across = slice.axis == 0 ? 1 : 0;
  const int up = slice.axis == 2 ? 1 : 2;
  const int width = d[across], height = d[up];
  std::vector<std::uint16_t> values(static_cast<std::size_t>(width) * height);
  for (int row = 0; row < height; ++row)
    for (int column = 0; column < width; ++column) {
      Dims voxel(0);
      voxel[slice.axis] = index;
      voxel[across] = column;
      voxel[up] = height - 1 - row;
      const std::size_t i = voxelIndex(d, voxel.x, voxel.y, voxel.z);
      const bool hidden = !volume.drawn.empty() && !volume.drawn[i];
      const float v = hidden ? 0.0f : std::clamp(volume.values[i], 0.0f, 1.0f);
      values[static_cast<std::size_t>(row) * width + column] =
          static_cast<std::uint16_t>(std::lround(v * 65535.0f));
    }
  // The session records the slice, so that `compute --session` of this PNG remakes it.
  Session recorded = session;
  recorded.plane.axis = slice.axis;
  recorded.plane.index = index;
  LIC3D_TRY_ASSIGN(const PngText text, pngText(recorded, path));
  return writePngGray16(path, width, height, values, text);
}

Result<void> writeRgbaVolumeFile(const std::string& path, const RgbaVolume& volume) {
  if (extensionOf(path) == ".vti") return writeRgbaVti(path, volume);
  return writeRgbaNrrd(path, volume);
}

std::string summaryLine(const RunSummary& summary) {
  using Json = nlohmann::ordered_json;
  Json field = {{"source", summary.field}};
  if (!summary.array.empty()) field["array"] = summary.array;
  field["grid"] = {summary.grid.x, summary.grid.y, summary.grid.z};
  const GridGeometry& g = summary.geometry;
  field["spacing"] = {g.spacing.x, g.spacing.y, g.spacing.z};
  field["origin"] = {g.origin.x, g.origin.y, g.origin.z};
  field["non_finite_vectors"] = summary.nonFiniteVectors;
  if (summary.readByBricks) field["read_by_bricks"] = true;
  Json line = {{"command", summary.command},
               {"frames", summary.frames},
               {"seconds", std::round(summary.seconds * 1000.0) / 1000.0},
               {"outputs", summary.outputs},
               {"device", summary.device},
               {"field", field}};
  if (summary.bricks) line["bricks"] = *summary.bricks;
  if (!summary.shares.empty()) {
    Json shares = Json::array();
    for (const DeviceShare& share : summary.shares)
      shares.push_back({{"device", share.device},
                        {"bricks", share.bricks},
                        {"voxels", share.voxels},
                        {"seconds", std::round(share.seconds * 1000.0) / 1000.0},
                        {"peak_device_mib", share.peakDeviceBytes >> 20}});
    line["devices"] = shares;
  }
  if (summary.reduction > 0)
    line["reduced"] = {
        {"factor", summary.reduction},
        {"grid", {summary.reducedGrid.x, summary.reducedGrid.y, summary.reducedGrid.z}}};
  if (summary.hiddenFraction)
    line["hidden_fraction"] = std::round(*summary.hiddenFraction * 10000.0) / 10000.0;
  Json timings = Json::object();
  for (const auto& [stage, seconds] : summary.timings)
    timings[stage] = std::round(seconds * 10000.0) / 10000.0;
  line["timings"] = timings;
  // File names need not be UTF-8: invalid bytes become U+FFFD rather than failing the run.
  return "lic3d-summary " + line.dump(-1, ' ', false, Json::error_handler_t::replace);
}

}  // namespace lic3d::cli
