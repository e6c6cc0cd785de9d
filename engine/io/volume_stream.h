// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A float volume written block by block into its file, never held whole: the LIC of a field
// larger than host memory, computed brick by brick; and the one way whole scalar volumes are
// written (writeScalarVolumeFile), in parallel runs straight from the volume's memory.
//
//   .nrrd  byte for byte what writeScalarNrrd writes for the whole volume
//   .vti   byte for byte what writeScalarVti writes: ImageData with one Float32 point array,
//          appended raw after its UInt64 byte count, in the host's byte order
//   .raw   float32, little endian, x fastest, with a JSON sidecar `<stem>.json` in the format of
//          raw_volume.h with "components": 1 (a scalar, which lic3d's raw reader, for vector
//          fields, does not take; for numpy and ParaView's raw reader)
//
// Every piece is written with pwrite at its place in the file, so any number of threads may write
// disjoint pieces at once (on a big-endian host, .nrrd and .raw values are swapped on the way,
// through a buffer).
// The file is written in place under a temporary name beside its target (TemporaryOutput, its
// size set up front) and appears under its name only when finish() has found every voxel written;
// a stream destroyed before that removes it, so no half-written file ever has the name.

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"
#include "io/volume_io.h"

namespace lic3d {

// A raw volume's sidecar: `<stem>.json` beside it.
std::filesystem::path rawSidecarPath(const std::filesystem::path& rawPath);
// Whether writing the raw volume `rawPath` may replace what its sidecar's name holds: nothing, or
// a raw-volume sidecar (a JSON object of the sidecar's keys only, as lic3d writes). Any other
// file there (a session, a preset, a user's notes) is refused, InvalidInput naming it, and so is
// an input of the run (checkNotAnInput).
Result<void> checkRawSidecarReplaceable(const std::filesystem::path& rawPath);

enum class ScalarFileFormat { Nrrd, Vti, Raw };

class ScalarVolumeStream {
 public:
  // The temporary file made and sized, its header (and a .vti's end) written. The format is the
  // extension's (.nrrd, .vti, .raw). InvalidInput (naming the file) for another extension, an
  // empty grid, a bad geometry, a .vti array name that is empty or holds a control character, or
  // a path that cannot be written; the grid may have up to kMaxStreamedVoxels voxels.
  static Result<ScalarVolumeStream> create(const std::filesystem::path& path, Dims dims,
                                           const GridGeometry& geometry,
                                           std::string_view name = kLicArrayName);
  // The same in `format`, whatever the extension.
  static Result<ScalarVolumeStream> create(const std::filesystem::path& path,
                                           ScalarFileFormat format, Dims dims,
                                           const GridGeometry& geometry,
                                           std::string_view name = kLicArrayName);

  ScalarVolumeStream(ScalarVolumeStream&& other) noexcept;
  ScalarVolumeStream& operator=(ScalarVolumeStream&& other) noexcept;
  ScalarVolumeStream(const ScalarVolumeStream&) = delete;
  ScalarVolumeStream& operator=(const ScalarVolumeStream&) = delete;
  ~ScalarVolumeStream();

  const std::filesystem::path& path() const;
  Dims dims() const;

  // The voxels [first, first + count) of the whole grid (x fastest, then y, then z): `count`
  // values written with pwrite where they lie in the file, and counted for finish()'s check.
  // Thread-safe: runs (and blocks) must not overlap, and any number of threads may write
  // disjoint ones at once.
  Result<void> writeRun(std::uint64_t first, const float* values, std::size_t count);

  // The voxels [offset, offset + dims), `voxelCount(dims)` values x fastest, as runs: a run per
  // row, per layer when the block spans x, one when it spans x and y. Thread-safe as writeRun.
  Result<void> write(Dims offset, Dims dims, const float* values);

  // Flushes the file to disk and renames it into place, or hands it to the open OutputGroup. A
  // .raw's sidecar is complete on disk before the data is renamed and renamed right after it. An
  // error, leaving no file under the name, unless the blocks written cover every voxel exactly once
  // (by count). Not while other threads write.
  Result<void> finish();

 private:
  struct State;
  explicit ScalarVolumeStream(std::unique_ptr<State> state);

  std::unique_ptr<State> state_;
};

// The runs writeScalarVolumeFile hands to its threads: large enough that a pwrite's cost is its
// copy, small enough that every thread of a large host gets many.
inline constexpr std::size_t kVolumeRunBytes = std::size_t{4} << 20;

// How writeScalarVolumeFile writes voxels that sparsity hides (`drawn` 0).
enum class HiddenVoxels { AsComputed, AsNaN };

struct ScalarFileOptions {
  std::string_view name = kLicArrayName;  // the array's (see create)
  HiddenVoxels hidden = HiddenVoxels::AsComputed;
  std::size_t runBytes = kVolumeRunBytes;  // a multiple of 4; tests make it small
};

// The whole volume through a ScalarVolumeStream in `format` (see create), cut into runs of
// `runBytes` that every thread takes in turn and writes with writeRun straight from
// `volume.values`, never copied whole. With HiddenVoxels::AsNaN and a `drawn` mask, a run holding
// hidden voxels goes through its thread's buffer, in which they are NaN ("no value" to ParaView
// and VisIt). Checks the volume as every writer does (checkVolumeForWriting), and its mask.
Result<void> writeScalarVolumeFile(const std::filesystem::path& path, ScalarFileFormat format,
                                   const ScalarVolume& volume,
                                   const ScalarFileOptions& options = {});

}  // namespace lic3d
