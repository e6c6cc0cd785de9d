#include "analytic_fields.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

namespace lic3d {
namespace {

constexpr std::array<std::string_view, 5> kNames = {"tornado", "corner", "solenoidal", "vortex",
                                                    "abc"};

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

std::span<const std::string_view> analyticFieldNames() { return kNames; }

std::optional<AnalyticField> parseAnalyticField(std::string_view name) {
  for (std::size_t i = 0; i < kNames.size(); ++i)
    if (kNames[i] == name) return static_cast<AnalyticField>(i);
  return std::nullopt;
}

std::string_view toString(AnalyticField field) { return kNames[static_cast<std::size_t>(field)]; }

VectorField makeAnalyticField(AnalyticField field, Dims dims, double time) {
  const Domain domain = domainOf(field);
  const int longest = std::max({dims.x, dims.y, dims.z});
  const double length = domain.max - domain.min;
  const double spacing = longest > 1 ? length / (longest - 1) : length;
  const double centre = 0.5 * (domain.min + domain.max);

  VectorField result;
  result.dims = dims;
  result.geometry.spacing = glm::dvec3(spacing);
  for (int a = 0; a < 3; ++a) result.geometry.origin[a] = centre - 0.5 * spacing * (dims[a] - 1);
  result.vectors.resize(voxelCount(dims));
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const glm::dvec3 p = result.geometry.origin + glm::dvec3(i, j, k) * spacing;
        result.vectors[voxelIndex(dims, i, j, k)] = glm::vec3(evaluate(field, p, time));
      }
  return result;
}

}  // namespace lic3d
