// SPDX-License-Identifier: BSD-3-Clause
#version 460
// Which bricks of the LIC volume the slice pass can show (docs/VISIBLE_WORK.md): one workgroup
// per brick. A brick is visible when its voxels, widened by the filter's margin, meet the kept
// part of the box (clip box, clip plane, region of interest) and hold a voxel that can be opaque
// under the opacity transfer. Conservative: a fragment slice.frag draws with non-zero opacity
// reads LIC voxels of visible bricks only. Visible bricks not made yet are listed for the LIC
// pass' indirect dispatch, one list per layer of bricks along z.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(local_size_x = kVisibleLocalSize) in;

// 0: every voxel can be opaque; 1: a voxel whose speed is not NaN; 2: a voxel whose speed is not
// NaN and whose opacity scalar o reaches the lowest opaque o (magnitude threshold or table).
layout(constant_id = kVisibleConstOpacityRule) const uint OPACITY_RULE = kVisibleDefaultOpacityRule;
layout(constant_id = kVisibleConstPacking) const uint PACKING = kVisibleDefaultPacking;
layout(constant_id = kVisibleConstClipPlane) const uint CLIP_PLANE = kVisibleDefaultClipPlane;
layout(constant_id = kVisibleConstRoiShape) const uint ROI_SHAPE = kVisibleDefaultRoiShape;
layout(constant_id = kVisibleConstRoiOutside) const uint ROI_OUTSIDE = kVisibleDefaultRoiOutside;

layout(set = 0, binding = kVisibleBindingField) uniform sampler3D fieldTexture;
layout(set = 0, binding = kVisibleBindingUniforms, std140) uniform Uniforms {
  VisibleBricksUniforms u;
};
layout(set = 0, binding = kVisibleBindingVisible, std430) buffer Visible { uint visible[]; };
layout(set = 0, binding = kVisibleBindingMade, std430) readonly buffer Made { uint made[]; };
layout(set = 0, binding = kVisibleBindingLists, std430) writeonly buffer Lists { uint lists[]; };
layout(set = 0, binding = kVisibleBindingDispatch, std430) buffer Dispatch { uint dispatch[]; };

shared bool kept;
shared bool opaque;

// Texture coordinates of a continuous voxel position (voxel centres at integers).
vec3 textureAt(vec3 voxel) { return (voxel + 0.5) / vec3(u.dims.xyz); }
vec3 worldAt(vec3 voxel) { return (textureAt(voxel) - 0.5) * 2.0 * u.halfExtent.xyz; }

bool insideRegion(vec3 p) {
  if (ROI_SHAPE == 1) return dot(p, p) <= 0.25;
  if (ROI_SHAPE == 2) return all(lessThanEqual(abs(p), vec3(0.5)));
  return dot(p.xy, p.xy) <= 0.25 && abs(p.z) <= 0.5;
}

// Whether the part of the box between voxel positions lo and hi (widened by the margin already)
// may hold a kept sample.
bool keptBox(vec3 lo, vec3 hi) {
  float jitter = u.halfExtent.w;
  vec3 worldLo = worldAt(lo) - jitter;
  vec3 worldHi = worldAt(hi) + jitter;
  if (any(greaterThan(worldLo, u.clipMax.xyz)) || any(lessThan(worldHi, u.clipMin.xyz)))
    return false;
  if (CLIP_PLANE == 1) {
    // The lowest dot(n, p) over the box: each axis at the end the normal points away from.
    vec3 n = u.clipPlane.xyz;
    vec3 lowest = mix(worldHi, worldLo, greaterThanEqual(n, vec3(0.0)));
    if (dot(n, lowest) > u.clipPlane.w) return false;
  }
  if (ROI_SHAPE != 0) {
    // The region is tested at the (jittered) sample's texture coordinate: no jitter margin; but
    // a halo's ring samples, read around a kept sample, are not tested.
    vec3 ring = u.opacity.w / (2.0 * u.halfExtent.xyz);
    vec3 tLo = textureAt(lo) - ring, tHi = textureAt(hi) + ring;
    vec3 corners[8];
    for (int k = 0; k < 8; ++k) {
      vec3 t = mix(tLo, tHi, bvec3((k & 1) != 0, (k & 2) != 0, (k & 4) != 0));
      corners[k] = (u.roiFromTexture * vec4(t, 1.0)).xyz;
    }
    if (ROI_OUTSIDE == 1) {
      // The shape is convex: with every corner inside, the whole box is.
      bool allInside = true;
      for (int k = 0; k < 8; ++k) allInside = allInside && insideRegion(corners[k]);
      return !allInside;
    }
    vec3 boundsLo = corners[0], boundsHi = corners[0];
    for (int k = 1; k < 8; ++k) {
      boundsLo = min(boundsLo, corners[k]);
      boundsHi = max(boundsHi, corners[k]);
    }
    if (ROI_SHAPE != 1 && (any(greaterThan(boundsLo, vec3(0.5))) ||
                           any(lessThan(boundsHi, vec3(-0.5)))))
      return false;
    if (ROI_SHAPE != 2) {
      vec3 centre = 0.5 * (corners[0] + corners[7]);
      float radius = 0.0;
      for (int k = 0; k < 8; ++k) radius = max(radius, distance(corners[k], centre));
      float reach = ROI_SHAPE == 1 ? length(centre) : length(centre.xy);
      if (reach > 0.5 + radius) return false;
    }
  }
  return true;
}

// Whether the voxel can be opaque: its speed computed as slice.frag computes a fragment's.
bool opaqueCapable(ivec3 voxel) {
  vec3 texel = texelFetch(fieldTexture, voxel, 0).xyz;
  if (PACKING == 1) texel *= length(texel);  // e |e| = u / max|u|
  float speed = length(texel * u.texelToPhysical.xyz) * u.texelToPhysical.w;
  if (isnan(speed)) return false;
  if (OPACITY_RULE == 1) return true;
  float o = clamp((speed - u.opacity.x) * u.opacity.y, 0.0, 1.0);
  return o >= u.opacity.z;
}

void main() {
  ivec3 brick = ivec3(gl_WorkGroupID);
  uint index = uint(brick.x + u.bricks.x * (brick.y + u.bricks.y * brick.z));
  ivec3 first = brick * int(kVisibleBrickSize);
  ivec3 last = min(first + int(kVisibleBrickSize), u.dims.xyz) - 1;
  int margin = u.dims.w;

  if (gl_LocalInvocationIndex == 0) {
    kept = keptBox(vec3(first - margin), vec3(last + margin));
    opaque = OPACITY_RULE == 0;
  }
  barrier();
  if (kept && OPACITY_RULE != 0) {
    ivec3 lo = max(first - margin, ivec3(0));
    ivec3 hi = min(last + margin, u.dims.xyz - 1);
    ivec3 size = hi - lo + 1;
    int count = size.x * size.y * size.z;
    bool found = false;
    for (int n = int(gl_LocalInvocationIndex); n < count && !found; n += int(kVisibleLocalSize)) {
      ivec3 voxel = lo + ivec3(n % size.x, (n / size.x) % size.y, n / (size.x * size.y));
      found = opaqueCapable(voxel);
    }
    if (found) opaque = true;  // every writer writes true
  }
  barrier();
  if (gl_LocalInvocationIndex != 0) return;
  bool shown = kept && opaque;
  visible[index] = shown ? 1u : 0u;
  if (shown && made[index] == 0u) {
    uint layer = uint(brick.z);
    uint slot = atomicAdd(dispatch[3u * layer], 1u);
    lists[layer * uint(u.bricks.x * u.bricks.y) + slot] = index;
  }
}
