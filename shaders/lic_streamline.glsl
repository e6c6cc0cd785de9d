// SPDX-License-Identifier: BSD-3-Clause
// What the 3D and the 2D LIC passes share (lic.comp, lic2d.comp): the kernel weight of a sample
// and one step along the streamline. The includer defines, before including this file:
//   LIC_VEC                  vec3 or vec2, a position in voxels (pixels)
//   KERNEL, INTEGRATOR       specialization constants (0 box, 1 hann, 2 gauss; 0 euler, 1 rk2, 2 rk4)
//   pc                       push constants with hannDenominator and gaussScale
//   LIC_VEC fieldAt(LIC_VEC) the field there (packed as its texture holds it)
//   LIC_VEC directionOf(LIC_VEC) the step direction from a field value; zero at critical points
#include "lic_kernel.h"

float weightOf(int i) { return licKernelWeight(KERNEL, i, pc.hannDenominator, pc.gaussScale); }

// One step of signed length sh from x, whose direction d0 = directionOf(fieldAt(x)) is non-zero.
LIC_VEC advance(LIC_VEC x, LIC_VEC d0, float sh) {
  if (INTEGRATOR == 0) return x + sh * d0;
  if (INTEGRATOR == 1) return x + sh * directionOf(fieldAt(x + 0.5 * sh * d0));
  LIC_VEC k2 = directionOf(fieldAt(x + 0.5 * sh * d0));
  LIC_VEC k3 = directionOf(fieldAt(x + 0.5 * sh * k2));
  LIC_VEC k4 = directionOf(fieldAt(x + sh * k3));
  return x + (sh / 6.0) * (d0 + 2.0 * k2 + 2.0 * k3 + k4);
}

// The ab2 scheme's step after the first (docs/LIC_SEMANTICS.md): two-step Adams-Bashforth,
// second order from the directions d and dPrevious already fetched at the last two samples.
LIC_VEC ab2Step(LIC_VEC x, LIC_VEC d, LIC_VEC dPrevious, float sh) {
  return x + sh * (1.5 * d - 0.5 * dPrevious);
}

// The fused scheme's step i >= 1 (docs/LIC_SEMANTICS.md): RK2 steps of 2h whose midpoint is a
// sample. Odd i: the midpoint, h along the direction d at the last sample x; even i: the step's
// end, 2h from the sample before x along the direction d at x (the midpoint).
LIC_VEC fusedStep(int i, LIC_VEC x, LIC_VEC d, LIC_VEC before, float sh) {
  return (i & 1) == 1 ? x + sh * d : before + 2.0 * sh * d;
}
