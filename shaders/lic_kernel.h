// The LIC kernel weights, one formula for GLSL and C++: lic.comp and lic2d.comp include it, and
// so does the CPU reference (core/lic_params.h, kernelWeight), in double precision there.
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

#undef LIC3D_REAL
#undef LIC3D_UINT
#undef LIC3D_INLINE
#ifdef __cplusplus
}  // namespace lic3d::glsl
#endif

#endif
