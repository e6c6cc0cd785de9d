// SPDX-License-Identifier: BSD-3-Clause
#version 460
// Shades one slice fragment: region of interest, grey transfer of the LIC intensity, colour and
// opacity by magnitude, sparsity mask, lighting, opacity correction, fog, anaglyph. Each of these
// is a specialization constant: a variant compiles to exactly the code it uses.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(set = 0, binding = kSliceBindingVolume) uniform sampler3D licVolume;
layout(set = 0, binding = kSliceBindingField) uniform sampler3D fieldTexture;
layout(set = 0, binding = kSliceBindingColormap) uniform sampler2D colormaps;
layout(set = 0, binding = kSliceBindingUniforms, std140) uniform Uniforms { SliceUniforms u; };
layout(set = 0, binding = kSliceBindingScalars) uniform sampler3D scalars;

#ifdef LIC3D_RUNTIME_MODES
// Built only for `lic3d bench --variants`: the same shader deciding every mode at run time, the
// "if constructs" of thesis 6.1.1, to measure what specialization saves.
#define OPACITY_MODE u.modes[0].x
#define ORTHOGRAPHIC u.modes[0].y
#define COLOR_MODE u.modes[0].z
#define COLORMAP u.modes[0].w
#define MAGNITUDE_OPACITY u.modes[1].x
#define SPARSITY u.modes[1].y
#define ROI_SHAPE u.modes[1].z
#define ROI_OUTSIDE u.modes[1].w
#define FOG u.modes[2].x
#define LIGHTING u.modes[2].y
#define FILTER u.modes[2].z
#define ANAGLYPH u.modes[2].w
#define OPACITY_TABLE u.modes[3].x
#define CLIP_PLANE u.modes[3].y
#define COLOR_SOURCE u.modes[3].z
#define OPACITY_SOURCE u.modes[3].w
#else
layout(constant_id = kSliceConstOpacityMode) const uint OPACITY_MODE = kSliceDefaultOpacityMode;
layout(constant_id = kSliceConstOrthographic) const uint ORTHOGRAPHIC = kSliceDefaultOrthographic;
layout(constant_id = kSliceConstColorMode) const uint COLOR_MODE = kSliceDefaultColorMode;
layout(constant_id = kSliceConstColormap) const uint COLORMAP = kSliceDefaultColormap;
layout(constant_id = kSliceConstMagnitudeOpacity) const uint MAGNITUDE_OPACITY =
    kSliceDefaultMagnitudeOpacity;
layout(constant_id = kSliceConstSparsity) const uint SPARSITY = kSliceDefaultSparsity;
layout(constant_id = kSliceConstRoiShape) const uint ROI_SHAPE = kSliceDefaultRoiShape;
layout(constant_id = kSliceConstRoiOutside) const uint ROI_OUTSIDE = kSliceDefaultRoiOutside;
layout(constant_id = kSliceConstFog) const uint FOG = kSliceDefaultFog;
layout(constant_id = kSliceConstLighting) const uint LIGHTING = kSliceDefaultLighting;
layout(constant_id = kSliceConstFilter) const uint FILTER = kSliceDefaultFilter;
layout(constant_id = kSliceConstAnaglyph) const uint ANAGLYPH = kSliceDefaultAnaglyph;
// Opacity from the transfer function's table (the custom row's alpha) instead of t^E.
layout(constant_id = kSliceConstOpacityTable) const uint OPACITY_TABLE = kSliceDefaultOpacityTable;
layout(constant_id = kSliceConstClipPlane) const uint CLIP_PLANE = kSliceDefaultClipPlane;
// What colour and opacity follow: 0 the speed |v| from the field texture, 1 the scalar texture.
layout(constant_id = kSliceConstColorSource) const uint COLOR_SOURCE = kSliceDefaultColorSource;
layout(constant_id = kSliceConstOpacitySource) const uint OPACITY_SOURCE =
    kSliceDefaultOpacitySource;
#endif

// Not a display mode: how the field texture is packed (shared_layout.h, kLicConstPacking).
layout(constant_id = kSliceConstFieldPacking) const uint FIELD_PACKING = kSliceDefaultFieldPacking;

layout(location = 0) in vec3 texCoord;
layout(location = 1) in vec3 world;
layout(location = 0) out vec4 color;

// Thesis 6.4: nearest filtering keeps neighbouring streamlines apart, linear smooths them.
vec2 sampleLic(vec3 uvw) {
  if (FILTER == 0) {
    ivec3 size = textureSize(licVolume, 0);
    return texelFetch(licVolume, clamp(ivec3(floor(uvw * vec3(size))), ivec3(0), size - 1), 0).rg;
  }
  return texture(licVolume, uvw).rg;
}

// Thesis 5.2.2: sphere, cube or cylinder (axis z) of unit size in the region's own frame, which
// is rotated with the region, so its texture coordinates rotate with it.
bool insideRegion(vec3 p) {
  if (ROI_SHAPE == 1) return dot(p, p) <= 0.25;
  if (ROI_SHAPE == 2) return all(lessThanEqual(abs(p), vec3(0.5)));
  return dot(p.xy, p.xy) <= 0.25 && abs(p.z) <= 0.5;
}

// The streamline's unit tangent at a texture coordinate, in world space: the texels hold the
// field in voxel units, and one voxel is voxelSize world units long on each axis.
vec3 tangentAt(vec3 uvw) {
  vec3 v = texture(fieldTexture, uvw).xyz * u.voxelSize.xyz;
  float len = length(v);
  return len > 1e-12 ? v / len : vec3(0.0);
}

// Thesis 5.3.3: N is the principal normal of the streamline's TNB frame, the direction in which
// the tangent turns (central difference one voxel along the streamline either way).
vec3 principalNormal(vec3 tangent, vec3 toEye) {
  vec3 step = normalize(tangent / u.voxelSize.xyz) / vec3(textureSize(fieldTexture, 0));
  vec3 turn = tangentAt(texCoord + step) - tangentAt(texCoord - step);
  vec3 normal = turn - dot(turn, tangent) * tangent;
  // A straight streamline has no principal normal: any normal will do, so take the one facing
  // the viewer most.
  if (dot(normal, normal) < 1e-10) normal = cross(tangent, cross(toEye, tangent));
  float len = length(normal);
  return len > 1e-12 ? normal / len : toEye;
}

vec3 applyLighting(vec3 base, vec3 toEye) {
  vec3 tangent = tangentAt(texCoord);
  if (tangent == vec3(0.0)) return base;
  vec3 toLight = u.light.xyz;
  float ambient = u.lightTerms.x, diffuse = u.lightTerms.y, specular = u.lightTerms.z;
  if (LIGHTING == 1) {
    // Cl = Ca + Cd |N.L| + Cs max(R.E, 0)^k, the LIC colour modulating the diffuse part.
    vec3 normal = principalNormal(tangent, toEye);
    float nl = dot(normal, toLight);
    vec3 reflected = reflect(-toLight, nl < 0.0 ? -normal : normal);
    float highlight = pow(max(dot(reflected, toEye), 0.0), u.light.w);
    return base * (ambient + diffuse * abs(nl)) + vec3(specular * highlight);
  }
  // Illuminated lines (Zockler, Stalling, Hege 1996): the light depends on the tangent alone.
  float lt = dot(toLight, tangent);
  float vt = dot(toEye, tangent);
  float sinL = sqrt(max(1.0 - lt * lt, 0.0));
  float sinV = sqrt(max(1.0 - vt * vt, 0.0));
  float highlight = pow(max(sinL * sinV - lt * vt, 0.0), u.light.w);
  return base * (ambient + diffuse * sinL) + vec3(specular * highlight);
}

// The colour table at t in [0,1]: texel centres at i / 255 of the range, so that t = 0 and 1
// are the first and the last entry and the legend (core/colormap.h) matches.
vec4 tableAt(float t, uint row) {
  float v = (float(row) + 0.5) / float(textureSize(colormaps, 0).y);
  return texture(colormaps, vec2((t * 255.0 + 0.5) / 256.0, v));
}

void main() {
  if (CLIP_PLANE == 1 && dot(u.clipPlane.xyz, world) > u.clipPlane.w) discard;
  if (ROI_SHAPE != 0) {
    vec3 p = (u.roiFromTexture * vec4(texCoord, 1.0)).xyz;
    if (insideRegion(p) == (ROI_OUTSIDE == 1)) discard;
  }

  vec2 lic = sampleLic(texCoord);
  float grey = clamp(u.transfer.x * lic.r + u.transfer.y, 0.0, 1.0);
  float alpha = OPACITY_MODE == 1 ? u.halfExtent.w * grey : u.halfExtent.w;
  if (SPARSITY == 1) alpha *= lic.g;

  vec3 rgb = vec3(grey);
  if (COLOR_MODE == 1 || MAGNITUDE_OPACITY == 1 || OPACITY_TABLE == 1) {
    float speed = 0.0;
    if (COLOR_SOURCE == 0 || OPACITY_SOURCE == 0) {
      // Physical |v|, as the colour range is: texels are in voxel units, scaled per axis.
      vec3 texel = texture(fieldTexture, texCoord).xyz;
      if (FIELD_PACKING == 1) texel *= length(texel);  // e |e| = u / max|u|
      speed = length(texel * u.texelToPhysical.xyz) * u.texelToPhysical.w;
    }
    vec2 scalar = vec2(0.0);
    if (COLOR_SOURCE == 1 || OPACITY_SOURCE == 1)
      scalar = u.scalarRange.xz + texture(scalars, texCoord).rg * u.scalarRange.yw;
    float colorValue = COLOR_SOURCE == 1 ? scalar.r : speed;
    float opacityValue = OPACITY_SOURCE == 1 ? scalar.g : speed;
    if (COLOR_MODE == 1) {
      // The LIC intensity modulates the colour (thesis 5.1.2).
      float t = clamp((colorValue - u.magnitude.x) * u.magnitude.y, 0.0, 1.0);
      rgb = tableAt(t, COLORMAP).rgb * grey;
    }
    float o = clamp((opacityValue - u.magnitudeOpacity.z) * u.magnitudeOpacity.w, 0.0, 1.0);
    // Thesis 5.1.3: slow regions fade; below the threshold they vanish.
    if (OPACITY_TABLE == 1) {
      alpha *= tableAt(o, kSliceCustomColormapRow).a;
    } else if (MAGNITUDE_OPACITY == 1) {
      alpha *= o < u.magnitudeOpacity.y ? 0.0 : pow(o, u.magnitudeOpacity.x);
    }
    // A scalar with no value there (NaN in the file) is empty space.
    if (isnan(colorValue) || isnan(opacityValue)) alpha = 0.0;
  }

  vec3 toEye = ORTHOGRAPHIC == 1 ? u.toViewer.xyz : normalize(u.eyePosition.xyz - world);
  if (LIGHTING != 0) rgb = applyLighting(rgb, toEye);

  // alpha is given per reference distance (one voxel); the slice spacing along this ray is the
  // plane spacing over |cos| of the angle between ray and plane normal.
  float spacing = u.eyePosition.w / max(abs(dot(toEye, u.planeNormal.xyz)), 1e-3);
  alpha = clamp(alpha, 0.0, 1.0);
  alpha = 1.0 - pow(1.0 - alpha, spacing / u.transfer.z);

  if (FOG == 1) {
    // Thesis 5.3.1: linear intensity depth cueing towards the fog colour.
    float depth = ORTHOGRAPHIC == 1 ? dot(u.eyePosition.xyz - world, u.toViewer.xyz)
                                    : distance(u.eyePosition.xyz, world);
    float f = clamp(1.0 - (depth - u.fog.x) * u.fog.y, 0.0, 1.0);
    rgb = mix(u.fogColor.rgb, rgb, f);
  }
  // Anaglyph eyes see grey levels: red for the left eye, green and blue for the right.
  if (ANAGLYPH != 0) rgb = vec3(dot(rgb, vec3(0.299, 0.587, 0.114)));

  color = vec4(clamp(rgb, 0.0, 1.0) * alpha, alpha);
}
