// SPDX-License-Identifier: BSD-3-Clause
#include "lic/resample.h"

#include <algorithm>
#include <cmath>

#include "core/parallel.h"

namespace lic3d {
namespace {

// Where new point i of `to` lies on an axis of `from` points, as the lower point and the weight
// of the upper one.
struct AxisSample {
  int i0 = 0;
  int i1 = 0;
  float t = 0.0f;
};

std::vector<AxisSample> axisSamples(int from, int to) {
  std::vector<AxisSample> samples(static_cast<std::size_t>(to));
  for (int i = 0; i < to; ++i) {
    const double x =
        to > 1 && from > 1 ? static_cast<double>(i) * (from - 1) / static_cast<double>(to - 1) : 0;
    const int i0 = std::clamp(static_cast<int>(std::floor(x)), 0, from - 1);
    samples[static_cast<std::size_t>(i)] = {i0, std::min(i0 + 1, from - 1),
                                            static_cast<float>(x - i0)};
  }
  return samples;
}

// Calls out(index, i000.., weights) through `lerp` for every new point.
template <class T, class Lerp>
std::vector<T> resampleValues(const std::vector<T>& values, Dims from, Dims to, unsigned threads,
                              Lerp lerp) {
  const std::vector<AxisSample> xs = axisSamples(from.x, to.x), ys = axisSamples(from.y, to.y),
                                zs = axisSamples(from.z, to.z);
  std::vector<T> out(voxelCount(to));
  const auto at = [&](int i, int j, int k) { return values[voxelIndex(from, i, j, k)]; };
  parallelFor(static_cast<std::size_t>(to.z), threads, [&](std::size_t layer) {
    const AxisSample& z = zs[layer];
    for (int j = 0; j < to.y; ++j) {
      const AxisSample& y = ys[static_cast<std::size_t>(j)];
      for (int i = 0; i < to.x; ++i) {
        const AxisSample& x = xs[static_cast<std::size_t>(i)];
        const T c00 = lerp(at(x.i0, y.i0, z.i0), at(x.i1, y.i0, z.i0), x.t);
        const T c10 = lerp(at(x.i0, y.i1, z.i0), at(x.i1, y.i1, z.i0), x.t);
        const T c01 = lerp(at(x.i0, y.i0, z.i1), at(x.i1, y.i0, z.i1), x.t);
        const T c11 = lerp(at(x.i0, y.i1, z.i1), at(x.i1, y.i1, z.i1), x.t);
        out[voxelIndex(to, i, j, static_cast<int>(layer))] =
            lerp(lerp(c00, c10, y.t), lerp(c01, c11, y.t), z.t);
      }
    }
  });
  return out;
}

}  // namespace

GridGeometry resampledGeometry(const GridGeometry& geometry, Dims from, Dims dims) {
  GridGeometry out = geometry;
  for (int a = 0; a < 3; ++a)
    if (from[a] > 1 && dims[a] > 1)
      out.spacing[a] = geometry.spacing[a] * (from[a] - 1) / static_cast<double>(dims[a] - 1);
  return out;
}

VectorField resampleField(const VectorField& field, Dims dims, unsigned threads) {
  VectorField out;
  out.dims = dims;
  out.geometry = resampledGeometry(field.geometry, field.dims, dims);
  out.unit = field.unit;
  out.vectors = resampleValues(
      field.vectors, field.dims, dims, threads,
      [](const glm::vec3& a, const glm::vec3& b, float t) { return a + t * (b - a); });
  return out;
}

PointScalars resampleScalars(const PointScalars& scalars, Dims dims, unsigned threads) {
  PointScalars out = scalars;
  out.dims = dims;
  out.geometry = resampledGeometry(scalars.geometry, scalars.dims, dims);
  // a + t (b - a) keeps NaN from either end: a NaN point is no value, and stays so around it.
  out.values = resampleValues(scalars.values, scalars.dims, dims, threads,
                              [](float a, float b, float t) { return a + t * (b - a); });
  return out;
}

}  // namespace lic3d
