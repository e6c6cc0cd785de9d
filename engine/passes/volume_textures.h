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

#include "core/error.h"
#include "core/field_precision.h"
#include "core/volume.h"
#include "gpu/gpu_resources.h"
#include "gpu/vulkan_context.h"

namespace lic3d {

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
