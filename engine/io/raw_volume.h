// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Raw vector fields: float32 (or float64) values in a file of their own, described by a small
// JSON sidecar beside it: `field.raw` with `field.json` (or `field.raw.json`).
//
//   {"dims": [nx, ny, nz],          required
//    "spacing": [sx, sy, sz],       default [1, 1, 1]
//    "origin": [x, y, z],           default [0, 0, 0]
//    "components": 3,               the only value allowed
//    "order": "interleaved",        xyzxyz... per voxel, or "planar": every x, then every y, then z
//    "type": "float32",             or "float64"
//    "endian": "little",            or "big"
//    "bytes": N}                    optional: the data file's size, which must match (a data
//                                   file replaced without its sidecar is told by it)
//
// Voxels are stored x fastest, then y, then z. Unknown keys are errors, so a misspelt key is not
// silently ignored. Inputs are untrusted: the sidecar is at most 64 KiB, the grid is limited
// (each axis in [1, 16384], at most 2^31 voxels) and the raw file's size must match the sidecar
// exactly before anything is allocated. Every error is InvalidInput and names the raw file (and
// the sidecar when the problem is there).

#include <bit>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string_view>

#include "core/error.h"
#include "core/volume.h"
#include "io/volume_io.h"

namespace lic3d {

// The sidecar of `rawPath`: "<stem>.json" or "<name>.json" beside it; an error when neither or
// both exist.
Result<std::filesystem::path> findRawSidecar(const std::filesystem::path& rawPath);

// Whether `key` is one of the sidecar's keys above.
bool isRawSidecarKey(std::string_view key);

// What a raw file's sidecar describes, checked.
struct RawLayout {
  Dims dims{0};
  GridGeometry geometry;
  bool planar = false;
  std::size_t valueBytes = 4;  // 4: float32, 8: float64
  std::endian order = std::endian::little;
};

// The sidecar of `rawPath` found and read; the grid at most `maxVoxels` voxels (kMaxVoxels for
// the whole-file reader, kMaxStreamedVoxels for a stream).
Result<RawLayout> readRawLayout(const std::filesystem::path& rawPath, std::uint64_t maxVoxels);

// Vectors with a NaN or infinite component become zero and are counted (finishVectorField).
Result<VectorField> readVectorFieldRaw(const std::filesystem::path& path,
                                       FieldReadInfo* info = nullptr);

}  // namespace lic3d
