// SPDX-License-Identifier: BSD-3-Clause
// `lic3d bench --read-field FILE`: how fast a field file read brick by brick (io/field_stream.h)
// feeds the device: the scan for the largest |u| and the bricks' reads, in GB/s of the file's
// bytes from the page cache (a warm-up read first puts the file there), then the host work of one
// brick's inputs (its noise, its statistics and its texels packed into the staging buffer).
// Wall-clock time, median of --repeats after --warmup.
#include <algorithm>
#include <cstdio>
#include <string>
#include <tuple>
#include <vector>

#include "bench/bench.h"
#include "core/stage_times.h"
#include "io/field_stream.h"
#include "jobs/bricks.h"
#include "lic/noise.h"
#include "passes/volume_textures.h"

namespace lic3d::cli {
namespace {

std::uint64_t vectorBytes(Dims dims) { return voxelCount(dims) * sizeof(glm::vec3); }

// The pieces a read covers the grid with: about an eighth of the file each, at most a GiB.
std::uint64_t pieceBytes(Dims dims) {
  return std::min(vectorBytes(dims) / 8, std::uint64_t{1} << 30);
}
// The piece whose inputs are packed: at most this many voxels (it must fit the device).
constexpr std::uint64_t kPackVoxels = std::uint64_t{1} << 24;

// Whole x-y layers, about `bytes` each: every piece one range of a raw file.
Dims slabOf(Dims dims, std::uint64_t bytes) {
  const std::uint64_t layer = vectorBytes({dims.x, dims.y, 1});
  return {dims.x, dims.y, static_cast<int>(std::clamp<std::uint64_t>(bytes / layer, 1, dims.z))};
}

// The grid halved along its longest axis until a piece is at most pieceBytes (bricks as
// chooseBrickCore cuts them): runs of rows in the file.
Dims cubeOf(Dims dims) {
  Dims core = dims;
  while (vectorBytes(core) > pieceBytes(dims) && core != Dims(1)) {
    int longest = 0;
    for (int a = 1; a < 3; ++a)
      if (core[a] > core[longest]) longest = a;
    core[longest] = (core[longest] + 1) / 2;
  }
  return core;
}

// Every piece of `piece` voxels that tiles the grid, read: each into new memory (as bricks are),
// or all into one field's (`reuse`: what reading alone costs, without the page faults).
Result<double> readPieces(const FieldStream& stream, Dims piece, bool reuse = false) {
  const Dims dims = stream.dims();
  VectorField field;
  const auto start = std::chrono::steady_clock::now();
  for (int z = 0; z < dims.z; z += piece.z)
    for (int y = 0; y < dims.y; y += piece.y)
      for (int x = 0; x < dims.x; x += piece.x) {
        const Dims at{x, y, z};
        if (!reuse) field = VectorField();
        LIC3D_TRY(stream.readPieceInto(at, glm::min(piece, dims - at), field));
      }
  return 1e3 * secondsSince(start);
}

double gigabytesPerSecond(std::uint64_t bytes, double milliseconds) {
  return static_cast<double>(bytes) / (1e6 * milliseconds);
}

nlohmann::json rateRow(const char* what, const std::string& grid, std::uint64_t bytes,
                       const Timing& timing) {
  nlohmann::json row{{"what", what}, {"grid", grid}, {"bytes", bytes}};
  if (timing.measured) {
    row["median_ms"] = timing.medianMs;
    row["gb_per_s"] = gigabytesPerSecond(bytes, timing.medianMs);
    std::printf("%-30s %16s %12.1f %10.3f\n", what, grid.c_str(), timing.medianMs,
                gigabytesPerSecond(bytes, timing.medianMs));
  } else {
    row["skipped"] = timing.skipped;
    std::printf("%-30s %16s skipped: %s\n", what, grid.c_str(), timing.skipped.c_str());
  }
  std::fflush(stdout);
  return row;
}

// The seconds `stage` took in the last stageTimings(), as milliseconds.
double stageMilliseconds(const char* stage) {
  for (const auto& [name, seconds] : stageTimings())
    if (name == stage) return 1e3 * seconds;
  return 0.0;
}

}  // namespace

Result<nlohmann::json> runReadRateBenchmarks(const Context& context, const BenchOptions& options) {
  LIC3D_TRY_ASSIGN(const FieldStream stream, FieldStream::open(options.readField));
  const Dims dims = stream.dims();
  const std::uint64_t bytes = stream.dataBytes();
  nlohmann::json report = newReport(context);
  report["file"] = options.readField;
  report["grid"] = gridText(dims);
  report["file_bytes"] = bytes;
  report["threads"] = availableThreads();
  report["rows"] = nlohmann::json::array();
  double budgetLeft = options.budgetSeconds;
  std::printf(
      "Reading %s (%s, %.3f GB of vectors) by pieces on %u threads, from the page cache after a "
      "warm-up read: median of %d, wall clock\n",
      options.readField.c_str(), gridText(dims).c_str(), static_cast<double>(bytes) / 1e9,
      availableThreads(), options.repeats);
  std::printf("%-30s %16s %12s %10s\n", "stage", "piece", "median ms", "GB/s");
  LIC3D_TRY_ASSIGN(const double warm, readPieces(stream, slabOf(dims, pieceBytes(dims))));
  report["warm_up_ms"] = warm;

  LIC3D_TRY_ASSIGN(const Timing scan, measure(options, budgetLeft, [&]() -> Result<double> {
                     const auto start = std::chrono::steady_clock::now();
                     LIC3D_TRY_ASSIGN([[maybe_unused]] const StreamScan s, scanFieldStream(stream));
                     return 1e3 * secondsSince(start);
                   }));
  report["rows"].push_back(rateRow("scan (largest |u|)", gridText(dims), bytes, scan));
  const Dims slab = slabOf(dims, pieceBytes(dims));
  for (const auto& [what, piece, reuse] :
       {std::tuple{"read by z-slabs", slab, false},
        std::tuple{"read by bricks", cubeOf(dims), false},
        std::tuple{"read by z-slabs, memory reused", slab, true}}) {
    LIC3D_TRY_ASSIGN(const Timing read, measure(options, budgetLeft, [&, p = piece, r = reuse] {
                       return readPieces(stream, p, r);
                     }));
    report["rows"].push_back(rateRow(what, gridText(piece), bytes, read));
  }

  // One brick's host inputs: its noise, then its statistics and texels (in the staging buffer).
  const Dims piece = slabOf(dims, kPackVoxels * sizeof(glm::vec3));
  const std::uint64_t voxels = voxelCount(piece);
  LIC3D_TRY_ASSIGN(const VectorField field, stream.readPiece({0, 0, 0}, piece));
  NoiseVolume noise;
  LIC3D_TRY_ASSIGN(const Timing noising, measure(options, budgetLeft, [&]() -> Result<double> {
                     const auto start = std::chrono::steady_clock::now();
                     noise = makeWhiteNoisePiece(dims, {0, 0, 0}, piece, options.seed);
                     return 1e3 * secondsSince(start);
                   }));
  report["rows"].push_back(rateRow("noise (GB of vectors)", gridText(piece), voxels * 12, noising));
  double statisticsMs = 0.0, uploadMs = 0.0;
  LIC3D_TRY_ASSIGN(const Timing packing, measure(options, budgetLeft, [&]() -> Result<double> {
                     clearStageTimings();
                     LIC3D_TRY_ASSIGN([[maybe_unused]] const FieldTexture texture,
                                      uploadLicInputs(context, field, noise, options.precision));
                     statisticsMs = stageMilliseconds("field statistics");
                     uploadMs = stageMilliseconds("field upload");
                     return stageMilliseconds("field packing");
                   }));
  report["rows"].push_back(
      rateRow("packing (GB of vectors)", gridText(piece), voxels * 12, packing));
  if (packing.measured) {  // of the last repeat
    report["statistics_ms"] = statisticsMs;
    report["upload_ms"] = uploadMs;
    std::printf("%-30s %16s %12.1f %10.3f\n", "statistics (last repeat)", gridText(piece).c_str(),
                statisticsMs, gigabytesPerSecond(voxels * 12, statisticsMs));
    std::printf("%-30s %16s %12.1f\n", "staging to image (last)", gridText(piece).c_str(),
                uploadMs);
  }
  clearStageTimings();
  return report;
}

}  // namespace lic3d::cli
