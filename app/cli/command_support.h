// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the subcommands share: their devices, inputs, messages and summary line.

#include <chrono>
#include <optional>
#include <string>
#include <vector>

#include "cli/batch.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"
#include "loading/session_inputs.h"
#include "options/session_options.h"

namespace lic3d::cli {

using Clock = std::chrono::steady_clock;

// The device of --device.
Result<Context> openContext(const GlobalOptions& global);
// --devices: the contexts of the devices named (of --device alone when empty), in that order.
Result<std::vector<Context>> openContexts(const GlobalOptions& global, const std::string& devices);
// "NVIDIA H100" or "2 devices (NVIDIA H100, NVIDIA H100)".
std::string devicesText(const std::vector<Context>& contexts);
std::vector<const Context*> pointersTo(const std::vector<Context>& contexts);
// With validation on, any message fails the command even if it otherwise succeeded.
int finish(const Context& context, int status);
int finish(const std::vector<Context>& contexts, int status);

// --time given for a field that has none is a mistake worth naming.
Result<void> checkTimeGiven(const SessionOptions& options, const TimeDomain& domain);
// `fieldOnDevice`: the run needs no host copy of an analytic field (InputOptions::fieldOnDevice).
Result<SessionInputs> loadInputs(const ComputeOptions& options, bool fieldOnDevice);
// What a file gave besides the field: which of several arrays was read, and vectors lost to NaN.
void reportFieldFile(const GlobalOptions& global, const FieldSource& source,
                     const SessionInputs& inputs);
// "tornado 64x64x64, spacing .., origin .." for the messages.
std::string fieldText(const FieldSource& source, const SessionInputs& inputs);
RunSummary makeSummary(const char* command, const FieldSource& source, const SessionInputs& inputs);
void noteHiddenFraction(const GlobalOptions& global, const LicParams& lic,
                        std::optional<double> hidden, RunSummary& summary);
std::optional<double> hiddenFractionOf(const ScalarVolume& volume);
void printSummary(const GlobalOptions& global, RunSummary summary, Clock::time_point start);
Result<ScalarVolume> computeOnCpu(const SessionInputs& inputs, const LicParams& lic, bool quiet);

}  // namespace lic3d::cli
