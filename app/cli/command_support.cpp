// SPDX-License-Identifier: BSD-3-Clause
#include "cli/command_support.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <future>
#include <map>
#include <optional>

#include "core/memory_budget.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "core/text.h"
#include "gpu/device_choice.h"
#include "gpu/timer.h"
#include "gpu/vulkan_context.h"
#include "io/file_util.h"
#include "io/png_writer.h"
#include "jobs/bricks.h"
#include "lic/analytic_fields.h"
#include "lic/colouring.h"
#include "lic/derived_fields.h"
#include "lic/field_plane.h"
#include "lic/lic2d_reference.h"
#include "lic/lic_reference.h"
#include "lic/time_series.h"
#include "loading/plane_inputs.h"
#include "loading/scalars.h"
#include "options/progress.h"
#include "passes/lic2d_pass.h"
#include "passes/time_blend_pass.h"
#include "render/lic_renderer.h"

namespace lic3d::cli {

Result<Context> openContext(const GlobalOptions& global) {
  ContextOptions options;
  options.validation = global.validation;
  options.device = global.device;
  const StageTimer timer("device");
  return Context::create(options);
}

// --devices: the contexts of the devices named (of --device alone when empty), in that order.
Result<std::vector<Context>> openContexts(const GlobalOptions& global, const std::string& devices) {
  std::vector<Context> contexts;
  if (devices.empty()) {
    LIC3D_TRY_ASSIGN(Context context, openContext(global));
    contexts.push_back(std::move(context));
    return contexts;
  }
  if (!global.device.empty())
    return inputError("--device " + global.device + " --devices " + devices +
                      ": give one device (--device) or several (--devices), not both");
  LIC3D_TRY_ASSIGN(const std::vector<DeviceInfo> listed, listDevices());
  Result<std::vector<int>> chosen = chooseDevices(listed, devices);
  if (!chosen) return inputError("--" + chosen.error().message);
  for (const int index : *chosen) {
    GlobalOptions one = global;
    one.device = std::to_string(index);
    LIC3D_TRY_ASSIGN(Context context, openContext(one));
    contexts.push_back(std::move(context));
  }
  return contexts;
}

// "NVIDIA H100" or "2 devices (NVIDIA H100, NVIDIA H100)".
std::string devicesText(const std::vector<Context>& contexts) {
  if (contexts.size() == 1) return contexts.front().deviceInfo().name;
  std::string names;
  for (const Context& context : contexts)
    names += (names.empty() ? "" : ", ") + context.deviceInfo().name;
  return std::to_string(contexts.size()) + " devices (" + names + ")";
}

std::vector<const Context*> pointersTo(const std::vector<Context>& contexts) {
  std::vector<const Context*> pointers;
  for (const Context& context : contexts) pointers.push_back(&context);
  return pointers;
}

// With validation on, any message fails the command even if it otherwise succeeded.
int finish(const Context& context, int status) {
  if (context.validationEnabled() && context.validationMessageCount() > 0) {
    std::fprintf(stderr, "lic3d: error: %zu validation message(s)\n",
                 context.validationMessageCount());
    return status == kExitOk ? kExitFailure : status;
  }
  return status;
}

int finish(const std::vector<Context>& contexts, int status) {
  for (const Context& context : contexts) status = finish(context, status);
  return status;
}

// --time given for a field that has none is a mistake worth naming.
Result<void> checkTimeGiven(const SessionOptions& options, const TimeDomain& domain) {
  if (given(options.time) && !domain.timeDependent)
    return inputError("--time: " + options.session.field.field +
                      " does not change with time (the tornado, the 2D wave and series of files "
                      "do)");
  return {};
}

// `fieldOnDevice`: the run needs no host copy of an analytic field (InputOptions::fieldOnDevice).
Result<SessionInputs> loadInputs(const ComputeOptions& options, bool fieldOnDevice) {
  const Session& session = options.inputs.session;
  if (session.twoD)
    return inputError(
        "this session is a 2D one (mode 2d): make it with `lic3d render2d --session`");
  LIC3D_TRY_ASSIGN(const TimeDomain domain, timeDomainOf(session));
  LIC3D_TRY(checkTimeGiven(options.inputs, domain));
  Result<SessionInputs> inputs =
      loadSessionInputs(session, {.gridGiven = options.inputs.grid.given(),
                                  .analyticTimeSteps = session.timeSteps,
                                  .fieldOnDevice = fieldOnDevice});
  if (!inputs) return fromSessionFile(inputs.error(), options.inputs);
  return inputs;
}

// What a file gave besides the field: which of several arrays was read, and vectors lost to NaN.
void reportFieldFile(const GlobalOptions& global, const FieldSource& source,
                     const SessionInputs& inputs) {
  const FieldReadInfo& info = inputs.info;
  if (info.nonFiniteVectors > 0)
    std::fprintf(stderr,
                 "lic3d: warning: %s: %zu vector(s) with a NaN or infinite component were read "
                 "as zero (streamlines stop there)\n",
                 source.field.c_str(), info.nonFiniteVectors);
  if (global.quiet || !source.array.empty() || info.arrayNames.size() < 2) return;
  std::string others;
  for (const std::string& name : info.arrayNames)
    if (name != info.arrayName) others += (others.empty() ? "'" : ", '") + name + "'";
  std::fprintf(stderr,
               "lic3d: %s has %zu vector arrays: read '%s'; the others are %s (choose one with "
               "--array NAME)\n",
               source.field.c_str(), info.arrayNames.size(), info.arrayName.c_str(),
               others.c_str());
}

// "tornado 128x128x128", or for a file its array, grid, spacing and origin.
std::string fieldText(const FieldSource& source, const SessionInputs& inputs) {
  const VectorField& field = inputs.field;
  if (!inputs.fromFile) return source.field + " " + gridText(field.dims);
  std::string text = inputs.series ? inputs.series->describe() : source.field;
  if (!inputs.info.arrayName.empty()) text += " array '" + inputs.info.arrayName + "'";
  return text + " " + gridText(field.dims) + ", spacing " +
         tripleText(field.geometry.spacing, ",") + ", origin " +
         tripleText(field.geometry.origin, ",");
}

RunSummary makeSummary(const char* command, const FieldSource& source,
                       const SessionInputs& inputs) {
  RunSummary summary;
  summary.command = command;
  summary.field = source.field;
  summary.array = inputs.info.arrayName;
  summary.grid = inputs.field.dims;
  summary.geometry = inputs.field.geometry;
  summary.nonFiniteVectors = inputs.info.nonFiniteVectors;
  return summary;
}

// The fraction of the voxels that sparsity hid, reported on stderr and in the summary.
void noteHiddenFraction(const GlobalOptions& global, const LicParams& lic,
                        std::optional<double> hidden, RunSummary& summary) {
  if (lic.sparsity.distribution == SparsityDistribution::None || !hidden) return;
  summary.hiddenFraction = hidden;
  if (global.quiet) return;
  std::fprintf(
      stderr, "lic3d: sparsity (%s%s) hid %.1f %% of the voxels\n",
      std::string(enumName(lic.sparsity.distribution)).c_str(),
      lic.sparsity.amount > 0.0f ? (", amount " + formatNumber(lic.sparsity.amount)).c_str() : "",
      100.0 * *hidden);
}

std::optional<double> hiddenFractionOf(const ScalarVolume& volume) {
  if (volume.drawn.empty()) return std::nullopt;
  const auto drawn = std::count(volume.drawn.begin(), volume.drawn.end(), 1);
  return 1.0 - static_cast<double>(drawn) / static_cast<double>(volume.drawn.size());
}

void printSummary(const GlobalOptions& global, RunSummary summary, Clock::time_point start) {
  summary.seconds = secondsSince(start);
  summary.timings = stageTimings();
  if (global.timings) printTimings(summary.seconds);
  if (global.quiet) return;
  std::printf("%s\n", summaryLine(summary).c_str());
  std::fflush(stdout);
}

Result<ScalarVolume> computeOnCpu(const SessionInputs& inputs, const LicParams& lic, bool quiet) {
  Progress progress("LIC " + gridText(inputs.field.dims) + " on the CPU", quiet);
  return computeLicReference(inputs.field, inputs.noise, lic, 0,
                             [&](double f) { progress.update(f); });
}

}  // namespace lic3d::cli
