// SPDX-License-Identifier: BSD-3-Clause
#include "lic/field_plane.h"

#include <algorithm>
#include <cmath>
#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <numbers>
#include <string>

namespace lic3d {
glm::ivec2 planeAxes(int axis) {
  switch (axis) {
    case 0: return {1, 2};
    case 1: return {0, 2};
    default: return {0, 1};
  }
}

Result<VectorField> extractPlane(const VectorField& field, int axis, int index) {
  if (axis < 0 || axis > 2) return inputError("a plane is across x, y or z");
  const Dims d = field.dims;
  if (index < 0 || index >= d[axis])
    return inputError("the grid " + gridText(d) + " has " + std::to_string(d[axis]) +
                      " layers across " + std::string(1, static_cast<char>('x' + axis)) + " (0.." +
                      std::to_string(d[axis] - 1) + "), not " + std::to_string(index));
  return makePlane(d, field.geometry, axis, index, [&](glm::ivec3 voxel) {
    return glm::dvec3(field.at(voxel.x, voxel.y, voxel.z));
  });
}

Result<VectorField> planarField(const VectorField& field, const std::string& what) {
  int flat = -1, flatAxes = 0;
  for (int a = 0; a < 3; ++a)
    if (field.dims[a] == 1) {
      flat = a;
      ++flatAxes;
    }
  if (flatAxes == 0)
    return parameterError("plane.axis", "must name a plane of " + what + ": its grid " +
                                            gridText(field.dims) + " is 3D");
  if (flatAxes > 1)
    return inputError(what + ": the grid " + gridText(field.dims) +
                      " is flat along more than one axis; 2D LIC needs a plane");
  return extractPlane(field, flat, 0);
}

PlaneAxes planePictureAxes(glm::dvec3 normal) {
  const glm::dvec3 n = glm::normalize(normal);
  // Within 30 degrees of z the projected z axis shrinks to nothing: the projected y axis takes
  // over, weighted linearly in |n.z| so that the axes stay continuous across the cone's edge.
  const double coneCos = std::cos(std::numbers::pi / 6.0);
  const double w = std::clamp((std::abs(n.z) - coneCos) / (1.0 - coneCos), 0.0, 1.0);
  const glm::dvec3 z(0.0, 0.0, 1.0), y(0.0, 1.0, 0.0);
  const glm::dvec3 up = glm::normalize((z - n.z * n) + w * (y - n.y * n));
  return {glm::cross(up, n), up};
}

VectorField isotropicPlane(const VectorField& plane) {
  const glm::dvec3 s = plane.geometry.spacing;
  const Dims d = plane.dims;
  if (std::abs(s.x - s.y) <= 1e-6 * std::max(s.x, s.y) || d.x < 2 || d.y < 2) return plane;
  const double finer = std::min(s.x, s.y);
  VectorField out;
  out.unit = plane.unit;
  out.dims = Dims(static_cast<int>(std::lround((d.x - 1) * s.x / finer)) + 1,
                  static_cast<int>(std::lround((d.y - 1) * s.y / finer)) + 1, 1);
  out.geometry = plane.geometry;
  // The same extent: the spacing of each axis is its extent over the new intervals.
  out.geometry.spacing.x = (d.x - 1) * s.x / (out.dims.x - 1);
  out.geometry.spacing.y = (d.y - 1) * s.y / (out.dims.y - 1);
  out.vectors.resize(voxelCount(out.dims));
  for (int j = 0; j < out.dims.y; ++j)
    for (int i = 0; i < out.dims.x; ++i) {
      const double x = static_cast<double>(i) * (d.x - 1) / (out.dims.x - 1);
      const double y = static_cast<double>(j) * (d.y - 1) / (out.dims.y - 1);
      const int i0 = std::min(static_cast<int>(x), d.x - 2),
                j0 = std::min(static_cast<int>(y), d.y - 2);
      const float tx = static_cast<float>(x - i0), ty = static_cast<float>(y - j0);
      const glm::vec3 a = glm::mix(plane.at(i0, j0, 0), plane.at(i0 + 1, j0, 0), tx);
      const glm::vec3 b = glm::mix(plane.at(i0, j0 + 1, 0), plane.at(i0 + 1, j0 + 1, 0), tx);
      out.vectors[voxelIndex(out.dims, i, j, 0)] = glm::mix(a, b, ty);
    }
  return out;
}

Result<ObliquePlane> obliquePlane(const VectorField& field, glm::dvec3 point, glm::dvec3 normal) {
  const GridGeometry& g = field.geometry;
  const Dims d = field.dims;
  const glm::dvec3 size = g.spacing * glm::dvec3(glm::max(d - 1, Dims(0)));
  // The normal in box axes is a normal of the box's unit cube; in physical space it scales by
  // the inverse of the box's size (planes map to planes, normals by the inverse transpose).
  glm::dvec3 n = normal / glm::max(size, glm::dvec3(1e-30));
  if (!(glm::length(n) > 0.0)) return parameterError("plane.normal", "must not be zero");
  n = glm::normalize(n);
  const glm::dvec3 p = g.origin + point * size;
  const PlaneAxes axes = planePictureAxes(n);
  const glm::dvec3 u = axes.right, v = axes.up;

  // The rectangle in (u, v) around the plane's cut through the box: the points where the plane
  // crosses the box's 12 edges.
  glm::dvec2 lo(1e300), hi(-1e300);
  const auto cornerAt = [&](int c) {
    return g.origin + size * glm::dvec3(c & 1, (c >> 1) & 1, (c >> 2) & 1);
  };
  for (int c = 0; c < 8; ++c)
    for (int bit = 1; bit < 8; bit <<= 1) {
      if (c & bit) continue;  // each edge once, from its corner with the bit clear
      const glm::dvec3 a = cornerAt(c), b = cornerAt(c | bit);
      const double da = glm::dot(a - p, n), db = glm::dot(b - p, n);
      if ((da > 0.0 && db > 0.0) || (da < 0.0 && db < 0.0)) continue;
      const glm::dvec3 x = da == db ? a : a + (da / (da - db)) * (b - a);
      const glm::dvec2 q(glm::dot(x - p, u), glm::dot(x - p, v));
      lo = glm::min(lo, q);
      hi = glm::max(hi, q);
    }
  if (lo.x > hi.x) return parameterError("plane.point", "the plane misses the field's box");
  const double spacing = std::min({g.spacing.x, g.spacing.y, g.spacing.z});
  const auto points = [&](double extent) {
    return static_cast<int>(std::min(std::floor(extent / spacing + 1e-9) + 1.0, 8192.0));
  };
  ObliquePlane plane;
  VectorField& out = plane.field;
  out.dims = Dims(points(hi.x - lo.x), points(hi.y - lo.y), 1);
  out.geometry.spacing = glm::dvec3(spacing);
  out.geometry.origin = glm::dvec3(lo.x, lo.y, 0.0);
  out.unit = field.unit;
  out.vectors.assign(voxelCount(out.dims), glm::vec3(0.0f));
  plane.outside.assign(out.vectors.size(), 1);
  std::size_t inside = 0;
  for (int j = 0; j < out.dims.y; ++j)
    for (int i = 0; i < out.dims.x; ++i) {
      const glm::dvec3 x = p + (lo.x + i * spacing) * u + (lo.y + j * spacing) * v;
      const glm::dvec3 voxel = (x - g.origin) / g.spacing;
      bool in = true;
      for (int a = 0; a < 3; ++a) in = in && voxel[a] >= -1e-9 && voxel[a] <= (d[a] - 1) + 1e-9;
      if (!in) continue;
      glm::dvec3 f(0.0);
      glm::ivec3 c0, c1;
      glm::dvec3 t;
      for (int a = 0; a < 3; ++a) {
        const double xa = std::clamp(voxel[a], 0.0, static_cast<double>(d[a] - 1));
        c0[a] = std::min(static_cast<int>(std::floor(xa)), d[a] - 1);
        c1[a] = std::min(c0[a] + 1, d[a] - 1);
        t[a] = xa - c0[a];
      }
      for (int corner = 0; corner < 8; ++corner) {
        const glm::ivec3 at((corner & 1) ? c1.x : c0.x, (corner & 2) ? c1.y : c0.y,
                            (corner & 4) ? c1.z : c0.z);
        const double w = ((corner & 1) ? t.x : 1.0 - t.x) * ((corner & 2) ? t.y : 1.0 - t.y) *
                         ((corner & 4) ? t.z : 1.0 - t.z);
        f += w * glm::dvec3(field.at(at.x, at.y, at.z));
      }
      const std::size_t index = voxelIndex(out.dims, i, j, 0);
      out.vectors[index] =
          glm::vec3(static_cast<float>(glm::dot(f, u)), static_cast<float>(glm::dot(f, v)), 0.0f);
      plane.outside[index] = 0;
      ++inside;
    }
  if (inside == 0) return parameterError("plane.point", "the plane misses the field's box");
  return plane;
}

}  // namespace lic3d
