#pragma once
// The LIC inputs on the GPU: one 3D texture holding the vector field and the noise together.
//
// xyz = the vector in voxel units over its largest length (u = v * voxelUnitScale, texel xyz =
// u / maxVoxelSpeed, see lic_reference.h; v / max|v| on isotropic grids), packed per
// FieldPrecision, and w = the noise value, so the texture fetch at a streamline sample gives both
// the noise there and the direction of the next step: the midpoint scheme fetches once per
// sample (docs/LIC_SEMANTICS.md).

#include <cstdint>
#include <string_view>

#include "error.h"
#include "gpu_resources.h"
#include "volume.h"
#include "vulkan_context.h"

namespace lic3d {

enum class FieldPrecision {
  Auto,   // Float on CPU devices (lavapipe), Half on GPUs
  Half,   // RGBA16F: half the memory and bandwidth; 11 significant bits per component
  Float,  // RGBA32F: exact float32 field and noise; GPUs fetch it markedly slower, CPUs faster
  // RGBA8 SNORM, a quarter of float's memory: xyz = e with e |e| = u / max|u| (the square root
  // of the relative speed scales the unit direction, so slow flow keeps 7-bit directions down to
  // 1e-4 of the top speed) and w = (255 n - 128) / 127 for noise n in [0,1] (8-bit noise).
  Byte,
};

// Bytes per texel of the field texture (Auto must be resolved first), and its format's name.
std::uint32_t fieldTexelBytes(FieldPrecision precision);
std::string_view fieldTextureFormatName(FieldPrecision precision);

struct FieldTexture {
  Image image;
  Dims dims{0};
  GridGeometry geometry;
  double minMagnitude = 0.0;  // physical |v| over the voxels: the colour range and legend
  double maxMagnitude = 0.0;
  double maxVoxelSpeed = 0.0;  // the texels' scale (maxVoxelSpeed in lic_reference.h)
  // Per axis, a texel's xyz times this is the physical vector: maxVoxelSpeed / voxelUnitScale.
  glm::dvec3 texelToPhysical{1.0};
  FieldPrecision precision = FieldPrecision::Half;
};

FieldPrecision resolvePrecision(const Context& context, FieldPrecision requested);

// Fails with InvalidInput when the grid exceeds the device's 3D image limit, its spacing is not
// positive or the noise is on another grid than the field.
Result<FieldTexture> uploadLicInputs(const Context& context, const VectorField& field,
                                     const NoiseVolume& noise, FieldPrecision precision);

// Checks that the device can hold a 3D image of `dims`.
Result<void> checkVolumeDims(const Context& context, Dims dims, const char* what);

}  // namespace lic3d
