// SPDX-License-Identifier: BSD-3-Clause
#version 460
// A sparsity mask made on the GPU (lic/sparsity.h): the distributions whose black voxels are each
// a function of their own index. The checkerboard writes one word of the bit-packed mask per
// invocation; Halton and Hammersley blacken the voxel of point i per invocation with an atomic OR
// into a zeroed mask. Both count the voxels they made black, for the continuation beyond the grid
// (MaskBeyondGrid). The distribution is a specialization constant.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"
#include "sparsity_mask.h"

layout(local_size_x = kMaskLocalSize) in;

// kMaskCheckerboard, kMaskHalton or kMaskHammersley
layout(constant_id = kMaskConstDistribution) const uint DISTRIBUTION = kMaskDefaultDistribution;

layout(set = 0, binding = kMaskBindingBits, std430) buffer Bits { uint bits[]; };
layout(set = 0, binding = kMaskBindingCount, std430) buffer Count { uint blackCount; };

layout(push_constant) uniform Push { SparsityMaskPushConstants pc; };

shared uint groupBlack;

// The 32 voxels of word w (a block of 4 x 4 x 2) under the checkerboard of diagonal planes.
uint checkerboardWord(uint w) {
  uint blocksX = licMaskBlocksX(pc.dims.x), blocksY = licMaskBlocksY(pc.dims.y);
  uvec3 origin = uvec3(w % blocksX * 4u, w / blocksX % blocksY * 4u, w / (blocksX * blocksY) * 2u);
  uint word = 0u;
  for (uint b = 0u; b < 32u; ++b) {
    uvec3 v = origin + uvec3(b & 3u, (b >> 2u) & 3u, b >> 4u);
    if (all(lessThan(v, uvec3(pc.dims.xyz))) &&
        licCheckerboardBlack(v.x + v.y + v.z, pc.pattern.x, pc.pattern.y))
      word |= 1u << licMaskBit(v.x, v.y, v.z);
  }
  return word;
}

// The voxel of point i (1..count), as makeSparsityMask computes it.
uvec3 pointVoxel(uint i) {
  uvec3 n = uvec3(pc.dims.xyz);
  if (DISTRIBUTION == kMaskHalton)
    return uvec3(licScaledRadicalInverse(2u, pc.powers.x, i, n.x),
                 licScaledRadicalInverse(3u, pc.powers.y, i, n.y),
                 licScaledRadicalInverse(5u, pc.powers.z, i, n.z));
  return uvec3(min(licMulDivFloor(i, n.x, pc.pattern.x), n.x - 1u),
               licScaledRadicalInverse(2u, pc.powers.x, i, n.y),
               licScaledRadicalInverse(3u, pc.powers.y, i, n.z));
}

void main() {
  if (gl_LocalInvocationIndex == 0u) groupBlack = 0u;
  barrier();
  uint id = (gl_WorkGroupID.y * gl_NumWorkGroups.x + gl_WorkGroupID.x) * kMaskLocalSize +
            gl_LocalInvocationIndex;
  uint black = 0u;
  if (DISTRIBUTION == kMaskCheckerboard) {
    if (id < pc.powers.w) {
      uint word = checkerboardWord(id);
      bits[id] = word;
      black = uint(bitCount(word));
    }
  } else if (id < pc.pattern.x) {
    uvec3 v = pointVoxel(id + 1u);
    uint bit = 1u << licMaskBit(v.x, v.y, v.z);
    uint word = licMaskWord(v.x, v.y, v.z, licMaskBlocksX(pc.dims.x), licMaskBlocksY(pc.dims.y));
    // Points that share a voxel: only the first to set its bit counts it.
    if ((atomicOr(bits[word], bit) & bit) == 0u) black = 1u;
  }
  if (black != 0u) atomicAdd(groupBlack, black);
  barrier();
  if (gl_LocalInvocationIndex == 0u && groupBlack != 0u) atomicAdd(blackCount, groupBlack);
}
