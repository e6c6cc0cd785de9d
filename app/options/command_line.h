// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The command line of `lic3d`: its subcommands, their flags and the checks of what they were
// given, apart from running anything, so that the program and the command-line fuzz target
// (tests/fuzz/fuzz_cli.cpp) parse alike.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "options/batch_options.h"
#include "options/bench_options.h"
#include "options/session_options.h"

namespace lic3d::cli {

// Every subcommand's options, filled by parseAndCheck, and which subcommand was given.
struct CommandLine {
  CommandLine();
  ~CommandLine();  // where CLI::App is whole
  std::unique_ptr<CLI::App> app;
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
