// lic3d: 3D Line Integral Convolution of vector fields with Vulkan, from the command line.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <new>
#include <string>
#include <vector>

#include "cli_options.h"
#include "commands.h"
#include "core/parallel.h"
#include "io/file_util.h"

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

}  // namespace

int main(int argc, char** argv) {
  if (const int view = findViewCommand(argc, argv)) return execViewer(argc, argv, view);
  // No output of a run may replace one of its inputs (docs/RELIABILITY.md, "Output files").
  lic3d::guardInputsFromWrites(true);

  CLI::App app{
      "lic3d: 3D Line Integral Convolution of vector fields with Vulkan.\n"
      "Computes a LIC volume on the GPU (or the CPU) and renders it with blended slices."};
  app.set_version_flag("--version", kVersionText);
  app.require_subcommand(1);
  app.fallthrough();
  app.footer(
      "Exit status: 0 success, 1 failure (no device, GPU error), 2 bad arguments or input "
      "files, 3 not enough memory for the request.");
  const std::string globalNote =
      "Global options (--device, --validation, --quiet) may also follow the command. Exit "
      "status: 0 success, 1 failure, 2 bad arguments or input files, 3 not enough memory for "
      "the request.";

  GlobalOptions global;
  addGlobalOptions(app, global);

  CLI::App* devices = app.add_subcommand("devices", "List the Vulkan devices lic3d can use");
  app.add_subcommand("view",
                     "Open the interactive desktop app (lic3d-view) with the render options");

  const std::string summaryNote =
      " On success the last line on stdout is `lic3d-summary {JSON}` (docs/BATCH.md).";

  ComputeOptions compute;
  BatchOptions computeBatch;
  CLI::App* computeCommand = app.add_subcommand(
      "compute",
      "Compute a LIC volume and write it as float32 NRRD or VTK image data (.vti), "
      "or one slice of it as a 16-bit PNG");
  addComputeOptions(*computeCommand, compute, "lic3d.nrrd");
  addComputeBatchOptions(*computeCommand, computeBatch);
  computeCommand->footer(globalNote + summaryNote);

  ComputeOptions render;
  BatchOptions renderBatch;
  CLI::App* renderCommand = app.add_subcommand(
      "render", "Compute a LIC volume and render it to a PNG image, or the frames of an animation");
  addComputeOptions(*renderCommand, render, "lic3d.png");
  addLookOption(*renderCommand, render.inputs);
  addViewOptions(*renderCommand, render.inputs);
  addRenderBatchOptions(*renderCommand, renderBatch);
  renderCommand->footer(globalNote + summaryNote);

  ComputeOptions render2d;
  BatchOptions render2dBatch;
  PlaneOptions plane;
  CLI::App* render2dCommand = app.add_subcommand(
      "render2d",
      "2D LIC (thesis chapter 3): a 2D field (circle, saddle, the time-varying wave, a 2D file) or "
      "a plane of a 3D field, white noise at the image's resolution, a PNG out; or the frames "
      "of a bias or time animation");
  addInputOptions(*render2dCommand, render2d.inputs, true, false);
  render2dCommand->add_flag("--cpu", render2d.cpu,
                            "Compute the LIC image with the CPU reference instead of the GPU");
  render2d.output = "lic2d.png";
  render2d.outputOption =
      render2dCommand
          ->add_option("-o,--output", render2d.output,
                       "Output PNG; for --animate-bias or --animate-time a pattern with one %d "
                       "or %0Nd for the frame number (default then lic2d_%04d.png)")
          ->capture_default_str();
  addPlaneOptions(*render2dCommand, render2d.inputs, plane);
  addImageBatchOptions(*render2dCommand, render2dBatch);
  render2dCommand->footer(globalNote + summaryNote);

  BenchOptions bench;
  CLI::App* benchCommand = app.add_subcommand(
      "bench", "Time the LIC pass and frames with GPU timestamps (median of repeats)");
  benchCommand->add_option("--field", bench.field, "Analytic field to time")->capture_default_str();
  benchCommand->add_option("--seed", bench.seed, "Seed of the white noise")
      ->check(wholeNumberText())
      ->capture_default_str();
  addEnumOption(*benchCommand, "--field-precision", bench.precision,
                "Field texture precision: auto (float on CPU drivers, half on GPUs)");
  benchCommand->add_option("--sizes", bench.sizes, "Volume sizes N (N^3) of the LIC table")
      ->capture_default_str();
  benchCommand->add_option("--lengths", bench.lengths, "LIC lengths L of the LIC table")
      ->capture_default_str();
  benchCommand
      ->add_option("--frame-sizes", bench.frameSizes, "Square image sizes of the frame table")
      ->capture_default_str();
  benchCommand->add_option("--frame-volume", bench.frameVolume, "Volume size N of the frame table")
      ->check(CLI::Range(4, 2048))
      ->capture_default_str();
  benchCommand->add_option("--repeats", bench.repeats, "Timed repeats per row (median reported)")
      ->check(CLI::Range(5, 1000))
      ->capture_default_str();
  benchCommand->add_option("--warmup", bench.warmup, "Untimed runs before the repeats")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  benchCommand
      ->add_option("--budget", bench.budgetSeconds,
                   "Seconds the whole benchmark may take; rows that would exceed it are "
                   "skipped")
      ->check(CLI::Range(1.0, 86400.0))
      ->capture_default_str();
  benchCommand->add_option("--json", bench.json, "Also write the results as JSON");
  benchCommand->add_flag("--variants", bench.variants,
                         "Instead: frame time of specialized pipelines against one shader with "
                         "runtime mode switches, for several display modes (thesis Table 6.1)");
  benchCommand->add_flag("--distributions", bench.distributions,
                         "Instead: time of each sparsity distribution for 1k..1M points, and of a "
                         "sparsity change end to end (thesis Figure 6.4)");
  benchCommand->add_flag("--kernels", bench.kernels,
                         "Instead: the naive reference LIC kernel (three texture fetches per "
                         "sample) against each shipped kernel (exact, ab2 and fused schemes; half, "
                         "float and byte textures) in one process, for --sizes x --lengths: "
                         "median times, speed-ups, correlations of the volumes, fetch rates; "
                         "then the masked (sparsity) pass against the unmasked one and the "
                         "workgroup shapes and walks, at the last length");
  benchCommand->add_flag("--fidelity", bench.fidelity,
                         "Instead: each RK2 scheme's error against a converged LIC (RK4 at h/8 on "
                         "the CPU) on the analytic fields at the first of --sizes and on "
                         "--fidelity-files, for the CPU reference and each field texture");
  benchCommand->add_option("--fidelity-files", bench.fidelityFiles,
                           "Comma-separated field files that --fidelity judges too");
  benchCommand
      ->add_option("--distribution-volume", bench.distributionVolume,
                   "Volume size N (N^3) of --distributions")
      ->check(CLI::Range(8, 1024))
      ->capture_default_str();
  benchCommand->footer(globalNote);

  // A session file is read before the flags, which then override it.
  if (const std::optional<int> status = parseCommandLine(
          app, argc, argv, "lic3d", "Run `lic3d --help` or `lic3d <command> --help`.",
          {&compute.inputs, &render.inputs, &render2d.inputs}))
    return *status;
  lic3d::setThreadLimit(global.threads);

  try {
    if (devices->parsed()) return runDevices(global);
    if (computeCommand->parsed()) {
      if (auto r = finishSessionOptions(compute.inputs, false); !r) return reportError(r.error());
      return runCompute(global, compute, computeBatch);
    }
    if (renderCommand->parsed()) {
      if (auto r = finishSessionOptions(render.inputs, true); !r) return reportError(r.error());
      return runRender(global, render, renderBatch);
    }
    if (render2dCommand->parsed()) {
      render2d.inputs.session.twoD = true;
      if (auto r = finishPlaneOptions(plane, render2d.inputs.session); !r)
        return reportError(r.error());
      if (auto r = finishSessionOptions(render2d.inputs, true); !r) return reportError(r.error());
      return runRender2D(global, render2d, render2dBatch);
    }
    if (benchCommand->parsed()) return runBench(global, bench);
  } catch (const std::bad_alloc&) {
    // Output files are written under temporary names, so nothing partial is left behind.
    std::fprintf(stderr, "lic3d: error: out of host memory\n");
    return kExitFailure;
  }
  return kExitBadInput;
}
