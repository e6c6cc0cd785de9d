// SPDX-License-Identifier: BSD-3-Clause
// Shared by GLSL and C++: descriptor bindings, specialization ids, workgroup sizes, push-constant
// and uniform layouts. The structs use only 4-byte scalars and 16-byte vectors/matrices, in an
// order where std140, std430 and C++ agree (checked by static_assert).
#ifndef LIC3D_SHARED_LAYOUT_H
#define LIC3D_SHARED_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace lic3d::gpu {
using uint = std::uint32_t;
using ivec4 = glm::ivec4;
using uvec4 = glm::uvec4;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
#define LIC3D_CONST inline constexpr uint
#else
#define LIC3D_CONST const uint
#endif

// ---- LIC compute pass -------------------------------------------------------------------------
LIC3D_CONST kLicBindingField = 0;   // sampler3D: the packed field and noise (volume_textures.h)
LIC3D_CONST kLicBindingOutput = 1;  // image3D rg16: r = LIC value, g = 1 if drawn, 0 if masked
LIC3D_CONST kLicBindingMask = 2;    // buffer: the sparsity mask, a bit per voxel (sparsity_mask.h)
LIC3D_CONST kLicBindingNoise = 3;   // sampler3D r8: the noise alone (the benchmark's naive kernel)
LIC3D_CONST kLicBindingBrickList = 4;   // buffer: the listed bricks (kVisibleBindingLists)
LIC3D_CONST kLicBindingMadeBricks = 5;  // buffer: a uint per brick, set to 1 once made

// Specialization constant ids of the LIC pipeline (see LicSpecialization in lic_pass.h).
LIC3D_CONST kLicConstIntegrator = 0;
LIC3D_CONST kLicConstKernel = 1;
LIC3D_CONST kLicConstNoiseFilter = 2;
LIC3D_CONST kLicConstDirection = 3;
LIC3D_CONST kLicConstLocalSizeX = 4;
LIC3D_CONST kLicConstLocalSizeY = 5;
LIC3D_CONST kLicConstLocalSizeZ = 6;
LIC3D_CONST kLicConstSparsity = 7;
LIC3D_CONST kLicConstScheme = 8;       // 0 exact (RK2: 2 fetches per sample), 1 midpoint (1 fetch)
LIC3D_CONST kLicConstPacking = 9;      // 0 linear vector (RGBA16F/32F), 1 square-root RGBA8 SNORM
LIC3D_CONST kLicConstInterleave = 10;  // 1: both directions in one loop, 0: one after the other
LIC3D_CONST kLicConstBrickList = 11;   // 0 every voxel of the slab, 1 the listed bricks' voxels
// Their one default each, which lic.comp and LicSpecialization both take: LicParams' defaults
// and the launch of CPU drivers (licLaunchFor).
LIC3D_CONST kLicDefaultIntegrator = 1;   // rk2
LIC3D_CONST kLicDefaultKernel = 0;       // box
LIC3D_CONST kLicDefaultNoiseFilter = 1;  // trilinear
LIC3D_CONST kLicDefaultDirection = 0;    // u/|u|
LIC3D_CONST kLicDefaultLocalSizeX = 8;
LIC3D_CONST kLicDefaultLocalSizeY = 8;
LIC3D_CONST kLicDefaultLocalSizeZ = 1;
LIC3D_CONST kLicDefaultSparsity = 0;
LIC3D_CONST kLicDefaultScheme = 0;
LIC3D_CONST kLicDefaultPacking = 0;
LIC3D_CONST kLicDefaultInterleave = 0;  // one after the other everywhere (lic_pass.cpp says why)
LIC3D_CONST kLicDefaultBrickList = 0;

struct LicPushConstants {
  ivec4 dims;             // xyz: grid size; w: first z slice of this dispatch (with the brick
                          // list: of the brick layer, a multiple of kVisibleBrickSize)
  vec4 invDims;           // xyz: 1 / dims (texture coordinates of voxel centres); w: unused
  int licLength;          // L
  int bias;               // Lb = L - bias backward, Lf = L + bias forward
  float step;             // h in voxels
  float criticalEpsilon;  // a texel's |xyz| at or below this stops a streamline
  float hannDenominator;  // L + |bias| + 1
  float gaussScale;       // 1 / (0.5 L), 0 when L = 0
  int zEnd;               // one past the last z slice of this dispatch (of the output)
  // Output voxel v holds the LIC of field voxel v * outputStride: 1 the full volume, 2, 4 or 8 a
  // coarse one (render/lic_volume_job.h), whose voxels are the full volume's at those positions.
  int outputStride;
  // The sparsity mask beyond the grid (lic_kernel.h): xyz the grid's offset in the whole grid
  // (a piece's; the bit patterns of signed ints), w the black threshold; maskSeed below.
  uvec4 maskBeyond;
  uint maskSeed;
  uint pad2;
  uint pad3;
  uint pad4;
};

// ---- Sparsity mask on the GPU (sparsity_mask.comp) ---------------------------------------------
LIC3D_CONST kMaskBindingBits = 0;   // buffer: the mask's words (sparsity_mask.h)
LIC3D_CONST kMaskBindingCount = 1;  // buffer: one uint, the black voxels made (added to)
LIC3D_CONST kMaskConstDistribution = 0;
// The distributions it makes, by their SparsityDistribution values (lic_params.h).
LIC3D_CONST kMaskCheckerboard = 1;
LIC3D_CONST kMaskHalton = 5;
LIC3D_CONST kMaskHammersley = 6;
LIC3D_CONST kMaskDefaultDistribution = kMaskCheckerboard;
LIC3D_CONST kMaskLocalSize = 64;
// Workgroups per row of the 2D dispatch: larger masks and point counts exceed the 65535 groups
// of one dimension.
LIC3D_CONST kMaskGroupsPerRow = 32768;

struct SparsityMaskPushConstants {
  ivec4 dims;     // xyz: the grid; w: unused
  uvec4 pattern;  // checkerboard: x black, y period (CheckerboardPattern); points: x the count
  uvec4 powers;   // x, y, z: radicalInversePower of bases 2, 3, 5 for the count; w: the words
};

// ---- LIC histogram (auto contrast window) ------------------------------------------------------
LIC3D_CONST kHistogramBindingVolume = 0;   // sampler3D: the LIC volume
LIC3D_CONST kHistogramBindingCounts = 1;   // kHistogramBins uints, then the masked voxels
LIC3D_CONST kHistogramBindingField = 2;    // sampler3D: the field texture (volume_textures.h)
LIC3D_CONST kHistogramBindingVisible = 3;  // buffer: a uint per brick (kVisibleBindingVisible)
// 0: every voxel of the grid; 1: the voxels of the visible bricks only (docs/VISIBLE_WORK.md)
LIC3D_CONST kHistogramConstVisibleBricks = 0;
LIC3D_CONST kHistogramDefaultVisibleBricks = 0;
LIC3D_CONST kHistogramBins = 1024;
LIC3D_CONST kHistogramLocalSize = 256;

struct HistogramPushConstants {
  ivec4 dims;            // xyz: the LIC volume's grid; w: the field texture's packing
  vec4 texelToPhysical;  // xyz: texelToPhysicalForShader's xyz (volume_textures.h); w: voxels
                         // with length(texel * xyz) below this are empty, not counted
  ivec4 stride;          // x: LIC voxel v lies at field voxel v * x (LicPushConstants)
};

// ---- Visible bricks (visible_bricks.comp, docs/VISIBLE_WORK.md) ---------------------------------
// One workgroup per brick of kVisibleBrickSize^3 voxels: whether a fragment the slice pass can
// draw with non-zero opacity reads one of its LIC voxels, and the list of the visible bricks not
// made yet, one list and one VkDispatchIndirectCommand per layer of bricks along z.
LIC3D_CONST kVisibleBrickSize = 8;
LIC3D_CONST kVisibleLocalSize = 64;
LIC3D_CONST kVisibleBindingField = 0;     // sampler3D: the field texture (volume_textures.h)
LIC3D_CONST kVisibleBindingUniforms = 1;  // uniform VisibleBricksUniforms
LIC3D_CONST kVisibleBindingVisible = 2;   // buffer: a uint per brick, 1 visible, 0 not
LIC3D_CONST kVisibleBindingMade = 3;      // buffer: a uint per brick, 1 if its LIC is made
LIC3D_CONST kVisibleBindingLists = 4;     // buffer: per brick layer, bricksX * bricksY indices
LIC3D_CONST kVisibleBindingDispatch = 5;  // buffer: per brick layer, x = listed count, y, z
// Specialization constant ids (see VisibleBricksSpecialization in visible_bricks_pass.h).
LIC3D_CONST kVisibleConstOpacityRule = 0;  // 0 every voxel, 1 not NaN, 2 not NaN and o >= threshold
LIC3D_CONST kVisibleConstPacking = 1;      // the field texture's packing (kLicConstPacking)
LIC3D_CONST kVisibleConstClipPlane = 2;    // as kSliceConstClipPlane
LIC3D_CONST kVisibleConstRoiShape = 3;     // as kSliceConstRoiShape
LIC3D_CONST kVisibleConstRoiOutside = 4;   // as kSliceConstRoiOutside
LIC3D_CONST kVisibleDefaultOpacityRule = 0;
LIC3D_CONST kVisibleDefaultPacking = kLicDefaultPacking;
LIC3D_CONST kVisibleDefaultClipPlane = 0;
LIC3D_CONST kVisibleDefaultRoiShape = 0;
LIC3D_CONST kVisibleDefaultRoiOutside = 0;

struct VisibleBricksUniforms {
  mat4 roiFromTexture;   // as SliceUniforms
  ivec4 dims;            // xyz: the grid; w: the margin M in voxels
  ivec4 bricks;          // xyz: bricks per axis; w: unused
  vec4 halfExtent;       // xyz: as SliceUniforms; w: the jitter margin J in world units
  vec4 clipMin;          // xyz: as SliceUniforms
  vec4 clipMax;          // xyz: as SliceUniforms
  vec4 clipPlane;        // as SliceUniforms
  vec4 texelToPhysical;  // as SliceUniforms
  vec4 opacity;          // x: low end of the opacity range, y: 1 / its width, z: the lowest o
                         // that may be opaque (o below it is transparent); w: the
                         // halo ring's radius in world units (widens the region test)
};

// ---- Slice rendering pass ----------------------------------------------------------------------
LIC3D_CONST kSliceBindingVolume = 0;      // sampler3D: the LIC volume (r = LIC, g = drawn)
LIC3D_CONST kSliceBindingField = 1;       // sampler3D: the field texture (volume_textures.h)
LIC3D_CONST kSliceBindingColormap = 2;    // sampler2D: one row per colour map
LIC3D_CONST kSliceBindingUniforms = 3;    // uniform SliceUniforms
LIC3D_CONST kSliceBindingScalars = 4;     // sampler3D RG16F: colour and opacity scalars
LIC3D_CONST kSliceVerticesPerSlice = 12;  // a convex polygon of up to 6 corners as 4 triangles

// Specialization constant ids of the slice pipeline (see SliceSpecialization in slice_pass.h).
LIC3D_CONST kSliceConstOpacityMode = 0;       // 0 constant alpha, 1 alpha * grey
LIC3D_CONST kSliceConstOrthographic = 1;      // 0 perspective, 1 orthographic
LIC3D_CONST kSliceConstColorMode = 2;         // 0 grey, 1 colour by magnitude
LIC3D_CONST kSliceConstColormap = 3;          // row of the colour map table (core/colormap.h)
LIC3D_CONST kSliceCustomColormapRow = 3;      // the transfer function's row: kCustomColormapRow
LIC3D_CONST kSliceConstMagnitudeOpacity = 4;  // 0 off, 1 alpha * normalised magnitude ^ exponent
LIC3D_CONST kSliceConstSparsity = 5;          // 0 off, 1 alpha * the LIC volume's mask channel
LIC3D_CONST kSliceConstRoiShape = 6;          // 0 none, 1 sphere, 2 cube, 3 cylinder
LIC3D_CONST kSliceConstRoiOutside = 7;        // 0 keep the inside, 1 keep the outside
LIC3D_CONST kSliceConstFog = 8;               // 0 off, 1 linear depth cueing
LIC3D_CONST kSliceConstLighting = 9;          // 0 none, 1 Phong with TNB normals, 2 lines
LIC3D_CONST kSliceConstFilter = 10;           // 0 nearest voxel, 1 trilinear, 2 cubic B-spline
LIC3D_CONST kSliceConstAnaglyph = 11;         // 0 colour, 1 left eye (red), 2 right eye (cyan)
LIC3D_CONST kSliceConstFieldPacking = 12;     // the field texture's packing (kLicConstPacking)
LIC3D_CONST kSliceConstOpacityTable = 13;     // 0 magnitude opacity, 1 the custom table row's alpha
LIC3D_CONST kSliceConstClipPlane = 14;        // 0 off, 1 discard where dot(p - point, n) > 0
LIC3D_CONST kSliceConstColorSource = 15;      // colour scalar: 0 |v| (field texture), 1 scalars.r
LIC3D_CONST kSliceConstOpacitySource = 16;    // opacity scalar: 0 |v|, 1 scalars.g
LIC3D_CONST kSliceConstHalo = 17;             // 0 off, 1 dark borders around streaks (halos)
LIC3D_CONST kSliceConstOcclusion = 18;        // 0 off, 1 front to back with an occlusion buffer
LIC3D_CONST kSliceConstJitter = 19;           // 0 off, 1 each pixel's samples offset along its ray
LIC3D_CONST kSliceConstSlicesPerFragment = 20;  // K: slices a fragment composites (1, 2 or 4)
// Their one default each, which slice.frag and SliceSpecialization both take.
LIC3D_CONST kSliceDefaultOpacityMode = 1;  // alpha * grey
LIC3D_CONST kSliceDefaultOrthographic = 0;
LIC3D_CONST kSliceDefaultColorMode = 0;
LIC3D_CONST kSliceDefaultColormap = 0;
LIC3D_CONST kSliceDefaultMagnitudeOpacity = 0;
LIC3D_CONST kSliceDefaultSparsity = 0;
LIC3D_CONST kSliceDefaultRoiShape = 0;
LIC3D_CONST kSliceDefaultRoiOutside = 0;
LIC3D_CONST kSliceDefaultFog = 0;
LIC3D_CONST kSliceDefaultLighting = 0;
LIC3D_CONST kSliceDefaultFilter = 1;  // trilinear
LIC3D_CONST kSliceDefaultAnaglyph = 0;
LIC3D_CONST kSliceDefaultFieldPacking = kLicDefaultPacking;
LIC3D_CONST kSliceDefaultOpacityTable = 0;
LIC3D_CONST kSliceDefaultClipPlane = 0;
LIC3D_CONST kSliceDefaultColorSource = 0;
LIC3D_CONST kSliceDefaultOpacitySource = 0;
LIC3D_CONST kSliceDefaultHalo = 0;
LIC3D_CONST kSliceDefaultOcclusion = 0;
LIC3D_CONST kSliceDefaultJitter = 1;
LIC3D_CONST kSliceDefaultSlicesPerFragment = 1;
// With K > 1, one proxy per group of K slices: the convex hull of their polygons seen from the
// eye, a fan of up to kSliceGroupCorners corners: as many as a group has points, so that near-
// collinear points (a box edge crossing the group's planes) never cut the hull short.
LIC3D_CONST kSliceGroupCorners = 24;
LIC3D_CONST kSliceVerticesPerGroup = 3 * (kSliceGroupCorners - 2);
LIC3D_CONST kSliceBindingOcclusion = 5;  // sampler2D: the occlusion buffer of the slice in front
LIC3D_CONST kOcclusionTaps = 6;  // the occlusion buffer blurred by a ring of taps and the centre
// The composite of the occlusion-shaded image into the frame (passes/occlusion_pass.h).
LIC3D_CONST kOcclusionBindingImage = 0;  // sampler2D: the finished image

// One draw's parameters (a uniform buffer slot each; stereo draws twice per frame).
struct SliceUniforms {
  mat4 viewProjection;    // world -> clip
  mat4 roiFromTexture;    // texture coordinates -> region-of-interest frame (unit size)
  vec4 halfExtent;        // xyz: half the box size in world units (box centred at the origin);
                          // w: alpha per reference distance (one voxel)
  vec4 clipMin;           // xyz: corner of the clip box in world units; w: unused
  vec4 clipMax;           // xyz: opposite corner
  vec4 planeNormal;       // xyz: unit normal of the slice planes, pointing towards the viewer;
                          // w: plane offset of slice 0 (the farthest)
  vec4 eyePosition;       // xyz: the camera (this eye); w: distance between slices
  vec4 toViewer;          // xyz: unit direction from the volume to the camera; w: slice count
  vec4 transfer;          // grey = clamp(x * intensity + y); z: reference distance; w: unused
  vec4 magnitude;         // x: low end of the colour range (physical |v|), y: 1 / (high - low),
                          // z: the opacity weight's floor above the threshold; w: unused
  vec4 magnitudeOpacity;  // x: exponent, y: threshold (normalised magnitude), z: low end of the
                          // opacity range, w: 1 / its width
  vec4 clipPlane;         // xyz: unit normal in world units, w: its offset (kept: dot(n, p) <= w)
  vec4 scalarRange;       // value = min + t * span of the scalar texture: x, y colour; z, w opacity
  vec4 fog;               // x: distance where fog starts, y: 1 / (end - start), zw: unused
  vec4 fogColor;          // rgb
  vec4 light;             // xyz: unit direction towards the light; w: specular exponent
  vec4 lightTerms;        // x: ambient, y: diffuse, z: specular, w: unused
  vec4 voxelSize;         // xyz: one voxel in world units (texel xyz, in voxel units, times this
                          // points along the flow in world space); w: unused
  vec4 texelToPhysical;   // texelToPhysicalForShader (volume_textures.h): a texel's physical
                          // speed is length(texel * xyz) * w
  vec4 screenRight;       // xyz: unit screen-right in world space; w: halo radius (world units)
  vec4 screenUp;          // xyz: unit screen-up in world space; w: halo strength
  vec4 haloColor;         // rgb: the halos' colour (the background)
  vec4 occlusion;         // x: occlusion strength, y: blur radius in pixels per slice,
                          // zw: 1 / the occlusion buffer's size in pixels
  uvec4 modes[5];         // the display-mode specialization constants in order, read only by the
                          // benchmark's runtime-mode build of slice.frag
};

// Push constants of the occlusion composite.
struct OcclusionPushConstants {
  ivec4 offset;  // xy: the viewport's offset in the frame
};

// ---- 2D LIC pass (lic2d.comp) -------------------------------------------------------------------
LIC3D_CONST kLic2DBindingField = 0;   // sampler2D: RG16F/32F, xy = u / max|u| in output pixels
LIC3D_CONST kLic2DBindingNoise = 1;   // sampler2D: the noise at the output image's resolution
LIC3D_CONST kLic2DBindingOutput = 2;  // image2D r32f: the LIC value per output pixel

// Specialization constant ids of the 2D LIC pipeline (see Lic2DSpecialization in lic2d_pass.h).
LIC3D_CONST kLic2DConstIntegrator = 0;
LIC3D_CONST kLic2DConstKernel = 1;
LIC3D_CONST kLic2DConstNoiseFilter = 2;
LIC3D_CONST kLic2DConstDirection = 3;
LIC3D_CONST kLic2DConstLocalSizeX = 4;
LIC3D_CONST kLic2DConstLocalSizeY = 5;
LIC3D_CONST kLic2DConstScheme = 6;  // LicParams::scheme, as kLicConstScheme
// Their one default each, which lic2d.comp and Lic2DSpecialization both take.
LIC3D_CONST kLic2DDefaultIntegrator = 1;   // rk2
LIC3D_CONST kLic2DDefaultKernel = 0;       // box
LIC3D_CONST kLic2DDefaultNoiseFilter = 1;  // bilinear
LIC3D_CONST kLic2DDefaultDirection = 0;    // u/|u|
LIC3D_CONST kLic2DDefaultLocalSizeX = 8;
LIC3D_CONST kLic2DDefaultLocalSizeY = 8;
LIC3D_CONST kLic2DDefaultScheme = 1;  // ab2 (LicParams' default is exact; every pipeline sets it)

struct Lic2DPushConstants {
  ivec4 size;             // xy: output image size in pixels; zw: unused
  vec4 invSize;           // xy: 1 / size (texture coordinates of pixel centres); zw: unused
  int licLength;          // L
  int bias;               // Lb = L - bias backward, Lf = L + bias forward
  float step;             // h in output pixels
  float criticalEpsilon;  // a texel's |xy| at or below this stops a streamline
  float hannDenominator;  // L + |bias| + 1
  float gaussScale;       // 1 / (0.5 L), 0 when L = 0
  float pad0;
  float pad1;
};

// ---- Time interpolation of the field texture (time_blend.comp) ----------------------------------
LIC3D_CONST kTimeBlendBindingStepA = 0;   // sampler3D: time step A, xyz = v / max|v| of that step
LIC3D_CONST kTimeBlendBindingStepB = 1;   // sampler3D: time step B, likewise
LIC3D_CONST kTimeBlendBindingNoise = 2;   // sampler3D r32f: the noise
LIC3D_CONST kTimeBlendBindingTarget = 3;  // image3D: the field texture (RGBA16F or RGBA32F) written
LIC3D_CONST kTimeBlendBindingRanges =
    4;  // buffer of kTimeBlendRangeCount uints, float bits (see below)
LIC3D_CONST kTimeBlendConstPhase = 0;  // 0: measure the interpolated field, 1: write the texture
LIC3D_CONST kTimeBlendDefaultPhase = 0;
LIC3D_CONST kTimeBlendLocalSizeX = 8;
LIC3D_CONST kTimeBlendLocalSizeY = 8;
// The ranges buffer: non-negative floats as uint bits (their order is the floats' order).
LIC3D_CONST kTimeBlendRangeMaxSpeed = 0;      // max |u| over the voxels (u: v in voxel units)
LIC3D_CONST kTimeBlendRangeMaxMagnitude = 1;  // max |v|
LIC3D_CONST kTimeBlendRangeMinMagnitude = 2;  // min |v|
LIC3D_CONST kTimeBlendRangeCount = 4;

struct TimeBlendPushConstants {
  ivec4 dims;       // xyz: grid size; w: unused
  vec4 unitScale;   // xyz: voxelUnitScale of the grid; w: the weight of step B, in [0,1]
  vec4 stepScales;  // x: step A's max|v| (its texels' scale), y: step B's; zw: unused
};

// Analytic fields made on the device (shaders/analytic_fields.glsl, passes/analytic_field_pass.h).
// analytic_vectors.comp writes the vectors of one slab of z layers per dispatch, three floats per
// voxel, x fastest (the oracle's layout: tests, and hosts that need the field).
// analytic_field.comp writes the packed field and noise texture (passes/volume_textures.h) in two
// phases, as time_blend.comp does: phase 0 measures max |u| (u: v in voxel units) and min and max
// |v|; phase 1 writes the texels normalised by phase 0's max |u|, the noise of lic/noise.h hashed
// from each voxel's index in the grid, and the histogram of |v| over [min, max]. For a brick of a
// larger grid (bricked LIC), phase 0 runs over the whole grid and phase 1 over the brick, at
// `offset` in it: positions and noise are the whole grid's.
LIC3D_CONST kAnalyticBindingVectors = 0;     // buffer of 3 floats per voxel of the slab
LIC3D_CONST kAnalyticBindingTexels = 0;      // image3D: the field and noise texture
LIC3D_CONST kAnalyticBindingStatistics = 1;  // AnalyticStatistics
LIC3D_CONST kAnalyticConstField = 0;         // the AnalyticField
LIC3D_CONST kAnalyticConstPhase = 1;         // analytic_field.comp: 0 measure, 1 write
LIC3D_CONST kAnalyticDefaultField = 0;       // AnalyticField::Tornado
LIC3D_CONST kAnalyticDefaultPhase = 0;
LIC3D_CONST kAnalyticLocalSizeX = 8;
LIC3D_CONST kAnalyticLocalSizeY = 8;
LIC3D_CONST kAnalyticLayersPerGroup = 16;   // z layers one texel workgroup walks
LIC3D_CONST kAnalyticHistogramBins = 4096;  // ValueHistogram::kBins

struct AnalyticPushConstants {
  ivec4 dims;      // xyz: the slab's (vectors) or the grid's (texels) size; w: first z layer
  vec4 origin;     // xyz: the grid's origin; w: the field's time
  vec4 spacing;    // xyz: the grid's spacing; w: unused
  vec4 unitScale;  // xyz: voxelUnitScale of the grid; w: unused
  uvec4 seed;      // xy: the noise seed (low, high word); zw: unused
  ivec4 offset;    // xyz: of the texels' first voxel in the grid (a brick's); w: unused
  ivec4 whole;     // xyz: the whole grid's size (the noise's voxel index); w: unused
};

// Unsigned integers of non-negative floats order as the floats do: atomicMin and atomicMax on
// their bits reduce the speeds.
LIC3D_CONST kAnalyticMaxSpeed = 0;      // max |u|
LIC3D_CONST kAnalyticMaxMagnitude = 1;  // max |v|
LIC3D_CONST kAnalyticMinMagnitude = 2;  // min |v|
LIC3D_CONST kAnalyticFirstBin = 4;      // then kAnalyticHistogramBins counts
LIC3D_CONST kAnalyticStatisticsWords = kAnalyticFirstBin + kAnalyticHistogramBins;

#ifdef __cplusplus
static_assert(sizeof(AnalyticPushConstants) == 112);
static_assert(sizeof(LicPushConstants) == 96);
static_assert(sizeof(Lic2DPushConstants) == 64);
static_assert(sizeof(TimeBlendPushConstants) == 48);
static_assert(sizeof(SparsityMaskPushConstants) == 48);
static_assert(sizeof(SliceUniforms) == 2 * 64 + 26 * 16);
static_assert(sizeof(OcclusionPushConstants) == 16);
static_assert(sizeof(VisibleBricksUniforms) == 64 + 8 * 16);
}  // namespace lic3d::gpu
#undef LIC3D_CONST
#endif

#endif
