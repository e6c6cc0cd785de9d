// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A float volume written block by block into its file, never held whole: the LIC of a field
// larger than host memory, computed brick by brick.
//
//   .nrrd  byte for byte what writeScalarNrrd writes for the whole volume
//   .raw   float32, little endian, x fastest, with a JSON sidecar `<stem>.json` in the format of
//          raw_volume.h with "components": 1 (a scalar, which lic3d's raw reader, for vector
//          fields, does not take; for numpy and ParaView's raw reader)
//
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

class ScalarVolumeStream {
 public:
  // The temporary file made and sized. InvalidInput (naming the file) for another extension, an
  // empty grid, a bad geometry or a path that cannot be written; the grid may have up to
  // kMaxStreamedVoxels voxels.
  static Result<ScalarVolumeStream> create(const std::filesystem::path& path, Dims dims,
                                           const GridGeometry& geometry,
                                           std::string_view name = kLicArrayName);

  ScalarVolumeStream(ScalarVolumeStream&& other) noexcept;
  ScalarVolumeStream& operator=(ScalarVolumeStream&& other) noexcept;
  ScalarVolumeStream(const ScalarVolumeStream&) = delete;
  ScalarVolumeStream& operator=(const ScalarVolumeStream&) = delete;
  ~ScalarVolumeStream();

  const std::filesystem::path& path() const;
  Dims dims() const;

  // The voxels [offset, offset + dims), `voxelCount(dims)` values x fastest. Blocks must not
  // overlap; threads may write disjoint blocks at once.
  Result<void> write(Dims offset, Dims dims, const float* values);

  // Flushes the file to disk and renames it into place, or hands it to the open OutputGroup. A
  // .raw's sidecar is complete on disk before the data is renamed and renamed right after it. An
  // error, leaving no file under the name, unless the blocks written cover every voxel exactly once
  // (by count).
  Result<void> finish();

 private:
  struct State;
  explicit ScalarVolumeStream(std::unique_ptr<State> state);

  std::unique_ptr<State> state_;
};

}  // namespace lic3d
