// lic3d: 3D Line Integral Convolution of vector fields with Vulkan, from the command line.
#include <cstdio>
#include <new>

#include <CLI/CLI.hpp>

#include "cli_options.h"
#include "commands.h"

using namespace lic3d::cli;

int main(int argc, char** argv) {
  CLI::App app{"lic3d: 3D Line Integral Convolution of vector fields with Vulkan.\n"
               "Computes a LIC volume on the GPU (or the CPU) and renders it with blended slices."};
  app.set_version_flag("--version", "lic3d 0.1.0");
  app.require_subcommand(1);
  app.fallthrough();
  app.footer("Exit status: 0 success, 1 failure (no device, GPU error), 2 bad arguments or input "
             "files.");
  const char* globalNote =
      "Global options (--device, --validation, --quiet) may also follow the command. Exit "
      "status: 0 success, 1 failure, 2 bad arguments or input files.";

  GlobalOptions global;
  addGlobalOptions(app, global);

  CLI::App* devices = app.add_subcommand("devices", "List the Vulkan devices lic3d can use");

  ComputeOptions compute;
  CLI::App* computeCommand =
      app.add_subcommand("compute", "Compute a LIC volume and write it as float32 NRRD");
  addComputeOptions(*computeCommand, compute, "lic3d.nrrd");
  computeCommand->footer(globalNote);

  RenderOptions render;
  CLI::App* renderCommand =
      app.add_subcommand("render", "Compute a LIC volume and render it to a PNG image");
  addComputeOptions(*renderCommand, render.compute, "lic3d.png");
  addViewOptions(*renderCommand, render);
  renderCommand->footer(globalNote);

  BenchOptions bench;
  CLI::App* benchCommand = app.add_subcommand(
      "bench", "Time the LIC pass and frames with GPU timestamps (median of repeats)");
  addFieldOptions(*benchCommand, bench.input);
  addPrecisionOption(*benchCommand, bench.precision);
  benchCommand->add_option("--sizes", bench.sizes, "Volume sizes N (N^3) of the LIC table")
      ->capture_default_str();
  benchCommand->add_option("--lengths", bench.lengths, "LIC lengths L of the LIC table")
      ->capture_default_str();
  benchCommand->add_option("--frame-sizes", bench.frameSizes, "Square image sizes of the frame table")
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
  benchCommand->add_option("--budget", bench.budgetSeconds,
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
  benchCommand->add_option("--distribution-volume", bench.distributionVolume,
                           "Volume size N (N^3) of --distributions")
      ->check(CLI::Range(8, 1024))
      ->capture_default_str();
  benchCommand->footer(globalNote);

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "lic3d: error: %s\nRun `lic3d --help` or `lic3d <command> --help`.\n",
                 e.what());
    return kExitBadInput;
  }

  try {
    if (devices->parsed()) return runDevices(global);
    if (computeCommand->parsed()) return runCompute(global, compute);
    if (renderCommand->parsed()) {
      if (auto r = finishViewOptions(render); !r) return reportError(r.error());
      return runRender(global, render);
    }
    if (benchCommand->parsed()) return runBench(global, bench);
  } catch (const std::bad_alloc&) {
    // Output files are written under temporary names, so nothing partial is left behind.
    std::fprintf(stderr, "lic3d: error: out of host memory\n");
    return kExitFailure;
  }
  return kExitBadInput;
}
