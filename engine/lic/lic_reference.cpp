// SPDX-License-Identifier: BSD-3-Clause
#include "lic/lic_reference.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <glm/glm.hpp>
#include <mutex>
#include <optional>

#include "core/parallel.h"

namespace lic3d {
namespace {

struct Corner {
  int i0, i1;
  double t;
};

// Trilinear weights along one axis with edge clamping; positions outside [0, n-1] clamp.
Corner axisCorner(double x, int n) {
  if (n == 1) return {0, 0, 0.0};
  x = std::clamp(x, 0.0, static_cast<double>(n - 1));
  int i0 = std::min(static_cast<int>(std::floor(x)), n - 2);
  return {i0, i0 + 1, x - i0};
}

bool inside(glm::dvec3 x, Dims dims) {
  for (int a = 0; a < 3; ++a)
    if (x[a] < 0.0 || x[a] > dims[a] - 1) return false;
  return true;
}

// The step direction at x, zero where |v| is at or below the critical threshold.
struct Stepper {
  const FieldSampler& sampler;
  const LicParams& params;
  double criticalMagnitude;

  glm::dvec3 direction(glm::dvec3 v) const {
    const double magnitude = glm::length(v);
    if (magnitude <= criticalMagnitude) return glm::dvec3(0.0);
    return params.direction == DirectionMode::Normalized ? v / magnitude : v / sampler.maxSpeed();
  }
  glm::dvec3 directionAt(glm::dvec3 x) const { return direction(sampler.at(x)); }

  glm::dvec3 advance(glm::dvec3 x, glm::dvec3 d0, double sh) const {
    switch (params.integrator) {
      case Integrator::Euler: return x + sh * d0;
      case Integrator::Rk2: return x + sh * directionAt(x + 0.5 * sh * d0);
      case Integrator::Rk4: {
        const glm::dvec3 k2 = directionAt(x + 0.5 * sh * d0);
        const glm::dvec3 k3 = directionAt(x + 0.5 * sh * k2);
        const glm::dvec3 k4 = directionAt(x + sh * k3);
        return x + (sh / 6.0) * (d0 + 2.0 * k2 + 2.0 * k3 + k4);
      }
    }
    return x;
  }
};

}  // namespace

Result<void> checkSpacing(const GridGeometry& geometry) { return checkGridGeometry(geometry); }

glm::dvec3 voxelUnitScale(const GridGeometry& geometry) {
  const glm::dvec3 s = geometry.spacing;
  // min / s[a] rather than s[a] / min: the axes with the smallest spacing get exactly 1.
  return std::min({s.x, s.y, s.z}) / s;
}

double maxVoxelSpeed(const VectorField& field) {
  if (field.piece) return field.piece->wholeMaxVoxelSpeed;
  return maxVoxelSpeedOverVoxels(field);
}

double maxVoxelSpeedOf(const glm::vec3* vectors, std::size_t count, glm::dvec3 scale) {
  double largest = 0.0;
  for (std::size_t i = 0; i < count; ++i) {
    const glm::vec3& v = vectors[i];
    // The same arithmetic as maxMagnitude (volume.cpp): equal to it on isotropic grids.
    const double x = v.x * scale.x, y = v.y * scale.y, z = v.z * scale.z;
    largest = std::max(largest, std::sqrt(x * x + y * y + z * z));
  }
  return largest;
}

double maxVoxelSpeedOverVoxels(const VectorField& field) {
  const glm::dvec3 scale = voxelUnitScale(field.geometry);
  std::mutex mutex;
  double largest = 0.0;
  parallelChunks(field.vectors.size(), [&](std::size_t begin, std::size_t end) {
    const double local = maxVoxelSpeedOf(field.vectors.data() + begin, end - begin, scale);
    const std::scoped_lock lock(mutex);
    largest = std::max(largest, local);
  });
  return largest;
}

FieldSampler::FieldSampler(const VectorField& field)
    : field_(field), scale_(voxelUnitScale(field.geometry)), maxSpeed_(maxVoxelSpeed(field)) {}

FieldSampler::FieldSampler(const VectorField& field, Dims output) : FieldSampler(field) {
  if (output == field.dims) return;
  resampled_ = true;
  fieldPerOutput_ = glm::dvec3(field.dims) / glm::dvec3(output);
  scale_ /= fieldPerOutput_;
  maxSpeed_ = 0.0;
  for (const glm::vec3& v : field.vectors) {
    const double x = v.x * scale_.x, y = v.y * scale_.y, z = v.z * scale_.z;
    maxSpeed_ = std::max(maxSpeed_, std::sqrt(x * x + y * y + z * z));
  }
}

glm::dvec3 FieldSampler::at(glm::dvec3 x) const {
  if (resampled_) x = (x + 0.5) * fieldPerOutput_ - 0.5;
  const Dims d = field_.dims;
  const Corner cx = axisCorner(x.x, d.x), cy = axisCorner(x.y, d.y), cz = axisCorner(x.z, d.z);
  auto v = [&](int i, int j, int k) { return glm::dvec3(field_.at(i, j, k)); };
  const glm::dvec3 c00 = glm::mix(v(cx.i0, cy.i0, cz.i0), v(cx.i1, cy.i0, cz.i0), cx.t);
  const glm::dvec3 c10 = glm::mix(v(cx.i0, cy.i1, cz.i0), v(cx.i1, cy.i1, cz.i0), cx.t);
  const glm::dvec3 c01 = glm::mix(v(cx.i0, cy.i0, cz.i1), v(cx.i1, cy.i0, cz.i1), cx.t);
  const glm::dvec3 c11 = glm::mix(v(cx.i0, cy.i1, cz.i1), v(cx.i1, cy.i1, cz.i1), cx.t);
  return glm::mix(glm::mix(c00, c10, cy.t), glm::mix(c01, c11, cy.t), cz.t) * scale_;
}

double sampleNoise(const NoiseVolume& noise, NoiseFilter filter, glm::dvec3 x) {
  const Dims d = noise.dims;
  if (filter == NoiseFilter::Nearest) {
    glm::ivec3 v;
    for (int a = 0; a < 3; ++a)
      v[a] = std::clamp(static_cast<int>(std::floor(x[a] + 0.5)), 0, d[a] - 1);
    return noise.value(voxelIndex(d, v.x, v.y, v.z));
  }
  const Corner cx = axisCorner(x.x, d.x), cy = axisCorner(x.y, d.y), cz = axisCorner(x.z, d.z);
  auto n = [&](int i, int j, int k) {
    return static_cast<double>(noise.value(voxelIndex(d, i, j, k)));
  };
  const double c00 = std::lerp(n(cx.i0, cy.i0, cz.i0), n(cx.i1, cy.i0, cz.i0), cx.t);
  const double c10 = std::lerp(n(cx.i0, cy.i1, cz.i0), n(cx.i1, cy.i1, cz.i0), cx.t);
  const double c01 = std::lerp(n(cx.i0, cy.i0, cz.i1), n(cx.i1, cy.i0, cz.i1), cx.t);
  const double c11 = std::lerp(n(cx.i0, cy.i1, cz.i1), n(cx.i1, cy.i1, cz.i1), cx.t);
  return std::lerp(std::lerp(c00, c10, cy.t), std::lerp(c01, c11, cy.t), cz.t);
}

Streamline followStreamline(const FieldSampler& sampler, Dims dims, const LicParams& params,
                            glm::dvec3 start, int sign, int steps) {
  const Stepper stepper{sampler, params, kCriticalFraction * sampler.maxSpeed()};
  Streamline line;
  line.samples.push_back(start);
  glm::dvec3 x = start;
  const double sh = sign * static_cast<double>(params.step);
  const bool rk2 = params.integrator == Integrator::Rk2;
  const bool ab2 = rk2 && params.scheme == StepScheme::Ab2;
  const bool fused = rk2 && params.scheme == StepScheme::Fused;
  glm::dvec3 previous(0.0);  // the direction at the sample before x (AB2)
  glm::dvec3 before = x;     // the sample before x (fused)
  for (int i = 1; i <= steps; ++i) {
    const glm::dvec3 d = stepper.directionAt(x);
    if (d == glm::dvec3(0.0)) break;  // critical point: x was the last sample
    glm::dvec3 next;
    if (ab2 && i > 1)
      next = x + sh * (1.5 * d - 0.5 * previous);
    else if (fused)  // odd i: the midpoint of an RK2 step of 2h; even i: that step's end
      next = i % 2 == 1 ? x + sh * d : before + 2.0 * sh * d;
    else
      next = stepper.advance(x, d, sh);
    previous = d;
    before = x;
    x = next;
    if (!inside(x, dims)) {  // never clamp a streamline back into the grid
      line.exit = StreamlineExit{x, sh * d, steps - i};
      break;
    }
    line.samples.push_back(x);
  }
  return line;
}

std::vector<glm::dvec3> traceStreamline(const FieldSampler& sampler, Dims dims,
                                        const LicParams& params, glm::dvec3 start, int sign,
                                        int steps) {
  return followStreamline(sampler, dims, params, start, sign, steps).samples;
}

namespace {

glm::ivec3 nearestVoxel(glm::dvec3 x) {
  return {static_cast<int>(std::floor(x.x + 0.5)), static_cast<int>(std::floor(x.y + 0.5)),
          static_cast<int>(std::floor(x.z + 0.5))};
}

// Whether the straight continuation of a streamline beyond the grid meets a black voxel.
bool exitTouchesBlack(const SparsityMask& mask, const StreamlineExit& exit) {
  for (int k = 0; k <= exit.stepsLeft; ++k)
    if (isBlack(mask, nearestVoxel(exit.outside + static_cast<double>(k) * exit.step))) return true;
  return false;
}

}  // namespace

double licAtVoxel(const FieldSampler& sampler, const NoiseVolume& noise, const LicParams& params,
                  glm::ivec3 voxel) {
  return licSampleAtVoxel(sampler, noise, params, voxel).value;
}

double convergedLicAtVoxel(const FieldSampler& sampler, const NoiseVolume& noise,
                           const LicParams& params, glm::ivec3 voxel, int refine) {
  LicParams fine = params;
  fine.integrator = Integrator::Rk4;
  fine.step = params.step / static_cast<float>(refine);
  const KernelShape shape = kernelShape(params.length, params.bias);
  double sum = 0.0, weights = 0.0;
  for (int sign : {-1, 1}) {
    const int steps = sign < 0 ? params.length - params.bias : params.length + params.bias;
    const std::vector<glm::dvec3> samples =
        traceStreamline(sampler, noise.dims, fine, glm::dvec3(voxel), sign, steps * refine);
    for (std::size_t k = sign < 0 ? 0 : 1; k * refine < samples.size(); ++k) {
      const double w = kernelWeight(params.kernel, sign * static_cast<int>(k), shape);
      sum += w * sampleNoise(noise, params.noiseFilter, samples[k * refine]);
      weights += w;
    }
  }
  return sum / weights;
}

LicSample licSampleAtVoxel(const FieldSampler& sampler, const NoiseVolume& noise,
                           const LicParams& params, glm::ivec3 voxel, const SparsityMask* mask) {
  const glm::dvec3 start(voxel);
  const KernelShape shape = kernelShape(params.length, params.bias);
  double sum = 0.0, weights = 0.0;
  for (int sign : {-1, 1}) {
    const int steps = sign < 0 ? params.length - params.bias : params.length + params.bias;
    const Streamline line = followStreamline(sampler, noise.dims, params, start, sign, steps);
    const std::vector<glm::dvec3>& samples = line.samples;
    // The start sample belongs to both directions; count it once (with the backward pass).
    for (std::size_t i = sign < 0 ? 0 : 1; i < samples.size(); ++i) {
      const double w = kernelWeight(params.kernel, sign * static_cast<int>(i), shape);
      sum += w * sampleNoise(noise, params.noiseFilter, samples[i]);
      weights += w;
      // A hidden voxel's value is never shown: its streamline is not followed further, and
      // the value is 0 on both implementations (docs/LIC_SEMANTICS.md, Sparsity).
      if (mask && isBlack(*mask, nearestVoxel(samples[i]))) return {0.0, false};
    }
    if (mask && line.exit && exitTouchesBlack(*mask, *line.exit)) return {0.0, false};
  }
  return {sum / weights, true};
}

Result<ScalarVolume> computeLicReference(const VectorField& field, const NoiseVolume& noise,
                                         const LicParams& params, unsigned threads,
                                         const ProgressCallback& progress) {
  LIC3D_TRY(validate(params));
  LIC3D_TRY(checkSpacing(field.geometry));
  if (noise.dims != field.dims)
    return inputError("the noise volume and the field must have the same grid");

  const FieldSampler sampler(field);
  std::optional<SparsityMask> mask;
  if (params.sparsity.distribution != SparsityDistribution::None) {
    const SparsityParams sparsity = maskParams(params);
    LIC3D_TRY_ASSIGN(mask, field.piece ? makeSparsityMaskPiece(sparsity, *field.piece, field.dims)
                                       : makeSparsityMask(sparsity, field.dims));
  }
  ScalarVolume out =
      computeLicOnGrid(sampler, noise, params, mask ? &*mask : nullptr, threads, progress);
  if (progress.stopRequested()) return cancelledError();
  out.geometry = field.geometry;
  return out;
}

ScalarVolume computeLicOnGrid(const FieldSampler& sampler, const NoiseVolume& noise,
                              const LicParams& params, const SparsityMask* mask, unsigned threads,
                              const ProgressCallback& progress) {
  const Dims dims = noise.dims;
  ScalarVolume out;
  out.dims = dims;
  out.values.resize(voxelCount(dims));
  if (mask) out.drawn.resize(out.values.size());

  // Work is handed out in rows (y, z pairs): a 2D grid has a single z slice.
  const auto rows = static_cast<std::size_t>(dims.y) * static_cast<std::size_t>(dims.z);
  parallelFor(
      rows, threads,
      [&](std::size_t row) {
        const int j = static_cast<int>(row % static_cast<std::size_t>(dims.y));
        const int k = static_cast<int>(row / static_cast<std::size_t>(dims.y));
        for (int i = 0; i < dims.x; ++i) {
          const std::size_t index = voxelIndex(dims, i, j, k);
          const LicSample sample = licSampleAtVoxel(sampler, noise, params, {i, j, k}, mask);
          out.values[index] = static_cast<float>(sample.value);
          if (mask) out.drawn[index] = sample.drawn ? 1 : 0;
        }
      },
      progress);
  if (progress && !progress.stopRequested()) progress(1.0);
  return out;
}

}  // namespace lic3d
