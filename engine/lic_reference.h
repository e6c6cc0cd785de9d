#pragma once
// The CPU reference of 3D LIC: the exact semantics of docs/LIC_SEMANTICS.md in double
// precision, multi-threaded. It is the oracle of the GPU tests and the `--cpu` fallback.

#include <functional>
#include <vector>

#include <glm/vec3.hpp>

#include "error.h"
#include "lic_params.h"
#include "sparsity.h"
#include "volume.h"

namespace lic3d {

// Called with the finished fraction in [0,1] from the calling thread.
using ProgressCallback = std::function<void(double fraction)>;

// Edge-clamped trilinear interpolation of a field at continuous voxel positions.
class FieldSampler {
 public:
  explicit FieldSampler(const VectorField& field);
  glm::dvec3 at(glm::dvec3 x) const;
  double maxMagnitude() const { return maxMagnitude_; }

 private:
  const VectorField& field_;
  double maxMagnitude_ = 0.0;
};

// The samples x_0 = start, x_1, ... that a streamline reaches in direction sign (+1 or -1) within
// `steps` steps: it stops before leaving the grid and after reaching a critical point.
std::vector<glm::dvec3> traceStreamline(const FieldSampler& sampler, Dims dims,
                                        const LicParams& params, glm::dvec3 start, int sign,
                                        int steps);

// The LIC value of voxel (i,j,k), and whether it is drawn: with a sparsity mask, a voxel is
// not drawn if any sample of its streamline lies in a black voxel (the voxel nearest to the
// sample, as for nearest noise).
struct LicSample {
  double value = 0.0;
  bool drawn = true;
};
LicSample licSampleAtVoxel(const FieldSampler& sampler, const NoiseVolume& noise,
                           const LicParams& params, glm::ivec3 voxel,
                           const SparsityMask* mask = nullptr);
double licAtVoxel(const FieldSampler& sampler, const NoiseVolume& noise, const LicParams& params,
                  glm::ivec3 voxel);

// The whole LIC volume (with `drawn` filled when params.sparsity has a distribution); `threads`
// = 0 uses every hardware thread.
Result<ScalarVolume> computeLicReference(const VectorField& field, const NoiseVolume& noise,
                                         const LicParams& params, unsigned threads = 0,
                                         const ProgressCallback& progress = {});

// Noise sample at a continuous position with the given filter (nearest voxel or trilinear).
double sampleNoise(const NoiseVolume& noise, NoiseFilter filter, glm::dvec3 x);

}  // namespace lic3d
