// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the 3D and the 2D LIC passes share: the LicParams fields of their push constants
// (shaders/shared_layout.h), the dispatch size and their pipelines' debug names.

#include <cstdint>
#include <cstdlib>
#include <string>

#include "core/lic_params.h"

namespace lic3d {

// Sets the streamline and kernel fields of a LIC pass's push constants from `params`.
template <class Push>
void setLicPushParams(Push& push, const LicParams& params) {
  push.licLength = params.length;
  push.bias = params.bias;
  push.step = params.step;
  push.criticalEpsilon = static_cast<float>(kCriticalFraction);
  const KernelShape shape = kernelShape(params.length, params.bias);
  push.hannDenominator = static_cast<float>(shape.hannDenominator);
  push.gaussScale = static_cast<float>(shape.gaussScale);
}

// Work groups of `localSize` invocations that cover `n` (n >= 0).
inline std::uint32_t groupCount(int n, std::uint32_t localSize) {
  return (static_cast<std::uint32_t>(n) + localSize - 1) / localSize;
}

// "integrator/kernel/noise filter/direction/scheme" of a LIC pass's specialization constants,
// after `prefix`: the debug name of its pipeline.
template <class Specialization>
std::string licPipelineName(const std::string& prefix, const Specialization& s) {
  return prefix + std::string(enumName(static_cast<Integrator>(s.integrator))) + "/" +
         std::string(enumName(static_cast<Kernel>(s.kernel))) + "/" +
         std::string(enumName(static_cast<NoiseFilter>(s.noiseFilter))) + "/" +
         std::string(enumName(static_cast<DirectionMode>(s.direction))) + "/" +
         std::string(enumName(static_cast<StepScheme>(s.scheme)));
}

}  // namespace lic3d
