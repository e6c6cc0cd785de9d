// SPDX-License-Identifier: BSD-3-Clause
// lic3d: 3D Line Integral Convolution of vector fields with Vulkan, from the command line.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <new>
#include <string>
#include <vector>

#include "bench/bench.h"
#include "cli/commands.h"
#include "core/parallel.h"
#include "io/file_util.h"
#include "options/command_line.h"

using namespace lic3d::cli;

namespace {

// `lic3d view ...` runs the desktop app, a separate binary so that this one needs no window
// system. Global options may come before `view`.
int execViewer(int argc, char** argv, int viewIndex) {
  std::error_code ec;
  std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (ec) self = argv[0];
  const std::filesystem::path viewer = self.parent_path() / "lic3d-view";
  std::vector<char*> args;
  const std::string program = viewer.string();
  args.push_back(const_cast<char*>(program.c_str()));
  for (int i = 1; i < argc; ++i)
    if (i != viewIndex) args.push_back(argv[i]);
  args.push_back(nullptr);
  execv(program.c_str(), args.data());
  std::fprintf(stderr,
               "lic3d: error: cannot start %s (%s): the desktop app is built with GLFW and Dear "
               "ImGui next to lic3d\n",
               program.c_str(), std::strerror(errno));
  return kExitFailure;
}

// The index of the subcommand `view` if it is the command given, else 0.
int findViewCommand(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--device") {
      ++i;  // its value
      continue;
    }
    if (!arg.empty() && arg[0] == '-') continue;
    return arg == "view" ? i : 0;
  }
  return 0;
}

// What lic3d writes to stdout (help, the device list, the summary line scripts read) must
// arrive: a closed or full stdout turns a successful run into a failure.
int checkStdout(int status) {
  std::cout.flush();
  const bool failed = !std::cout || std::fflush(stdout) != 0 || std::ferror(stdout);
  if (!failed || status != kExitOk) return status;
  std::fprintf(stderr, "lic3d: error: cannot write to standard output: %s\n",
               std::strerror(errno != 0 ? errno : EIO));
  return kExitFailure;
}

int run(int argc, char** argv) {
  // No output of a run may replace one of its inputs (docs/RELIABILITY.md, "Output files").
  lic3d::guardInputsFromWrites(true);

  const std::unique_ptr<CommandLine> line = makeCommandLine();
  if (const std::optional<int> status = parseAndCheck(*line, argc, argv)) return *status;
  const GlobalOptions& global = line->global;
  lic3d::setThreadLimit(global.threads);

  try {
    const CommandLine& l = *line;
    if (l.devices->parsed()) return runDevices(global);
    if (l.computeCommand->parsed()) return runCompute(global, l.compute, l.computeBatch);
    if (l.renderCommand->parsed()) return runRender(global, l.render, l.renderBatch);
    if (l.render2dCommand->parsed()) return runRender2D(global, l.render2d, l.render2dBatch);
    if (l.benchCommand->parsed()) return runBench(global, l.bench);
  } catch (const std::bad_alloc&) {
    // Output files are written under temporary names, so nothing partial is left behind.
    std::fprintf(stderr, "lic3d: error: out of host memory\n");
    return kExitFailure;
  }
  return kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  if (const int view = findViewCommand(argc, argv)) return execViewer(argc, argv, view);
  return checkStdout(run(argc, argv));
}
