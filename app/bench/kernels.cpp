// SPDX-License-Identifier: BSD-3-Clause
// `lic3d bench --kernels`: every LIC kernel lic3d ships against the naive reference kernel, the
// masked (sparsity) pass against the unmasked one, and the launch shapes, in one process on the
// same field and noise: ratios hold on machines whose absolute speed varies from run to run.
#include <algorithm>
#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "bench/bench.h"
#include "core/volume_compare.h"
#include "gpu/shader_library.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "render/lic_renderer.h"

namespace lic3d::cli {
namespace {

// One renderer with the field and noise uploaded, for one texture precision (and kernel): the
// uploads are the slow part at large sizes, so variants of one texture share it.
class Renderer {
 public:
  Renderer(const Context& context, const VectorField& field, const NoiseVolume& noise)
      : context_(context), field_(field), noise_(noise) {}

  // The renderer for these options (made and given the inputs unless it is the current one),
  // or why the device cannot hold them.
  Result<LicRenderer*> get(FieldPrecision precision, bool naive, std::string& skipped) {
    skipped.clear();
    if (!renderer_ || precision_ != precision || naive_ != naive) {
      renderer_.reset();
      RendererOptions options;
      options.fieldPrecision = precision;
      options.naiveLicKernel = naive;
      LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context_, options));
      if (!timer_.valid() && context_.supportsTimestamps()) {
        LIC3D_TRY_ASSIGN(timer_, GpuTimer::create(context_, 1, "bench timestamps"));
      }
      precision_ = precision;
      naive_ = naive;
      if (Result<void> r = renderer.setInputs(field_, noise_); !r) {
        setupError_ = r.error().message;
      } else {
        setupError_.clear();
      }
      renderer_ = std::move(renderer);
    }
    skipped = setupError_;
    return &*renderer_;
  }

  // GPU milliseconds of one LIC dispatch of the current renderer with `launch` (always dispatched).
  Result<double> timeLic(const LicSpecialization& launch, const LicParams& params) {
    renderer_->licJob().setLaunch(launch);
    return timeLicDispatch(context_, renderer_->licJob(), renderer_->fieldTextures(), timer_,
                           params);
  }

 private:
  const Context& context_;
  const VectorField& field_;
  const NoiseVolume& noise_;
  std::optional<LicRenderer> renderer_;
  GpuTimer timer_;
  FieldPrecision precision_ = FieldPrecision::Auto;
  bool naive_ = false;
  std::string setupError_;
};

struct KernelRun {
  Timing timing;
  std::vector<std::pair<std::string, std::string>> statistics;  // the driver's, if it gives any
  FieldPrecision precision = FieldPrecision::Auto;              // as the renderer resolved it
  std::optional<ScalarVolume> volume;
  std::optional<double> hidden;  // the fraction the sparsity mask hid
  std::string skipped;
};

// Times one kernel; the volume is kept for the correlations when asked.
Result<KernelRun> runKernel(const BenchOptions& options, double& budgetLeft, Renderer& renderers,
                            FieldPrecision precision, bool naive, const LicSpecialization& launch,
                            const LicParams& params, bool keepVolume) {
  KernelRun run;
  LIC3D_TRY_ASSIGN(LicRenderer * renderer, renderers.get(precision, naive, run.skipped));
  run.precision = renderer->fieldPrecision();
  if (!run.skipped.empty()) return run;
  LIC3D_TRY_ASSIGN(run.timing,
                   measure(options, budgetLeft, [&] { return renderers.timeLic(launch, params); }));
  if (!run.timing.measured) {
    run.skipped = run.timing.skipped;
    return run;
  }
  run.hidden = renderer->hiddenFraction();
  run.statistics = renderer->licJob().pipelineStatistics(params, renderer->fieldPrecision());
  if (keepVolume) {
    LIC3D_TRY_ASSIGN(ScalarVolume volume, renderer->readLicVolume());
    run.volume = std::move(volume);
  }
  return run;
}

struct KernelVariant {
  bool naive;
  StepScheme scheme;
  FieldPrecision precision;
};

// Trilinear texture fetches per streamline sample of RK2 (the naive kernel's noise has a texture
// of its own, so an exact sample costs three).
double fetchesPerSample(const KernelVariant& v) {
  if (v.naive) return 3.0;
  return v.scheme == StepScheme::Exact ? 2.0 : 1.0;
}

std::string variantName(const KernelVariant& v, FieldPrecision resolved) {
  if (v.naive) return "naive (half + R8 noise)";
  return std::string(enumName(v.scheme)) + ", " + std::string(fieldTextureFormatName(resolved));
}

// The registers per invocation among the driver's statistics, "-" when it gives none: the
// occupancy of a latency-bound kernel follows from them.
std::string registersOf(const KernelRun& run) {
  for (const auto& [name, value] : run.statistics)
    if (name.find("egister") != std::string::npos) return value;
  return "-";
}

nlohmann::json statisticsJson(const KernelRun& run) {
  nlohmann::json statistics = nlohmann::json::object();
  for (const auto& [name, value] : run.statistics) statistics[name] = value;
  return statistics;
}

std::string launchName(const LicSpecialization& l) {
  return std::to_string(l.localSizeX) + "x" + std::to_string(l.localSizeY) + "x" +
         std::to_string(l.localSizeZ) + (l.interleave ? ", both directions" : ", one by one");
}

// Table 1: the naive kernel and each scheme and texture precision. The fetch ceiling is the
// fetch rate of the naive and exact kernels, whose time is their fetches' (docs/BENCHMARKS.md).
Result<void> kernelTable(const Context& context, const BenchOptions& options, double& budgetLeft,
                         Renderer& renderers, const VectorField& field, int length,
                         nlohmann::json& rows) {
  const FieldPrecision automatic = resolvePrecision(context, FieldPrecision::Auto);
  const LicSpecialization launch = licLaunchFor(context.deviceInfo().type);
  const LicParams defaults;
  // In groups of one texture each, which share an upload.
  const std::vector<KernelVariant> variants{
      {true, StepScheme::Exact, FieldPrecision::Half},
      {false, StepScheme::Exact, FieldPrecision::Half},
      {false, StepScheme::Ab2, FieldPrecision::Half},
      {false, StepScheme::Fused, FieldPrecision::Half},
      {false, StepScheme::Exact, FieldPrecision::Float},
      {false, StepScheme::Fused, FieldPrecision::Float},
      {false, StepScheme::Ab2, FieldPrecision::Byte},
      {false, StepScheme::Fused, FieldPrecision::Byte},
  };
  const int n = field.dims.x;
  std::printf("\n%d^3, L = %d\n%-26s %10s %9s %9s %10s %10s %11s %8s %5s\n", n, length, "kernel",
              "median ms", "min ms", "speed-up", "r (naive)", "r (exact)", "Gfetches/s", "ceiling",
              "regs");
  std::optional<ScalarVolume> naiveVolume, exactVolume;
  double naiveMs = 0.0, ceiling = 0.0;
  for (const KernelVariant& v : variants) {
    LicParams params;
    params.length = length;
    params.scheme = v.scheme;
    LIC3D_TRY_ASSIGN(KernelRun run, runKernel(options, budgetLeft, renderers, v.precision, v.naive,
                                              launch, params, true));
    const std::string name = variantName(v, run.precision);
    const bool isDefault = !v.naive && v.scheme == defaults.scheme && run.precision == automatic;
    nlohmann::json row{{"n", n},
                       {"length", length},
                       {"kernel", name},
                       {"scheme", enumName(v.scheme)},
                       {"precision", fieldTextureFormatName(run.precision)},
                       {"naive", v.naive},
                       {"default", isDefault}};
    if (!run.skipped.empty()) {
      std::printf("%-26s (skipped: %s)\n", name.c_str(), run.skipped.c_str());
      row["skipped"] = run.skipped;
      rows.push_back(row);
      continue;
    }
    const Timing& t = run.timing;
    if (v.naive) naiveMs = t.medianMs;
    const double rNaive = naiveVolume ? correlation(*naiveVolume, *run.volume) : 1.0;
    const double rExact = exactVolume ? correlation(*exactVolume, *run.volume) : 1.0;
    const double samples = static_cast<double>(voxelCount(field.dims)) * (2.0 * length + 1.0);
    const double rate = samples * fetchesPerSample(v) / (t.medianMs * 1e6);
    if (v.naive || v.scheme == StepScheme::Exact) ceiling = std::max(ceiling, rate);
    const double speedUp = naiveMs > 0.0 ? naiveMs / t.medianMs : 0.0;
    std::printf("%-25s%s %10.3f %9.3f %9.2f %10.5f %10.5f %11.1f %7.0f%% %5s\n", name.c_str(),
                isDefault ? "*" : " ", t.medianMs, t.minMs, speedUp, rNaive, rExact, rate,
                100.0 * rate / ceiling, registersOf(run).c_str());
    std::fflush(stdout);
    row["median_ms"] = t.medianMs;
    row["min_ms"] = t.minMs;
    row["speed_up"] = speedUp;
    row["r_naive"] = rNaive;
    row["r_exact"] = rExact;
    row["gfetches_per_s"] = rate;
    row["fraction_of_fetch_ceiling"] = rate / ceiling;
    row["pipeline_statistics"] = statisticsJson(run);
    rows.push_back(row);
    if (v.naive)
      naiveVolume = std::move(run.volume);
    else if (!exactVolume && v.scheme == StepScheme::Exact)
      exactVolume = std::move(run.volume);
  }
  return {};
}

// Table 2: the masked pass against the unmasked one, same scheme, texture and launch.
Result<void> maskTable(const Context& context, const BenchOptions& options, double& budgetLeft,
                       Renderer& renderers, const VectorField& field, int length,
                       nlohmann::json& rows) {
  const LicSpecialization launch = licLaunchFor(context.deviceInfo().type);
  const int n = field.dims.x;
  std::printf("\n%d^3, L = %d, sparsity halton (automatic amount)\n%-26s %12s %12s %7s %8s %13s\n",
              n, length, "kernel", "unmasked ms", "masked ms", "ratio", "hidden", "regs (masked)");
  std::vector<StepScheme> schemes{LicParams{}.scheme};
  if (schemes.front() != StepScheme::Fused) schemes.push_back(StepScheme::Fused);
  for (const StepScheme scheme : schemes) {
    LicParams params;
    params.length = length;
    params.scheme = scheme;
    LicParams masked = params;
    masked.sparsity.distribution = SparsityDistribution::Halton;
    LIC3D_TRY_ASSIGN(const KernelRun plain,
                     runKernel(options, budgetLeft, renderers, FieldPrecision::Auto, false, launch,
                               params, false));
    LIC3D_TRY_ASSIGN(const KernelRun sparse,
                     runKernel(options, budgetLeft, renderers, FieldPrecision::Auto, false, launch,
                               masked, false));
    const std::string name =
        std::string(enumName(scheme)) + ", " + std::string(fieldTextureFormatName(plain.precision));
    nlohmann::json row{{"n", n}, {"length", length}, {"kernel", name}};
    if (!plain.skipped.empty() || !sparse.skipped.empty()) {
      const std::string why = plain.skipped.empty() ? sparse.skipped : plain.skipped;
      std::printf("%-26s (skipped: %s)\n", name.c_str(), why.c_str());
      row["skipped"] = why;
      rows.push_back(row);
      continue;
    }
    const double ratio = sparse.timing.medianMs / plain.timing.medianMs;
    std::printf("%-26s %12.3f %12.3f %7.2f %7.0f%% %13s\n", name.c_str(), plain.timing.medianMs,
                sparse.timing.medianMs, ratio, 100.0 * sparse.hidden.value_or(0.0),
                (registersOf(plain) + " / " + registersOf(sparse)).c_str());
    std::fflush(stdout);
    row["unmasked_ms"] = plain.timing.medianMs;
    row["masked_ms"] = sparse.timing.medianMs;
    row["ratio"] = ratio;
    row["hidden_fraction"] = sparse.hidden.value_or(0.0);
    row["pipeline_statistics_unmasked"] = statisticsJson(plain);
    row["pipeline_statistics_masked"] = statisticsJson(sparse);
    rows.push_back(row);
  }
  return {};
}

// Table 3: workgroup shapes and walks for the default scheme and the fused one.
Result<void> launchTable(const Context& context, const BenchOptions& options, double& budgetLeft,
                         Renderer& renderers, const VectorField& field, int length,
                         nlohmann::json& rows) {
  const int n = field.dims.x;
  const LicSpecialization chosen = licLaunchFor(context.deviceInfo().type);
  std::printf(
      "\n%d^3, L = %d, launch shapes (* = the one this device type gets)\n%-14s %-34s %10s %5s\n",
      n, length, "scheme", "workgroup, walk", "median ms", "regs");
  std::vector<StepScheme> schemes{LicParams{}.scheme};
  if (schemes.front() != StepScheme::Fused) schemes.push_back(StepScheme::Fused);
  const std::uint32_t shapes[][3] = {{8, 8, 1},  {16, 8, 1}, {32, 4, 1}, {16, 16, 1},
                                     {64, 1, 1}, {8, 4, 2},  {4, 4, 4}};
  for (const StepScheme scheme : schemes) {
    for (const bool interleave : {true, false}) {
      for (const auto& shape : shapes) {
        const LicSpecialization launch = licLaunch(shape[0], shape[1], shape[2], interleave);
        LicParams params;
        params.length = length;
        params.scheme = scheme;
        LIC3D_TRY_ASSIGN(const KernelRun run,
                         runKernel(options, budgetLeft, renderers, FieldPrecision::Auto, false,
                                   launch, params, false));
        const std::string name = launchName(launch);
        const bool isChosen = launch == chosen;
        nlohmann::json row{{"n", n},
                           {"length", length},
                           {"scheme", enumName(scheme)},
                           {"workgroup", {shape[0], shape[1], shape[2]}},
                           {"both_directions_at_once", interleave},
                           {"chosen_for_this_device_type", isChosen}};
        if (!run.skipped.empty()) {
          std::printf("%-14s %-34s (skipped: %s)\n", std::string(enumName(scheme)).c_str(),
                      name.c_str(), run.skipped.c_str());
          row["skipped"] = run.skipped;
        } else {
          std::printf("%-14s %-33s%s %10.3f %5s\n", std::string(enumName(scheme)).c_str(),
                      name.c_str(), isChosen ? "*" : " ", run.timing.medianMs,
                      registersOf(run).c_str());
          row["median_ms"] = run.timing.medianMs;
        }
        std::fflush(stdout);
        rows.push_back(row);
      }
    }
  }
  return {};
}

}  // namespace

Result<nlohmann::json> runKernelBenchmarks(const Context& context, const BenchOptions& options) {
  if (!hasRuntimeModeShaders())
    return unsupportedError(
        "bench --kernels needs a build configured with "
        "-DLIC3D_BENCH_RUNTIME_MODES=ON (cmake --preset bench)");
  LIC3D_TRY_ASSIGN(const std::vector<int> sizes, parseIntList(options.sizes, "--sizes", 4, 2048));
  LIC3D_TRY_ASSIGN(const std::vector<int> lengths,
                   parseIntList(options.lengths, "--lengths", 0, kMaxLicLength));
  const auto fieldKind = parseEnum<AnalyticField>(options.field);
  if (!fieldKind) return inputError("bench: --field must be an analytic field");

  const DeviceInfo& device = context.deviceInfo();
  nlohmann::json report = newReport(context);
  report["field"] = options.field;
  report["repeats"] = options.repeats;
  report["rows"] = nlohmann::json::array();
  report["masked"] = nlohmann::json::array();
  report["launch"] = nlohmann::json::array();
  std::printf("lic3d bench --kernels on %s (%s, %s), %s\n", device.name.c_str(),
              deviceTypeName(device.type), device.driver.c_str(), today().c_str());
  std::printf(
      "%s field, RK2, box kernel, h = 0.5, trilinear noise; median of %d after %d warm-up (GPU "
      "timestamps, LIC pass and its histogram); r = correlation of the volumes; * = the default "
      "here; ceiling = the fetch rate against the naive and exact kernels' best\n",
      options.field.c_str(), options.repeats, options.warmup);
  double budgetLeft = options.budgetSeconds;
  for (const int n : sizes) {
    const Dims dims(n);
    const VectorField field = makeAnalyticField(*fieldKind, dims);
    const NoiseVolume noise = makeWhiteNoise(dims, options.seed);
    Renderer renderers(context, field, noise);
    for (const int length : lengths)
      LIC3D_TRY(
          kernelTable(context, options, budgetLeft, renderers, field, length, report["rows"]));
    LIC3D_TRY(maskTable(context, options, budgetLeft, renderers, field, lengths.back(),
                        report["masked"]));
    LIC3D_TRY(launchTable(context, options, budgetLeft, renderers, field, lengths.back(),
                          report["launch"]));
  }
  return report;
}

}  // namespace lic3d::cli
