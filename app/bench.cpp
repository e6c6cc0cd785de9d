// `lic3d bench`: GPU timestamps of the LIC pass and of frames, median of repeats after warm-up.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <functional>

#include <nlohmann/json.hpp>

#include "analytic_fields.h"
#include "commands.h"
#include "file_util.h"
#include "lic_renderer.h"
#include "noise.h"

namespace lic3d::cli {
namespace {

struct Timing {
  bool measured = false;
  std::string skipped;  // why not, when !measured
  double medianMs = 0.0;
  double minMs = 0.0;
  int repeats = 0;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Runs `once` for warm-up, then `repeats` times; gives up early when the warm-up shows the
// repeats would not fit in the remaining budget.
Result<Timing> measure(const BenchOptions& options, double& budgetLeft,
                       const std::function<Result<double>()>& once) {
  Timing timing;
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  for (int i = 0; i < std::max(1, options.warmup); ++i) {
    LIC3D_TRY_ASSIGN([[maybe_unused]] const double ms, once());
    if (elapsed() / (i + 1) * options.repeats > budgetLeft) {
      timing.skipped = "over the time budget";
      budgetLeft -= elapsed();
      return timing;
    }
  }
  std::vector<double> samples;
  for (int i = 0; i < options.repeats; ++i) {
    LIC3D_TRY_ASSIGN(const double ms, once());
    samples.push_back(ms);
  }
  budgetLeft -= elapsed();
  timing.measured = true;
  timing.medianMs = median(samples);
  timing.minMs = *std::min_element(samples.begin(), samples.end());
  timing.repeats = options.repeats;
  return timing;
}

// Field and noise texture, LIC volume (R16) and the texture's upload staging.
double residentBytes(int n, FieldPrecision precision) {
  const double texel = precision == FieldPrecision::Half ? 8.0 : 16.0;
  return static_cast<double>(n) * n * n * (2.0 * texel + 2.0);
}

Result<void> setVolume(LicRenderer& renderer, AnalyticField field, int n, std::uint64_t seed) {
  const Dims dims(n);
  return renderer.setInputs(makeAnalyticField(field, dims), makeWhiteNoise(dims, seed));
}

std::string today() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d", std::gmtime(&now));
  return text;
}

Result<nlohmann::json> runBenchmarks(const Context& context, const BenchOptions& options) {
  LIC3D_TRY_ASSIGN(const std::vector<int> sizes, parseIntList(options.sizes, "--sizes", 4, 2048));
  LIC3D_TRY_ASSIGN(const std::vector<int> lengths,
                   parseIntList(options.lengths, "--lengths", 0, kMaxLicLength));
  LIC3D_TRY_ASSIGN(const std::vector<int> frameSizes,
                   parseIntList(options.frameSizes, "--frame-sizes", 16, 16384));
  const auto fieldKind = parseAnalyticField(options.input.field);
  if (!fieldKind) return inputError("bench: --field must be an analytic field");

  const DeviceInfo& device = context.deviceInfo();
  const double memory = static_cast<double>(device.deviceLocalBytes);
  double budgetLeft = options.budgetSeconds;
  nlohmann::json report;
  report["device"] = device.name;
  report["driver"] = device.driver;
  report["date"] = today();
  report["field"] = options.input.field;
  report["repeats"] = options.repeats;
  report["warmup"] = options.warmup;

  std::printf("lic3d bench on %s (%s, %s), %s\n", device.name.c_str(), deviceTypeName(device.type),
              device.driver.c_str(), report["date"].get<std::string>().c_str());
  std::printf("LIC compute: %s field, rk2, box kernel, h = 0.5, trilinear noise, %s-precision "
              "field texture; median of %d after %d warm-up (GPU timestamps)\n",
              options.input.field.c_str(),
              resolvePrecision(context, options.precision) == FieldPrecision::Half ? "half" : "float",
              options.repeats, options.warmup);
  std::printf("%8s %6s %12s %12s %14s\n", "volume", "L", "median ms", "min ms", "Gsamples/s");

  LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, {options.precision}));
  const FieldPrecision precision = renderer.fieldPrecision();
  report["field_precision"] = precision == FieldPrecision::Half ? "half" : "float";
  report["lic"] = nlohmann::json::array();
  for (const int n : sizes) {
    if (residentBytes(n, precision) > 0.8 * memory) {
      std::printf("%6d^3 %6s %12s (skipped: needs %.1f GiB of device memory)\n", n, "-", "-",
                  residentBytes(n, precision) / (1 << 30));
      report["lic"].push_back({{"n", n}, {"skipped", "device memory"}});
      continue;
    }
    LIC3D_TRY(setVolume(renderer, *fieldKind, n, options.input.seed));
    for (const int length : lengths) {
      LicParams params;
      params.length = length;
      LIC3D_TRY_ASSIGN(const Timing t, measure(options, budgetLeft, [&] {
                         return renderer.timeLicDispatch(params);
                       }));
      nlohmann::json row{{"n", n}, {"length", length}};
      if (t.measured) {
        const double samples = static_cast<double>(n) * n * n * (2.0 * length + 1.0);
        std::printf("%6d^3 %6d %12.3f %12.3f %14.2f\n", n, length, t.medianMs, t.minMs,
                    samples / (t.medianMs * 1e6));
        row["median_ms"] = t.medianMs;
        row["min_ms"] = t.minMs;
      } else {
        std::printf("%6d^3 %6d %12s (skipped: %s)\n", n, length, "-", t.skipped.c_str());
        row["skipped"] = t.skipped;
      }
      std::fflush(stdout);
      report["lic"].push_back(row);
    }
  }

  const int n = options.frameVolume;
  std::printf("\nFrame: %d^3 volume, %d view-aligned slices (one per voxel), default camera\n", n,
              n);
  std::printf("%12s %10s %12s %12s\n", "image", "buffer", "median ms", "min ms");
  report["frame"] = {{"volume", n}, {"slices", n}, {"rows", nlohmann::json::array()}};
  if (residentBytes(n, precision) > 0.8 * memory) {
    report["frame"]["skipped"] = "device memory";
  } else {
    LIC3D_TRY(setVolume(renderer, *fieldKind, n, options.input.seed));
    LIC3D_TRY_ASSIGN([[maybe_unused]] const double ms, renderer.timeLicDispatch(LicParams{}));
    for (const FramePrecision frame : {FramePrecision::Float16, FramePrecision::Unorm8}) {
      LIC3D_TRY(renderer.setFramePrecision(frame));
      const char* bufferName = frame == FramePrecision::Float16 ? "rgba16f" : "rgba8";
      for (const int size : frameSizes) {
        ViewParams view;
        view.width = view.height = size;
        view.slices = n;
        LIC3D_TRY_ASSIGN(const Timing t, measure(options, budgetLeft,
                                                 [&] { return renderer.timeFrame(view); }));
        nlohmann::json row{{"image", size}, {"buffer", bufferName}};
        if (t.measured) {
          std::printf("%9d^2 %10s %12.3f %12.3f\n", size, bufferName, t.medianMs, t.minMs);
          row["median_ms"] = t.medianMs;
          row["min_ms"] = t.minMs;
        } else {
          std::printf("%9d^2 %10s %12s (skipped: %s)\n", size, bufferName, "-", t.skipped.c_str());
          row["skipped"] = t.skipped;
        }
        std::fflush(stdout);
        report["frame"]["rows"].push_back(row);
      }
    }
  }
  return report;
}

}  // namespace

int runBench(const GlobalOptions& global, const BenchOptions& options) {
  if (!options.json.empty()) {
    if (auto r = checkOutputPath(options.json, ".json"); !r) return reportError(r.error());
  }
  ContextOptions contextOptions;
  contextOptions.validation = global.validation;
  contextOptions.device = global.device;
  Result<Context> context = Context::create(contextOptions);
  if (!context) return reportError(context.error());
  const Result<nlohmann::json> report = runBenchmarks(*context, options);
  if (!report) return reportError(report.error());
  if (!options.json.empty()) {
    if (auto r = writeFileAtomically(options.json, report->dump(2) + "\n"); !r)
      return reportError(r.error());
    if (!global.quiet) std::fprintf(stderr, "lic3d: wrote %s\n", options.json.c_str());
  }
  return kExitOk;
}

}  // namespace lic3d::cli
