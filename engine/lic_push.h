#pragma once
// What the 3D and the 2D LIC passes push alike: the LicParams fields of their push constants
// (shaders/shared_layout.h) and the dispatch size.

#include <cstdint>
#include <cstdlib>

#include "lic_params.h"

namespace lic3d {

// Sets the streamline and kernel fields of a LIC pass's push constants from `params`.
template <class Push>
void setLicPushParams(Push& push, const LicParams& params) {
  push.licLength = params.length;
  push.bias = params.bias;
  push.step = params.step;
  push.criticalEpsilon = static_cast<float>(kCriticalFraction);
  push.hannDenominator = static_cast<float>(params.length + std::abs(params.bias) + 1);
  push.gaussScale = params.length > 0 ? 1.0f / (0.5f * static_cast<float>(params.length)) : 0.0f;
}

// Work groups of `localSize` invocations that cover `n` (n >= 0).
inline std::uint32_t groupCount(int n, std::uint32_t localSize) {
  return (static_cast<std::uint32_t>(n) + localSize - 1) / localSize;
}

}  // namespace lic3d
