#include "core/lic_params.h"

#include <cmath>
#include <cstdlib>
#include <numbers>

namespace lic3d {

Result<void> validate(const LicParams& params) {
  if (params.length < 0 || params.length > kMaxLicLength)
    return inputError("LIC length must be in [0, " + std::to_string(kMaxLicLength) + "], got " +
                      std::to_string(params.length));
  if (!(params.step > 0.0f) || params.step > 8.0f)
    return inputError("LIC step must be in (0, 8] voxels, got " + std::to_string(params.step));
  if (std::abs(params.bias) > params.length)
    return inputError("LIC bias must satisfy |bias| <= length (" + std::to_string(params.length) +
                      "), got " + std::to_string(params.bias));
  return {};
}

double kernelWeight(Kernel kernel, int i, int length, int bias) {
  switch (kernel) {
    case Kernel::Box: return 1.0;
    case Kernel::Hann:
      return 0.5 * (1.0 + std::cos(std::numbers::pi * i / (length + std::abs(bias) + 1)));
    case Kernel::Gauss: {
      if (length == 0) return 1.0;  // only the centre sample exists
      const double t = i / (0.5 * length);
      return std::exp(-0.5 * t * t);
    }
  }
  return 1.0;
}

}  // namespace lic3d
