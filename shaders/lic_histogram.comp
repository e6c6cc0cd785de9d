// SPDX-License-Identifier: BSD-3-Clause
#version 460
// Histogram of the drawn voxels of the LIC volume outside empty space: the renderer's contrast
// stretch and percentile window come from it. Empty space (voxels slower than a small fraction
// of the field's fast speeds: zero, NaN or masked vectors) holds the bare noise, or the bare
// seeds of seed noise, which would otherwise set the window of the flow. One workgroup per z slice,
// counts gathered in shared memory first so the global atomics stay few.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(local_size_x = kHistogramLocalSize) in;

// 1: only the voxels of visible bricks count (the others may never have been made), so that the
// LIC over the visible bricks and the full LIC have the same statistics.
layout(constant_id = kHistogramConstVisibleBricks) const uint VISIBLE_BRICKS =
    kHistogramDefaultVisibleBricks;

layout(set = 0, binding = kHistogramBindingVolume) uniform sampler3D licVolume;
layout(set = 0, binding = kHistogramBindingCounts, std430) buffer Counts { uint counts[]; };
layout(set = 0, binding = kHistogramBindingField) uniform sampler3D fieldTexture;
layout(set = 0, binding = kHistogramBindingVisible, std430) readonly buffer Visible {
  uint visibleBricks[];
};
layout(push_constant) uniform Push { HistogramPushConstants pc; };

bool inVisibleBrick(ivec3 voxel) {
  const int size = int(kVisibleBrickSize);
  ivec3 bricks = (pc.dims.xyz + size - 1) / size;
  ivec3 brick = voxel / size;
  return visibleBricks[brick.x + bricks.x * (brick.y + bricks.y * brick.z)] != 0u;
}

shared uint localCounts[kHistogramBins];
shared uint localMasked;

void main() {
  for (uint b = gl_LocalInvocationID.x; b < kHistogramBins; b += kHistogramLocalSize)
    localCounts[b] = 0;
  if (gl_LocalInvocationID.x == 0) localMasked = 0;
  barrier();

  int z = int(gl_WorkGroupID.x);
  int sliceVoxels = pc.dims.x * pc.dims.y;
  for (int n = int(gl_LocalInvocationID.x); n < sliceVoxels; n += int(kHistogramLocalSize)) {
    ivec3 voxel = ivec3(n % pc.dims.x, n / pc.dims.x, z);
    if (VISIBLE_BRICKS == 1 && !inVisibleBrick(voxel)) continue;
    vec2 texel = texelFetch(licVolume, voxel, 0).rg;
    if (texel.g < 0.5) {  // masked by sparsity: never drawn, so counted apart
      atomicAdd(localMasked, 1);
      continue;
    }
    vec3 v = texelFetch(fieldTexture, voxel * pc.stride.x, 0).xyz;
    if (pc.dims.w == 1) v *= length(v);                                       // e |e| = u / max|u|
    if (length(v * pc.texelToPhysical.xyz) < pc.texelToPhysical.w) continue;  // empty space
    float value = clamp(texel.r, 0.0, 1.0);
    uint bin = min(uint(value * float(kHistogramBins)), kHistogramBins - 1);
    atomicAdd(localCounts[bin], 1);
  }
  barrier();

  for (uint b = gl_LocalInvocationID.x; b < kHistogramBins; b += kHistogramLocalSize)
    if (localCounts[b] != 0) atomicAdd(counts[b], localCounts[b]);
  if (gl_LocalInvocationID.x == 0 && localMasked != 0)
    atomicAdd(counts[kHistogramBins], localMasked);
}
