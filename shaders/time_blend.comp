// SPDX-License-Identifier: BSD-3-Clause
#version 460
// Unsteady fields (docs/TIME.md): the field at a time between two resident time steps, linearly
// interpolated per voxel and written into the LIC pass' field texture with its packing (xyz = u /
// max|u|, u the field in voxel units; w = noise; engine/volume_textures.h). Two phases, one
// pipeline each: phase 0 measures the interpolated field (max |u|, min and max |v|) with one
// atomic per workgroup and value; phase 1 writes the texture, normalised by phase 0's max |u|.
// Compiled three times, one per field texture format (field_texel.glsl).
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(local_size_x = kTimeBlendLocalSizeX, local_size_y = kTimeBlendLocalSizeY, local_size_z = 1) in;

layout(constant_id = kTimeBlendConstPhase) const uint PHASE = kTimeBlendDefaultPhase;

layout(set = 0, binding = kTimeBlendBindingStepA) uniform sampler3D stepA;
layout(set = 0, binding = kTimeBlendBindingStepB) uniform sampler3D stepB;
layout(set = 0, binding = kTimeBlendBindingNoise) uniform sampler3D noiseVolume;
#define FIELD_TEXEL_BINDING kTimeBlendBindingTarget
#include "field_texel.glsl"
layout(set = 0, binding = kTimeBlendBindingRanges) buffer Ranges { uint ranges[kTimeBlendRangeCount]; };

layout(push_constant) uniform Push { TimeBlendPushConstants pc; };

shared float groupMaxSpeed[kTimeBlendLocalSizeX * kTimeBlendLocalSizeY];
shared float groupMaxMagnitude[kTimeBlendLocalSizeX * kTimeBlendLocalSizeY];
shared float groupMinMagnitude[kTimeBlendLocalSizeX * kTimeBlendLocalSizeY];

void main() {
  ivec3 voxel = ivec3(gl_GlobalInvocationID);
  bool inside = all(lessThan(voxel, pc.dims.xyz));
  // The physical vector at this time: each step's texels times its scale, then the linear blend.
  vec3 v = vec3(0.0);
  if (inside) {
    vec3 a = texelFetch(stepA, voxel, 0).xyz * pc.stepScales.x;
    vec3 b = texelFetch(stepB, voxel, 0).xyz * pc.stepScales.y;
    v = mix(a, b, pc.unitScale.w);
  }
  vec3 u = v * pc.unitScale.xyz;

  if (PHASE == 1) {
    if (!inside) return;
    float maxSpeed = uintBitsToFloat(ranges[kTimeBlendRangeMaxSpeed]);
    vec3 texel = maxSpeed > 0.0 ? u / maxSpeed : u;
    float noise = texelFetch(noiseVolume, voxel, 0).r;
    imageStore(fieldTexels, voxel, fieldTexel(texel, noise));
    return;
  }

  // Phase 0: a workgroup reduces its values in shared memory, then one invocation merges them.
  // Non-negative floats order like their bit patterns, so uint atomics compare them.
  uint local = gl_LocalInvocationIndex;
  groupMaxSpeed[local] = inside ? length(u) : 0.0;
  groupMaxMagnitude[local] = inside ? length(v) : 0.0;
  groupMinMagnitude[local] = inside ? length(v) : 3.0e38;
  barrier();
  for (uint stride = gl_WorkGroupSize.x * gl_WorkGroupSize.y / 2; stride > 0; stride /= 2) {
    if (local < stride) {
      groupMaxSpeed[local] = max(groupMaxSpeed[local], groupMaxSpeed[local + stride]);
      groupMaxMagnitude[local] = max(groupMaxMagnitude[local], groupMaxMagnitude[local + stride]);
      groupMinMagnitude[local] = min(groupMinMagnitude[local], groupMinMagnitude[local + stride]);
    }
    barrier();
  }
  if (local == 0) {
    atomicMax(ranges[kTimeBlendRangeMaxSpeed], floatBitsToUint(groupMaxSpeed[0]));
    atomicMax(ranges[kTimeBlendRangeMaxMagnitude], floatBitsToUint(groupMaxMagnitude[0]));
    atomicMin(ranges[kTimeBlendRangeMinMagnitude], floatBitsToUint(groupMinMagnitude[0]));
  }
}
