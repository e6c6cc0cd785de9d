#pragma once
// What the volume readers and writers of every format share: what a vector-field reader reports
// besides the field, the rule for NaN and infinite vectors, cell-centred grids, zlib blocks, the
// checks every writer makes, and the RGBA volume the writers save.

#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
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
};

// An 8-bit RGBA volume (the colour-mapped LIC volume): 4 bytes per voxel, x fastest.
struct RgbaVolume {
  Dims dims{0};
  GridGeometry geometry;
  std::vector<std::uint8_t> rgba;  // 4 * voxelCount(dims) bytes
};

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
// kMaxVoxels voxels), else the problem in words.
std::string gridLimitProblem(std::uint64_t nx, std::uint64_t ny, std::uint64_t nz);

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

// The checks every writer makes before creating a file: a non-empty grid, `valueCount` values
// (`valuesPerVoxel` per voxel) and, when given, a positive finite spacing and a finite origin.
Result<void> checkVolumeForWriting(const std::filesystem::path& path, Dims dims,
                                   std::size_t valueCount, std::size_t valuesPerVoxel,
                                   const GridGeometry* geometry);

}  // namespace lic3d
