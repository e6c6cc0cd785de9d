// Shared by GLSL and C++: descriptor bindings, workgroup sizes and push-constant layouts.
// Push-constant structs use only 4-byte scalars and 16-byte vectors/matrices in std430-compatible
// order, so the C++ and GLSL layouts match without padding surprises (checked by static_assert).
#ifndef LIC3D_SHARED_LAYOUT_H
#define LIC3D_SHARED_LAYOUT_H

#ifdef __cplusplus
#include <cstdint>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
namespace lic3d::gpu {
using uint = std::uint32_t;
using ivec4 = glm::ivec4;
using vec4 = glm::vec4;
using mat4 = glm::mat4;
#define LIC3D_CONST inline constexpr uint
#else
#define LIC3D_CONST const uint
#endif

// ---- LIC compute pass -------------------------------------------------------------------------
LIC3D_CONST kLicBindingField = 0;   // sampler3D: RGBA16F/32F, xyz = v / max|v|, w = noise
LIC3D_CONST kLicBindingOutput = 1;  // image3D r16: the LIC volume

// Specialization constant ids of the LIC pipeline (see LicSpecialization in lic_pass.h).
LIC3D_CONST kLicConstIntegrator = 0;
LIC3D_CONST kLicConstKernel = 1;
LIC3D_CONST kLicConstNoiseFilter = 2;
LIC3D_CONST kLicConstDirection = 3;
LIC3D_CONST kLicConstLocalSizeX = 4;
LIC3D_CONST kLicConstLocalSizeY = 5;
LIC3D_CONST kLicConstLocalSizeZ = 6;

struct LicPushConstants {
  ivec4 dims;             // xyz: grid size; w: first z slice of this dispatch
  vec4 invDims;           // xyz: 1 / dims (texture coordinates of voxel centres); w: unused
  int licLength;          // L
  int bias;               // Lb = L - bias backward, Lf = L + bias forward
  float step;             // h in voxels
  float criticalEpsilon;  // |v / max|v|| at or below this stops a streamline
  float hannDenominator;  // L + |bias| + 1
  float gaussScale;       // 1 / (0.5 L), 0 when L = 0
  float pad0;
  float pad1;
};

// ---- LIC histogram (auto contrast window) ------------------------------------------------------
LIC3D_CONST kHistogramBindingVolume = 0;  // sampler3D: the LIC volume
LIC3D_CONST kHistogramBindingCounts = 1;  // buffer of kHistogramBins uints
LIC3D_CONST kHistogramBins = 1024;
LIC3D_CONST kHistogramLocalSize = 256;

struct HistogramPushConstants {
  ivec4 dims;
};

// ---- Slice rendering pass ----------------------------------------------------------------------
LIC3D_CONST kSliceBindingVolume = 0;  // sampler3D: the LIC volume
LIC3D_CONST kSliceVerticesPerSlice = 12;  // a convex polygon of up to 6 corners as 4 triangles

// Specialization constant ids of the slice pipeline (see SliceSpecialization in slice_pass.h).
LIC3D_CONST kSliceConstOpacityMode = 0;  // 0: constant alpha, 1: alpha weighted by intensity
LIC3D_CONST kSliceConstOrthographic = 1;

// 128 bytes: the minimum maxPushConstantsSize every Vulkan device guarantees.
struct SlicePushConstants {
  mat4 viewProjection;  // world -> clip
  vec4 halfExtent;      // xyz: half the box size in world units (box centred at the origin);
                        // w: alpha per reference distance (one voxel)
  vec4 planeNormal;     // xyz: unit normal of the slice planes, pointing towards the viewer;
                        // w: plane offset of slice 0 (the farthest)
  vec4 eye;             // xyz: camera position (perspective) or direction to the viewer
                        // (orthographic); w: distance between slices
  vec4 transfer;        // grey = clamp(x * intensity + y); z: reference distance; w: unused
};

#ifdef __cplusplus
static_assert(sizeof(LicPushConstants) == 64);
static_assert(sizeof(SlicePushConstants) == 128);
}  // namespace lic3d::gpu
#undef LIC3D_CONST
#endif

#endif
