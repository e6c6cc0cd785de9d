// SPDX-License-Identifier: BSD-3-Clause
#version 460
// 3D LIC, one invocation per voxel (thesis ch. 4, with the semantics of docs/LIC_SEMANTICS.md):
// follow the streamline through the voxel centre backward Lb and forward Lf steps and average
// the noise along it with the kernel's weights. Integrator, kernel, noise filter and direction
// mode are specialization constants, so each variant compiles to a branch-free loop.
#extension GL_GOOGLE_include_directive : require
#include "lic_kernel.h"
#include "shared_layout.h"
#include "sparsity_mask.h"

layout(local_size_x = kLicDefaultLocalSizeX, local_size_x_id = kLicConstLocalSizeX,
       local_size_y = kLicDefaultLocalSizeY, local_size_y_id = kLicConstLocalSizeY,
       local_size_z = kLicDefaultLocalSizeZ, local_size_z_id = kLicConstLocalSizeZ) in;

// 0 euler, 1 rk2, 2 rk4
layout(constant_id = kLicConstIntegrator) const uint INTEGRATOR = kLicDefaultIntegrator;
// 0 box, 1 hann, 2 gauss
layout(constant_id = kLicConstKernel) const uint KERNEL = kLicDefaultKernel;
// 0 nearest, 1 trilinear
layout(constant_id = kLicConstNoiseFilter) const uint NOISE_FILTER = kLicDefaultNoiseFilter;
// 0 u/|u|, 1 u/max|u|
layout(constant_id = kLicConstDirection) const uint DIRECTION = kLicDefaultDirection;
// Thesis 5.1.4: a voxel is not drawn if its streamline touches a black voxel of the mask.
layout(constant_id = kLicConstSparsity) const uint SPARSITY = kLicDefaultSparsity;
// 0 exact: every RK2 step of h fetches its midpoint and its end (two fetches per sample).
// 1 ab2: after a first RK2 step, two-step Adams-Bashforth steps of h (one fetch per sample).
// 2 fused: RK2 steps of 2h whose midpoint is a sample (one fetch per sample, nothing else).
// Only RK2 has a choice: Euler already fetches once per sample, RK4 stays as it is
// (docs/LIC_SEMANTICS.md).
layout(constant_id = kLicConstScheme) const uint SCHEME = kLicDefaultScheme;
// 0: texel xyz = u / max|u|, w = noise (RGBA16F/32F). 1: RGBA8 SNORM, xyz = e with
// e |e| = u / max|u| (square-root magnitude, so slow flow keeps its direction in 8 bits) and
// w = (255 noise - 128) / 127 (engine/volume_textures.h).
layout(constant_id = kLicConstPacking) const uint PACKING = kLicDefaultPacking;
// How the two directions are walked (the same samples either way): 1 in one loop, so an
// invocation waits on two independent fetches at a time; 0 one after the other, which needs
// fewer registers. licLaunchFor keeps the default, 0, on every device type (by measurement:
// docs/BENCHMARKS.md, "Launch shapes").
layout(constant_id = kLicConstInterleave) const uint INTERLEAVE = kLicDefaultInterleave;
// 1: the voxels of the bricks visible_bricks.comp listed for one layer of bricks
// (docs/VISIBLE_WORK.md), dispatched indirectly with workgroups of 8 x 8 x 1: workgroup (i, j)
// makes slice j of the layer's i-th listed brick, and marks the brick made.
layout(constant_id = kLicConstBrickList) const uint BRICK_LIST = kLicDefaultBrickList;

// The field u in voxel units and the noise (engine/volume_textures.h): integrating u in voxel
// coordinates follows the physical field on anisotropic grids.
layout(set = 0, binding = kLicBindingField) uniform sampler3D fieldTexture;
layout(set = 0, binding = kLicBindingOutput, rg16) uniform writeonly image3D licImage;
layout(set = 0, binding = kLicBindingMask, std430) restrict readonly buffer SparsityMask {
  uint sparsityMask[];  // one bit per voxel (sparsity_mask.h)
};
#ifdef LIC3D_SEPARATE_NOISE
// Built only for `lic3d bench`: the naive reference kernel, with the noise in a texture of its
// own, so an exact RK2 sample costs three fetches (midpoint, end, noise) instead of two.
layout(set = 0, binding = kLicBindingNoise) uniform sampler3D noiseTexture;
#endif

layout(set = 0, binding = kLicBindingBrickList, std430) readonly buffer BrickList {
  uint brickList[];
};
layout(set = 0, binding = kLicBindingMadeBricks, std430) writeonly buffer MadeBricks {
  uint madeBricks[];
};

layout(push_constant) uniform Push { LicPushConstants pc; };

// The texel at continuous voxel position x (voxel centres at integers): hardware trilinear
// interpolation with clamp-to-edge is the edge-clamped trilinear field of the semantics. xyz is
// still packed (directionOf decodes it); w is the noise, decoded (linear, so it commutes with
// the interpolation).
vec4 fieldAndNoiseAt(vec3 x) {
  vec4 texel = textureLod(fieldTexture, (x + 0.5) * pc.invDims.xyz, 0.0);
  if (PACKING == 1) texel.w = (127.0 * texel.w + 128.0) / 255.0;
  return texel;
}
vec3 fieldAt(vec3 x) { return fieldAndNoiseAt(x).xyz; }

// Step direction from an interpolated (packed) vector; zero at (near) critical points.
vec3 directionOf(vec3 v) {
  // Squared lengths spare a square root per sample. Packing 1 holds e with |u| / max|u| = |e|^2
  // (its direction is u's), packing 0 u / max|u| itself.
  float squared = dot(v, v);
  float threshold = PACKING == 1 ? pc.criticalEpsilon : pc.criticalEpsilon * pc.criticalEpsilon;
  if (squared <= threshold) return vec3(0.0);
  if (DIRECTION == 0) return v * inversesqrt(squared);
  return PACKING == 1 ? v * sqrt(squared) : v;
}

// The noise at x given the interpolated texel there: trilinear noise comes with it for free.
float noiseAt(vec3 x, vec4 texel) {
#ifdef LIC3D_SEPARATE_NOISE
  if (NOISE_FILTER == 0) return texelFetch(noiseTexture, ivec3(floor(x + 0.5)), 0).r;
  return textureLod(noiseTexture, (x + 0.5) * pc.invDims.xyz, 0.0).r;
#endif
  if (NOISE_FILTER == 0) {
    float w = texelFetch(fieldTexture, ivec3(floor(x + 0.5)), 0).w;
    return PACKING == 1 ? (127.0 * w + 128.0) / 255.0 : w;
  }
  return texel.w;
}

// The mask's bit of voxel v, which must lie inside the grid (no bounds test on the buffer).
bool maskBitAt(uvec3 v) {
  uint word = licMaskWord(v.x, v.y, v.z, licMaskBlocksX(pc.dims.x), licMaskBlocksY(pc.dims.y));
  return ((sparsityMask[word] >> licMaskBit(v.x, v.y, v.z)) & 1u) != 0u;
}

// Whether the sample at x, inside the grid, lies in a black voxel of the mask (the voxel nearest
// to x). Samples are inside by construction (walk() ends a streamline at its first outside
// point), so the sample loop carries no test for the grid's bounds.
bool touchesBlackInside(vec3 x) {
  if (SPARSITY == 0) return false;
  return maskBitAt(uvec3(floor(x + 0.5)));
}

// touchesBlackInside anywhere: beyond the grid, the mask's random continuation (lic_kernel.h).
bool touchesBlack(vec3 x) {
  ivec3 v = ivec3(floor(x + 0.5));
  if (all(greaterThanEqual(v, ivec3(0))) && all(lessThan(v, pc.dims.xyz)))
    return maskBitAt(uvec3(v));
  uvec3 w = uvec3(v) + pc.maskBeyond.xyz;
  return licBlackBeyondGrid(w.x, w.y, w.z, pc.maskSeed, pc.maskBeyond.w);
}

#define LIC_VEC vec3
#include "lic_streamline.glsl"

// For the mask alone, a streamline that left the grid at `outside` goes on straight by `step`
// for the steps it had left (lic_reference.h, StreamlineExit): boundary streamlines then touch as
// many mask voxels as interior ones.
bool exitTouchesBlack(vec3 outside, vec3 step, int stepsLeft) {
  for (int k = 0; k <= stepsLeft; ++k)
    if (touchesBlack(outside + float(k) * step)) return true;
  return false;
}

bool outsideGrid(vec3 x) {
  return any(lessThan(x, vec3(0.0))) || any(greaterThan(x, vec3(pc.dims.xyz - 1)));
}

// One direction of a streamline, advanced a sample (fused: two) at a time, so that main() can
// walk the two directions one after the other or interleaved (INTERLEAVE).
struct Walker {
  vec3 x;       // the last sample (fused: the last even one); after an exit, the point outside
  vec3 d;       // the direction there (non-zero while alive)
  vec3 dPrev;   // the direction at the sample before (ab2)
  int steps;    // Lb or Lf; after an exit, the steps left
  float sh;     // signed h
  bool alive;
  bool exited;  // left the grid: x, sh d and steps describe the straight continuation
};

// Takes sample i at x: adds its noise to the sums and sets w.d to the direction there. False
// where the streamline ends: x is outside the grid (not a sample; w records the exit, its
// continuation stepping by sh times the direction at the last sample inside, w.d), or x is a
// critical sample (the last one).
bool takeSample(inout Walker w, vec3 x, int i, int sign, inout float sum, inout float weights,
                inout bool masked) {
  // One fetch gives this sample's noise and the next step's direction. It is issued before the
  // test below, which then runs while the fetch is in flight instead of before it: the walk is a
  // chain of dependent fetches, so every step of that chain's latency counts (8 % of the fused
  // kernel's time on the H100). Outside the grid the clamped texel is fetched and dropped.
  vec4 texel = fieldAndNoiseAt(x);
  // Outside the grid the streamline ends; outside samples are never clamped back in. The mask's
  // straight continuation beyond the grid is checked once, after the sample loop (main).
  if (outsideGrid(x)) {
    w.alive = false;
    w.exited = true;
    w.x = x;
    w.steps -= i;
    return false;
  }
  float weight = weightOf(sign * i);
  sum += weight * noiseAt(x, texel);
  weights += weight;
  if (touchesBlackInside(x)) masked = true;
  w.d = directionOf(texel.xyz);
  w.alive = w.d != vec3(0.0);
  return w.alive;
}

// Takes the next samples of the walker's direction, from sample i, if it still runs: one, or
// two for the fused scheme (the midpoint i of an RK2 step of 2h from the even sample w.x, and
// the step's end i + 1), so that sample parity needs no test and the even sample is all that
// is kept.
void walk(inout Walker w, int i, int sign, inout float sum, inout float weights,
          inout bool masked, bool firstStep) {
  if (!w.alive) return;
  if (i > w.steps) {
    w.alive = false;
    return;
  }
  if (SCHEME == 2 && INTEGRATOR == 1) {
    if (!takeSample(w, w.x + w.sh * w.d, i, sign, sum, weights, masked)) return;
    if (i + 1 > w.steps) {
      w.alive = false;
      return;
    }
    vec3 end = w.x + 2.0 * w.sh * w.d;  // w.d is the midpoint's direction now
    if (takeSample(w, end, i + 1, sign, sum, weights, masked)) w.x = end;
    return;
  }
  vec3 d = w.d;
  vec3 x;
  if (SCHEME == 1 && INTEGRATOR == 1 && !firstStep) {
    // Adams-Bashforth from the directions already fetched: the sample's own fetch is the only one.
    x = ab2Step(w.x, d, w.dPrev, w.sh);
  } else {
    x = advance(w.x, d, w.sh);
  }
  if (takeSample(w, x, i, sign, sum, weights, masked)) {
    w.x = x;
    w.dPrev = d;
  }
}

// The index from which a direction's loop goes on: 1, or for ab2 2 after taking its first step
// here, an RK2 step (two fetches) where the others take one. A CPU driver runs both sides of a
// test for every SIMD lane, so a test of the index inside the loop would pay the RK2 step's
// fetch at every sample (docs/BENCHMARKS.md, "The CPU driver against KVS"). The samples and their
// order within a direction are the same either way.
int walkFirstStep(inout Walker w, int sign, inout float sum, inout float weights,
                  inout bool masked) {
  if (SCHEME != 1 || INTEGRATOR != 1) return 1;
  walk(w, 1, sign, sum, weights, masked, true);
  return 2;
}

// The voxel this invocation makes: of the slab, or of a listed brick.
ivec3 voxelOfInvocation() {
  if (BRICK_LIST == 0) return ivec3(gl_GlobalInvocationID) + ivec3(0, 0, pc.dims.w);
  const int size = int(kVisibleBrickSize);
  ivec3 bricks = (pc.dims.xyz + size - 1) / size;
  int layer = pc.dims.w / size;
  int index = int(brickList[layer * bricks.x * bricks.y + int(gl_WorkGroupID.x)]);
  ivec3 brick = ivec3(index % bricks.x, (index / bricks.x) % bricks.y, layer);
  // Read by the next classification only, after this dispatch.
  if (gl_WorkGroupID.y == 0 && gl_LocalInvocationIndex == 0) madeBricks[index] = 1u;
  return brick * size + ivec3(gl_LocalInvocationID.xy, gl_WorkGroupID.y);
}

void main() {
  ivec3 voxel = voxelOfInvocation();  // of the output; its streamline starts at voxel * stride
  // Workgroups deeper than one slice overhang the dispatch's slab: the next slab's voxels are its.
  if (any(greaterThanEqual(voxel * pc.outputStride, pc.dims.xyz)) || voxel.z >= pc.zEnd) return;

  vec3 start = vec3(voxel * pc.outputStride);
  vec4 startTexel = fieldAndNoiseAt(start);
  float w0 = weightOf(0);
  float sum = w0 * noiseAt(start, startTexel);
  float weights = w0;
  // A voxel whose streamline touches a black voxel of the mask is hidden; its value is never
  // shown (0, as in the CPU reference), so its streamline is not followed any further.
  bool masked = touchesBlackInside(start);

  vec3 d0 = directionOf(startTexel.xyz);
  bool moves = d0 != vec3(0.0) && !masked;
  Walker back = Walker(start, d0, d0, pc.licLength - pc.bias, -pc.step, moves, false);
  Walker ahead = Walker(start, d0, d0, pc.licLength + pc.bias, pc.step, moves, false);
  // Samples per walk() call.
  const int stride = SCHEME == 2 && INTEGRATOR == 1 ? 2 : 1;
  if (INTERLEAVE == 1) {
    int first = walkFirstStep(back, -1, sum, weights, masked);
    walkFirstStep(ahead, 1, sum, weights, masked);
    for (int i = first; (back.alive || ahead.alive) && !masked; i += stride) {
      walk(back, i, -1, sum, weights, masked, false);
      walk(ahead, i, 1, sum, weights, masked, false);
    }
  } else {
    for (int i = walkFirstStep(back, -1, sum, weights, masked); back.alive && !masked;
         i += stride)
      walk(back, i, -1, sum, weights, masked, false);
    // Done with the backward walker here, so its exit is not kept live (in registers, which
    // bound how many invocations a GPU core holds) through the forward walk.
    if (SPARSITY != 0 && !masked && back.exited &&
        exitTouchesBlack(back.x, back.sh * back.d, back.steps))
      masked = true;
    for (int i = walkFirstStep(ahead, 1, sum, weights, masked); ahead.alive && !masked;
         i += stride)
      walk(ahead, i, 1, sum, weights, masked, false);
  }
  if (SPARSITY != 0 && !masked) {
    if (INTERLEAVE == 1 && back.exited && exitTouchesBlack(back.x, back.sh * back.d, back.steps))
      masked = true;
    if (ahead.exited && exitTouchesBlack(ahead.x, ahead.sh * ahead.d, ahead.steps)) masked = true;
  }
  imageStore(licImage, voxel, masked ? vec4(0.0) : vec4(sum / weights, 1.0, 0.0, 0.0));
}
