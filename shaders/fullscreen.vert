// SPDX-License-Identifier: BSD-3-Clause
#version 460
// One triangle that covers the viewport: the composite of the occlusion-shaded image
// (passes/occlusion_pass.h).

void main() {
  vec2 corner = vec2((gl_VertexIndex << 1) & 2, gl_VertexIndex & 2);
  gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
