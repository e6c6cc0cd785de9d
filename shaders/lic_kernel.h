// SPDX-License-Identifier: BSD-3-Clause
// The LIC kernel weights and the sparsity mask beyond the grid, one formula for GLSL and C++:
// lic.comp and lic2d.comp include it, and so do the CPU reference (core/lic_params.h,
// kernelWeight, in double precision there) and lic/sparsity.h.
#ifndef LIC3D_LIC_KERNEL_H
#define LIC3D_LIC_KERNEL_H

#ifdef __cplusplus
#include <cmath>
namespace lic3d::glsl {
using std::cos;
using std::exp;
#define LIC3D_REAL double
#define LIC3D_UINT unsigned
#define LIC3D_INLINE inline
#else
#define LIC3D_REAL float
#define LIC3D_UINT uint
#define LIC3D_INLINE
#endif

// Weight of sample i (i = -Lb..Lf) for kernel 0 box, 1 hann, 2 gauss, with hannDenominator =
// L + |bias| + 1 and gaussScale = 1 / (0.5 L) (0 when L = 0, where only the centre sample
// exists): a Hann window that reaches zero just past the longer side, and a Gaussian whose
// standard deviation is half of L.
LIC3D_INLINE LIC3D_REAL licKernelWeight(LIC3D_UINT kernel, int i, LIC3D_REAL hannDenominator,
                                        LIC3D_REAL gaussScale) {
  if (kernel == 1u)
    return 0.5 * (1.0 + cos(3.14159265358979323846 * LIC3D_REAL(i) / hannDenominator));
  if (kernel == 2u) {
    LIC3D_REAL t = LIC3D_REAL(i) * gaussScale;
    return exp(-0.5 * t * t);
  }
  return 1.0;
}

// Beyond the grid the sparsity mask goes on with voxels black at random with the mask's own black
// fraction, so that streamlines that leave the grid are hidden as often as interior ones
// (docs/LIC_SEMANTICS.md, Sparsity). lowbias32 (C. Wellons, 2018): a 32-bit integer hash whose
// bits are close to independent.
LIC3D_INLINE LIC3D_UINT licHashMix(LIC3D_UINT h) {
  h ^= h >> 16u;
  h *= 0x7feb352du;
  h ^= h >> 15u;
  h *= 0x846ca68bu;
  h ^= h >> 16u;
  return h;
}
// Whether voxel (x, y, z) of the whole grid's coordinates (the bit patterns of the signed
// indices), outside the grid, is black: its hash with the mask's seed falls below threshold =
// black fraction * 2^32.
LIC3D_INLINE bool licBlackBeyondGrid(LIC3D_UINT x, LIC3D_UINT y, LIC3D_UINT z, LIC3D_UINT seed,
                                     LIC3D_UINT threshold) {
  LIC3D_UINT h = licHashMix(seed ^ x);
  h = licHashMix(h ^ y);
  h = licHashMix(h ^ z);
  return h < threshold;
}

#undef LIC3D_REAL
#undef LIC3D_UINT
#undef LIC3D_INLINE
#ifdef __cplusplus
}  // namespace lic3d::glsl
#endif

#endif
