// SPDX-License-Identifier: BSD-3-Clause
#version 460
// 2D LIC (thesis chapter 3, with the semantics of docs/LIC_SEMANTICS.md restricted to a plane),
// one invocation per output pixel. The output image may be finer than the field: the noise lives
// at the output's resolution and the field is sampled bilinearly at the same texture coordinate,
// so positions, steps and noise lookups are all in output pixels. Integrator, kernel, noise
// filter and direction mode are specialization constants, as in lic.comp.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(local_size_x = kLic2DDefaultLocalSizeX, local_size_x_id = kLic2DConstLocalSizeX,
       local_size_y = kLic2DDefaultLocalSizeY, local_size_y_id = kLic2DConstLocalSizeY,
       local_size_z = 1) in;

// 0 euler, 1 rk2, 2 rk4
layout(constant_id = kLic2DConstIntegrator) const uint INTEGRATOR = kLic2DDefaultIntegrator;
// 0 box, 1 hann, 2 gauss
layout(constant_id = kLic2DConstKernel) const uint KERNEL = kLic2DDefaultKernel;
// 0 nearest, 1 bilinear
layout(constant_id = kLic2DConstNoiseFilter) const uint NOISE_FILTER = kLic2DDefaultNoiseFilter;
// 0 u/|u|, 1 u/max|u|
layout(constant_id = kLic2DConstDirection) const uint DIRECTION = kLic2DDefaultDirection;
// How RK2 steps, as in lic.comp (LicParams::scheme): 0 exact, every step an RK2 step; 1 the first
// step RK2 and the others two-step Adams-Bashforth steps from the directions at the last two
// samples (one fetch per sample); 2 fused, RK2 steps of 2h whose midpoint is a sample.
layout(constant_id = kLic2DConstScheme) const uint SCHEME = kLic2DDefaultScheme;

// xy = u / max|u|, u the field in output pixel units (engine/lic2d_pass.h).
layout(set = 0, binding = kLic2DBindingField) uniform sampler2D fieldTexture;
layout(set = 0, binding = kLic2DBindingNoise) uniform sampler2D noiseTexture;
layout(set = 0, binding = kLic2DBindingOutput, r32f) uniform writeonly image2D licImage;

layout(push_constant) uniform Push { Lic2DPushConstants pc; };

// Pixel x (centres at integers) lies at texture coordinate (x + 0.5) / size in both textures:
// hardware bilinear filtering with clamp-to-edge is the semantics' edge-clamped interpolation.
vec2 textureCoordinate(vec2 x) { return (x + 0.5) * pc.invSize.xy; }
vec2 fieldAt(vec2 x) { return textureLod(fieldTexture, textureCoordinate(x), 0.0).xy; }

float noiseAt(vec2 x) {
  if (NOISE_FILTER == 0) return texelFetch(noiseTexture, ivec2(floor(x + 0.5)), 0).r;
  return textureLod(noiseTexture, textureCoordinate(x), 0.0).r;
}

// Step direction from an interpolated vector; zero at (near) critical points.
vec2 directionOf(vec2 v) {
  float magnitude = length(v);
  if (magnitude <= pc.criticalEpsilon) return vec2(0.0);
  return DIRECTION == 0 ? v / magnitude : v;
}

#define LIC_VEC vec2
#include "lic_streamline.glsl"

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(pixel, pc.size.xy))) return;

  vec2 start = vec2(pixel);
  vec2 upper = vec2(pc.size.xy - 1);
  float w0 = weightOf(0);
  float sum = w0 * noiseAt(start);
  float weights = w0;
  vec2 startVector = fieldAt(start);

  for (int direction = -1; direction <= 1; direction += 2) {
    int steps = direction < 0 ? pc.licLength - pc.bias : pc.licLength + pc.bias;
    float sh = float(direction) * pc.step;
    vec2 x = start;
    vec2 v = startVector;
    vec2 previous = vec2(0.0);  // the direction at the sample before x (ab2)
    vec2 before = x;            // the sample before x (fused)
    for (int i = 1; i <= steps; ++i) {
      // A streamline ends at a critical point (the sample there was already taken) ...
      vec2 d = directionOf(v);
      if (d == vec2(0.0)) break;
      vec2 next;
      if (SCHEME == 1 && INTEGRATOR == 1 && i > 1) next = ab2Step(x, d, previous, sh);
      else if (SCHEME == 2 && INTEGRATOR == 1) next = fusedStep(i, x, d, before, sh);
      else next = advance(x, d, sh);
      previous = d;
      before = x;
      x = next;
      // ... or where it leaves the image: outside samples are never clamped back in.
      if (any(lessThan(x, vec2(0.0))) || any(greaterThan(x, upper))) break;
      float w = weightOf(direction * i);
      sum += w * noiseAt(x);
      weights += w;
      v = fieldAt(x);
    }
  }
  imageStore(licImage, pixel, vec4(sum / weights, 0.0, 0.0, 0.0));
}
