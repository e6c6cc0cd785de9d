// SPDX-License-Identifier: BSD-3-Clause
#version 460
// An analytic field and its white noise made on the device straight into the LIC pass' field
// texture (passes/volume_textures.h), with the field's statistics, so that nothing of the field
// passes through the host (shared_layout.h). Two phases, as time_blend.comp: phase 0 measures
// max |u| and min and max |v|; phase 1 writes the texels normalised by max |u| and counts |v| into
// the histogram over [min, max]. Each workgroup walks kAnalyticLayersPerGroup z layers of an 8x8
// column, so that its shared histogram is merged once per 1024 voxels. Compiled once per texture
// format (field_texel.glsl).
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"
#include "analytic_fields.glsl"
#define FIELD_TEXEL_BINDING kAnalyticBindingTexels
#include "field_texel.glsl"

layout(local_size_x = kAnalyticLocalSizeX, local_size_y = kAnalyticLocalSizeY) in;
layout(constant_id = kAnalyticConstPhase) const uint PHASE = kAnalyticDefaultPhase;

layout(set = 0, binding = kAnalyticBindingStatistics, std430) buffer Statistics {
  uint statistics[kAnalyticStatisticsWords];
};
layout(push_constant) uniform Push { AnalyticPushConstants pc; };

shared uint groupMaxSpeed, groupMaxMagnitude, groupMinMagnitude;
shared uint groupBins[kAnalyticHistogramBins];

// ---- The noise of lic/noise.h: the top byte of SplitMix64(seed, voxel index) (lic/random.h),
// ---- in 32-bit words (x the low one).

uvec2 mul64(uvec2 a, uvec2 b) {
  uint high, low;
  umulExtended(a.x, b.x, high, low);
  return uvec2(low, high + a.x * b.y + a.y * b.x);
}

uvec2 add64(uvec2 a, uvec2 b) {
  uint carry;
  uint low = uaddCarry(a.x, b.x, carry);
  return uvec2(low, a.y + b.y + carry);
}

uvec2 xorShift(uvec2 z, int s) {  // z ^ (z >> s) for 0 < s < 32
  return z ^ uvec2((z.x >> s) | (z.y << (32 - s)), z.y >> s);
}

uint noiseByte(uvec2 seed, uvec2 index) {
  uvec2 z = add64(mul64(seed, uvec2(0xD192ED03u, 0xD1B54A32u)),
                  mul64(index, uvec2(0x7F4A7C15u, 0x9E3779B9u)));
  z = mul64(xorShift(z, 30), uvec2(0x1CE4E5B9u, 0xBF58476Du));
  z = mul64(xorShift(z, 27), uvec2(0x133111EBu, 0x94D049BBu));
  return xorShift(z, 31).y >> 24;
}

void main() {
  uint local = gl_LocalInvocationIndex;
  const uint groupSize = kAnalyticLocalSizeX * kAnalyticLocalSizeY;
  if (PHASE == 0) {
    if (local == 0u) {
      groupMaxSpeed = 0u;
      groupMaxMagnitude = 0u;
      groupMinMagnitude = floatBitsToUint(3.0e38);
    }
  } else {
    for (uint b = local; b < kAnalyticHistogramBins; b += groupSize) groupBins[b] = 0u;
  }
  barrier();

  ivec2 xy = ivec2(gl_GlobalInvocationID.xy);
  int zBegin = pc.dims.w + int(gl_WorkGroupID.z * kAnalyticLayersPerGroup);
  int zEnd = min(zBegin + int(kAnalyticLayersPerGroup), pc.dims.z);
  float maxSpeed = uintBitsToFloat(statistics[kAnalyticMaxSpeed]);
  float lowest = uintBitsToFloat(statistics[kAnalyticMinMagnitude]);
  float highest = uintBitsToFloat(statistics[kAnalyticMaxMagnitude]);
  float binsPerUnit = highest > lowest ? float(kAnalyticHistogramBins) / (highest - lowest) : 0.0;
  if (xy.x < pc.dims.x && xy.y < pc.dims.y && zBegin < zEnd) {
    float speedHigh = 0.0, high = 0.0, low = 3.0e38;
    uint layer = uint(pc.whole.x) * uint(pc.whole.y);
    for (int z = zBegin; z < zEnd; ++z) {
      ivec3 at = ivec3(xy, z) + pc.offset.xyz;  // in the whole grid
      vec3 v = evaluate(pc.origin.xyz + vec3(at) * pc.spacing.xyz, pc.origin.w);
      vec3 u = v * pc.unitScale.xyz;
      float magnitude = length(v);
      if (PHASE == 0) {
        speedHigh = max(speedHigh, length(u));
        high = max(high, magnitude);
        low = min(low, magnitude);
        continue;
      }
      uint bin = uint(max(magnitude - lowest, 0.0) * binsPerUnit);
      atomicAdd(groupBins[min(bin, kAnalyticHistogramBins - 1u)], 1u);
      // The voxel's index in the grid, 64 bits wide.
      uvec2 index = add64(mul64(uvec2(layer, 0u), uvec2(uint(at.z), 0u)),
                          uvec2(uint(at.x) + uint(pc.whole.x) * uint(at.y), 0u));
      float noise = float(noiseByte(pc.seed.xy, index)) / 255.0;
      imageStore(fieldTexels, ivec3(xy, z),
                 fieldTexel(maxSpeed > 0.0 ? u / maxSpeed : u, noise));
    }
    if (PHASE == 0) {
      atomicMax(groupMaxSpeed, floatBitsToUint(speedHigh));
      atomicMax(groupMaxMagnitude, floatBitsToUint(high));
      atomicMin(groupMinMagnitude, floatBitsToUint(low));
    }
  }
  barrier();
  if (PHASE == 0) {
    if (local == 0u) {
      atomicMax(statistics[kAnalyticMaxSpeed], groupMaxSpeed);
      atomicMax(statistics[kAnalyticMaxMagnitude], groupMaxMagnitude);
      atomicMin(statistics[kAnalyticMinMagnitude], groupMinMagnitude);
    }
    return;
  }
  for (uint b = local; b < kAnalyticHistogramBins; b += groupSize)
    if (groupBins[b] != 0u) atomicAdd(statistics[kAnalyticFirstBin + b], groupBins[b]);
}
