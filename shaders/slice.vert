// SPDX-License-Identifier: BSD-3-Clause
#version 460
// Proxy geometry for slice-based volume rendering: instance k is the k-th plane (back to front)
// cut with the clip box (the volume's box unless clip planes shrink it), a convex polygon of 3 to
// 6 corners emitted as a fan of 4 triangles. Clipping here, rather than discarding fragments,
// means clipped space costs nothing to draw.
//
// With K slices per fragment (SLICES_PER_FRAGMENT > 1), instance k is the group of slices kK to
// kK + K - 1: the convex hull of their polygons as the eye sees them, laid in the plane of the
// group's farthest slice, covers every pixel any of them covers; slice.frag finds each slice's
// point along the pixel's ray and tests it against the clip box.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(set = 0, binding = kSliceBindingUniforms, std140) uniform Uniforms { SliceUniforms u; };

layout(location = 0) out vec3 outTexCoord;
layout(location = 1) out vec3 outWorld;
layout(location = 2) flat out uint outSlice;  // the slice's index, 0 the farthest (K > 1: the
                                              // group's first)

layout(constant_id = kSliceConstSlicesPerFragment) const uint SLICES_PER_FRAGMENT =
    kSliceDefaultSlicesPerFragment;

// The 12 box edges as pairs of corner indices; corner bit 0/1/2 selects max x/y/z.
const ivec2 kEdges[12] = ivec2[12](ivec2(0, 1), ivec2(2, 3), ivec2(4, 5), ivec2(6, 7),
                                   ivec2(0, 2), ivec2(1, 3), ivec2(4, 6), ivec2(5, 7),
                                   ivec2(0, 4), ivec2(1, 5), ivec2(2, 6), ivec2(3, 7));

vec3 corner(int c) {
  return mix(u.clipMin.xyz, u.clipMax.xyz, vec3(c & 1, (c >> 1) & 1, (c >> 2) & 1));
}

// The corners of slice planes cut with the clip box, each plane's deduplicated.
const int kMaxPoints = 24;  // 4 slices of up to 6 corners
vec3 points[kMaxPoints];
int pointCount = 0;

void addCut(vec3 n, float offset) {
  int first = pointCount;
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
    for (int i = first; i < pointCount; ++i)
      duplicate = duplicate || distance(points[i], p) <= tolerance;
    if (!duplicate && pointCount - first < 6) points[pointCount++] = p;
  }
}

// One slice's polygon: its corners ordered by angle around their centre, a fan of 4 triangles.
vec3 slicePolygonVertex(vec3 n) {
  addCut(n, u.planeNormal.w + float(gl_InstanceIndex) * u.eyePosition.w);
  int count = pointCount;

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
  return count >= 3 ? points[min(index, count - 1)] : vec3(0.0);
}

// A group's proxy: the corners of its slices moved along their rays (from the eye, or along the
// view direction when orthographic) into the plane of the group's first slice, and the convex
// hull of those (gift wrapping), a fan of up to kSliceGroupCorners corners. Seen from the eye, a
// corner moved along its ray stays where it was on the screen, so the hull covers every slice.
vec3 groupPolygonVertex(vec3 n, uint first) {
  float offset = u.planeNormal.w + float(first) * u.eyePosition.w;
  uint count = uint(u.toViewer.w);
  for (uint j = 0u; j < SLICES_PER_FRAGMENT && first + j < count; ++j)
    addCut(n, offset + float(j) * u.eyePosition.w);
  // An orthographic projection leaves w at 1 whatever the point.
  bool orthographic = u.viewProjection[0][3] == 0.0 && u.viewProjection[1][3] == 0.0 &&
                      u.viewProjection[2][3] == 0.0;
  vec3 eye = u.eyePosition.xyz;
  vec3 axisU = normalize(cross(n, abs(n.x) < 0.9 ? vec3(1.0, 0.0, 0.0) : vec3(0.0, 1.0, 0.0)));
  vec3 axisV = cross(n, axisU);
  vec2 flat2[kMaxPoints];
  int leftmost = 0;
  for (int i = 0; i < pointCount; ++i) {
    vec3 p = points[i];
    vec3 ray = orthographic ? u.toViewer.xyz : p - eye;
    p += ray * (offset - dot(n, p)) / dot(n, ray);
    points[i] = p;
    flat2[i] = vec2(dot(p, axisU), dot(p, axisV));
    if (flat2[i].x < flat2[leftmost].x ||
        (flat2[i].x == flat2[leftmost].x && flat2[i].y < flat2[leftmost].y))
      leftmost = i;
  }
  float tolerance = 1e-6 * length(u.halfExtent.xyz);
  int hull[kSliceGroupCorners];
  int corners = 0;
  int current = leftmost;
  while (pointCount >= 3 && corners < int(kSliceGroupCorners)) {
    hull[corners++] = current;
    // The next corner: the point with every other point on one side (the farthest if in line).
    int next = -1;
    for (int i = 0; i < pointCount; ++i) {
      vec2 d = flat2[i] - flat2[current];
      if (dot(d, d) <= tolerance * tolerance) continue;
      if (next < 0) {
        next = i;
        continue;
      }
      vec2 dn = flat2[next] - flat2[current];
      float turn = dn.x * d.y - dn.y * d.x;
      if (turn < 0.0 || (turn == 0.0 && dot(d, d) > dot(dn, dn))) next = i;
    }
    if (next < 0 || next == leftmost) break;
    current = next;
  }
  int triangle = gl_VertexIndex / 3;
  int k = gl_VertexIndex % 3;
  int index = k == 0 ? 0 : triangle + k;
  return corners >= 3 ? points[hull[min(index, corners - 1)]] : vec3(0.0);
}

void main() {
  vec3 n = u.planeNormal.xyz;
  uint first = uint(gl_InstanceIndex) * SLICES_PER_FRAGMENT;
  vec3 world = SLICES_PER_FRAGMENT == 1u ? slicePolygonVertex(n) : groupPolygonVertex(n, first);
  outWorld = world;
  outSlice = first;
  outTexCoord = world / (2.0 * u.halfExtent.xyz) + 0.5;
  gl_Position = u.viewProjection * vec4(world, 1.0);
}
