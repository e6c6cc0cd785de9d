#include "inputs/session_inputs.h"

#include <filesystem>
#include <string>

#include "core/memory_budget.h"
#include "gpu/gpu_resources.h"
#include "io/field_io.h"
#include "lic/noise.h"
#include "lic/sparsity.h"
#include "passes/volume_textures.h"

namespace lic3d {

Result<TimeDomain> timeDomainOf(const Session& session) {
  const std::string& field = session.field.field;
  double period = 0.0;
  if (const auto analytic = parseEnum<AnalyticField>(field)) period = timePeriod(*analytic);
  if (const auto analytic = parseEnum<AnalyticField2D>(field)) period = timePeriod(*analytic);
  if (period > 0.0) return TimeDomain{0.0, period, true, true};
  if (!parseEnum<AnalyticField>(field) && !parseEnum<AnalyticField2D>(field) &&
      isFieldSeriesPattern(field)) {
    LIC3D_TRY_ASSIGN(const TimeSeries series, fileSeries(field));
    return TimeDomain{0.0, series.endTime(), false, true};
  }
  return TimeDomain{};
}

Result<void> checkHostMemory(Dims dims) {
  // Before the field is made: its host copies alone must fit (the device is checked later, with
  // the whole request, by checkRequestMemory). The float texture is the larger of the two.
  MemoryRequest request;
  request.dims = dims;
  request.precision = FieldPrecision::Float;
  return checkMemoryBudget(request, hostMemoryBudget(), "the field");
}

Result<void> checkRequestMemory(const Context& context, const Session& session, Dims dims,
                                const RequestShape& shape) {
  MemoryRequest request;
  request.dims = dims;
  request.precision = resolvePrecision(context, session.precision);
  request.sparsity = session.lic.sparsity.distribution != SparsityDistribution::None;
  request.doubleBuffered = shape.doubleBuffered;
  request.volumeReadback = shape.volumeReadback;
  request.timeSeries = shape.timeSeries;
  if (shape.frame) {
    const bool sideBySide = session.view.stereo == StereoMode::SideBySide;
    request.frameWidth =
        shape.frameWidth > 0 ? shape.frameWidth : session.view.width * (sideBySide ? 2 : 1);
    request.frameHeight = shape.frameHeight > 0 ? shape.frameHeight : session.view.height;
  }
  return checkMemoryBudget(request, queryMemoryBudget(context),
                           "the LIC of " + session.field.field);
}

Result<VectorField> loadField(const FieldSource& source, bool gridGiven, FieldReadInfo* info,
                              double time) {
  if (const auto analytic = parseEnum<AnalyticField>(source.field)) {
    if (!source.array.empty())
      return parameterError("field.array", source.array + ": " + source.field +
                                               " is an analytic field; field.array picks a "
                                               "vector array of a .vtk or .vti file");
    LIC3D_TRY(checkHostMemory(source.grid));
    return makeAnalyticField(*analytic, source.grid, time);
  }
  if (parseEnum<AnalyticField2D>(source.field))
    return parameterError("field.source", source.field +
                                              " is a 2D field: make its LIC with `lic3d "
                                              "render2d` (or the app's 2D mode)");
  if (isFieldSeriesPattern(source.field))
    return parameterError("field.source", source.field + " names a time series, not one field");
  if (gridGiven)
    return parameterError("field.grid",
                          "applies to analytic fields only; " + source.field + " has its own grid");
  const std::filesystem::path path(source.field);
  if (!path.has_extension())
    return parameterError("field.source", "'" + source.field + "' is neither an analytic field (" +
                                              enumChoices<AnalyticField>() +
                                              ") nor a file name with an extension");
  return readVectorField(path, source.array, info);
}

Result<NoiseVolume> loadNoise(const NoiseSource& source, Dims dims) {
  if (source.seedSpots > 0 && !source.file.empty())
    return parameterError("noise.seed_spots", "and noise.file both choose the noise: give one");
  if (source.seedSpots > 0) {
    if (static_cast<std::size_t>(source.seedSpots) > voxelCount(dims))
      return parameterError("noise.seed_spots",
                            "asks for more spots than the grid " + gridText(dims) + " has voxels");
    return makeSeedNoise(dims, static_cast<std::size_t>(source.seedSpots), source.seed);
  }
  if (source.file.empty()) return makeWhiteNoise(dims, source.seed);
  LIC3D_TRY_ASSIGN(NoiseVolume noise, readNoise(source.file));
  if (noise.dims != dims)
    return inputError(source.file + ": the noise grid " + gridText(noise.dims) +
                      " does not match the field grid " + gridText(dims));
  return noise;
}

Result<NoiseVolume> loadNoise(const NoiseSource& source, const VectorField& field) {
  if (!field.piece || field.piece->wholeDims == field.dims) return loadNoise(source, field.dims);
  if (source.seedSpots > 0 || !source.file.empty())
    return parameterError("noise.file",
                          "cannot be given for a piece of a distributed field: its noise is "
                          "the whole grid's seeded white noise");
  return makeWhiteNoisePiece(field.piece->wholeDims, field.piece->offset, field.dims, source.seed);
}

Result<SessionInputs> loadSessionInputs(const Session& session, const InputOptions& options) {
  SessionInputs inputs;
  inputs.time = session.time;
  const FieldSource& source = session.field;
  const std::optional<AnalyticField> analytic = parseEnum<AnalyticField>(source.field);
  if (analytic && options.analyticTimeSteps > 0) {
    LIC3D_TRY(checkHostMemory(source.grid));
    LIC3D_TRY_ASSIGN(inputs.series,
                     analyticSeries(*analytic, source.grid, options.analyticTimeSteps));
  } else if (!analytic && !parseEnum<AnalyticField2D>(source.field) &&
             isFieldSeriesPattern(source.field)) {
    if (options.gridGiven)
      return parameterError(
          "field.grid", "applies to analytic fields only; " + source.field + " has its own grid");
    LIC3D_TRY_ASSIGN(inputs.series, fileSeries(source.field));
    inputs.fromFile = true;
  }
  if (inputs.series) {
    const int first = inputs.series->bracket(session.time).first;
    LIC3D_TRY_ASSIGN(inputs.field, inputs.series->loadStep(first, source.array, &inputs.info));
    inputs.fieldStep = first;  // used as the step itself, not read again
    inputs.stepsRead = 1;
  } else {
    LIC3D_TRY_ASSIGN(inputs.field,
                     loadField(source, options.gridGiven, &inputs.info, session.time));
    inputs.fromFile = !analytic.has_value();
    if (analytic && timePeriod(*analytic) > 0.0) inputs.sampled = analytic;
  }
  LIC3D_TRY(validate(session.lic.sparsity, inputs.field.dims));
  LIC3D_TRY_ASSIGN(inputs.noise, loadNoise(session.noise, inputs.field));
  return inputs;
}

Result<VectorField> loadSeriesStep(const TimeSeries& series, std::string_view array, int k,
                                   Dims dims, const GridGeometry& geometry, FieldReadInfo* info) {
  FieldReadInfo read;
  LIC3D_TRY_ASSIGN(VectorField step, series.loadStep(k, array, &read));
  if (step.dims != dims || !(step.geometry == geometry))
    return inputError((series.files.empty() ? "time step " + std::to_string(k)
                                            : series.files[static_cast<std::size_t>(k)].string()) +
                      ": the steps of a time series must share the first step's grid " +
                      gridText(dims) + ", spacing and origin");
  if (info) info->nonFiniteVectors += read.nonFiniteVectors;
  return step;
}

std::vector<int> missingSteps(const LicRenderer& renderer, const TimeBracket& bracket) {
  std::vector<int> missing;
  for (const int k : {bracket.first, bracket.second})
    if (!renderer.hasTimeStep(k) && (missing.empty() || missing.front() != k)) missing.push_back(k);
  return missing;
}

Result<void> uploadSteps(LicRenderer& renderer, const TimeBracket& bracket,
                         std::span<const std::pair<int, VectorField>> loaded) {
  for (const auto& [k, step] : loaded)
    if (k == bracket.first || k == bracket.second)
      LIC3D_TRY(renderer.setTimeStep(k, step, k == bracket.first ? bracket.second : bracket.first));
  return {};
}

namespace {

// A step of the inputs' series: the one `field` holds, or read and counted.
Result<VectorField> stepOf(SessionInputs& inputs, const Session& session, int k) {
  if (inputs.fieldStep == k) return inputs.field;
  LIC3D_TRY_ASSIGN(VectorField step,
                   loadSeriesStep(*inputs.series, session.field.array, k, inputs.field.dims,
                                  inputs.field.geometry, &inputs.info));
  ++inputs.stepsRead;
  return step;
}

}  // namespace

Result<VectorField> hostFieldAt(SessionInputs& inputs, const Session& session, double time) {
  if (inputs.sampled) return makeAnalyticField(*inputs.sampled, session.field.grid, time);
  if (!inputs.series) return inputs.field;
  const TimeBracket b = inputs.series->bracket(time);
  std::erase_if(inputs.hostSteps,
                [&](const auto& step) { return step.first != b.first && step.first != b.second; });
  for (const int k : {b.first, b.second})
    if (!inputs.hostSteps.count(k)) {
      LIC3D_TRY_ASSIGN(VectorField step, stepOf(inputs, session, k));
      inputs.hostSteps.emplace(k, std::move(step));
    }
  return interpolateFields(inputs.hostSteps.at(b.first), inputs.hostSteps.at(b.second), b.weight);
}

Result<void> moveToTime(SessionInputs& inputs, const Session& session, double time,
                        LicRenderer& renderer, bool first, bool onHost) {
  if (!inputs.sampled && !inputs.series) {
    if (first) return renderer.setInputs(inputs.field, inputs.noise);
    return {};
  }
  if (!first && time == inputs.time) return {};
  inputs.time = time;
  if (inputs.sampled || onHost) {
    LIC3D_TRY_ASSIGN(inputs.field, hostFieldAt(inputs, session, time));
    inputs.fieldStep.reset();
    return renderer.setInputs(inputs.field, inputs.noise);
  }
  if (first) LIC3D_TRY(renderer.setTimeNoise(inputs.noise));
  const TimeBracket b = inputs.series->bracket(time);
  std::vector<std::pair<int, VectorField>> loaded;
  for (const int k : missingSteps(renderer, b)) {
    LIC3D_TRY_ASSIGN(VectorField step, stepOf(inputs, session, k));
    loaded.emplace_back(k, std::move(step));
  }
  LIC3D_TRY(uploadSteps(renderer, b, loaded));
  LIC3D_TRY(renderer.interpolateTime(b.first, b.second, b.weight));
  inputs.blendMs.push_back(renderer.lastBlendMilliseconds());
  return {};
}

}  // namespace lic3d
