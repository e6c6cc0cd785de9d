// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the volume readers and writers of every format share: what a vector-field reader reports
// besides the field, the rule for NaN and infinite vectors, VTK's mask of valid points, the scalar
// arrays read for colour and opacity, cell-centred grids, zlib blocks, the checks every writer
// makes, and the RGBA volume the writers save.

#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"
#include "core/volume.h"

namespace lic3d {

// What a vector-field reader found besides the field.
struct FieldReadInfo {
  // Vectors with a NaN or infinite component (or a double beyond the float range), read as zero.
  std::size_t nonFiniteVectors = 0;
  // The array read; empty for formats that hold one unnamed array (NRRD, raw).
  std::string arrayName;
  // Every vector (3-component) array in the file, in file order.
  std::vector<std::string> arrayNames;
  // Every 1-component point-data array of the file, in file order: the scalars that can colour
  // the field or set its opacity (readPointScalars). kValidPointMaskName is not one of them.
  std::vector<std::string> scalarNames;
  // Vectors set to zero because the file's kValidPointMaskName array is 0 there.
  std::size_t maskedVectors = 0;
  // The unit of the vectors where the file gives one (NRRD `sample units`), else empty.
  std::string unit;
};

// A scalar on the points of a field's grid (colour or opacity by it).
struct PointScalars {
  Dims dims{0};
  GridGeometry geometry;
  std::vector<float> values;  // voxelCount(dims), x fastest; NaN where the file has NaN
  std::string name;           // the array's name (for NRRD: the file name's stem)
  std::string unit;           // where the file gives one (NRRD sample units), else empty
};

// The point array VTK's probe and resample filters add: 0 where a point fell outside the data they
// sampled, whose values there are only fill (zero, or NaN). The readers zero the vectors at those
// points, so LIC treats them as critical points and the renderer leaves them transparent, instead
// of drawing flow that is not there.
inline constexpr std::string_view kValidPointMaskName = "vtkValidPointMask";

// Sets every vector whose `valid` flag is 0 to zero; returns how many were. `valid` holds one flag
// per vector.
std::size_t maskVectors(std::span<const std::uint8_t> valid, std::vector<glm::vec3>& vectors);

// An 8-bit RGBA volume (the colour-mapped LIC volume): 4 bytes per voxel, x fastest.
struct RgbaVolume {
  Dims dims{0};
  GridGeometry geometry;
  std::vector<std::uint8_t> rgba;  // 4 * voxelCount(dims) bytes
};

// The name of the LIC array in every file lic3d writes (VTI arrays, NRRD labels) and in the
// ParaView filter's output: one name, so a script or a ParaView state finds it in any of them.
inline constexpr std::string_view kLicArrayName = "LIC";

// deflate cannot compress better than about 1032:1, so compressed data that would have to
// inflate further is corrupt and is refused before its output is allocated.
inline constexpr std::uint64_t kMaxDeflateRatio = 1032;

// The float a vector component is stored as. A double beyond the float range becomes infinity
// (a plain cast would be undefined behaviour), which finishVectorField then treats like NaN.
float vectorComponent(double value);

// The last step of every vector-field reader. A vector with a NaN or infinite component cannot be
// followed: it becomes zero, a critical point where streamlines stop, and is counted in
// `info->nonFiniteVectors` (when `info` is given) so the caller can warn. A field without a
// single non-zero vector has no streamlines at all and is an InvalidInput error naming `path`.
Result<void> finishVectorField(const std::filesystem::path& path, VectorField& field,
                               FieldReadInfo* info);

// Cell data on a grid of `pointDims` points: one voxel per cell, at the cell's centre. An axis of
// n > 1 points has n - 1 cells, whose centres start half a spacing after the first point; an axis
// of one point has one (flat) cell at that point, as VTK counts them.
struct CellCentredGrid {
  Dims dims{0};
  GridGeometry geometry;
};
CellCentredGrid cellCentredGrid(Dims pointDims, const GridGeometry& pointGeometry);

// An empty string when nx x ny x nz is a grid lic3d reads (each axis in [1, kMaxAxisSize], at most
// kMaxVoxels voxels, or `maxVoxels` for a stream), else the problem in words.
std::string gridLimitProblem(std::uint64_t nx, std::uint64_t ny, std::uint64_t nz);
std::string gridLimitProblem(std::uint64_t nx, std::uint64_t ny, std::uint64_t nz,
                             std::uint64_t maxVoxels);

// A zlib inflate stream (zlib or gzip header detected), ended when it goes out of scope.
class InflateStream {
 public:
  InflateStream() = default;
  InflateStream(const InflateStream&) = delete;
  InflateStream& operator=(const InflateStream&) = delete;
  ~InflateStream();
  bool init();
  z_stream& stream() { return stream_; }

 private:
  z_stream stream_{};
  bool initialized_ = false;
};

// Inflates one whole zlib or gzip stream into exactly `output.size()` bytes; an error (naming
// `path` and `what`) when the stream is corrupt, shorter, longer or not ended.
Result<void> inflateExactly(const std::filesystem::path& path, std::string_view what,
                            std::string_view compressed, std::span<char> output);

// ResourceLimit error naming `path` when `bytes` exceed the memory the host has available
// (requests under 1 MiB are not checked).
Result<void> checkHostCanHold(const std::filesystem::path& path, std::uint64_t bytes);

// Storage for items decoded from a file, taken as decoded data arrives. Compressed data proves
// its size only as it inflates, so a reader reserves what the header promises and grows into it
// chunk by chunk: a file that promises more than it holds costs what it held, not what it
// promised.
//
// Reserves address space for `total` items of `v` (no memory until written) once the host can
// hold them, else a ResourceLimit error naming `path`; nothing when already reserved.
template <class Vector>
Result<void> reserveDecoded(Vector& v, std::size_t total, const std::filesystem::path& path) {
  if (v.capacity() >= total) return {};
  LIC3D_TRY(checkHostCanHold(path, std::uint64_t{total} * sizeof(*v.data())));
  v.reserve(total);
  adviseHugePages(v.data(), v.capacity() * sizeof(*v.data()));
  return {};
}
// Makes `v` hold `count` items (at most what reserveDecoded reserved) before they are written.
template <class Vector>
void growDecoded(Vector& v, std::size_t count) {
  if (count > v.size()) v.resize(std::min(count, v.capacity()));
}

// The checks every writer makes before creating a file: a non-empty grid, `valueCount` values
// (`valuesPerVoxel` per voxel) and, when given, a positive finite spacing and a finite origin.
Result<void> checkVolumeForWriting(const std::filesystem::path& path, Dims dims,
                                   std::size_t valueCount, std::size_t valuesPerVoxel,
                                   const GridGeometry* geometry);

}  // namespace lic3d
