// SPDX-License-Identifier: BSD-3-Clause
#include "loading/plane_inputs.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "lic/analytic_fields.h"
#include "lic/field_plane.h"
#include "loading/session_inputs.h"

namespace lic3d {
namespace {

// The plane of a file's field: a 2D file is its own plane, a 3D one is cut across plane.axis.
Result<VectorField> planeOfFile(const VectorField& field, const Session& session,
                                const std::string& what, PlaneSource& inputs) {
  const PlaneParams& p = session.plane;
  inputs.outside.clear();
  if (p.oblique) {
    if (field.dims.x == 1 || field.dims.y == 1 || field.dims.z == 1)
      return parameterError("plane.normal", what +
                                                ": a plane at any orientation cuts a 3D "
                                                "grid; " +
                                                gridText(field.dims) + " is flat");
    LIC3D_TRY_ASSIGN(ObliquePlane plane,
                     obliquePlane(field, glm::dvec3(p.point), glm::dvec3(p.normal)));
    inputs.outside = std::move(plane.outside);
    return std::move(plane.field);
  }
  // Pixels square in physical space whatever the grid's spacings (field_plane.h).
  const bool flat = field.dims.x == 1 || field.dims.y == 1 || field.dims.z == 1;
  if (flat && p.index < 0 && p.axis == 2) {
    LIC3D_TRY_ASSIGN(const VectorField plane, planarField(field, what));
    return isotropicPlane(plane);
  }
  Result<VectorField> plane =
      extractPlane(field, p.axis, p.index >= 0 ? p.index : field.dims[p.axis] / 2);
  if (!plane) return parameterError("plane.index", what + ": " + plane.error().message);
  return isotropicPlane(*plane);
}

}  // namespace

Result<VectorField> planeField(const Session& session, bool gridGiven, double time,
                               PlaneSource& inputs) {
  const FieldSource& source = session.field;
  const PlaneParams& p = session.plane;
  if (const auto field2D = parseEnum<AnalyticField2D>(source.field)) {
    if (!source.array.empty())
      return parameterError("field.array",
                            "picks an array of a file; " + source.field + " is an analytic field");
    return makeAnalyticField2D(*field2D, {source.grid.x, source.grid.y}, time);
  }
  if (const auto field3D = parseEnum<AnalyticField>(source.field)) {
    if (!source.array.empty())
      return parameterError("field.array",
                            "picks an array of a file; " + source.field + " is an analytic field");
    if (p.oblique) {
      LIC3D_TRY(checkHostMemory(source.grid));
      return planeOfFile(makeAnalyticField(*field3D, source.grid, time), session, source.field,
                         inputs);
    }
    const int index = p.index >= 0 ? p.index : source.grid[p.axis] / 2;
    if (index >= source.grid[p.axis])
      return parameterError("plane.index",
                            "must be a layer of the grid: it has " +
                                std::to_string(source.grid[p.axis]) + " layers across " +
                                std::string(1, static_cast<char>('x' + p.axis)) + " (0.." +
                                std::to_string(source.grid[p.axis] - 1) + ")");
    return isotropicPlane(makeAnalyticFieldPlane(*field3D, source.grid, p.axis, index, time));
  }
  if (gridGiven)
    return parameterError("field.grid",
                          "applies to analytic fields only; " + source.field + " has its own grid");
  if (!inputs.series && isFieldSeriesPattern(source.field)) {
    LIC3D_TRY_ASSIGN(inputs.series, fileSeries(source.field));
  }
  if (!inputs.series) {
    LIC3D_TRY_ASSIGN(const VectorField field, loadField(source, false, &inputs.info));
    return planeOfFile(field, session, source.field, inputs);
  }
  const TimeBracket b = inputs.series->bracket(time);
  for (auto it = inputs.steps.begin(); it != inputs.steps.end();)
    it = it->first == b.first || it->first == b.second ? std::next(it) : inputs.steps.erase(it);
  for (const int k : {b.first, b.second}) {
    if (inputs.steps.count(k)) continue;
    const std::string file = inputs.series->files[static_cast<std::size_t>(k)].string();
    LIC3D_TRY_ASSIGN(const VectorField step,
                     inputs.series->loadStep(k, source.array, &inputs.info));
    LIC3D_TRY_ASSIGN(VectorField plane, planeOfFile(step, session, file, inputs));
    if (!inputs.steps.empty() && (plane.dims != inputs.steps.begin()->second.dims ||
                                  !(plane.geometry == inputs.steps.begin()->second.geometry)))
      return inputError(file +
                        ": the steps of a time series must share their grid, spacing "
                        "and origin");
    inputs.steps.emplace(k, std::move(plane));
  }
  return interpolateFields(inputs.steps.at(b.first), inputs.steps.at(b.second), b.weight);
}

Dims imageSize(Dims plane, const PlaneParams& p) {
  auto scaled = [](int side, int to, int from) {
    return std::max(1, static_cast<int>(std::lround(static_cast<double>(side) * to / from)));
  };
  if (p.width > 0 && p.height > 0) return {p.width, p.height, 1};
  if (p.width > 0) return {p.width, scaled(p.width, plane.y, plane.x), 1};
  if (p.height > 0) return {scaled(p.height, plane.x, plane.y), p.height, 1};
  return plane;
}

}  // namespace lic3d
