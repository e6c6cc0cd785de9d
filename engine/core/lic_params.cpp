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

}  // namespace lic3d
