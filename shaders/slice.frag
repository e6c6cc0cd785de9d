#version 460
// Shades one slice fragment: LIC intensity through the grey transfer, opacity corrected for the
// distance between slices along this fragment's ray, premultiplied for back-to-front "over".
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(constant_id = 0) const uint OPACITY_MODE = 1;  // 0 constant alpha, 1 alpha * grey
layout(constant_id = 1) const uint ORTHOGRAPHIC = 0;

layout(set = 0, binding = kSliceBindingVolume) uniform sampler3D licVolume;
layout(push_constant) uniform Push { SlicePushConstants pc; };

layout(location = 0) in vec3 texCoord;
layout(location = 1) in vec3 world;
layout(location = 0) out vec4 color;

void main() {
  float intensity = texture(licVolume, texCoord).r;
  float grey = clamp(pc.transfer.x * intensity + pc.transfer.y, 0.0, 1.0);

  // alpha is given per reference distance (one voxel); the slice spacing along this ray is the
  // plane spacing over |cos| of the angle between ray and plane normal.
  vec3 toViewer = ORTHOGRAPHIC == 1 ? pc.eye.xyz : normalize(pc.eye.xyz - world);
  float spacing = pc.eye.w / max(abs(dot(toViewer, pc.planeNormal.xyz)), 1e-3);
  float alpha = clamp(OPACITY_MODE == 1 ? pc.halfExtent.w * grey : pc.halfExtent.w, 0.0, 1.0);
  alpha = 1.0 - pow(1.0 - alpha, spacing / pc.transfer.z);

  color = vec4(vec3(grey) * alpha, alpha);
}
