// SPDX-License-Identifier: BSD-3-Clause
// The bit-packed sparsity mask, one formula for GLSL and C++: where a voxel's bit lies (lic.comp
// reads it, sparsity_mask.comp writes it, lic/sparsity.cpp packs the CPU's mask), and the black
// voxels of the distributions the GPU makes, in exact integer arithmetic so both sides agree bit
// for bit (lic/sparsity.h).
#ifndef LIC3D_SPARSITY_MASK_H
#define LIC3D_SPARSITY_MASK_H

#ifdef __cplusplus
#include <cstdint>
namespace lic3d::glsl {
#define LIC3D_UINT std::uint32_t
#define LIC3D_INLINE inline
#else
#define LIC3D_UINT uint
#define LIC3D_INLINE
#endif

// One bit per voxel, 1 = black, in blocks of 4 x 4 x 2 voxels per 32-bit word: a streamline's
// neighbouring samples mostly share a word whichever way it runs (a row of x would put y and z
// neighbours 1/32 of a slice apart). Blocks are x fastest, then y, then z; bits inside a block
// likewise. Bits of voxels past the grid in a partial block are 0 and never read.
LIC3D_INLINE LIC3D_UINT licMaskBlocksX(int nx) { return LIC3D_UINT((nx + 3) / 4); }
LIC3D_INLINE LIC3D_UINT licMaskBlocksY(int ny) { return LIC3D_UINT((ny + 3) / 4); }
LIC3D_INLINE LIC3D_UINT licMaskBlocksZ(int nz) { return LIC3D_UINT((nz + 1) / 2); }
LIC3D_INLINE LIC3D_UINT licMaskWord(LIC3D_UINT x, LIC3D_UINT y, LIC3D_UINT z, LIC3D_UINT blocksX,
                                    LIC3D_UINT blocksY) {
  return ((z >> 1u) * blocksY + (y >> 2u)) * blocksX + (x >> 2u);
}
LIC3D_INLINE LIC3D_UINT licMaskBit(LIC3D_UINT x, LIC3D_UINT y, LIC3D_UINT z) {
  return ((z & 1u) << 4u) | ((y & 3u) << 2u) | (x & 3u);
}

// The checkerboard (lic/point_sets.h, CheckerboardPattern): the diagonal plane s = i + j + k is
// black where (s * black) mod period < black.
LIC3D_INLINE bool licCheckerboardBlack(LIC3D_UINT s, LIC3D_UINT black, LIC3D_UINT period) {
  return (s * black) % period < black;
}

// floor(n * phi_b(index)), the voxel of a low-discrepancy coordinate on an axis of n voxels,
// exactly: phi_b(index) = 0.d1 d2 ... dK in base b, with d1 the lowest digit of the index, and
// floor((A + floor(B / b)) / b) = floor((A b + B) / b^2) for integers A, B >= 0 takes
// n * phi_b digit by digit from dK up, every partial value below (n + 1) b.
// `power` is b^(K-1) for some K with b^K > index.
LIC3D_INLINE LIC3D_UINT licScaledRadicalInverse(LIC3D_UINT base, LIC3D_UINT power, LIC3D_UINT index,
                                                LIC3D_UINT n) {
  LIC3D_UINT carry = 0u;
  for (LIC3D_UINT p = power; p > 0u; p /= base) carry = (n * ((index / p) % base) + carry) / base;
  return carry;
}

// floor(a * b / d) for a <= d < 2^31 and b < 2^31 (Hammersley's x: floor(n i / count)), by long
// division of the 64-bit product.
LIC3D_INLINE LIC3D_UINT licMulDivFloor(LIC3D_UINT a, LIC3D_UINT b, LIC3D_UINT d) {
#ifdef __cplusplus
  return static_cast<LIC3D_UINT>(std::uint64_t{a} * b / d);
#else
  uint hi, lo;
  umulExtended(a, b, hi, lo);
  uint q = 0u, r = 0u;
  for (int bit = 63; bit >= 0; --bit) {
    r = (r << 1u) | ((bit >= 32 ? hi >> uint(bit - 32) : lo >> uint(bit)) & 1u);
    if (r >= d) {
      r -= d;
      if (bit < 32) q |= 1u << uint(bit);
    }
  }
  return q;
#endif
}

#undef LIC3D_UINT
#undef LIC3D_INLINE
#ifdef __cplusplus
}  // namespace lic3d::glsl
#endif

#endif
