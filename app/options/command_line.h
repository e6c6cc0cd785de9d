// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The command line of `lic3d`: its subcommands, their flags and the checks of what they were
// given, apart from running anything, so that the program and the command-line fuzz target
// (tests/fuzz/fuzz_cli.cpp) parse alike.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "options/batch_options.h"
#include "options/session_options.h"

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

// Every subcommand's options, filled by parseAndCheck, and which subcommand was given.
struct CommandLine {
  CLI::App app;
  GlobalOptions global;
  ComputeOptions compute;
  BatchOptions computeBatch;
  ComputeOptions render;
  BatchOptions renderBatch;
  ComputeOptions render2d;
  BatchOptions render2dBatch;
  PlaneOptions plane;
  BenchOptions bench;
  CLI::App* devices = nullptr;
  CLI::App* computeCommand = nullptr;
  CLI::App* renderCommand = nullptr;
  CLI::App* render2dCommand = nullptr;
  CLI::App* benchCommand = nullptr;
};

// Declares every subcommand and flag (a CLI::App cannot move, hence the pointer).
std::unique_ptr<CommandLine> makeCommandLine();

// Parses `argv` (the session files it names first, the flags over them) and finishes the
// session options of the subcommand given. Nothing when that subcommand should run; else the
// exit status: 0 when help or the version was printed, kExitBadInput when a flag or value was
// refused (the message printed, naming it).
std::optional<int> parseAndCheck(CommandLine& line, int argc, char** argv);

// The second half of parseAndCheck, for front ends that parse with parseArguments: finishes the
// session options of the subcommand given (InvalidInput naming the flag).
Result<void> finishCommand(CommandLine& line);

}  // namespace lic3d::cli
