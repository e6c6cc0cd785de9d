// SPDX-License-Identifier: BSD-3-Clause
#version 460
#extension GL_EXT_control_flow_attributes : require
// Shades one slice fragment: region of interest, grey transfer of the LIC intensity, colour and
// opacity by magnitude, sparsity mask, lighting, halos, occlusion, opacity correction, fog,
// anaglyph. Each of these is a specialization constant: a variant compiles to exactly the code it
// uses.
//
// With K slices per fragment (SLICES_PER_FRAGMENT > 1) the fragment stands for a group of K slices
// (slice.vert): it shades each slice's sample on its ray and composites them before one blend.
#extension GL_GOOGLE_include_directive : require
#include "shared_layout.h"

layout(set = 0, binding = kSliceBindingVolume) uniform sampler3D licVolume;
layout(set = 0, binding = kSliceBindingField) uniform sampler3D fieldTexture;
layout(set = 0, binding = kSliceBindingColormap) uniform sampler2D colormaps;
layout(set = 0, binding = kSliceBindingUniforms, std140) uniform Uniforms { SliceUniforms u; };
layout(set = 0, binding = kSliceBindingScalars) uniform sampler3D scalars;
layout(set = 0, binding = kSliceBindingOcclusion) uniform sampler2D occlusionBuffer;

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
#define HALO u.modes[4].x
#define OCCLUSION u.modes[4].y
#define JITTER u.modes[4].z
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
// Visibility-impeding halos (Interrante and Grosch 1997): around a streak, the slice takes the
// streak's opacity in the background colour, so a near streak cuts the far ones it crosses.
layout(constant_id = kSliceConstHalo) const uint HALO = kSliceDefaultHalo;
// Directional occlusion (Schott et al. 2009): slices drawn front to back, each shaded by the
// opacity in front of it, blurred over a cone towards the viewer, and adding its own.
layout(constant_id = kSliceConstOcclusion) const uint OCCLUSION = kSliceDefaultOcclusion;
// Each pixel's samples moved along its ray by a fraction of the slice spacing that varies from
// pixel to pixel: the slices' wood-grain pattern turns into fine noise.
layout(constant_id = kSliceConstJitter) const uint JITTER = kSliceDefaultJitter;
#endif

// Not a display mode: how the field texture is packed (shared_layout.h, kLicConstPacking).
layout(constant_id = kSliceConstFieldPacking) const uint FIELD_PACKING = kSliceDefaultFieldPacking;
// Not a display mode either: how many slices one fragment composites (slice.vert). The picture is
// the same whatever it is, but for the rounding of the blend.
layout(constant_id = kSliceConstSlicesPerFragment) const uint SLICES_PER_FRAGMENT =
    kSliceDefaultSlicesPerFragment;

layout(location = 0) in vec3 slicePoint;  // texture coordinates on the slice
layout(location = 1) in vec3 sliceWorld;
layout(location = 2) flat in uint sliceIndex;
layout(location = 0) out vec4 color;
// The opacity this fragment adds to the occlusion buffer (OCCLUSION only; without, the frame has
// no second attachment and the output is dropped).
layout(location = 1) out float occlusionOut;

// Where this fragment samples: the slice point, moved along the ray when jittered.
vec3 texCoord;
vec3 world;

// Thesis 6.4: nearest filtering keeps neighbouring streamlines apart, linear smooths them. Cubic:
// the cubic B-spline from 8 linear fetches (Sigg and Hadwiger 2005), smooth across voxel faces
// where linear filtering shows the voxels as facets when a voxel covers several pixels. `coarse`
// samples (halo rings, gradients) take linear filtering instead of cubic: they are not seen.
vec2 sampleLic(vec3 uvw, bool coarse) {
  if (FILTER == 0) {
    ivec3 size = textureSize(licVolume, 0);
    return texelFetch(licVolume, clamp(ivec3(floor(uvw * vec3(size))), ivec3(0), size - 1), 0).rg;
  }
  if (FILTER == 1 || coarse) return texture(licVolume, uvw).rg;
  vec3 size = vec3(textureSize(licVolume, 0));
  vec3 coord = uvw * size - 0.5;
  vec3 index = floor(coord);
  vec3 f = coord - index;
  vec3 one = 1.0 - f;
  vec3 w0 = one * one * one / 6.0;
  vec3 w1 = (4.0 - 6.0 * f * f + 3.0 * f * f * f) / 6.0;
  vec3 w2 = (4.0 - 6.0 * one * one + 3.0 * one * one * one) / 6.0;
  vec3 w3 = f * f * f / 6.0;
  vec3 g0 = w0 + w1;
  vec3 g1 = w2 + w3;
  vec3 h0 = (index - 0.5 + w1 / g0) / size;  // texel centres are at i + 0.5
  vec3 h1 = (index + 1.5 + w3 / g1) / size;
  vec2 result = vec2(0.0);
  for (int k = 0; k < 8; ++k) {
    bvec3 upper = bvec3((k & 1) != 0, (k & 2) != 0, (k & 4) != 0);
    vec3 at = mix(h0, h1, upper);
    vec3 weight = mix(g0, g1, upper);
    result += weight.x * weight.y * weight.z * texture(licVolume, at).rg;
  }
  return result;
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
  if (LIGHTING == 3) {
    // The streak as a tube: its normal is the LIC intensity's gradient across the flow (the
    // intensity falls away from a streak's core), lit from both sides.
    vec3 h = 1.0 / vec3(textureSize(licVolume, 0));
    float here = sampleLic(texCoord, true).r;
    vec3 gradient = (vec3(sampleLic(texCoord + vec3(h.x, 0, 0), true).r,
                          sampleLic(texCoord + vec3(0, h.y, 0), true).r,
                          sampleLic(texCoord + vec3(0, 0, h.z), true).r) -
                     here) /
                    u.voxelSize.xyz;
    vec3 across = gradient - dot(gradient, tangent) * tangent;
    float len = length(across);
    // Where the intensity is flat across the flow there is no surface: light it as facing the
    // viewer.
    vec3 normal = len > 1e-6 ? -across / len : toEye;
    if (dot(normal, toEye) < 0.0) normal = -normal;
    float nl = abs(dot(normal, toLight));
    vec3 reflected = reflect(-toLight, dot(normal, toLight) < 0.0 ? -normal : normal);
    float highlight = pow(max(dot(reflected, toEye), 0.0), u.light.w);
    return base * (ambient + diffuse * nl) + vec3(specular * highlight);
  }
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

// A fraction in [0, 1) per pixel from a hash of its coordinates (PCG, Jarzynski and Olano 2020):
// white noise, with no pattern of its own for the eye to follow.
float pixelJitter() {
  uvec2 p = uvec2(gl_FragCoord.xy);
  uint v = p.x * 1664525u + p.y * 22695477u + 1013904223u;
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return float((word >> 22u) ^ word) * (1.0 / 4294967296.0);
}

// A sample's grey and opacity before the slice spacing is accounted for: alpha is per reference
// distance (one voxel). `weight` is the part of alpha that follows speed or a scalar (1 without):
// it varies slowly, the LIC part from streak to streak.
struct Sample {
  vec3 rgb;
  float alpha;
  float weight;
};

// Whether the opacity follows the LIC volume (its grey or its sparsity mask): then streaks have
// halos of their own.
bool streakOpacity() { return OPACITY_MODE == 1 || SPARSITY == 1; }

float greyOf(vec2 lic) { return clamp(u.transfer.x * lic.r + u.transfer.y, 0.0, 1.0); }

// The LIC part of a sample's opacity.
float licOpacity(vec2 lic) {
  float alpha = OPACITY_MODE == 1 ? u.halfExtent.w * greyOf(lic) : u.halfExtent.w;
  if (SPARSITY == 1) alpha *= lic.g;
  return alpha;
}

Sample shadeAt(vec3 uvw, bool coarse) {
  vec2 lic = sampleLic(uvw, coarse);
  float grey = greyOf(lic);
  float alpha = licOpacity(lic);
  float weight = 1.0;

  vec3 rgb = vec3(grey);
  if (COLOR_MODE == 1 || MAGNITUDE_OPACITY == 1 || OPACITY_TABLE == 1) {
    float speed = 0.0;
    if (COLOR_SOURCE == 0 || OPACITY_SOURCE == 0) {
      // Physical |v|, as the colour range is: texels are in voxel units, scaled per axis.
      vec3 texel = texture(fieldTexture, uvw).xyz;
      if (FIELD_PACKING == 1) texel *= length(texel);  // e |e| = u / max|u|
      speed = length(texel * u.texelToPhysical.xyz) * u.texelToPhysical.w;
    }
    vec2 scalar = vec2(0.0);
    if (COLOR_SOURCE == 1 || OPACITY_SOURCE == 1)
      scalar = u.scalarRange.xz + texture(scalars, uvw).rg * u.scalarRange.yw;
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
      weight = tableAt(o, kSliceCustomColormapRow).a;
    } else if (MAGNITUDE_OPACITY == 1) {
      weight = o < u.magnitudeOpacity.y ? 0.0 : max(pow(o, u.magnitudeOpacity.x), u.magnitude.z);
    }
    // A scalar with no value there (NaN in the file) is empty space.
    if (isnan(colorValue) || isnan(opacityValue)) weight = 0.0;
  }
  return Sample(rgb, alpha * weight, weight);
}

// The strongest opacity on a ring around `p` in the screen plane, the halo's radius out: what a
// streak passing near this point would cover. Four taps, the ring turned from pixel to pixel by
// `turn` in [0, 1) so that neighbouring pixels cover the angles between. Where the opacity follows
// the LIC, a tap reads the LIC volume alone and takes the centre's `weight`: speed and scalars
// change little over the halo's radius of a voxel or two, and their fetches and transfer were
// two thirds of the halo's cost on a CPU driver.
float ringOpacity(vec3 p, float turn, float weight) {
  float strongest = 0.0;
  for (int k = 0; k < 4; ++k) {
    float angle = 1.57079633 * (float(k) + turn);
    vec3 q = p + u.screenRight.w * (cos(angle) * u.screenRight.xyz + sin(angle) * u.screenUp.xyz);
    vec3 at = q / (2.0 * u.halfExtent.xyz) + 0.5;
    float alpha = streakOpacity() ? licOpacity(sampleLic(at, true)) : shadeAt(at, true).alpha;
    strongest = max(strongest, alpha);
  }
  return streakOpacity() ? strongest * weight : strongest;
}

// The occlusion buffer of the slice in front, blurred over the cone's footprint (one slice's
// spread): a ring of taps and the centre.
float occlusionInFront() {
  vec2 at = gl_FragCoord.xy * u.occlusion.zw;
  float sum = texture(occlusionBuffer, at).r;
  for (int k = 0; k < kOcclusionTaps; ++k) {
    float angle = 6.28318531 * float(k) / float(kOcclusionTaps);
    sum += texture(occlusionBuffer, at + u.occlusion.y * vec2(cos(angle), sin(angle)) *
                                             u.occlusion.zw).r;
  }
  return sum / float(kOcclusionTaps + 1);
}

// How much of the ray this slice's sample stands for: the slice spacing, except at the ends of
// the ray's way through the kept box (clip box and clip plane), where the first and the last
// slice reach to the boundary. Without this, the number of slices a pixel meets steps across
// the picture where slices leave the box, and the steps show as bands when zoomed.
float segmentLength(vec3 point, vec3 forward, float spacing) {
  vec3 inverse = 1.0 / (abs(forward) + 1e-12) * sign(forward + 1e-20);
  vec3 t1 = (u.clipMin.xyz - point) * inverse;
  vec3 t2 = (u.clipMax.xyz - point) * inverse;
  vec3 low = min(t1, t2);
  vec3 high = max(t1, t2);
  float entry = max(max(low.x, low.y), low.z);
  float exit = min(min(high.x, high.y), high.z);
  if (CLIP_PLANE == 1) {
    float towards = dot(u.clipPlane.xyz, forward);
    float at = (u.clipPlane.w - dot(u.clipPlane.xyz, point)) / (abs(towards) > 1e-12 ? towards : 1e-12);
    if (towards > 0.0) exit = min(exit, at);
    if (towards < 0.0) entry = max(entry, at);
  }
  // The slice before (after) is drawn only if its point lies inside.
  float back = -entry < spacing ? max(-entry, 0.0) : 0.5 * spacing;
  float ahead = exit < spacing ? max(exit, 0.0) : 0.5 * spacing;
  return back + ahead;
}

// One slice's sample: slice `index`, its point `point` in world units and `pointTexture` in texture
// coordinates, `haloSlice` whether it draws the halo. Premultiplied colour and opacity; `removed`
// where the clip plane or the region of interest takes the point away (nothing drawn), and with
// occlusion the buffer the next slice reads in `occlusionAfter`.
vec4 shadeSlice(vec3 point, vec3 pointTexture, bool haloSlice, out bool removed,
                out float occlusionAfter) {
  texCoord = pointTexture;
  world = point;
  vec3 toEye = ORTHOGRAPHIC == 1 ? u.toViewer.xyz : normalize(u.eyePosition.xyz - world);
  // The slice spacing along this ray: the plane spacing over |cos| of the angle between ray and
  // plane normal.
  float spacing = u.eyePosition.w / max(abs(dot(toEye, u.planeNormal.xyz)), 1e-3);
  float jitter = JITTER == 1 || HALO == 1 ? pixelJitter() : 0.5;
  if (JITTER == 1) {
    world -= toEye * (jitter - 0.5) * spacing;
    texCoord = world / (2.0 * u.halfExtent.xyz) + 0.5;
  }

  // With occlusion, a removed fragment still carries the buffer to the next slice.
  removed = CLIP_PLANE == 1 && dot(u.clipPlane.xyz, point) > u.clipPlane.w;
  if (ROI_SHAPE != 0) {
    vec3 p = (u.roiFromTexture * vec4(texCoord, 1.0)).xyz;
    removed = removed || insideRegion(p) == (ROI_OUTSIDE == 1);
  }
  occlusionAfter = 0.0;
  if (removed && OCCLUSION == 0) return vec4(0.0);

  float inFront = OCCLUSION == 1 ? occlusionInFront() : 0.0;
  Sample s = shadeAt(texCoord, false);
  vec3 rgb = s.rgb;
  float alpha = removed ? 0.0 : s.alpha;
  if (LIGHTING != 0) rgb = applyLighting(rgb, toEye);
  if (OCCLUSION == 1) rgb *= 1.0 - u.occlusion.x * inFront;

  // Halo: where a neighbouring streak is more opaque than this point, the point takes up to its
  // opacity in the background colour. Every other slice draws it, over twice its spacing: a halo
  // reaches across a voxel or two, the slices are a voxel apart, and the ring is most of a
  // fragment's cost on a CPU driver.
  haloSlice = HALO == 1 && !removed && haloSlice;
  float haloAlpha = 0.0;
  if (haloSlice) {
    float ring = ringOpacity(world, jitter, s.weight);
    haloAlpha = clamp(u.screenUp.w * (ring - alpha), 0.0, 1.0 - alpha);
  }

  // Opacity per slice spacing from opacity per reference distance; the halo's share of the
  // light kept, (1 - alpha - halo) / (1 - alpha), over two spacings.
  float exponent = segmentLength(point, -toEye, spacing) / u.transfer.z;
  alpha = clamp(alpha, 0.0, 1.0);
  float kept = pow(1.0 - alpha, exponent);
  float total = 1.0 - kept;
  if (haloSlice) {
    float haloKept = clamp(1.0 - haloAlpha / max(1.0 - alpha, 1e-6), 0.0, 1.0);
    total = 1.0 - kept * pow(haloKept, 2.0 * exponent);
  }
  alpha = 1.0 - kept;
  haloAlpha = total - alpha;

  if (FOG == 1) {
    // Thesis 5.3.1: linear intensity depth cueing towards the fog colour.
    float depth = ORTHOGRAPHIC == 1 ? dot(u.eyePosition.xyz - world, u.toViewer.xyz)
                                    : distance(u.eyePosition.xyz, world);
    float f = clamp(1.0 - (depth - u.fog.x) * u.fog.y, 0.0, 1.0);
    rgb = mix(u.fogColor.rgb, rgb, f);
  }
  // Anaglyph eyes see grey levels: red for the left eye, green and blue for the right.
  if (ANAGLYPH != 0) rgb = vec3(dot(rgb, vec3(0.299, 0.587, 0.114)));

  // The buffer the next slice reads: what lies in front of it, this slice included.
  if (OCCLUSION == 1) occlusionAfter = inFront + (1.0 - inFront) * total;
  return vec4(clamp(rgb, 0.0, 1.0) * alpha + u.haloColor.rgb * haloAlpha, total);
}

// Whether a point lies in the clip box: where the slice's polygon (slice.vert) reaches.
bool insideClipBox(vec3 p) {
  vec3 tolerance = vec3(1e-6 * length(u.halfExtent.xyz));
  return all(greaterThanEqual(p, u.clipMin.xyz - tolerance)) &&
         all(lessThanEqual(p, u.clipMax.xyz + tolerance));
}

void main() {
  if (SLICES_PER_FRAGMENT == 1u) {
    bool removed;
    float occlusionAfter;
    color = shadeSlice(sliceWorld, slicePoint, (sliceIndex & 1u) == 0u, removed, occlusionAfter);
    if (removed && OCCLUSION == 0) discard;
    if (OCCLUSION == 1) occlusionOut = occlusionAfter;
    return;
  }
  // K slices, the group's first (the farthest) where the proxy lies: each slice's point where the
  // pixel's ray meets its plane, composited back to front ("over") as the blend would, then
  // blended once. The group's first slice has an even index when K is even, so which slices draw
  // the halo is known as the loop unrolls.
  vec3 n = u.planeNormal.xyz;
  vec3 ray = ORTHOGRAPHIC == 1 ? u.toViewer.xyz : sliceWorld - u.eyePosition.xyz;
  float firstOffset = u.planeNormal.w + float(sliceIndex) * u.eyePosition.w;
  uint count = uint(u.toViewer.w);
  vec4 sum = vec4(0.0);
  bool drawn = false;
  [[unroll]] for (uint j = 0u; j < SLICES_PER_FRAGMENT; ++j) {
    if (sliceIndex + j >= count) break;
    float offset = firstOffset + float(j) * u.eyePosition.w;
    vec3 point = j == 0u ? sliceWorld : sliceWorld + ray * (offset - dot(n, sliceWorld)) / dot(n, ray);
    if (!insideClipBox(point)) continue;
    bool removed;
    float occlusionAfter;
    vec4 c = shadeSlice(point, point / (2.0 * u.halfExtent.xyz) + 0.5,
                        ((SLICES_PER_FRAGMENT % 2u == 0u ? 0u : sliceIndex) + j) % 2u == 0u,
                        removed, occlusionAfter);
    if (removed) continue;
    drawn = true;
    sum = c + (1.0 - c.a) * sum;
  }
  if (!drawn) discard;
  color = sum;
}
