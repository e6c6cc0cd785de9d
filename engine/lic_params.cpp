#include "lic_params.h"

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

std::string_view toString(Integrator value) {
  switch (value) {
    case Integrator::Euler: return "euler";
    case Integrator::Rk2: return "rk2";
    case Integrator::Rk4: return "rk4";
  }
  return "?";
}
std::string_view toString(Kernel value) {
  switch (value) {
    case Kernel::Box: return "box";
    case Kernel::Hann: return "hann";
    case Kernel::Gauss: return "gauss";
  }
  return "?";
}
std::string_view toString(NoiseFilter value) {
  return value == NoiseFilter::Nearest ? "nearest" : "linear";
}
std::string_view toString(DirectionMode value) {
  return value == DirectionMode::Normalized ? "normalized" : "magnitude";
}
std::string_view toString(StepScheme value) {
  return value == StepScheme::Exact ? "exact" : "ab2";
}

}  // namespace lic3d
