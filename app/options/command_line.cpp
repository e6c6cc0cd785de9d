// SPDX-License-Identifier: BSD-3-Clause
#include "options/command_line.h"

#include "options/flags.h"

namespace lic3d::cli {

CommandLine::CommandLine() : app(std::make_unique<CLI::App>()) {}
CommandLine::~CommandLine() = default;

std::unique_ptr<CommandLine> makeCommandLine() {
  auto line = std::make_unique<CommandLine>();
  CLI::App& app = *line->app;
  app.description(
      "lic3d: 3D Line Integral Convolution of vector fields with Vulkan.\n"
      "Computes a LIC volume on the GPU (or the CPU) and renders it with blended slices.");
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

  GlobalOptions& global = line->global;
  addGlobalOptions(app, global);

  line->devices = app.add_subcommand("devices", "List the Vulkan devices lic3d can use");
  app.add_subcommand("view",
                     "Open the interactive desktop app (lic3d-view) with the render options");

  const std::string summaryNote =
      " On success the last line on stdout is `lic3d-summary {JSON}` (docs/BATCH.md).";

  ComputeOptions& compute = line->compute;
  BatchOptions& computeBatch = line->computeBatch;
  CLI::App* computeCommand = line->computeCommand = app.add_subcommand(
      "compute",
      "Compute a LIC volume and write it as float32 NRRD, VTK image data (.vti) or OpenVDB "
      "(.vdb), or one slice of it as a 16-bit PNG");
  addComputeOptions(*computeCommand, compute, "lic3d.nrrd");
  compute.inputs.colorBy = computeCommand->add_option(
      "--color-by", compute.inputs.session.view.colorBy,
      "With -o FILE.vdb: a scalar written as a further grid of its name, as render colours "
      "by it: vorticity, helicity, a scalar array of the field's file, or a scalar .nrrd on "
      "the field's grid (speed is always written)");
  addComputeBatchOptions(*computeCommand, computeBatch);
  computeCommand->footer(globalNote + summaryNote);

  ComputeOptions& render = line->render;
  BatchOptions& renderBatch = line->renderBatch;
  CLI::App* renderCommand = line->renderCommand = app.add_subcommand(
      "render", "Compute a LIC volume and render it to a PNG image, or the frames of an animation");
  addComputeOptions(*renderCommand, render, "lic3d.png");
  addLookOption(*renderCommand, render.inputs);
  addViewOptions(*renderCommand, render.inputs);
  addRenderBatchOptions(*renderCommand, renderBatch);
  renderCommand->footer(globalNote + summaryNote);

  ComputeOptions& render2d = line->render2d;
  BatchOptions& render2dBatch = line->render2dBatch;
  PlaneOptions& plane = line->plane;
  CLI::App* render2dCommand = line->render2dCommand = app.add_subcommand(
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

  BenchOptions& bench = line->bench;
  CLI::App* benchCommand = line->benchCommand = app.add_subcommand(
      "bench", "Time the LIC pass and frames with GPU timestamps (median of repeats)");
  benchCommand->add_option("--field", bench.field, "Analytic field to time")->capture_default_str();
  benchCommand->add_option("--seed", bench.seed, "Seed of the white noise")
      ->check(wholeNumberText())
      ->capture_default_str();
  addEnumOption(*benchCommand, "--field-precision", bench.precision,
                "Field texture precision: auto (float on CPU drivers, half on GPUs)");
  benchCommand
      ->add_option(
          "--sizes", bench.sizes,
          "Volume sizes N (N^3) of the LIC table; one larger than the device is made in bricks, "
          "once (docs/SCALE.md)")
      ->capture_default_str();
  benchCommand->add_option("--lengths", bench.lengths, "LIC lengths L of the LIC table")
      ->capture_default_str();
  benchCommand
      ->add_option("--frame-sizes", bench.frameSizes, "Square image sizes of the frame table")
      ->capture_default_str();
  benchCommand->add_option("--frame-volume", bench.frameVolume, "Volume size N of the frame table")
      ->check(rangeCheck(4, 2048))
      ->capture_default_str();
  benchCommand
      ->add_option("--frame-buffers", bench.frameBuffers,
                   "Colour buffers of the frame table: rgba16f, rgba16, rgb10a2, rgba8")
      ->capture_default_str();
  benchCommand
      ->add_option("--frame-looks", bench.frameLooks,
                   "Views of the frame table: plain (no halos, the view's defaults) and default "
                   "(the default look, with halos)")
      ->capture_default_str();
  benchCommand
      ->add_option("--slices-per-fragment", bench.slicesPerFragment,
                   "Slices composited per fragment (K) of the frame table's rows: 1, 2, 4, or 0 "
                   "for the device's choice")
      ->capture_default_str();
  benchCommand->add_option("--repeats", bench.repeats, "Timed repeats per row (median reported)")
      ->check(rangeCheck(5, 1000))
      ->capture_default_str();
  benchCommand->add_option("--warmup", bench.warmup, "Untimed runs before the repeats")
      ->check(rangeCheck(1, 100))
      ->capture_default_str();
  benchCommand
      ->add_option("--budget", bench.budgetSeconds,
                   "Seconds the whole benchmark may take; rows that would exceed it are "
                   "skipped")
      ->check(rangeCheck(1.0, 86400.0))
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
  benchCommand->add_flag(
      "--visible", bench.visible,
      "Instead: the full LIC pass against visible work (classification of the bricks the view "
      "can show + LIC over them, docs/VISIBLE_WORK.md) for the default look and a clip plane "
      "removing half the box: the analytic --field at each of --sizes, or --visible-files");
  benchCommand->add_option("--visible-files", bench.visibleFiles,
                           "Comma-separated field files that --visible times instead");
  benchCommand
      ->add_option("--resolution", bench.resolution,
                   "Grid of the --visible-files, as render's --resolution (e.g. 2x)")
      ->capture_default_str();
  benchCommand->add_flag("--drag", bench.drag,
                         "Instead: the app's frames while a LIC slider is dragged, offscreen: per "
                         "frame the LIC length one step on, the LIC job the app records (coarse "
                         "at the stride it picks from the full LIC's time) and the slices; median "
                         "and 95th percentile frame time for --sizes, at the first of --lengths");
  benchCommand->add_option("--drag-picture", bench.dragPicture, "Square picture size of --drag")
      ->check(rangeCheck(16, 16384))
      ->capture_default_str();
  benchCommand->add_option("--drag-slices", bench.dragSlices, "Slices drawn by --drag")
      ->check(rangeCheck(1, 4096))
      ->capture_default_str();
  benchCommand->add_option("--drag-frames", bench.dragFrames, "Frames --drag times")
      ->check(rangeCheck(10, 100000))
      ->capture_default_str();
  benchCommand->add_option(
      "--read-field", bench.readField,
      "Instead: the rates at which this field file (raw, raw NRRD, appended-raw VTI) is read "
      "brick by brick: the scan for its largest |u| and the reads by z-slabs and by bricks, in "
      "GB/s of the file's bytes from the page cache after a warm-up read, then one brick's noise "
      "and texel packing; wall clock, median of --repeats");
  benchCommand
      ->add_option("--write-dir", bench.writeDir,
                   "A size larger than the device (made in bricks) is also written as a NRRD "
                   "into this folder (removed after), for the write rate")
      ->check(CLI::ExistingDirectory);
  benchCommand
      ->add_option("--distribution-volume", bench.distributionVolume,
                   "Volume size N (N^3) of --distributions")
      ->check(rangeCheck(8, 1024))
      ->capture_default_str();
  benchCommand->footer(globalNote);

  return line;
}

std::optional<int> parseAndCheck(CommandLine& line, int argc, char** argv) {
  // A session file is read before the flags, which then override it.
  if (const std::optional<int> status = parseCommandLine(
          *line.app, argc, argv, "lic3d", "Run `lic3d --help` or `lic3d <command> --help`.",
          {&line.compute.inputs, &line.render.inputs, &line.render2d.inputs}))
    return *status;
  if (Result<void> checked = finishCommand(line); !checked) return reportError(checked.error());
  return std::nullopt;
}

Result<void> finishCommand(CommandLine& line) {
  Result<void> checked;
  if (line.computeCommand->parsed()) checked = finishSessionOptions(line.compute.inputs, false);
  if (line.renderCommand->parsed()) checked = finishSessionOptions(line.render.inputs, true);
  if (line.render2dCommand->parsed()) {
    line.render2d.inputs.session.twoD = true;
    checked = finishPlaneOptions(line.plane, line.render2d.inputs.session);
    if (checked) checked = finishSessionOptions(line.render2d.inputs, true);
  }
  return checked;
}

}  // namespace lic3d::cli
