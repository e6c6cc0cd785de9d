// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The CPU reference of 3D LIC: the exact semantics of docs/LIC_SEMANTICS.md in double
// precision, multi-threaded. It is the oracle of the GPU tests and the `--cpu` fallback.

#include <functional>
#include <glm/vec3.hpp>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/progress.h"
#include "core/volume.h"
#include "lic/sparsity.h"

namespace lic3d {

// ---- Voxel units (docs/LIC_SEMANTICS.md, "Anisotropic grids") ----------------------------------
// LIC integrates in voxel units: component a of a physical vector is divided by the spacing along
// a. The result is multiplied by the smallest spacing, so the factor is exactly 1 on every axis of
// an isotropic grid and such grids keep their vectors bit for bit. The GPU upload
// (volume_textures.cpp) and this reference both convert with these two, so they cannot drift.

// An input error unless the spacing is positive and finite on every axis (the readers ensure it;
// computeLicReference and uploadLicInputs check it for fields made in code).
Result<void> checkSpacing(const GridGeometry& geometry);
// min(spacing) / spacing per axis, for a geometry that passes checkSpacing.
glm::dvec3 voxelUnitScale(const GridGeometry& geometry);
// What directions and magnitude steps are normalised by: the largest |v * voxelUnitScale| over
// the grid's voxels, or for a piece of a larger field the whole field's (FieldPiece), so that
// every piece steps as the whole would.
double maxVoxelSpeed(const VectorField& field);
// The largest |v * voxelUnitScale| over this field's own voxels, piece or not.
double maxVoxelSpeedOverVoxels(const VectorField& field);
// The same over `count` vectors with `scale` = voxelUnitScale(geometry), on this thread (a part of
// a field read by threads).
double maxVoxelSpeedOf(const glm::vec3* vectors, std::size_t count, glm::dvec3 scale);

// Edge-clamped trilinear interpolation of a field at continuous voxel positions, in voxel units.
class FieldSampler {
 public:
  explicit FieldSampler(const VectorField& field);
  // LIC on a grid of `output` voxels covering the same box as the field's (2D LIC's image, which
  // may be finer than the field; docs/LIC_SEMANTICS.md, "2D LIC"): positions are in output
  // voxels, output voxel x lies at field position (x + 0.5) * N / W - 0.5 per axis (N field, W
  // output voxels), and vectors are in output voxel units (voxelUnitScale times W / N per axis).
  // With output == field.dims this is the field's own sampler.
  FieldSampler(const VectorField& field, Dims output);
  // The interpolated vector times voxelUnitScale (interpolation and the per-axis scale commute).
  glm::dvec3 at(glm::dvec3 x) const;
  // maxVoxelSpeed of the field (in output voxel units when resampled).
  double maxSpeed() const { return maxSpeed_; }
  // Per axis, what at() multiplies the interpolated vector by (the GPU uploads use the same).
  glm::dvec3 unitScale() const { return scale_; }

 private:
  const VectorField& field_;
  glm::dvec3 scale_{1.0};
  double maxSpeed_ = 0.0;
  bool resampled_ = false;
  glm::dvec3 fieldPerOutput_{1.0};  // N / W per axis
};

// Where a streamline left the grid: its first sample outside, the step that took it there
// (sh times the direction at the last sample inside) and the steps it had left after that one.
// For the sparsity mask alone, the streamline goes on straight: outside + k step, k = 0..stepsLeft.
struct StreamlineExit {
  glm::dvec3 outside{0.0};
  glm::dvec3 step{0.0};
  int stepsLeft = 0;
};
struct Streamline {
  std::vector<glm::dvec3> samples;
  std::optional<StreamlineExit> exit;  // none if it ran its steps or stopped at a critical point
};

// The samples x_0 = start, x_1, ... that a streamline reaches in direction sign (+1 or -1) within
// `steps` steps: it stops before leaving the grid and after reaching a critical point.
Streamline followStreamline(const FieldSampler& sampler, Dims dims, const LicParams& params,
                            glm::dvec3 start, int sign, int steps);
// followStreamline's samples.
std::vector<glm::dvec3> traceStreamline(const FieldSampler& sampler, Dims dims,
                                        const LicParams& params, glm::dvec3 start, int sign,
                                        int steps);

// The LIC value of voxel (i,j,k), and whether it is drawn: with a sparsity mask, a voxel is
// not drawn if any sample of its streamline lies in a black voxel (the voxel nearest to the
// sample, as for nearest noise), counting the straight continuation of a streamline that left
// the grid (StreamlineExit, MaskBeyondGrid).
struct LicSample {
  double value = 0.0;
  bool drawn = true;
};
LicSample licSampleAtVoxel(const FieldSampler& sampler, const NoiseVolume& noise,
                           const LicParams& params, glm::ivec3 voxel,
                           const SparsityMask* mask = nullptr);
double licAtVoxel(const FieldSampler& sampler, const NoiseVolume& noise, const LicParams& params,
                  glm::ivec3 voxel);

// The converged LIC value of a voxel, what the schemes' errors are measured against
// (docs/LIC_SEMANTICS.md, "Fidelity"): the streamline integrated with RK4 at h / refine and
// sampled every `refine` substeps, so the samples lie where a converged integrator puts them at
// steps of h; the kernel and noise filter of `params`, no sparsity mask.
double convergedLicAtVoxel(const FieldSampler& sampler, const NoiseVolume& noise,
                           const LicParams& params, glm::ivec3 voxel, int refine = 8);

// The whole LIC volume (with `drawn` filled when params.sparsity has a distribution); `threads`
// = 0 uses every CPU the process may run on (availableThreads, core/parallel.h).
Result<ScalarVolume> computeLicReference(const VectorField& field, const NoiseVolume& noise,
                                         const LicParams& params, unsigned threads = 0,
                                         const ProgressCallback& progress = {});

// The LIC value of every voxel of the noise's grid, whose streamlines follow `sampler` (made for
// that grid), with the sparsity `mask` when given; rows are shared by `threads` threads (0: every
// CPU the process may run on). computeLicReference and the 2D reference (lic2d_reference.h) both
// use it.
ScalarVolume computeLicOnGrid(const FieldSampler& sampler, const NoiseVolume& noise,
                              const LicParams& params, const SparsityMask* mask,
                              unsigned threads = 0, const ProgressCallback& progress = {});

// Noise sample at a continuous position with the given filter (nearest voxel or trilinear).
double sampleNoise(const NoiseVolume& noise, NoiseFilter filter, glm::dvec3 x);

}  // namespace lic3d
