// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// OpenVDB files (.vdb, openvdb.org), the sparse volumes Blender, Houdini and other renderers read:
// the LIC volume as a float grid, with further float grids (speed, a colour scalar) on the same
// voxels. Written with OpenVDB's own library, which is an optional dependency (LIC3D_OPENVDB):
// this header names none of it, and a build without it has only the refusal (vdb_absent.cpp).

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/volume.h"

namespace lic3d {

// Whether this build writes OpenVDB files (built with OpenVDB).
bool openVdbAvailable();

// One float grid of a VDB file: `values` per voxel of the file's grid (x fastest), written at
// the active voxels only.
struct VdbGrid {
  std::string name;
  std::span<const float> values;
  std::string unit;         // metadata "units", where known
  std::string description;  // metadata "description"
  bool fog = false;         // grid class fog volume (densities in [0,1]); else unknown
};

// A volume as a VDB file: every grid on the voxels of `dims`, voxel (i,j,k) at index coordinate
// (i,j,k) and at world position origin + (i,j,k) * spacing (a scale and translation transform,
// one scale per axis). Only the voxels `active` marks (one byte per voxel, 1 active; empty: all
// of them) are stored; the others are inactive with the background value 0.
struct VdbVolume {
  Dims dims{0};
  GridGeometry geometry;
  std::span<const std::uint8_t> active;
  std::vector<VdbGrid> grids;
  std::string creator;  // the file's "creator" metadata of each grid
};

// At most the bytes writeVdb writes for `grids` float grids on `dims`, all voxels active (the
// free-space check before a run): OpenVDB's float tree has leaves of 8^3 voxels under nodes of
// 16^3 leaves under nodes of 32^3 of those (vdb_write.cpp checks it), and stores per node its
// masks and every value, compressed or, where that does not help, as it is.
inline std::uint64_t vdbFileBytesBound(Dims dims, int grids) {
  const auto nodes = [&](int size) { return std::uint64_t{voxelCount((dims + size - 1) / size)}; };
  const std::uint64_t leaves = nodes(8) * (512 * 4 + 256);
  const std::uint64_t lower = nodes(128) * (2 * 512 + 4096 * 4 + 256);
  const std::uint64_t upper = nodes(4096) * (2 * 4096 + 32768 * 4 + 256);
  return static_cast<std::uint64_t>(grids) * (leaves + lower + upper + 4096) + 1024;
}

// Writes the volume to `path` atomically (a temporary file renamed over it; never a half-written
// file). Errors name the path: InvalidInput for grids that do not match `dims`, names that repeat
// or a path that cannot be written, Runtime for a failure while writing, and InvalidInput saying
// so in a build without OpenVDB.
Result<void> writeVdb(const std::filesystem::path& path, const VdbVolume& volume);

}  // namespace lic3d
