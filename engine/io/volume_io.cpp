// SPDX-License-Identifier: BSD-3-Clause
#include "io/volume_io.h"

#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cfloat>
#include <cmath>
#include <limits>

#include "core/memory_budget.h"
#include "core/parallel.h"
#include "io/file_util.h"

namespace lic3d {

float vectorComponent(double value) {
  if (std::isnan(value)) return std::numeric_limits<float>::quiet_NaN();
  if (std::abs(value) > static_cast<double>(FLT_MAX))
    return value > 0.0 ? std::numeric_limits<float>::infinity()
                       : -std::numeric_limits<float>::infinity();
  return static_cast<float>(value);
}

Result<void> finishVectorField(const std::filesystem::path& path, VectorField& field,
                               FieldReadInfo* info) {
  if (Result<void> drawable = checkGridGeometry(field.geometry); !drawable)
    return fileError(path, drawable.error().message);
  // On the available threads: every chunk counts its own, the sums do not depend on the order.
  std::atomic<std::size_t> nonFinite{0};
  std::atomic<bool> anyNonZero{false};
  parallelChunks(field.vectors.size(), [&](std::size_t begin, std::size_t end) {
    std::size_t bad = 0;
    bool flowing = false;
    for (std::size_t i = begin; i < end; ++i) {
      glm::vec3& v = field.vectors[i];
      if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
        v = glm::vec3(0.0f);
        ++bad;
      } else if (v.x != 0.0f || v.y != 0.0f || v.z != 0.0f) {
        flowing = true;
      }
    }
    nonFinite += bad;
    if (flowing) anyNonZero = true;
  });
  if (info) info->nonFiniteVectors = nonFinite;
  if (!anyNonZero) {
    std::string problem = "every vector of the field is zero";
    if (nonFinite > 0)
      problem += " (" + std::to_string(nonFinite) + " of the " +
                 std::to_string(field.vectors.size()) +
                 " were NaN, infinite or beyond a float's range of 3.4e38)";
    return fileError(path, problem + ": there is no flow to show");
  }
  return {};
}

std::size_t maskVectors(std::span<const std::uint8_t> valid, std::vector<glm::vec3>& vectors) {
  std::size_t masked = 0;
  for (std::size_t i = 0; i < valid.size() && i < vectors.size(); ++i) {
    if (valid[i] != 0) continue;
    vectors[i] = glm::vec3(0.0f);
    ++masked;
  }
  return masked;
}

CellCentredGrid cellCentredGrid(Dims pointDims, const GridGeometry& pointGeometry) {
  CellCentredGrid cells;
  cells.geometry = pointGeometry;
  for (glm::length_t axis = 0; axis < 3; ++axis) {
    cells.dims[axis] = std::max(pointDims[axis] - 1, 1);
    if (pointDims[axis] > 1) cells.geometry.origin[axis] += 0.5 * pointGeometry.spacing[axis];
  }
  return cells;
}

std::string gridLimitProblem(std::uint64_t nx, std::uint64_t ny, std::uint64_t nz) {
  return gridLimitProblem(nx, ny, nz, kMaxVoxels);
}

std::string gridLimitProblem(std::uint64_t nx, std::uint64_t ny, std::uint64_t nz,
                             std::uint64_t maxVoxels) {
  for (const std::uint64_t n : {nx, ny, nz})
    if (n < 1 || n > kMaxAxisSize)
      return "the grid " + std::to_string(nx) + "x" + std::to_string(ny) + "x" +
             std::to_string(nz) + " has an axis outside [1, " + std::to_string(kMaxAxisSize) + "]";
  // Each factor is at most 2^14, so the product cannot overflow 64 bits.
  const std::uint64_t voxels = nx * ny * nz;
  if (voxels > maxVoxels)
    return "the grid " + std::to_string(nx) + "x" + std::to_string(ny) + "x" + std::to_string(nz) +
           " has " + std::to_string(voxels) + " voxels, more than the limit of " +
           std::to_string(maxVoxels);
  return {};
}

InflateStream::~InflateStream() {
  if (initialized_) inflateEnd(&stream_);
}

bool InflateStream::init() {
  // 15 + 32: the largest window, with the zlib or gzip header detected automatically.
  initialized_ = inflateInit2(&stream_, 15 + 32) == Z_OK;
  return initialized_;
}

Result<void> checkHostCanHold(const std::filesystem::path& path, std::uint64_t bytes) {
  // Reading /proc/meminfo costs as much as reading a small file (a .pvti's 50,000 pieces of 2^3
  // points spent a third of their time there); what a request of under 1 MiB needs, a host that
  // runs lic3d has.
  if (bytes < (std::uint64_t{1} << 20)) return {};
  const std::uint64_t available = hostAvailableBytes();
  if (bytes <= available) return {};
  constexpr std::uint64_t kMiB = std::uint64_t{1} << 20;
  return resourceLimitError(
      path.string() + ": its data needs " + std::to_string((bytes + kMiB - 1) / kMiB) +
      " MiB of host memory; the host has " + std::to_string(available / kMiB) + " MiB available");
}

Result<void> inflateExactly(const std::filesystem::path& path, std::string_view what,
                            std::string_view compressed, std::span<char> output) {
  const std::string prefix = std::string(what) + ": ";
  InflateStream inflater;
  if (!inflater.init()) return runtimeError("zlib: cannot initialise inflate for " + path.string());
  z_stream& zs = inflater.stream();
  // zlib counts in uInt; blocks and outputs beyond 4 GiB are fed in pieces.
  constexpr std::size_t kPiece = std::size_t{1} << 30;
  std::size_t inputDone = 0;
  std::size_t outputGiven = 0;
  // One spare byte past the promised size reveals a stream that holds more.
  char extra = 0;
  bool intoExtra = false;
  for (;;) {
    if (zs.avail_in == 0 && inputDone < compressed.size()) {
      const std::size_t n = std::min(kPiece, compressed.size() - inputDone);
      zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(compressed.data() + inputDone));
      zs.avail_in = static_cast<uInt>(n);
      inputDone += n;
    }
    if (zs.avail_out == 0) {
      if (outputGiven == output.size()) {
        zs.next_out = reinterpret_cast<Bytef*>(&extra);
        zs.avail_out = 1;
        intoExtra = true;
      } else {
        const std::size_t n = std::min(kPiece, output.size() - outputGiven);
        zs.next_out = reinterpret_cast<Bytef*>(output.data() + outputGiven);
        zs.avail_out = static_cast<uInt>(n);
        outputGiven += n;
      }
    }
    const int status = inflate(&zs, Z_NO_FLUSH);
    if (intoExtra && zs.avail_out == 0)
      return fileError(path, prefix + "compressed data holds more than the " +
                                 std::to_string(output.size()) + " bytes expected");
    if (status == Z_STREAM_END) break;
    if (status == Z_MEM_ERROR) return runtimeError("zlib: out of memory reading " + path.string());
    if (status == Z_BUF_ERROR && zs.avail_in == 0 && inputDone == compressed.size())
      return fileError(path, prefix + "compressed data is truncated");
    if (status != Z_OK && status != Z_BUF_ERROR)
      return fileError(path, prefix + "compressed data is corrupt: " +
                                 (zs.msg ? std::string(zs.msg) : std::string("inflate failed")));
  }
  const std::uint64_t produced = zs.total_out;
  if (produced != output.size())
    return fileError(path, prefix + "compressed data holds " + std::to_string(produced) +
                               " bytes, expected " + std::to_string(output.size()));
  return {};
}

Result<void> checkVolumeForWriting(const std::filesystem::path& path, Dims dims,
                                   std::size_t valueCount, std::size_t valuesPerVoxel,
                                   const GridGeometry* geometry) {
  const std::string grid =
      std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z);
  if (dims.x < 1 || dims.y < 1 || dims.z < 1)
    return inputError("cannot write '" + path.string() + "': the grid " + grid + " is empty");
  if (valueCount != valuesPerVoxel * voxelCount(dims))
    return inputError("cannot write '" + path.string() + "': the volume holds " +
                      std::to_string(valueCount) + " values, its " + grid + " grid needs " +
                      std::to_string(valuesPerVoxel * voxelCount(dims)));
  if (geometry) {
    for (glm::length_t axis = 0; axis < 3; ++axis) {
      if (!std::isfinite(geometry->spacing[axis]) || !(geometry->spacing[axis] > 0.0) ||
          !std::isfinite(geometry->origin[axis]))
        return inputError(
            "cannot write '" + path.string() +
            "': the grid's spacing must be positive and finite and its origin finite");
    }
  }
  return {};
}

}  // namespace lic3d
