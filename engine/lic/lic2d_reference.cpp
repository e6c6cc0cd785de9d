// SPDX-License-Identifier: BSD-3-Clause
#include "lic/lic2d_reference.h"

#include <string>

#include "lic/field_plane.h"

namespace lic3d {

GridGeometry imageGeometry(const VectorField& field, Dims image) {
  GridGeometry g = field.geometry;
  for (int a = 0; a < 2; ++a) {
    const double fieldPerPixel = static_cast<double>(field.dims[a]) / image[a];
    g.origin[a] += (0.5 * fieldPerPixel - 0.5) * g.spacing[a];
    g.spacing[a] *= fieldPerPixel;
  }
  return g;
}

Result<void> checkLic2DInputs(const VectorField& field, const NoiseVolume& noise) {
  LIC3D_TRY(checkSpacing(field.geometry));
  if (!isPlanar(field)) return inputError("2D LIC needs a 2D field (one voxel along z)");
  for (const glm::vec3& v : field.vectors)
    if (v.z != 0.0f) return inputError("a 2D field's vectors lie in its plane (z components 0)");
  if (noise.dims.z != 1 || noise.dims.x < 1 || noise.dims.y < 1)
    return inputError("2D LIC needs a noise image of one layer");
  return {};
}

Result<void> checkLic2DParams(const LicParams& params) {
  LIC3D_TRY(validate(params));
  if (params.sparsity.distribution != SparsityDistribution::None)
    return parameterError("lic.sparsity.distribution",
                          "hides voxels of a volume; 2D LIC shows every pixel");
  return {};
}

Result<ScalarVolume> computeLic2DReference(const VectorField& field, const NoiseVolume& noise,
                                           const LicParams& params, unsigned threads,
                                           const ProgressCallback& progress) {
  LIC3D_TRY(checkLic2DParams(params));
  LIC3D_TRY(checkLic2DInputs(field, noise));
  const FieldSampler sampler(field, noise.dims);
  ScalarVolume image = computeLicOnGrid(sampler, noise, params, nullptr, threads, progress);
  image.geometry = imageGeometry(field, noise.dims);
  return image;
}

}  // namespace lic3d
