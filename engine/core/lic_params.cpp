// SPDX-License-Identifier: BSD-3-Clause
#include "core/lic_params.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "lic_kernel.h"

namespace lic3d {

Result<void> validate(const LicParams& params) {
  LIC3D_TRY(checkRange(ranges::kLength, params.length));
  LIC3D_TRY(checkRange(ranges::kStep, params.step));
  if (std::abs(params.bias) > params.length)
    return parameterError("lic.bias", "must satisfy |bias| <= lic.length (" +
                                          std::to_string(params.length) + "), got " +
                                          std::to_string(params.bias));
  LIC3D_TRY(checkRange(ranges::kSparsityPoints, params.sparsity.points));
  LIC3D_TRY(checkRange(ranges::kSparsityRadius, params.sparsity.radius));
  LIC3D_TRY(checkRange(ranges::kSparsityAmount, params.sparsity.amount));
  return checkRange(ranges::kSparsityRatio, params.sparsity.ratio);
}

KernelShape kernelShape(int length, int bias) {
  KernelShape shape;
  shape.hannDenominator = length + std::abs(bias) + 1;
  shape.gaussScale = length > 0 ? 1.0 / (0.5 * length) : 0.0;
  return shape;
}

double kernelWeight(Kernel kernel, int i, const KernelShape& shape) {
  return glsl::licKernelWeight(static_cast<unsigned>(kernel), i, shape.hannDenominator,
                               shape.gaussScale);
}

int biasInCycle(int length, double phase) {
  phase -= std::floor(phase);
  const double bias =
      phase <= 0.5 ? -length + 4.0 * length * phase : 3.0 * length - 4.0 * length * phase;
  return std::clamp(static_cast<int>(std::lround(bias)), -length, length);
}

double streamlineVoxels(const LicParams& params) {
  return kVoxelsPerStreamlineVoxel * 2.0 * params.length * static_cast<double>(params.step) + 1.0;
}

SparsityParams maskParams(const LicParams& params) {
  SparsityParams sparsity = params.sparsity;
  const bool given = sparsity.amount > 0.0f;
  // Whether the mask is made from the black fraction at all: with its points or radius given it
  // is not, and a change of the streamline length must not make it again.
  bool automatic = given;
  switch (sparsity.distribution) {
    case SparsityDistribution::None:
    case SparsityDistribution::Checkerboard: break;
    case SparsityDistribution::Halton:
    case SparsityDistribution::Hammersley:
    case SparsityDistribution::PoissonApprox: automatic = sparsity.points <= 0; break;
    case SparsityDistribution::Poisson:
      automatic = sparsity.points <= 0 && sparsity.radius <= 0.0f;
      break;
    case SparsityDistribution::Jitter: automatic = sparsity.radius <= 0.0f; break;
  }
  if (!automatic) return sparsity;
  const double keep = 1.0 - static_cast<double>(given ? sparsity.amount : kDefaultSparsityAmount);
  sparsity.blackFraction = 1.0 - std::pow(keep, 1.0 / streamlineVoxels(params));
  if (given && sparsity.distribution == SparsityDistribution::Checkerboard)
    sparsity.ratio = static_cast<float>(sparsity.blackFraction);
  return sparsity;
}

}  // namespace lic3d
