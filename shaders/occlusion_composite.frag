// SPDX-License-Identifier: BSD-3-Clause
#version 460
// The occlusion-shaded image (premultiplied, drawn front to back) over the frame.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(set = 0, binding = kOcclusionBindingImage) uniform sampler2D image;
layout(push_constant) uniform Push { OcclusionPushConstants push; };

layout(location = 0) out vec4 color;

void main() { color = texelFetch(image, ivec2(gl_FragCoord.xy) - push.offset.xy, 0); }
