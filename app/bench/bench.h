// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the `lic3d bench` modes share (bench.cpp, kernels.cpp, fidelity.cpp).

#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "core/error.h"
#include "gpu/vulkan_context.h"
#include "options/bench_options.h"
#include "options/session_options.h"

namespace lic3d::cli {

// `lic3d bench`: GPU timings (timestamp queries) of the passes, kernels and schemes.
int runBench(const GlobalOptions& global, const BenchOptions& options);

struct Timing {
  bool measured = false;
  std::string skipped;  // why not, when !measured
  double medianMs = 0.0;
  double minMs = 0.0;
  int repeats = 0;
};

// Runs `once` (which returns GPU milliseconds) for warm-up, then options.repeats times; gives up
// early when the warm-up shows the repeats would not fit in the remaining budget.
Result<Timing> measure(const BenchOptions& options, double& budgetLeft,
                       const std::function<Result<double>()>& once);

// Today's date, UTC, as YYYY-MM-DD.
std::string today();

// What every report starts with: the device, its driver and the date (UTC).
nlohmann::json newReport(const Context& context);

// `bench --kernels`: the naive kernel and every shipped one, the masked pass, the launch shapes.
// A LIC larger than the device, made in bricks as `lic3d compute` makes it: its LIC rate and the
// host path's rates (bricked.cpp).
Result<nlohmann::json> benchBricked(const Context& context, const BenchOptions& options, int n,
                                    int length);

Result<nlohmann::json> runKernelBenchmarks(const Context& context, const BenchOptions& options);

// `bench --visible`: the full LIC pass against classification + LIC of the visible bricks.
Result<nlohmann::json> runVisibleBenchmarks(const Context& context, const BenchOptions& options);
// `bench --drag`: the app's frames while a LIC slider is dragged (bench/drag.cpp).
Result<nlohmann::json> runDragBenchmarks(const Context& context, const BenchOptions& options);

// `bench --read-field FILE`: the scan and piece-read rates of a streamed field file, and one
// brick's noise and packing (bench/read_rate.cpp).
Result<nlohmann::json> runReadRateBenchmarks(const Context& context, const BenchOptions& options);

// `bench --fidelity`: each RK2 scheme's error against a converged LIC, on the CPU and the device.
Result<nlohmann::json> runFidelityBenchmarks(const Context& context, const BenchOptions& options);

}  // namespace lic3d::cli
