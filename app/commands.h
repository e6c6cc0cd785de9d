#pragma once
// The subcommands. Each returns the process exit status.

#include <string>

#include "batch.h"
#include "cli_options.h"

namespace lic3d::cli {

struct BenchOptions {
  std::string field = "tornado";
  std::uint64_t seed = 1;
  FieldPrecision precision = FieldPrecision::Auto;
  std::string sizes = "64,128,256,512";
  std::string lengths = "10,20";
  std::string frameSizes = "512,1024,2048";
  int frameVolume = 256;
  int repeats = 7;
  int warmup = 2;
  double budgetSeconds = 120.0;
  std::string json;
  bool variants = false;       // specialized pipelines against runtime mode switches
  bool distributions = false;  // sparsity point generation and mask + LIC recompute
  bool kernels = false;        // the naive LIC kernel against each shipped one
  bool fidelity = false;       // each scheme's error against a converged LIC
  std::string fidelityFiles;   // fields judged besides the analytic ones (comma-separated)
  int distributionVolume = 256;
};

int runDevices(const GlobalOptions& global);
int runCompute(const GlobalOptions& global, const ComputeOptions& options,
               const BatchOptions& batch);
int runRender(const GlobalOptions& global, const ComputeOptions& options,
              const BatchOptions& batch);
// 2D LIC of a plane (thesis chapter 3): a PNG, or the frames of a bias or time animation.
int runRender2D(const GlobalOptions& global, const ComputeOptions& options,
                const BatchOptions& batch);
int runBench(const GlobalOptions& global, const BenchOptions& options);

}  // namespace lic3d::cli
