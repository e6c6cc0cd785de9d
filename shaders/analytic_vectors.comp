// SPDX-License-Identifier: BSD-3-Clause
#version 460
// The analytic fields evaluated on the device, one slab of z layers per dispatch, into a buffer
// the host reads (shared_layout.h).
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"
#include "analytic_fields.glsl"

layout(local_size_x = kAnalyticLocalSizeX, local_size_y = kAnalyticLocalSizeY) in;

layout(set = 0, binding = kAnalyticBindingVectors, std430) writeonly buffer Vectors {
  float vectors[];
};
layout(push_constant) uniform Push { AnalyticPushConstants pc; };

void main() {
  ivec3 id = ivec3(gl_GlobalInvocationID.xy, gl_WorkGroupID.z);
  if (id.x >= pc.dims.x || id.y >= pc.dims.y || id.z >= pc.dims.z) return;
  vec3 p = pc.origin.xyz + vec3(id.x, id.y, id.z + pc.dims.w) * pc.spacing.xyz;
  vec3 v = evaluate(p, pc.origin.w);
  uint i = 3u * (uint(id.x) + uint(pc.dims.x) * (uint(id.y) + uint(pc.dims.y) * uint(id.z)));
  vectors[i] = v.x;
  vectors[i + 1u] = v.y;
  vectors[i + 2u] = v.z;
}
