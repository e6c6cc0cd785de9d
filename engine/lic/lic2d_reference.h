// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The CPU reference of 2D LIC (thesis chapter 3): docs/LIC_SEMANTICS.md restricted to a plane, on
// an output image that may be finer than the field. It is the oracle of the 2D GPU pass
// (lic2d_pass.h) and `lic3d render2d --cpu`.

#include "core/error.h"
#include "core/lic_params.h"
#include "core/volume.h"
#include "lic/lic_reference.h"

namespace lic3d {

// The LIC image of a 2D field (field_plane.h) on the noise's grid: W x H x 1 pixels covering the
// field's box, so a noise image larger than the field gives a sharper picture of the same flow.
// Pixel (i, j) samples the field at ((i + 0.5) * NX / W - 0.5, (j + 0.5) * NY / H - 0.5) in field
// voxels; steps are h pixels. Sparsity is refused (it is a 3D technique). The image's geometry
// places the pixels in the field's space.
Result<ScalarVolume> computeLic2DReference(const VectorField& field, const NoiseVolume& noise,
                                           const LicParams& params, unsigned threads = 0,
                                           const ProgressCallback& progress = {});

// Where the pixels of a W x H image over `field` lie: spacing N / W times the field's, the first
// pixel centre half a field voxel minus half a pixel before the field's first voxel.
GridGeometry imageGeometry(const VectorField& field, Dims image);

// What 2D LIC needs: a 2D field (one voxel along z, z components 0) with a valid spacing and a
// noise image of one layer.
Result<void> checkLic2DInputs(const VectorField& field, const NoiseVolume& noise);
// Valid LicParams without sparsity (a technique for volumes: 2D LIC shows every pixel).
Result<void> checkLic2DParams(const LicParams& params);

}  // namespace lic3d
