// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/loading.h"

#include <chrono>

namespace lic3d::viewer {
namespace {

template <class T>
bool ready(const std::future<T>& future) {
  return future.valid() && future.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
}

}  // namespace

void FieldLoader::start(const Session& session, bool gridGiven, int defaultTimeSteps) {
  Session wanted = session;
  wanted.lic.sparsity = SparsityParams{};  // checked against the grid by the app, once read
  // Only a field that changes with time becomes a series (a steady one ignores the steps).
  const auto analytic = parseEnum<AnalyticField>(session.field.field);
  const bool timeDependent = analytic && timePeriod(*analytic) > 0.0;
  const InputOptions options{.gridGiven = gridGiven,
                             .analyticTimeSteps = !timeDependent          ? 0
                                                  : session.timeSteps > 0 ? session.timeSteps
                                                                          : defaultTimeSteps};
  loading_ = std::async(std::launch::async, [wanted, options]() -> Result<Loaded> {
    Loaded loaded;
    LIC3D_TRY_ASSIGN(loaded.inputs, loadSessionInputs(wanted, options));
    const SessionInputs& inputs = loaded.inputs;
    if (!inputs.series) return loaded;
    // Both steps around the time, so the first picture needs no further read.
    loaded.bracket = inputs.series->bracket(wanted.time);
    loaded.steps.emplace_back(*inputs.fieldStep, inputs.field);
    if (loaded.bracket.second != loaded.bracket.first) {
      LIC3D_TRY_ASSIGN(VectorField second,
                       loadSeriesStep(*inputs.series, wanted.field.array, loaded.bracket.second,
                                      inputs.field.dims, inputs.field.geometry));
      loaded.steps.emplace_back(loaded.bracket.second, std::move(second));
    }
    return loaded;
  });
}

std::optional<Result<FieldLoader::Loaded>> FieldLoader::finished() {
  if (!ready(loading_)) return std::nullopt;
  return loading_.get();
}

Result<void> FieldLoader::show(const Loaded& loaded, LicRenderer& renderer) {
  series_ = loaded.inputs.series;
  grid_ = loaded.inputs.field.dims;
  geometry_ = loaded.inputs.field.geometry;
  blended_.reset();
  stepLoading_ = {};
  failedSteps_.clear();
  if (!series_) return renderer.setInputs(loaded.inputs.field, loaded.inputs.noise);
  LIC3D_TRY(renderer.setTimeNoise(loaded.inputs.noise));
  return uploadSteps(renderer, loaded.bracket, loaded.steps);
}

Result<bool> FieldLoader::updateTime(LicRenderer& renderer, const Session& session,
                                     std::string& message, std::uint64_t& stepReads) {
  if (!series_) return false;
  const TimeBracket b = series_->bracket(session.time);
  if (stepLoading_.valid()) {
    if (!ready(stepLoading_)) return false;
    Result<Steps> steps = stepLoading_.get();
    if (!steps) {
      message = steps.error().message;
      failedSteps_ = stepsLoading_;
      return false;
    }
    stepReads += steps->size();
    LIC3D_TRY(uploadSteps(renderer, b, *steps));
  }
  if (blended_ && *blended_ == b) return false;
  const std::vector<int> missing = missingSteps(renderer, b);
  if (!missing.empty()) {
    if (missing == failedSteps_) return false;  // the message says why; another time may work
    stepsLoading_ = missing;
    stepLoading_ = std::async(
        std::launch::async,
        [series = *series_, missing, grid = grid_, geometry = geometry_,
         array = session.field.array]() -> Result<Steps> {
          Steps steps;
          for (const int k : missing) {
            LIC3D_TRY_ASSIGN(VectorField step, loadSeriesStep(series, array, k, grid, geometry));
            steps.emplace_back(k, std::move(step));
          }
          return steps;
        });
    return false;
  }
  // The time moves on once the volume of the last blend is shown: a new blend restarts the LIC,
  // and where a volume takes more than a frame, blending every frame would never show one.
  if (blended_ && renderer.licStatus().pending) return false;
  if (auto r = renderer.blendTime(b.first, b.second, b.weight); !r) {
    message = r.error().message;
    return false;
  }
  blended_ = b;
  return true;
}

bool FieldLoader::timePending(double time) const {
  return series_ && (stepLoading_.valid() || !blended_ || !(*blended_ == series_->bracket(time)));
}

void FieldLoader::dropSeries() {
  if (stepLoading_.valid()) stepLoading_.wait();
  stepLoading_ = {};
  series_.reset();
  blended_.reset();
}

}  // namespace lic3d::viewer
