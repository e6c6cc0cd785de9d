// SPDX-License-Identifier: BSD-3-Clause
#include "lic/analytic_fields.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "core/parallel.h"
#include "lic/field_plane.h"

namespace lic3d {
namespace {

struct Domain {
  double min;
  double max;
};

Domain domainOf(AnalyticField field) {
  switch (field) {
    case AnalyticField::Tornado:
    case AnalyticField::Corner: return {0.0, 1.0};
    case AnalyticField::Solenoidal:
    case AnalyticField::Vortex: return {-1.0, 1.0};
    case AnalyticField::Abc: return {0.0, 2.0 * std::numbers::pi};
  }
  return {0.0, 1.0};
}

// Crawfis' tornado, written from the published formula (tornadoSrc.c). Kept in its original
// form, including the magnitude discontinuity its author notes at |r - d| = r2.
glm::dvec3 tornado(glm::dvec3 p, double time) {
  const double x = p.x, y = p.y, z = p.z;
  const double xc = 0.5 + 0.1 * std::sin(0.04 * time + 10.0 * z);
  const double yc = 0.5 + 0.1 * std::cos(0.03 * time + 3.0 * z);
  const double r = 0.1 + 0.4 * z * z + 0.1 * z * std::sin(8.0 * z);
  const double r2 = 0.2 + 0.1 * z;
  double temp = std::sqrt((y - yc) * (y - yc) + (x - xc) * (x - xc));
  double scale = std::abs(r - temp);
  scale = scale > r2 ? 0.8 - scale : 1.0;
  const double z0 = std::max(0.1 * (0.1 - temp * z), 0.0);
  temp = std::sqrt(temp * temp + z0 * z0);
  scale = (r + r2 - temp) * scale / (temp + 1e-11);
  scale = scale / (1.0 + z);
  return {scale * (y - yc) + 0.1 * (x - xc), scale * -(x - xc) + 0.1 * (y - yc), scale * z0};
}

glm::dvec3 evaluate(AnalyticField field, glm::dvec3 p, double time) {
  const double x = p.x, y = p.y, z = p.z;
  switch (field) {
    case AnalyticField::Tornado: return tornado(p, time);
    case AnalyticField::Corner:
      return {-3.0 + 6.0 * x - 4.0 * x * (y + 1.0) - 4.0 * z,
              12.0 * x - 4.0 * x * x - 12.0 * z + 4.0 * z * z,
              3.0 + 4.0 * x - 4.0 * x * (y + 1.0) - 6.0 * z + 4.0 * (y + 1.0) * z};
    case AnalyticField::Solenoidal:
      return {y * z * (y * y + z * z), x * z * (x * x + z * z), x * y * (x * x + y * y)};
    case AnalyticField::Vortex: return {-y, x, 0.2};
    case AnalyticField::Abc: {
      const double a = std::sqrt(3.0), b = std::sqrt(2.0), c = 1.0;
      return {a * std::sin(z) + c * std::cos(y), b * std::sin(x) + a * std::cos(z),
              c * std::sin(y) + b * std::cos(x)};
    }
  }
  return {};
}

}  // namespace

namespace {

// Voxel (i,j,k) of makeAnalyticField(field, dims) lies at origin + (i,j,k) * spacing.
GridGeometry cubicGeometry(Domain domain, Dims dims) {
  const int longest = std::max({dims.x, dims.y, dims.z});
  const double length = domain.max - domain.min;
  const double spacing = longest > 1 ? length / (longest - 1) : length;
  const double centre = 0.5 * (domain.min + domain.max);
  GridGeometry geometry;
  geometry.spacing = glm::dvec3(spacing);
  for (int a = 0; a < 3; ++a) geometry.origin[a] = centre - 0.5 * spacing * (dims[a] - 1);
  return geometry;
}

}  // namespace

GridGeometry analyticGeometry(AnalyticField field, Dims dims) {
  return cubicGeometry(domainOf(field), dims);
}

VectorField makeAnalyticField(AnalyticField field, Dims dims, double time) {
  VectorField result;
  result.dims = dims;
  result.geometry = cubicGeometry(domainOf(field), dims);
  resizeLarge(result.vectors, voxelCount(dims));
  // One z layer per task: each voxel's value depends on its position alone.
  parallelFor(static_cast<std::size_t>(dims.z), 0, [&](std::size_t layer) {
    const int k = static_cast<int>(layer);
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const glm::dvec3 p = result.geometry.origin + glm::dvec3(i, j, k) * result.geometry.spacing;
        result.vectors[voxelIndex(dims, i, j, k)] = glm::vec3(evaluate(field, p, time));
      }
  });
  return result;
}

VectorField makeAnalyticFieldPlane(AnalyticField field, Dims dims, int axis, int index,
                                   double time) {
  const GridGeometry geometry = cubicGeometry(domainOf(field), dims);
  return makePlane(dims, geometry, axis, index, [&](glm::ivec3 voxel) {
    return evaluate(field, geometry.origin + glm::dvec3(voxel) * geometry.spacing, time);
  });
}

double timePeriod(AnalyticField field) {
  return field == AnalyticField::Tornado ? 200.0 * std::numbers::pi : 0.0;
}

// ---- 2D fields ----------------------------------------------------------------------------------

namespace {

glm::dvec2 evaluate2D(AnalyticField2D field, glm::dvec2 p, double time) {
  switch (field) {
    case AnalyticField2D::Circle: return {-p.y, p.x};
    case AnalyticField2D::Saddle: return {p.x, -p.y};
    case AnalyticField2D::Wave: {
      // Thesis 3.5: Vx = cos(2pi(s - Time)), Vy = sin(2pi(s - Time)), s the horizontal texture
      // coordinate: the direction turns once across the picture and the pattern travels right.
      const double phase = 2.0 * std::numbers::pi * (p.x - time);
      return {std::cos(phase), std::sin(phase)};
    }
  }
  return {};
}

Domain domainOf(AnalyticField2D field) {
  return field == AnalyticField2D::Wave ? Domain{0.0, 1.0} : Domain{-1.0, 1.0};
}

}  // namespace

VectorField makeAnalyticField2D(AnalyticField2D field, glm::ivec2 size, double time) {
  VectorField result;
  result.dims = Dims(size.x, size.y, 1);
  result.geometry = cubicGeometry(domainOf(field), result.dims);
  result.vectors.resize(voxelCount(result.dims));
  for (int j = 0; j < size.y; ++j)
    for (int i = 0; i < size.x; ++i) {
      const glm::dvec3 p = result.geometry.origin + glm::dvec3(i, j, 0) * result.geometry.spacing;
      const glm::dvec2 v = evaluate2D(field, glm::dvec2(p), time);
      result.vectors[voxelIndex(result.dims, i, j, 0)] =
          glm::vec3(static_cast<float>(v.x), static_cast<float>(v.y), 0.0f);
    }
  return result;
}

double timePeriod(AnalyticField2D field) { return field == AnalyticField2D::Wave ? 1.0 : 0.0; }

}  // namespace lic3d
