#version 460
// 3D LIC, one invocation per voxel (thesis ch. 4, with the semantics of docs/LIC_SEMANTICS.md):
// follow the streamline through the voxel centre backward Lb and forward Lf steps and average
// the noise along it with the kernel's weights. Integrator, kernel, noise filter and direction
// mode are specialization constants, so each variant compiles to a branch-free loop.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(local_size_x_id = kLicConstLocalSizeX, local_size_y_id = kLicConstLocalSizeY,
       local_size_z_id = kLicConstLocalSizeZ) in;

layout(constant_id = kLicConstIntegrator) const uint INTEGRATOR = 1;    // 0 euler, 1 rk2, 2 rk4
layout(constant_id = kLicConstKernel) const uint KERNEL = 0;            // 0 box, 1 hann, 2 gauss
layout(constant_id = kLicConstNoiseFilter) const uint NOISE_FILTER = 1; // 0 nearest, 1 trilinear
layout(constant_id = kLicConstDirection) const uint DIRECTION = 0;      // 0 u/|u|, 1 u/max|u|
// Thesis 5.1.4: a voxel is not drawn if its streamline touches a black voxel of the mask.
layout(constant_id = kLicConstSparsity) const uint SPARSITY = 0;

// xyz = u / max|u| with u the field in voxel units, w = noise (engine/volume_textures.h):
// integrating u in voxel coordinates follows the physical field on anisotropic grids.
layout(set = 0, binding = kLicBindingField) uniform sampler3D fieldTexture;
layout(set = 0, binding = kLicBindingOutput, rg16) uniform writeonly image3D licImage;
layout(set = 0, binding = kLicBindingMask) uniform usampler3D sparsityMask;

layout(push_constant) uniform Push { LicPushConstants pc; };

// (u / max|u|, noise) at continuous voxel position x (voxel centres at integers): hardware
// trilinear interpolation with clamp-to-edge is the edge-clamped trilinear field of the semantics.
vec4 fieldAndNoiseAt(vec3 x) { return textureLod(fieldTexture, (x + 0.5) * pc.invDims.xyz, 0.0); }
vec3 fieldAt(vec3 x) { return fieldAndNoiseAt(x).xyz; }

// Step direction from an interpolated vector; zero at (near) critical points.
vec3 directionOf(vec3 v) {
  float magnitude = length(v);
  if (magnitude <= pc.criticalEpsilon) return vec3(0.0);
  return DIRECTION == 0 ? v / magnitude : v;
}

// The noise at x given the interpolated texel there: trilinear noise comes with it for free.
float noiseAt(vec3 x, vec4 texel) {
  if (NOISE_FILTER == 0) return texelFetch(fieldTexture, ivec3(floor(x + 0.5)), 0).w;
  return texel.w;
}

// Whether the sample at x lies in a black voxel of the mask (the voxel nearest to x).
bool touchesBlack(vec3 x) {
  return SPARSITY != 0 && texelFetch(sparsityMask, ivec3(floor(x + 0.5)), 0).r != 0u;
}

float weightOf(int i) {
  if (KERNEL == 1) return 0.5 * (1.0 + cos(3.14159265358979 * float(i) / pc.hannDenominator));
  if (KERNEL == 2) {
    float t = float(i) * pc.gaussScale;
    return exp(-0.5 * t * t);
  }
  return 1.0;
}

// One step of signed length sh from x, whose direction d0 = directionOf(v(x)) is non-zero.
vec3 advance(vec3 x, vec3 d0, float sh) {
  if (INTEGRATOR == 0) return x + sh * d0;
  if (INTEGRATOR == 1) return x + sh * directionOf(fieldAt(x + 0.5 * sh * d0));
  vec3 k2 = directionOf(fieldAt(x + 0.5 * sh * d0));
  vec3 k3 = directionOf(fieldAt(x + 0.5 * sh * k2));
  vec3 k4 = directionOf(fieldAt(x + sh * k3));
  return x + (sh / 6.0) * (d0 + 2.0 * k2 + 2.0 * k3 + k4);
}

void main() {
  ivec3 voxel = ivec3(gl_GlobalInvocationID) + ivec3(0, 0, pc.dims.w);
  if (any(greaterThanEqual(voxel, pc.dims.xyz))) return;

  vec3 start = vec3(voxel);
  vec3 upper = vec3(pc.dims.xyz - 1);
  vec4 startTexel = fieldAndNoiseAt(start);
  float w0 = weightOf(0);
  float sum = w0 * noiseAt(start, startTexel);
  float weights = w0;
  // A voxel whose streamline touches a black voxel of the mask is hidden; its value is never
  // shown (0, as in the CPU reference), so its streamline is not followed any further.
  bool masked = touchesBlack(start);

  for (int direction = -1; direction <= 1 && !masked; direction += 2) {
    int steps = direction < 0 ? pc.licLength - pc.bias : pc.licLength + pc.bias;
    float sh = float(direction) * pc.step;
    vec3 x = start;
    vec3 v = startTexel.xyz;
    for (int i = 1; i <= steps; ++i) {
      // A streamline ends at a critical point (the sample there was already taken) ...
      vec3 d = directionOf(v);
      if (d == vec3(0.0)) break;
      x = advance(x, d, sh);
      // ... or where it leaves the grid: outside samples are never clamped back in.
      if (any(lessThan(x, vec3(0.0))) || any(greaterThan(x, upper))) break;
      // One fetch gives this sample's noise and the next step's vector.
      vec4 texel = fieldAndNoiseAt(x);
      float w = weightOf(direction * i);
      sum += w * noiseAt(x, texel);
      weights += w;
      if (touchesBlack(x)) {
        masked = true;
        break;
      }
      v = texel.xyz;
    }
  }
  imageStore(licImage, voxel, masked ? vec4(0.0) : vec4(sum / weights, 1.0, 0.0, 0.0));
}
