// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The LIC inputs on the GPU: one 3D texture holding the vector field and the noise together.
//
// xyz = the vector in voxel units over its largest length (u = v * voxelUnitScale, texel xyz =
// u / maxVoxelSpeed, see lic_reference.h; v / max|v| on isotropic grids), packed per
// FieldPrecision, and w = the noise value, so the texture fetch at a streamline sample gives both
// the noise there and the direction of the next step: the midpoint scheme fetches once per
// sample (docs/LIC_SEMANTICS.md).

#include <cstdint>
#include <glm/vec4.hpp>
#include <memory>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/field_precision.h"
#include "core/value_histogram.h"
#include "core/volume.h"
#include "gpu/resources.h"
#include "gpu/vulkan_context.h"
#include "io/field_io.h"

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
  std::shared_ptr<const ValueHistogram> speeds;  // |v| over the voxels (automatic ranges)
  std::string unit;                              // VectorField::unit
};

// The scalars colour and opacity follow when they are not the speed (loading/scalars.h), on the
// field's grid: R the colour scalar, G the opacity scalar, each as (value - min) / (max - min)
// in half floats (filterable on every device; 11 bits of the range are finer than the 256
// entries of a colour table), NaN where the scalar has no value. A 1x1x1 texture when both
// follow the speed.
struct ScalarTexture {
  Image image;
  bool color = false;    // R holds the colour scalar
  bool opacity = false;  // G holds the opacity scalar
  // Per channel: value = min + t * span (span 1 for a constant scalar).
  glm::vec4 range{0.0f, 1.0f, 0.0f, 1.0f};  // colour min, span, opacity min, span
  std::shared_ptr<const ValueHistogram> colorValues;
  std::shared_ptr<const ValueHistogram> opacityValues;
  std::string colorName;  // the quantity or array, for the legend
  std::string colorUnit;
};

// `color`, `opacity`: null for the speed; otherwise on `dims`.
Result<ScalarTexture> uploadScalars(const Context& context, Dims dims, const PointScalars* color,
                                    const PointScalars* opacity);

FieldPrecision resolvePrecision(const Context& context, FieldPrecision requested);
// texelToPhysical as the shaders take it: xyz divided by its largest component and w that
// component, so that length(texel * xyz) * w is the physical speed and the squares inside
// length() stay in the float range whatever the field's unit (speeds of 1e-20 or 1e25 square to
// beyond it).
glm::vec4 texelToPhysicalForShader(glm::dvec3 texelToPhysical);
// resolvePrecision, refusing Float where the device cannot filter RGBA32F textures.
Result<FieldPrecision> checkFieldPrecision(const Context& context, FieldPrecision requested);
// The field texture's format for a resolved precision.
VkFormat fieldTextureFormat(FieldPrecision resolved);
// The shaders that write the field texture are compiled once per format (shaders/field_texel.glsl):
// variant 0 writes RGBA32F, 1 RGBA16F, 2 RGBA8 SNORM. The variant of a resolved precision, and
// each variant's name for pipeline names.
int fieldTexelVariant(FieldPrecision resolved);
inline constexpr const char* kFieldTexelVariantNames[3] = {"rgba32f", "rgba16f", "rgba8 snorm"};

// A field texture for shaders to write (a storage image as well as sampled, in the format of
// `precision`, resolved): its image, grid and precision; the statistics are the writer's.
Result<FieldTexture> createWritableFieldTexture(const Context& context, Dims dims,
                                                const GridGeometry& geometry,
                                                FieldPrecision precision, const std::string& name);

// Fails with InvalidInput when the grid exceeds the device's 3D image limit, its spacing is not
// positive or the noise is on another grid than the field.
Result<FieldTexture> uploadLicInputs(const Context& context, const VectorField& field,
                                     const NoiseVolume& noise, FieldPrecision precision);

// Checks that the device can hold a 3D image of `dims`.
Result<void> checkVolumeDims(const Context& context, Dims dims, const char* what);

}  // namespace lic3d
