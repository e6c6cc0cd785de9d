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

// The black fraction that automatic parameters (points = 0, radius = 0) aim at. A LIC voxel is
// drawn only if its streamline (about 20 voxels long with the default L = 20, h = 0.5) touches
// no black voxel: with a fraction f black that is roughly (1 - f)^20, so 10 % draws about an
// eighth of the voxels. Fewer black points leave a 128-voxel-deep volume opaque (we rendered
// 2 %, 5 % and 10 %: only about 10 % showed the inside), and the thesis' figures black up to
// 12 % (250,000 Hammersley points).
//
// How each automatic value follows from it, for a grid of V voxels and f = kDefaultBlackFraction:
//  - halton, hammersley: points = f V (low-discrepancy points seldom share a voxel).
//  - poisson-approx: points = f V, at most kAutomaticBestCandidatePoints (its time grows with
//    the square of the points), so grids above about 59^3 get a smaller fraction.
//  - poisson: points = f V unless given, radius = cbrt(kPoissonDensity V / (1.1 points)) unless
//    given (1.7 voxels for f = 10 %); the maximal set for that radius has about 10 % more points
//    than asked, and a uniform random subset of exactly `points` is kept (stopping the sampling
//    early would leave the end of the volume empty). With a radius and no points, all of the
//    maximal set. A radius >= sqrt(3) puts every point in its own voxel: points = black voxels.
//  - jitter: radius = cbrt(kJitterDensity / f) (1.6 voxels).
// The checkerboard has no automatic value: its ratio is always explicit (default 0.05).
inline constexpr double kDefaultBlackFraction = 0.10;

// Ranges: points in [0, voxels] and at most kMaxSparsityPoints (poisson-approx:
// kMaxBestCandidatePoints), radius 0 or in [kMinSparsityRadius, largest axis], ratio in (0, 1),
// and the memory the distribution would need on these dims. InvalidInput names the flag:
// --sparsity-points, --sparsity-radius, --sparsity-ratio.
Result<void> validate(const SparsityParams& params, Dims dims);

struct SparsityMask {
  Dims dims{0};
  std::vector<std::uint8_t> black;  // voxelCount(dims) entries, 1 = black
  std::size_t blackCount = 0;
};

// Black voxels for the distribution: each point blackens the voxel that contains it; the
// checkerboard blackens its pattern; None leaves every voxel white. Validates first.
Result<SparsityMask> makeSparsityMask(const SparsityParams& params, Dims dims);

// The part of the whole grid's mask that a piece of `dims` covers (validated against the whole
// grid): every piece of a distributed run masks exactly as the whole would. The whole mask is
// made first, so each piece pays for all of it.
Result<SparsityMask> makeSparsityMaskPiece(const SparsityParams& params, const FieldPiece& piece,
                                           Dims dims);

}  // namespace lic3d
