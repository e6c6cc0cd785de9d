#version 460
// Histogram of the drawn voxels of the LIC volume: the renderer's contrast stretch comes from
// their mean and spread. One workgroup per z slice, counts gathered in shared memory first so the global
// atomics stay few.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(local_size_x = kHistogramLocalSize) in;

layout(set = 0, binding = kHistogramBindingVolume) uniform sampler3D licVolume;
layout(set = 0, binding = kHistogramBindingCounts, std430) buffer Counts { uint counts[]; };
layout(push_constant) uniform Push { HistogramPushConstants pc; };

shared uint localCounts[kHistogramBins];

void main() {
  for (uint b = gl_LocalInvocationID.x; b < kHistogramBins; b += kHistogramLocalSize)
    localCounts[b] = 0;
  barrier();

  int z = int(gl_WorkGroupID.x);
  int sliceVoxels = pc.dims.x * pc.dims.y;
  for (int n = int(gl_LocalInvocationID.x); n < sliceVoxels; n += int(kHistogramLocalSize)) {
    ivec3 voxel = ivec3(n % pc.dims.x, n / pc.dims.x, z);
    vec2 texel = texelFetch(licVolume, voxel, 0).rg;
    if (texel.g < 0.5) continue;  // masked by sparsity: never drawn, so not in the statistics
    float value = clamp(texel.r, 0.0, 1.0);
    uint bin = min(uint(value * float(kHistogramBins)), kHistogramBins - 1);
    atomicAdd(localCounts[bin], 1);
  }
  barrier();

  for (uint b = gl_LocalInvocationID.x; b < kHistogramBins; b += kHistogramLocalSize)
    if (localCounts[b] != 0) atomicAdd(counts[b], localCounts[b]);
}
