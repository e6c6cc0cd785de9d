// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Sparsity masks (thesis 5.1.4): a volume "T2" with chosen voxels black. A LIC voxel whose
// streamline touches a black voxel is not drawn, which cuts gaps between the streamlines so the
// inside of the field shows. The black voxels come from the point distributions of
// lic/point_sets.h, or from its regular checkerboard.

#include <cstddef>
#include <cstdint>
#include <glm/vec3.hpp>
#include <optional>
#include <span>
#include <string_view>
#include <utility>
#include <vector>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/volume.h"
#include "lic/point_sets.h"

namespace lic3d {

// How each automatic value follows from the black fraction f = params.blackFraction
// (kDefaultBlackFraction, or what maskParams() derives from an amount; core/lic_params.h), for a
// grid of V voxels:
//  - halton, hammersley, poisson-approx: points = f V (these points seldom share a voxel).
//  - poisson: points = f V unless given, radius = cbrt(kPoissonDensity V / (1.1 points)) unless
//    given (1.7 voxels for f = 10 %); the maximal set for that radius has about 10 % more points
//    than asked, and a uniform random subset of exactly `points` is kept (stopping the sampling
//    early would leave the end of the volume empty). With a radius and no points, all of the
//    maximal set. A radius >= sqrt(3) puts every point in its own voxel: points = black voxels.
//  - jitter: radius = cbrt(kJitterDensity / f) (1.6 voxels for 10 %).
// The checkerboard has no automatic value: its ratio is explicit (default 0.05) unless an amount
// sets it.

// Ranges: points in [0, voxels] and at most kMaxSparsityPoints (poisson-approx:
// kMaxBestCandidatePoints), radius 0 or in [kMinSparsityRadius, largest axis], ratio in (0, 1),
// and the memory the distribution would need on these dims. InvalidInput names the flag:
// --sparsity-points, --sparsity-radius, --sparsity-ratio.
Result<void> validate(const SparsityParams& params, Dims dims);

// How the mask goes on beyond the grid (shaders/lic_kernel.h, licBlackBeyondGrid): a streamline
// that leaves the grid is followed on, straight, for the mask alone, through voxels that are black
// at random with the whole mask's black fraction. Without it, streamlines near faces and edges,
// cut short by the grid, would touch fewer black voxels and be drawn far more often than interior
// ones (22 % of the voxels drawn inside, 48 % on faces, 69 % on edges).
struct MaskBeyondGrid {
  Dims offset{0};               // of this grid in the whole grid (a piece's; 0 for the whole)
  std::uint32_t seed = 0;       // from the distribution's seed
  std::uint32_t threshold = 0;  // the whole mask's black fraction * 2^32
};

struct SparsityMask {
  Dims dims{0};
  std::vector<std::uint8_t> black;  // voxelCount(dims) entries, 1 = black
  std::size_t blackCount = 0;
  MaskBeyondGrid beyond;
};

// Whether voxel v (this mask's coordinates; any integers) is black: the mask inside its grid,
// licBlackBeyondGrid outside.
bool isBlack(const SparsityMask& mask, glm::ivec3 v);

// Black voxels for the distribution: each point blackens the voxel that contains it; the
// checkerboard blackens its pattern; None leaves every voxel white. Validates first. Halton and
// Hammersley take the voxel of point i as floor(n * coordinate) of the exact rational coordinate
// (shaders/sparsity_mask.h), which sparsity_mask.comp computes the same way: the float points of
// haltonPoints() and hammersleyPoints() can round up into the next voxel where a coordinate lies
// within a float's precision below a voxel face (from about 2^17 points on).
Result<SparsityMask> makeSparsityMask(const SparsityParams& params, Dims dims);

// The part of the whole grid's mask that a piece of `dims` covers (validated against the whole
// grid): every piece of a distributed run masks exactly as the whole would. The whole mask is
// made first, so each piece pays for all of it.
Result<SparsityMask> makeSparsityMaskPiece(const SparsityParams& params, const FieldPiece& piece,
                                           Dims dims);

// The continuation beyond the grid of a mask of the whole grid `dims` with `blackCount` black
// voxels (makeSparsityMask sets it; a mask made on the GPU takes it from its count).
MaskBeyondGrid maskBeyondGrid(const SparsityParams& params, std::size_t blackCount, Dims dims);

// The mask as the GPU reads it: one bit per voxel in blocks of 4 x 4 x 2 voxels per 32-bit word
// (shaders/sparsity_mask.h), sparsityMaskWords(dims) words, an eighth of a byte per voxel.
std::size_t sparsityMaskWords(Dims dims);
std::vector<std::uint32_t> packSparsityMask(const SparsityMask& mask);

// b^(K-1) for the smallest K with b^K > count: the digits of Halton and Hammersley indices
// 1..count in base b (licScaledRadicalInverse).
std::uint32_t radicalInversePower(std::uint32_t base, std::size_t count);

}  // namespace lic3d
