// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the LIC volume depends on. Any change here means the compute pass runs again; nothing
// else (camera, opacity, slices) does.

#include <cstdint>
#include <string>

#include "core/enum_names.h"
#include "core/error.h"
#include "core/parameter_ranges.h"

namespace lic3d {

enum class Integrator : std::uint32_t { Euler = 0, Rk2 = 1, Rk4 = 2 };
enum class Kernel : std::uint32_t { Box = 0, Hann = 1, Gauss = 2 };
enum class NoiseFilter : std::uint32_t { Nearest = 0, Linear = 1 };
// Normalized: unit steps of h voxels. Magnitude: steps of h * |v| / max|v| voxels (the thesis'
// velocity-scaled steps, which shorten streamlines in slow regions).
enum class DirectionMode : std::uint32_t { Normalized = 0, Magnitude = 1 };
// How the rk2 integrator steps (docs/LIC_SEMANTICS.md). Exact: every step of h is an RK2
// (midpoint) step, two texture fetches per sample. Ab2: the first step is RK2, the others
// two-step Adams-Bashforth steps of h, second order from the directions at the last two
// samples: one fetch per sample. Fused: RK2 steps of 2h whose midpoint is itself a sample, so
// samples alternate between a midpoint (h along the last sample's direction) and an RK2 step's
// end (2h from the sample before along the midpoint's direction): one fetch per sample, and
// nothing else fetched. Euler and RK4 ignore it.
enum class StepScheme : std::uint32_t { Exact = 0, Ab2 = 1, Fused = 2 };

LIC3D_ENUM_NAMES(Integrator, {Integrator::Euler, "euler"}, {Integrator::Rk2, "rk2"},
                 {Integrator::Rk4, "rk4"})
LIC3D_ENUM_NAMES(Kernel, {Kernel::Box, "box"}, {Kernel::Hann, "hann"}, {Kernel::Gauss, "gauss"})
LIC3D_ENUM_NAMES(NoiseFilter, {NoiseFilter::Nearest, "nearest"}, {NoiseFilter::Linear, "linear"})
LIC3D_ENUM_NAMES(DirectionMode, {DirectionMode::Normalized, "normalized"},
                 {DirectionMode::Magnitude, "magnitude"})
LIC3D_ENUM_NAMES(StepScheme, {StepScheme::Exact, "exact"}, {StepScheme::Ab2, "ab2"},
                 {StepScheme::Fused, "fused"})

// Sparsity masks (thesis 5.1.4, lic/sparsity.h): the point distribution whose black voxels hide
// the LIC voxels whose streamlines touch them.

// The black fraction of a mask made on its own (makeSparsityMask without LIC parameters, the
// benchmark). A LIC voxel is drawn only if its streamline (about 20 voxels long with the default
// L = 20, h = 0.5) touches no black voxel: with a fraction f black that is roughly (1 - f)^21,
// so 10 % draws about an eighth of the voxels; the thesis' figures black up to 12 % (250,000
// Hammersley points). The LIC itself aims at kDefaultSparsityAmount instead (maskParams).
inline constexpr double kDefaultBlackFraction = 0.10;
// The fraction of the LIC voxels automatic values (points = 0, radius = 0) hide when no amount is
// given: half. A tenth of the mask black hid 92 % of the tornado's voxels (`lic3d render --grid
// 48 --sparsity poisson`), a nearly empty picture.
inline constexpr float kDefaultSparsityAmount = 0.5f;
enum class SparsityDistribution : std::uint32_t {
  None,
  Checkerboard,
  Poisson,
  PoissonApprox,
  Jitter,
  Halton,
  Hammersley,
};
LIC3D_ENUM_NAMES(SparsityDistribution, {SparsityDistribution::None, "none"},
                 {SparsityDistribution::Checkerboard, "checkerboard"},
                 {SparsityDistribution::Poisson, "poisson"},
                 {SparsityDistribution::PoissonApprox, "poisson-approx"},
                 {SparsityDistribution::Jitter, "jitter"}, {SparsityDistribution::Halton, "halton"},
                 {SparsityDistribution::Hammersley, "hammersley"})

struct SparsityParams {
  SparsityDistribution distribution = SparsityDistribution::None;
  int points = 0;  // black points for poisson, poisson-approx, halton, hammersley; 0 = automatic
  float radius = 0.0f;  // minimum distance in voxels for poisson and jitter; 0 = automatic
  float ratio = 0.05f;  // checkerboard: fraction of black voxels, in (0, 1)
  std::uint64_t seed = 1;
  // > 0: about this fraction of the LIC voxels is hidden, in (0, 1). The black fraction of the
  // mask follows from it and the streamline length (maskParams below), and the automatic values
  // (points = 0, radius = 0) and the checkerboard's ratio follow from the black fraction.
  float amount = 0.0f;
  // Derived, not a session key: the fraction of the mask's voxels that automatic values make
  // black. maskParams() sets it; kDefaultBlackFraction when no amount is given.
  double blackFraction = kDefaultBlackFraction;
  bool operator==(const SparsityParams&) const = default;
};

struct LicParams {
  int length = 20;    // L: steps each way (before bias); with h = 0.5, 10 voxels
  float step = 0.5f;  // h: step length in voxels
  int bias = 0;       // Lb = L - bias steps backward, Lf = L + bias forward; |bias| <= L
  Integrator integrator = Integrator::Rk2;
  Kernel kernel = Kernel::Box;
  NoiseFilter noiseFilter = NoiseFilter::Linear;
  DirectionMode direction = DirectionMode::Normalized;
  StepScheme scheme = StepScheme::Exact;  // ab2 is not the default: docs/LIC_SEMANTICS.md
  // Thesis 5.1.4: voxels whose streamline touches a black voxel of this mask are not drawn.
  SparsityParams sparsity;

  bool operator==(const LicParams&) const = default;
};

// The ranges of core/parameter_ranges.h, and |bias| <= L; InvalidInput naming the parameter.
Result<void> validate(const LicParams& params);

// Distinct voxels a streamline's samples fall in, per voxel of its length: 1 along an axis, more
// on a slant. Measured with the hidden fraction of a known black fraction (n = ln(1 - hidden) /
// ln(1 - f), halton, `lic3d render --grid 64 --sparsity halton --sparsity-amount A`): 1.02 on
// the tornado, 1.2 on ABC.
inline constexpr double kVoxelsPerStreamlineVoxel = 1.1;

// Mask voxels a streamline of these parameters touches: kVoxelsPerStreamlineVoxel times its
// length (Lb + Lf) h in voxels, plus the voxel it starts in.
double streamlineVoxels(const LicParams& params);

// The sparsity parameters the mask is made from: params.sparsity with blackFraction set. With an
// amount a > 0 a voxel is hidden when any of the n = streamlineVoxels voxels of its streamline
// is black, so (1 - f)^n = 1 - a: f = 1 - (1 - a)^(1/n) (a = 0.5 with the default L = 20,
// h = 0.5: n = 23, f = 3.0 %), and the checkerboard's ratio is f. Without an amount, f follows
// from kDefaultSparsityAmount and the checkerboard's ratio is kept. The hidden fraction actually
// reached depends on the field (streamlines that stop early cross fewer voxels) and is reported
// after the LIC.
SparsityParams maskParams(const LicParams& params);

// A streamline stops where |v| <= kCriticalFraction * max|v| (a critical point).
inline constexpr double kCriticalFraction = 1e-6;

// The two numbers the kernel weights depend on besides i: the GPU passes push them (as floats),
// the CPU reference takes them in double (shaders/lic_kernel.h has the formula both run).
struct KernelShape {
  double hannDenominator = 1.0;  // L + |bias| + 1
  double gaussScale = 0.0;       // 1 / (0.5 L), 0 when L = 0
};
KernelShape kernelShape(int length, int bias);

// Kernel weight of sample i (i = -Lb..Lf): shaders/lic_kernel.h in double.
double kernelWeight(Kernel kernel, int i, const KernelShape& shape);
inline double kernelWeight(Kernel kernel, int i, int length, int bias) {
  return kernelWeight(kernel, i, kernelShape(length, bias));
}

// The bias animation (thesis 3.3.3): over one cycle, phase 0 to 1, the bias runs -L..L..-L (a
// triangle, so a looped animation has no jump and the texture flows back and forth along the
// streamlines). Phases outside [0, 1) wrap around. The CLI's --animate-bias and the app's "play
// bias" both run it.
int biasInCycle(int length, double phase);

}  // namespace lic3d
