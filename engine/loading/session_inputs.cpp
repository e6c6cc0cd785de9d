// SPDX-License-Identifier: BSD-3-Clause
#include "loading/session_inputs.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <glm/geometric.hpp>
#include <string>

#include "core/look.h"
#include "core/memory_budget.h"
#include "core/resolution.h"
#include "core/stage_times.h"
#include "core/text.h"
#include "core/value_histogram.h"
#include "gpu/resources.h"
#include "io/field_io.h"
#include "lic/noise.h"
#include "lic/resample.h"
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
  request.scalars = session.view.colorBy != "speed" || session.view.opacityBy != "speed";
  request.doubleBuffered = shape.doubleBuffered;
  request.volumeReadback = shape.volumeReadback;
  request.licOnHost = shape.licOnHost;
  request.timeSeries = shape.timeSeries;
  if (shape.frame) {
    const bool sideBySide = session.view.stereo == StereoMode::SideBySide;
    request.frameWidth =
        shape.frameWidth > 0 ? shape.frameWidth : session.view.width * (sideBySide ? 2 : 1);
    request.frameHeight = shape.frameHeight > 0 ? shape.frameHeight : session.view.height;
  }
  MemoryBudget budget = queryMemoryBudget(context);
  if (shape.deviceCap > 0 && shape.deviceCap < budget.deviceBytes) {
    budget.deviceBytes = shape.deviceCap;
    budget.deviceCapped = true;
  }
  return checkMemoryBudget(request, budget, "the LIC of " + session.field.field);
}

namespace {

Error analyticResolutionError(const FieldSource& source) {
  return parameterError("field.resolution", source.resolution + ": " + source.field +
                                                " is an analytic field; field.grid sets its grid");
}

// What an analytic field's source may not name.
Result<void> checkAnalyticSource(const FieldSource& source) {
  if (!source.resolution.empty()) return analyticResolutionError(source);
  if (!source.array.empty())
    return parameterError("field.array", source.array + ": " + source.field +
                                             " is an analytic field; field.array picks a "
                                             "vector array of a .vtk or .vti file");
  return {};
}

}  // namespace

bool isWhiteNoise(const NoiseSource& source) {
  return source.file.empty() && source.seedSpots == 0 && source.seedFraction <= 0.0f;
}

Result<VectorField> loadField(const FieldSource& source, bool gridGiven, FieldReadInfo* info,
                              double time) {
  if (const auto analytic = parseEnum<AnalyticField>(source.field)) {
    LIC3D_TRY(checkAnalyticSource(source));
    LIC3D_TRY(checkHostMemory(source.grid));
    const StageTimer timer("field (analytic)");
    return makeAnalyticField(*analytic, source.grid, time);
  }
  if (parseEnum<AnalyticField2D>(source.field))
    return parameterError("field.source", quoteForMessage(source.field) +
                                              " is a 2D field: make its LIC with `lic3d "
                                              "render2d` (or the app's 2D mode)");
  if (isFieldSeriesPattern(source.field))
    return parameterError("field.source",
                          quoteForMessage(source.field) + " names a time series, not one field");
  if (gridGiven)
    return parameterError("field.grid", "applies to analytic fields only; " +
                                            quoteForMessage(source.field) +
                                            " has its own grid (a finer LIC grid: "
                                            "field.resolution)");
  const std::filesystem::path path(source.field);
  if (!path.has_extension())
    return parameterError("field.source",
                          quoteForMessage(source.field) + " is neither an analytic field (" +
                              enumChoices<AnalyticField>() + ") nor a file name with an extension");
  FieldReadInfo read;
  StageTimer reading("field (read)");
  LIC3D_TRY_ASSIGN(VectorField field, readVectorField(path, source.array, &read));
  reading.stop();
  field.unit = read.unit;
  if (info) *info = read;
  return atResolution(std::move(field), source);
}

Result<VectorField> atResolution(VectorField field, const FieldSource& source) {
  LIC3D_TRY_ASSIGN(const Resolution resolution, parseResolution(source.resolution));
  LIC3D_TRY_ASSIGN(const Dims dims, resolveGrid(resolution, field.dims, source.resolution));
  if (dims == field.dims) return field;
  LIC3D_TRY(checkHostMemory(dims));
  const StageTimer timer("field (resample)");
  return resampleField(field, dims);
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
  if (source.seedFraction > 0.0f && source.file.empty()) {
    // At least one spot: a tiny grid keeps a streamline.
    const auto spots = std::max<std::size_t>(
        1, static_cast<std::size_t>(std::llround(static_cast<double>(source.seedFraction) *
                                                 static_cast<double>(voxelCount(dims)))));
    return makeSeedNoise(dims, spots, source.seed);
  }
  if (source.file.empty()) return makeWhiteNoise(dims, source.seed);
  LIC3D_TRY_ASSIGN(NoiseVolume noise, readNoise(source.file));
  if (noise.dims != dims)
    return inputError(source.file + ": the noise grid " + gridText(noise.dims) +
                      " does not match the field grid " + gridText(dims));
  return noise;
}

Result<NoiseVolume> loadNoise(const NoiseSource& source, const VectorField& field) {
  if (source.seedFraction > 0.0f && source.seedSpots == 0 && source.file.empty() && !field.piece) {
    // The fraction counts the voxels where the field flows: a vessel tree filling 3 % of its
    // box gets as many seeds per flowing voxel as a field filling all of it. Flowing: faster
    // than the looks' empty-space threshold (kEmptySpeedFraction of the fastest speeds).
    const ValueHistogram speeds = speedHistogram(field);
    const double empty = emptySpaceSpeed(speeds);
    double flowing = 0.0;
    for (const glm::vec3& v : field.vectors) flowing += glm::length(v) > empty ? 1.0 : 0.0;
    const double share = std::max(flowing / static_cast<double>(field.vectors.size()), 0.01);
    NoiseSource scaled = source;
    scaled.seedFraction =
        static_cast<float>(std::min(static_cast<double>(source.seedFraction) / share, 0.5));
    return loadNoise(scaled, field.dims);
  }
  if (!field.piece || field.piece->wholeDims == field.dims) return loadNoise(source, field.dims);
  if (source.seedSpots > 0 || source.seedFraction > 0.0f || !source.file.empty())
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
    if (!source.resolution.empty()) return analyticResolutionError(source);
    LIC3D_TRY(checkHostMemory(source.grid));
    LIC3D_TRY_ASSIGN(inputs.series,
                     analyticSeries(*analytic, source.grid, options.analyticTimeSteps));
  } else if (!analytic && !parseEnum<AnalyticField2D>(source.field) &&
             isFieldSeriesPattern(source.field)) {
    if (options.gridGiven)
      return parameterError(
          "field.grid", "applies to analytic fields only; " + source.field + " has its own grid");
    if (!source.resolution.empty())
      return parameterError("field.resolution",
                            source.resolution + ": applies to one file, not to a time series");
    LIC3D_TRY_ASSIGN(inputs.series, fileSeries(source.field));
    inputs.fromFile = true;
  }
  if (analytic && !inputs.series && options.fieldOnDevice && isWhiteNoise(session.noise)) {
    LIC3D_TRY(checkAnalyticSource(source));
    inputs.field.dims = source.grid;
    inputs.field.geometry = analyticGeometry(*analytic, source.grid);
    inputs.noise.dims = source.grid;
    inputs.noise.type = NoiseType::UInt8;
    if (timePeriod(*analytic) > 0.0) inputs.sampled = analytic;
    inputs.device = AnalyticInputs{*analytic, source.grid, inputs.sampled ? session.time : 0.0,
                                   session.noise.seed};
    LIC3D_TRY(validate(session.lic.sparsity, inputs.field.dims));
    return inputs;
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
  const StageTimer timer("noise");
  LIC3D_TRY_ASSIGN(inputs.noise, loadNoise(session.noise, inputs.field));
  return inputs;
}

Result<SessionInputs> sessionInputsOf(const Session& session, VectorField field,
                                      std::optional<NoiseVolume> noise, const std::string& what) {
  SessionInputs inputs;
  inputs.time = session.time;
  inputs.fromFile = true;
  LIC3D_TRY(finishVectorField(what, field, &inputs.info));
  LIC3D_TRY_ASSIGN(inputs.field, atResolution(std::move(field), session.field));
  LIC3D_TRY(validate(session.lic.sparsity, inputs.field.dims));
  if (!noise) {
    const StageTimer timer("noise");
    LIC3D_TRY_ASSIGN(inputs.noise, loadNoise(session.noise, inputs.field));
  } else if (noise->dims != inputs.field.dims) {
    return inputError("noise: the noise grid " + gridText(noise->dims) +
                      " does not match the LIC grid " + gridText(inputs.field.dims));
  } else {
    // Checked and rescaled as a noise file's values are.
    if (auto r = finishFloatNoise(*noise); !r) return inputError("noise: " + r.error().message);
    inputs.noise = std::move(*noise);
  }
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
  if (inputs.device)
    return makeAnalyticField(inputs.device->field, inputs.device->dims,
                             inputs.sampled ? time : 0.0);
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
  if (inputs.device) {
    if (onHost)
      return inputError("the field is made on the device; the CPU reference needs it on the host");
    if (!first && (!inputs.sampled || time == inputs.time)) return {};
    inputs.time = time;
    if (inputs.sampled) inputs.device->time = time;
    return renderer.setAnalyticInputs(*inputs.device);
  }
  if (!inputs.sampled && !inputs.series) {
    if (first) return renderer.setInputs(inputs.field, inputs.noise);
    return {};
  }
  if (!first && time == inputs.time) return {};
  // loadSessionInputs made a sampled field at inputs.time: it is not made again (the tornado at
  // 512^3 took 1.3 s on 16 cores, twice).
  const bool current = first && time == inputs.time && inputs.sampled && !inputs.series;
  inputs.time = time;
  if (inputs.sampled || onHost) {
    if (!current) {
      LIC3D_TRY_ASSIGN(inputs.field, hostFieldAt(inputs, session, time));
      inputs.fieldStep.reset();
    }
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
  LIC3D_TRY(renderer.blendTime(b.first, b.second, b.weight));
  inputs.blendMs.push_back(renderer.lastBlendMilliseconds());
  return {};
}

}  // namespace lic3d
