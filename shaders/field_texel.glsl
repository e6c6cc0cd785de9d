// SPDX-License-Identifier: BSD-3-Clause
// The field and noise texture as a storage image, and its texel encoding (passes/volume_textures.h),
// for the shaders that write it on the device. Compiled once per format: rgba32f, rgba16f
// (LIC3D_HALF_FIELD) and rgba8_snorm with its square-root packing (LIC3D_BYTE_FIELD). The includer
// defines FIELD_TEXEL_BINDING.
#ifndef LIC3D_FIELD_TEXEL_GLSL
#define LIC3D_FIELD_TEXEL_GLSL

#if defined(LIC3D_HALF_FIELD)
layout(set = 0, binding = FIELD_TEXEL_BINDING, rgba16f) uniform writeonly image3D fieldTexels;
#elif defined(LIC3D_BYTE_FIELD)
layout(set = 0, binding = FIELD_TEXEL_BINDING, rgba8_snorm) uniform writeonly image3D fieldTexels;
#else
layout(set = 0, binding = FIELD_TEXEL_BINDING, rgba32f) uniform writeonly image3D fieldTexels;
#endif

// `texel`: u / max|u| (|texel| <= 1); `noise` in [0, 1].
vec4 fieldTexel(vec3 texel, float noise) {
#ifdef LIC3D_BYTE_FIELD
  // FieldPrecision::Byte: e with e |e| = u / max|u|, noise shifted into the signed range (byte 0
  // is stored as -127 rather than -128; both read as -1).
  float speed = length(texel);
  texel = speed > 0.0 ? texel / sqrt(speed) : vec3(0.0);
  noise = (round(clamp(noise, 0.0, 1.0) * 255.0) - 128.0) / 127.0;
#endif
  return vec4(texel, noise);
}

#endif
