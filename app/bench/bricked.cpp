// SPDX-License-Identifier: BSD-3-Clause
// The bench rows of LICs larger than the device (`lic3d bench --sizes 2048`): the bricks' LIC
// rate beside the rates of the host path that bounds such a run (docs/SCALE.md): the read-back
// with its conversion, the conversion alone, and, with --write-dir, the NRRD written in place.
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "bench/bench.h"
#include "core/stage_times.h"
#include "io/volume_stream.h"
#include "jobs/bricks.h"
#include "loading/session_inputs.h"

namespace lic3d::cli {
namespace {

// Peak resident memory of this process (getrusage), in bytes.
std::uint64_t hostPeakBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<std::uint64_t>(usage.ru_maxrss) * 1024u;
}

struct BrickedRun {
  LicVolumeRun run;
  double wall = 0.0;
};

// One bricked run of the session into `target`, the field made on the device brick by brick.
Result<BrickedRun> runOnce(const Context& context, const Session& session,
                           const VoxelTarget& target) {
  LIC3D_TRY_ASSIGN(SessionInputs inputs, loadSessionInputs(session, {.fieldOnDevice = true}));
  const Context* devices[] = {&context};
  LicVolumeOptions how;
  how.timeLic = true;
  how.target = &target;
  const auto start = std::chrono::steady_clock::now();
  LIC3D_TRY_ASSIGN(LicVolumeRun run, computeLicVolume(devices, session, inputs, how));
  return BrickedRun{std::move(run), secondsSince(start)};
}

double gbPerSecond(std::uint64_t bytes, double seconds) {
  return seconds > 0.0 ? static_cast<double>(bytes) / seconds / 1e9 : 0.0;
}

}  // namespace

Result<nlohmann::json> benchBricked(const Context& context, const BenchOptions& options, int n,
                                    int length) {
  Session session;
  session.field.field = options.field;
  session.field.grid = Dims(n);
  session.noise.seed = options.seed;
  session.lic.length = length;
  session.precision = options.precision;
  // First the voxels converted and dropped: the LIC, the link and the conversion.
  VoxelTarget dropped;
  dropped.dims = Dims(n);
  dropped.write = [](std::uint64_t, const float*, std::size_t) -> Result<void> { return {}; };
  LIC3D_TRY_ASSIGN(const BrickedRun kept, runOnce(context, session, dropped));
  const LicVolumeRun& run = kept.run;
  const DeviceShare& share = run.devices.front();
  const double samples = static_cast<double>(n) * n * n * (2.0 * length + 1.0);
  const double readback = gbPerSecond(share.readbackBytes, share.readbackSeconds);
  const double conversion = gbPerSecond(share.readbackBytes, share.convertSeconds);
  std::printf(
      "%6d^3 %6d %12.3f %12s %14.2f  in %d bricks of %s; whole run %.1f s (%.2f "
      "Gsamples/s); device peak %.1f GiB, host peak %.1f GiB\n"
      "%16s read-back %.1f GB/s (%.2f GiB in %.2f s, %.2f s of it waiting for the link), "
      "conversion %.1f GB/s\n",
      n, length, share.licMilliseconds, "-", samples / (share.licMilliseconds * 1e6), run.bricks,
      gridText(run.brickCore).c_str(), kept.wall, samples / (kept.wall * 1e9),
      static_cast<double>(share.peakDeviceBytes) / (1 << 30),
      static_cast<double>(hostPeakBytes()) / (1 << 30), "", readback,
      static_cast<double>(share.readbackBytes) / (1 << 30), share.readbackSeconds,
      share.readbackWaitSeconds, conversion);
  nlohmann::json row{{"n", n},
                     {"length", length},
                     {"bricks", run.bricks},
                     {"brick_core", {run.brickCore.x, run.brickCore.y, run.brickCore.z}},
                     {"lic_ms", share.licMilliseconds},
                     {"wall_s", kept.wall},
                     {"readback_bytes", share.readbackBytes},
                     {"readback_s", share.readbackSeconds},
                     {"readback_wait_s", share.readbackWaitSeconds},
                     {"readback_gb_per_s", readback},
                     {"conversion_gb_per_s", conversion},
                     {"device_peak_bytes", share.peakDeviceBytes}};
  if (!options.writeDir.empty()) {
    // Then written in place into a NRRD there (removed after: the stream is never finished).
    const std::filesystem::path path = std::filesystem::path(options.writeDir) /
                                       ("lic3d-bench-" + std::to_string(getpid()) + ".nrrd");
    LIC3D_TRY_ASSIGN(ScalarVolumeStream stream, ScalarVolumeStream::create(path, Dims(n), {}));
    VoxelTarget file;
    file.dims = Dims(n);
    file.write = [&stream](std::uint64_t first, const float* values, std::size_t count) {
      return stream.writeRun(first, values, count);
    };
    LIC3D_TRY_ASSIGN(const BrickedRun written, runOnce(context, session, file));
    const DeviceShare& into = written.run.devices.front();
    const std::uint64_t bytes = voxelCount(Dims(n)) * sizeof(float);
    const double inPlace = gbPerSecond(into.readbackBytes, into.readbackSeconds);
    // The write's own rate: its bytes over the time it added to the conversion.
    const double writeAlone = gbPerSecond(bytes, into.convertSeconds - share.convertSeconds);
    std::printf(
        "%16s read-back written into %s: %.1f GB/s; the write alone %.1f GB/s; whole run "
        "%.1f s\n",
        "", options.writeDir.c_str(), inPlace, writeAlone, written.wall);
    row["write_dir"] = options.writeDir;
    row["readback_written_gb_per_s"] = inPlace;
    row["write_gb_per_s"] = writeAlone;
    row["written_wall_s"] = written.wall;
  }
  row["host_peak_bytes"] = hostPeakBytes();
  std::fflush(stdout);
  return row;
}

}  // namespace lic3d::cli
