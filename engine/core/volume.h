// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Plain volume data on uniform grids, shared by the CPU reference, the GPU passes and file I/O.
// Every volume stores x fastest, then y, then z: index = i + NX * (j + NY * k).

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"

namespace lic3d {

using Dims = glm::ivec3;

inline std::size_t voxelCount(Dims dims) {
  return static_cast<std::size_t>(dims.x) * static_cast<std::size_t>(dims.y) *
         static_cast<std::size_t>(dims.z);
}
// The grid of every `stride`-th voxel of `dims` along each axis (stride >= 1): voxel v of it is
// voxel v * stride of the grid, so its extent rounds up.
inline Dims coarseDims(Dims dims, int stride) { return (dims + stride - 1) / stride; }

inline std::size_t voxelIndex(Dims dims, int i, int j, int k) {
  return static_cast<std::size_t>(i) +
         static_cast<std::size_t>(dims.x) *
             (static_cast<std::size_t>(j) +
              static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(k));
}

// Where the grid sits in physical space: voxel (i,j,k) is at origin + (i,j,k) * spacing.
struct GridGeometry {
  glm::dvec3 spacing{1.0};
  glm::dvec3 origin{0.0};
  bool operator==(const GridGeometry&) const = default;
};

// The spacings lic3d can draw: each in [kMinSpacing, kMaxSpacing] (the GPU works in float) and
// at most kMaxSpacingRatio apart between axes, the origin finite within the same bound. Beyond
// them a picture would be black or a line: InvalidInput naming what is wrong.
inline constexpr double kMinSpacing = 1e-30;
inline constexpr double kMaxSpacing = 1e30;
inline constexpr double kMaxSpacingRatio = 1e6;
Result<void> checkGridGeometry(const GridGeometry& geometry);

// Where a field cut from a larger one lies in it: one piece of a distributed run (the ParaView
// plugin under MPI), its ghost layers included. LIC on a piece normalises by the whole field's
// largest |u| and masks with the whole grid's sparsity mask, so at every voxel whose streamlines
// stay inside the piece it gives the whole field's value (docs/LIC_SEMANTICS.md, "Pieces").
struct FieldPiece {
  Dims wholeDims{0};
  Dims offset{0};                   // of the piece's voxel (0,0,0) in the whole grid
  double wholeMaxVoxelSpeed = 0.0;  // maxVoxelSpeed (lic_reference.h) of the whole field
  bool operator==(const FieldPiece&) const = default;
};

// A 3D vector field sampled at voxel centres (VTK "point data").
struct VectorField {
  Dims dims{0};
  GridGeometry geometry;
  std::vector<glm::vec3> vectors;   // voxelCount(dims) entries
  std::optional<FieldPiece> piece;  // set when this is a piece of a larger field
  std::string unit;                 // of the vectors, where the file gives one (the legend's)

  const glm::vec3& at(int i, int j, int k) const { return vectors[voxelIndex(dims, i, j, k)]; }
};

// "NXxNYxNZ", and "NXxNY" for a picture or a plane, for messages.
std::string gridText(Dims dims);
std::string sizeText(Dims dims);

// Largest |v| over the grid's voxels (the thesis' normalisation for velocity-scaled steps).
double maxMagnitude(const VectorField& field);
double minMagnitude(const VectorField& field);

// The input texture of LIC. Integer noise keeps its type so the GPU gets it bit-exact
// (UNORM textures); values read as [0,1] (integers scaled by their type's maximum).
enum class NoiseType : std::uint8_t { UInt8, UInt16, Float32 };

struct NoiseVolume {
  Dims dims{0};
  NoiseType type = NoiseType::UInt8;
  std::vector<std::uint8_t> bytes;  // voxelCount(dims) values of `type`, native byte order

  float value(std::size_t index) const;
};

std::size_t bytesPerValue(NoiseType type);

// Float noise as the noise readers take it: every value finite (else InvalidInput naming the
// voxel), and values outside [0,1] rescaled from their minimum and maximum onto [0,1] (a constant
// outside [0,1] cannot be, and is refused). Integer noise is left as it is.
Result<void> finishFloatNoise(NoiseVolume& noise);

// A float scalar volume: the LIC result read back or computed on the CPU.
struct ScalarVolume {
  Dims dims{0};
  GridGeometry geometry;
  std::vector<float> values;
  // Per voxel 1 if drawn, 0 if sparsity masks it; empty when every voxel is drawn.
  std::vector<std::uint8_t> drawn;

  float at(int i, int j, int k) const { return values[voxelIndex(dims, i, j, k)]; }
};

// The voxels sparsity hides as NaN, "no value" to ParaView, VisIt and numpy (as lic3d writes LIC
// volumes).
void markHiddenVoxels(ScalarVolume& volume);

}  // namespace lic3d
