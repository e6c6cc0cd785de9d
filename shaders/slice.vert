// SPDX-License-Identifier: BSD-3-Clause
#version 460
// Proxy geometry for slice-based volume rendering: instance k is the k-th plane (back to front)
// cut with the clip box (the volume's box unless clip planes shrink it), a convex polygon of 3 to
// 6 corners emitted as a fan of 4 triangles. Clipping here, rather than discarding fragments,
// means clipped space costs nothing to draw.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(set = 0, binding = kSliceBindingUniforms, std140) uniform Uniforms { SliceUniforms u; };

layout(location = 0) out vec3 outTexCoord;
layout(location = 1) out vec3 outWorld;
layout(location = 2) flat out uint outSlice;  // the slice's index, 0 the farthest

// The 12 box edges as pairs of corner indices; corner bit 0/1/2 selects max x/y/z.
const ivec2 kEdges[12] = ivec2[12](ivec2(0, 1), ivec2(2, 3), ivec2(4, 5), ivec2(6, 7),
                                   ivec2(0, 2), ivec2(1, 3), ivec2(4, 6), ivec2(5, 7),
                                   ivec2(0, 4), ivec2(1, 5), ivec2(2, 6), ivec2(3, 7));

vec3 corner(int c) {
  return mix(u.clipMin.xyz, u.clipMax.xyz, vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
}

void main() {
  vec3 n = u.planeNormal.xyz;
  float offset = u.planeNormal.w + float(gl_InstanceIndex) * u.eyePosition.w;

  vec3 points[6];
  int count = 0;
  float tolerance = 1e-6 * length(u.halfExtent.xyz);
  for (int e = 0; e < 12; ++e) {
    vec3 a = corner(kEdges[e].x);
    vec3 b = corner(kEdges[e].y);
    float da = dot(n, a) - offset;
    float db = dot(n, b) - offset;
    if ((da <= 0.0) == (db <= 0.0)) continue;
    vec3 p = mix(a, b, da / (da - db));
    // A plane through a box corner meets several edges there: keep the corner once.
    bool duplicate = false;
    for (int i = 0; i < count; ++i) duplicate = duplicate || distance(points[i], p) <= tolerance;
    if (!duplicate && count < 6) points[count++] = p;
  }

  // Order the corners by angle around their centre so the fan is convex.
  vec3 center = vec3(0.0);
  for (int i = 0; i < count; ++i) center += points[i];
  center /= float(max(count, 1));
  vec3 axisU = normalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
  vec3 axisV = cross(n, axisU);
  float angles[6];
  for (int i = 0; i < count; ++i) {
    vec3 r = points[i] - center;
    angles[i] = atan(dot(r, axisV), dot(r, axisU));
  }
  for (int i = 1; i < count; ++i) {
    for (int j = i; j > 0 && angles[j - 1] > angles[j]; --j) {
      float ta = angles[j]; angles[j] = angles[j - 1]; angles[j - 1] = ta;
      vec3 tp = points[j]; points[j] = points[j - 1]; points[j - 1] = tp;
    }
  }

  // Fan triangle t uses corners (0, t+1, t+2); missing corners collapse onto the last one, and a
  // plane that misses the box gives zero-area triangles.
  int triangle = gl_VertexIndex / 3;
  int k = gl_VertexIndex % 3;
  int index = k == 0 ? 0 : triangle + k;
  vec3 world = count >= 3 ? points[min(index, count - 1)] : vec3(0.0);

  outWorld = world;
  outSlice = uint(gl_InstanceIndex);
  outTexCoord = world / (2.0 * u.halfExtent.xyz) + 0.5;
  gl_Position = u.viewProjection * vec4(world, 1.0);
}
