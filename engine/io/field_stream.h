// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A vector field read piece by piece from its file, never whole: for fields larger than host or
// device memory (a 2048^3 float field is 96 GiB), whose LIC is computed brick by brick.
//
// Streamed: `.raw` with its JSON sidecar (raw_volume.h), `.nrrd` and `.nhdr` with raw encoding
// (attached or detached data), and `.vti` whose vectors are appended raw and uncompressed. Only
// the header is read on open; each piece is read with pread, so threads may read pieces at once.
// The grid may have up to kMaxStreamedVoxels voxels (each axis at most kMaxAxisSize); the data's
// size is checked against the file's before anything is read.
//
// Files whose data must be decoded from the start (gzip NRRD; ascii, base64 or compressed VTI;
// .vtk; .pvti) are Unsupported: the caller reads them whole (readVectorField), within host memory.

#include <algorithm>
#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "core/volume.h"
#include "io/file_util.h"
#include "io/number_type.h"

namespace lic3d {

class FieldStream {
 public:
  // The header read and checked. `arrayName` picks a .vti array as readVectorField does (a NRRD or
  // raw file holds one unnamed array). InvalidInput for a bad file, Unsupported (naming the file
  // and the reason) for one that must be read whole.
  static Result<FieldStream> open(const std::filesystem::path& path,
                                  std::string_view arrayName = {});

  const std::filesystem::path& path() const { return path_; }
  Dims dims() const { return dims_; }
  const GridGeometry& geometry() const { return geometry_; }
  const std::string& unit() const { return unit_; }            // NRRD `sample units`, else empty
  const std::string& arrayName() const { return arrayName_; }  // the .vti array, else empty
  // The bytes of the file that readPiece reads over the whole grid (the vectors and any mask).
  std::uint64_t dataBytes() const;

  // The voxels [offset, offset + dims) as a field of `dims` voxels whose origin is the piece's
  // first voxel (as cutFieldPiece places it; `piece` is left for the caller), with unit(). Vectors
  // with a NaN or infinite component become zero and are counted in `*nonFinite` (VTK's
  // vtkValidPointMask applied first, as readVectorField applies it). Safe from several threads at
  // once; errors name the file.
  // The piece's file bytes are read with pread on all available threads, in tasks of about
  // chunkBytes() each, and each task's vectors checked as soon as they are read.
  Result<VectorField> readPiece(Dims offset, Dims dims, std::uint64_t* nonFinite = nullptr) const;
  // Sees `count` vectors of a piece being read, final (masked, non-finite ones zero), on the
  // thread that read them: called from several threads at once, once for each part of the piece.
  using RunVisitor = std::function<void(const glm::vec3* vectors, std::size_t count)>;
  // readPiece into `field`, whose vectors' memory is kept where it is large enough (a scan's
  // slabs), each part handed to `visit` (when given) once it is read.
  Result<void> readPieceInto(Dims offset, Dims dims, VectorField& field,
                             std::uint64_t* nonFinite = nullptr,
                             const RunVisitor& visit = {}) const;

  // The bytes of the file one thread reads at a time (a few MiB: large enough for pread to run at
  // the page cache's speed, small enough that the threads share a piece evenly and find its
  // vectors still in cache when they check them). Smaller only in tests, to spread a small piece.
  std::size_t chunkBytes() const { return chunkBytes_; }
  void setChunkBytes(std::size_t bytes) { chunkBytes_ = std::max<std::size_t>(bytes, 1); }

 private:
  // One array in a file: `components` values per voxel of `valueBytes`, from byte `offset` on;
  // interleaved (xyzxyz...) or planar (every x, then every y, then every z).
  struct ArrayLayout {
    std::uint64_t offset = 0;
    NumberType type = NumberType::Float32;
    std::size_t valueBytes = 4;
    std::endian order = std::endian::little;
    std::size_t components = 3;
    bool planar = false;
  };

  FieldStream(FileReader file, std::filesystem::path path);
  static Result<FieldStream> openRaw(const std::filesystem::path& path);
  static Result<FieldStream> openNrrd(const std::filesystem::path& path);
  static Result<FieldStream> openVti(const std::filesystem::path& path, std::string_view name);
  // `file` holds the array on a grid of `dims` (exactly: nothing after it); `path` as given.
  static Result<void> checkFileHolds(const FileReader& file, const std::filesystem::path& path,
                                     Dims dims, const ArrayLayout& array, bool exact);
  // The values of `count` voxels of `array` from voxel `first` on, handed to
  // store(voxel in the run, component, value), through `buffer`.
  template <class Store>
  Result<void> readValues(const ArrayLayout& array, std::uint64_t first, std::size_t count,
                          std::vector<unsigned char>& buffer, Store&& store) const;

  FileReader file_;
  std::filesystem::path path_;  // as given (a detached header's, not its data file's)
  Dims dims_{0};
  GridGeometry geometry_;
  std::string unit_;
  std::string arrayName_;
  ArrayLayout vectors_;
  bool hasMask_ = false;  // vtkValidPointMask, on the same points
  ArrayLayout mask_;
  std::size_t chunkBytes_ = std::size_t{4} << 20;
};

}  // namespace lic3d
