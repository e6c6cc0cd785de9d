// SPDX-License-Identifier: BSD-3-Clause
#include "lic/sparsity.h"

#include <algorithm>
#include <string>

#include "core/text.h"
#include "io/file_util.h"
#include "lic/fixed_point.h"
#include "lic/sparsity_automatic.h"
#include "lic_kernel.h"
#include "sparsity_mask.h"

namespace lic3d {
using namespace points;
namespace {

// Voxel containing a point; points are inside the volume by construction, the clamp only guards
// the floor of a coordinate that rounded up to the far face.
std::size_t voxelOf(Dims dims, const glm::vec3& p) {
  const auto axis = [](float v, int n) { return std::clamp(static_cast<int>(v), 0, n - 1); };
  return voxelIndex(dims, axis(p.x, dims.x), axis(p.y, dims.y), axis(p.z, dims.z));
}

}  // namespace

Result<void> validate(const SparsityParams& params, Dims dims) {
  // The voxel limit is the mask's: without a distribution no mask is made (grids past 2^31
  // voxels fit a large device, or go in bricks).
  const bool masked = params.distribution != SparsityDistribution::None;
  if (!validDims(dims) || (masked && voxelCount(dims) > kMaxVoxels))
    return inputError("sparsity mask: grid " + gridText(dims) + " must have 1.." +
                      std::to_string(kMaxAxisSize) + " voxels per axis and at most " +
                      std::to_string(kMaxVoxels) + " voxels");
  const std::size_t voxels = voxelCount(dims);
  if (params.points < 0 || static_cast<std::size_t>(params.points) > voxels)
    return parameterError("lic.sparsity.points", "must be in [0, " + std::to_string(voxels) +
                                                     "] (0 = automatic, at most one per voxel of " +
                                                     gridText(dims) + "), got " +
                                                     std::to_string(params.points));
  const float largest = largestAxis(dims);
  if (!(params.radius == 0.0f || (params.radius >= kMinSparsityRadius && params.radius <= largest)))
    return parameterError("lic.sparsity.radius", "must be 0 (automatic) or in [" +
                                                     formatNumber(kMinSparsityRadius) + ", " +
                                                     formatNumber(largest) + "] voxels, got " +
                                                     formatNumber(params.radius));
  if (!(params.blackFraction > 0.0 && params.blackFraction < 1.0))
    return parameterError("lic.sparsity.amount", "gives a black fraction of " +
                                                     formatNumber(params.blackFraction) +
                                                     ", which must be in (0, 1)");
  if (!(params.ratio > 0.0f && params.ratio < 1.0f))
    return parameterError("lic.sparsity.ratio",
                          "must be in (0, 1), got " + formatNumber(params.ratio));

  const ResolvedParams resolved = resolve(params, dims);
  const std::size_t pointLimit = params.distribution == SparsityDistribution::PoissonApprox
                                     ? kMaxBestCandidatePoints
                                     : kMaxSparsityPoints;
  if (resolved.points > pointLimit)
    return parameterError("lic.sparsity.points",
                          "must be at most " + std::to_string(pointLimit) + " for " +
                              std::string(enumName(params.distribution)) +
                              (params.distribution == SparsityDistribution::PoissonApprox
                                   ? " (its time grows with the square of the points)"
                                   : "") +
                              ", got " + std::to_string(params.points));
  if (params.distribution == SparsityDistribution::Poisson && !poissonFits(dims, resolved.radius)) {
    const float smallest =
        smallestRadiusThatFits([&](float r) { return poissonFits(dims, r); }, largest);
    const std::string problem = " for poisson on " + gridText(dims) +
                                ": its search grid would exceed " +
                                std::to_string(kMaxPoissonGridCells) + " cells; ";
    if (resolved.radiusFromPoints)
      return parameterError("lic.sparsity.points", std::to_string(params.points) + " is too many" +
                                                       problem + "give lic.sparsity.radius " +
                                                       formatNumber(smallest) + " or more");
    return parameterError("lic.sparsity.radius", formatNumber(resolved.radius) + " is too small" +
                                                     problem + "use " + formatNumber(smallest) +
                                                     " or more");
  }
  if (params.distribution == SparsityDistribution::Jitter && !jitterFits(dims, resolved.radius))
    return parameterError("lic.sparsity.radius",
                          formatNumber(resolved.radius) + " is too small for jitter on " +
                              gridText(dims) + ": more than " + std::to_string(kMaxSparsityPoints) +
                              " cells; use " +
                              formatNumber(smallestRadiusThatFits(
                                  [&](float r) { return jitterFits(dims, r); }, largest)) +
                              " or more");
  return {};
}

bool isBlack(const SparsityMask& mask, glm::ivec3 v) {
  const Dims d = mask.dims;
  if (v.x >= 0 && v.y >= 0 && v.z >= 0 && v.x < d.x && v.y < d.y && v.z < d.z)
    return mask.black[voxelIndex(d, v.x, v.y, v.z)] != 0;
  const glm::ivec3 w = v + mask.beyond.offset;
  return glsl::licBlackBeyondGrid(static_cast<std::uint32_t>(w.x), static_cast<std::uint32_t>(w.y),
                                  static_cast<std::uint32_t>(w.z), mask.beyond.seed,
                                  mask.beyond.threshold);
}

namespace {

Result<SparsityMask> makeWholeMask(const SparsityParams& params, Dims dims);

}  // namespace

Result<SparsityMask> makeSparsityMask(const SparsityParams& params, Dims dims) {
  LIC3D_TRY_ASSIGN(SparsityMask mask, makeWholeMask(params, dims));
  mask.beyond = maskBeyondGrid(params, mask.blackCount, dims);
  return mask;
}

// The threshold of licBlackBeyondGrid for a mask's black fraction, and a 32-bit seed.
MaskBeyondGrid maskBeyondGrid(const SparsityParams& params, std::size_t blackCount, Dims dims) {
  MaskBeyondGrid beyond;
  const double fraction = static_cast<double>(blackCount) / static_cast<double>(voxelCount(dims));
  beyond.threshold =
      static_cast<std::uint32_t>(std::min(std::floor(fraction * 4294967296.0), 4294967295.0));
  beyond.seed = static_cast<std::uint32_t>(params.seed ^ (params.seed >> 32));
  return beyond;
}

std::uint32_t radicalInversePower(std::uint32_t base, std::size_t count) {
  std::uint64_t power = 1;
  while (power * base <= count) power *= base;
  return static_cast<std::uint32_t>(power);
}

std::size_t sparsityMaskWords(Dims dims) {
  return std::size_t{glsl::licMaskBlocksX(dims.x)} * glsl::licMaskBlocksY(dims.y) *
         glsl::licMaskBlocksZ(dims.z);
}

std::vector<std::uint32_t> packSparsityMask(const SparsityMask& mask) {
  const Dims d = mask.dims;
  std::vector<std::uint32_t> words(sparsityMaskWords(d), 0u);
  const std::uint32_t blocksX = glsl::licMaskBlocksX(d.x), blocksY = glsl::licMaskBlocksY(d.y);
  std::size_t index = 0;
  for (std::uint32_t k = 0; k < static_cast<std::uint32_t>(d.z); ++k)
    for (std::uint32_t j = 0; j < static_cast<std::uint32_t>(d.y); ++j)
      for (std::uint32_t i = 0; i < static_cast<std::uint32_t>(d.x); ++i, ++index)
        if (mask.black[index])
          words[glsl::licMaskWord(i, j, k, blocksX, blocksY)] |= 1u << glsl::licMaskBit(i, j, k);
  return words;
}

namespace {

Result<SparsityMask> makeWholeMask(const SparsityParams& params, Dims dims) {
  LIC3D_TRY(validate(params, dims));
  SparsityMask mask;
  mask.dims = dims;
  mask.black.assign(voxelCount(dims), 0);
  const ResolvedParams resolved = resolve(params, dims);
  std::vector<glm::vec3> points;
  switch (params.distribution) {
    case SparsityDistribution::None: return mask;
    case SparsityDistribution::Checkerboard: {
      const CheckerboardPattern pattern = checkerboardPattern(params.ratio, dims);
      std::vector<std::uint8_t> planeIsBlack(static_cast<std::size_t>(dims.x + dims.y + dims.z));
      for (std::size_t s = 0; s < planeIsBlack.size(); ++s) planeIsBlack[s] = pattern.isBlack(s);
      for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
          for (int i = 0; i < dims.x; ++i) {
            const std::uint8_t black = planeIsBlack[static_cast<std::size_t>(i + j + k)];
            mask.black[voxelIndex(dims, i, j, k)] = black;
            mask.blackCount += black;
          }
      return mask;
    }
    case SparsityDistribution::Poisson:
      points = poissonDiskPoints(dims, resolved.radius, params.seed, kMaxSparsityPoints);
      keepRandomSubset(points, resolved.points, params.seed);
      break;
    case SparsityDistribution::PoissonApprox:
      points = bestCandidatePoints(dims, resolved.points, kBestCandidateFactor, params.seed);
      break;
    case SparsityDistribution::Jitter:
      points = jitteredPoints(dims, resolved.radius, params.seed);
      break;
    case SparsityDistribution::Halton:
    case SparsityDistribution::Hammersley:
      // The exact voxels sparsity_mask.comp blackens (see makeSparsityMask in the header).
      for (const glm::ivec3& v : lowDiscrepancyVoxels(
               dims, resolved.points, params.distribution == SparsityDistribution::Halton)) {
        std::uint8_t& voxel = mask.black[voxelIndex(dims, v.x, v.y, v.z)];
        mask.blackCount += voxel == 0;
        voxel = 1;
      }
      return mask;
  }
  for (const glm::vec3& p : points) {
    std::uint8_t& voxel = mask.black[voxelOf(dims, p)];
    mask.blackCount += voxel == 0;
    voxel = 1;
  }
  return mask;
}

}  // namespace

Result<SparsityMask> makeSparsityMaskPiece(const SparsityParams& params, const FieldPiece& piece,
                                           Dims dims) {
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || piece.offset[a] < 0 || piece.offset[a] + dims[a] > piece.wholeDims[a])
      return inputError("a piece of a field must lie inside the whole grid");
  LIC3D_TRY_ASSIGN(const SparsityMask whole, makeSparsityMask(params, piece.wholeDims));
  SparsityMask mask;
  mask.dims = dims;
  mask.beyond = whole.beyond;
  mask.beyond.offset = piece.offset;
  mask.black.resize(voxelCount(dims));
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const std::uint8_t black = whole.black[voxelIndex(piece.wholeDims, piece.offset.x + i,
                                                          piece.offset.y + j, piece.offset.z + k)];
        mask.black[voxelIndex(dims, i, j, k)] = black;
        mask.blackCount += black;
      }
  return mask;
}

}  // namespace lic3d
