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

// Writes the volume to `path` atomically (a temporary file renamed over it; never a half-written
// file). Errors name the path: InvalidInput for grids that do not match `dims`, names that repeat
// or a path that cannot be written, Runtime for a failure while writing, and InvalidInput saying
// so in a build without OpenVDB.
Result<void> writeVdb(const std::filesystem::path& path, const VdbVolume& volume);

}  // namespace lic3d
