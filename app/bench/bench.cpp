// SPDX-License-Identifier: BSD-3-Clause
// `lic3d bench`: GPU timestamps of the LIC pass and of frames, median of repeats after warm-up.
#include "bench/bench.h"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "core/look.h"
#include "core/stage_times.h"
#include "core/volume_compare.h"
#include "gpu/shader_library.h"
#include "gpu/submit.h"
#include "gpu/timer.h"
#include "io/file_util.h"
#include "jobs/bricks.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "lic/sparsity.h"
#include "loading/session_inputs.h"
#include "options/flags.h"
#include "passes/sparsity_mask_pass.h"
#include "render/lic_renderer.h"

namespace lic3d::cli {

Result<Timing> measure(const BenchOptions& options, double& budgetLeft,
                       const std::function<Result<double>()>& once) {
  Timing timing;
  const auto start = std::chrono::steady_clock::now();
  auto elapsed = [&] { return secondsSince(start); };
  // At least the requested warm-up runs, and at least a quarter of a second of them: a GPU that
  // idled while the host prepared the inputs needs that long to raise its clocks again.
  for (int i = 0; i < std::max(1, options.warmup) || elapsed() < 0.25; ++i) {
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

std::string today() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d", std::gmtime(&now));
  return text;
}

nlohmann::json newReport(const Context& context) {
  nlohmann::json report;
  report["device"] = context.deviceInfo().name;
  report["driver"] = context.deviceInfo().driver;
  report["date"] = today();
  return report;
}

namespace {

// Field and noise texture, LIC volume (R16) and the texture's upload staging.
double residentBytes(int n, FieldPrecision precision) {
  const double texel = fieldTexelBytes(precision);
  return static_cast<double>(n) * n * n * (2.0 * texel + 2.0);
}

// GPU timestamps, one region, where the device has them (an invalid timer otherwise: the
// timings below then report that the device has no timestamp queries).
Result<GpuTimer> benchTimer(const Context& context) {
  if (!context.supportsTimestamps()) return GpuTimer();
  return GpuTimer::create(context, 1, "bench timestamps");
}

// GPU milliseconds of one LIC dispatch over the whole volume (always dispatched).
Result<double> timeLic(const Context& context, LicRenderer& renderer, const GpuTimer& timer,
                       const LicParams& params) {
  return timeLicDispatch(context, renderer.licJob(), renderer.fieldTextures(), timer, params);
}

// GPU milliseconds of one frame's draw into `target` (no read-back).
Result<double> timeFrame(const Context& context, LicRenderer& renderer, OffscreenTarget& target,
                         const GpuTimer& timer, const ViewParams& view) {
  if (!timer.valid()) return unsupportedError("the device has no timestamp queries");
  if (!renderer.hasVolume()) return inputError("no LIC volume has been computed");
  LIC3D_TRY(validate(view));
  LIC3D_TRY(target.resize(view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width,
                          view.height));
  Result<void> status;
  LIC3D_TRY(submitAndWait(
      context,
      [&](VkCommandBuffer cmd) {
        timer.reset(cmd, 0);
        timer.begin(cmd, 0);
        status = renderer.recordFrame(cmd, target, view);
        timer.end(cmd, 0);
        target.recordUnread(cmd);
      },
      "frame timing"));
  LIC3D_TRY(std::move(status));
  return timer.milliseconds(0);
}

Result<void> setVolume(LicRenderer& renderer, AnalyticField field, int n, std::uint64_t seed) {
  const Dims dims(n);
  return renderer.setInputs(makeAnalyticField(field, dims), makeWhiteNoise(dims, seed));
}

// The frame table's rows for a volume of n^3 in `renderer`: each view (look), K and buffer
// format at each size, with one slice per voxel and with a quarter of them: how the time splits
// between what each slice costs and what each frame costs.
Result<void> frameRows(const Context& context, const BenchOptions& options, double& budgetLeft,
                       LicRenderer& renderer, const GpuTimer& timer, int n,
                       const std::vector<int>& frameSizes, nlohmann::json& rows) {
  LIC3D_TRY_ASSIGN(OffscreenTarget target,
                   OffscreenTarget::create(context, FramePrecision::Float16));
  LIC3D_TRY_ASSIGN(const std::vector<int> ks,
                   parseIntList(options.slicesPerFragment, "--slices-per-fragment", 0, 4));
  for (const int k : ks)
    if (k == 3) return inputError("--slices-per-fragment: K is 0, 1, 2 or 4");
  constexpr std::pair<FramePrecision, const char*> kBuffers[] = {
      {FramePrecision::Float16, "rgba16f"},
      {FramePrecision::Unorm16, "rgba16"},
      {FramePrecision::Unorm10, "rgb10a2"},
      {FramePrecision::Unorm8, "rgba8"}};
  std::vector<std::pair<FramePrecision, const char*>> buffers;
  for (const std::string_view name : splitCommas(options.frameBuffers)) {
    const auto* found = std::find_if(std::begin(kBuffers), std::end(kBuffers),
                                     [&](const auto& b) { return name == b.second; });
    if (found == std::end(kBuffers))
      return inputError("--frame-buffers: unknown buffer " + std::string(name));
    buffers.push_back(*found);
  }
  std::vector<std::pair<std::string, ViewParams>> looks;
  for (const std::string_view name : splitCommas(options.frameLooks)) {
    if (name == "plain") {
      looks.emplace_back(std::string(name), ViewParams{});
    } else if (name == "default") {
      Session session;
      applyLook(kDefaultLook, session);
      looks.emplace_back(std::string(name), session.view);
    } else {
      return inputError("--frame-looks: plain or default, not " + std::string(name));
    }
  }
  for (const int slices : {n, std::max(1, n / 4)}) {
    for (const auto& [lookName, lookView] : looks) {
      for (const auto& [frame, bufferName] : buffers) {
        LIC3D_TRY(target.setPrecision(frame));
        for (const int size : frameSizes) {
          for (const int k : ks) {
            renderer.setSlicesPerFragment(k);
            ViewParams view = lookView;
            view.width = view.height = size;
            view.slices = slices;
            LIC3D_TRY_ASSIGN(const Timing t, measure(options, budgetLeft, [&] {
                               return timeFrame(context, renderer, target, timer, view);
                             }));
            nlohmann::json row{{"image", size},    {"buffer", bufferName}, {"slices", slices},
                               {"look", lookName}, {"halo", view.halo},    {"k", k}};
            if (t.measured) {
              std::printf("%9d^2 %10s %7d %8s %2d %12.3f %12.3f\n", size, bufferName, slices,
                          lookName.c_str(), k, t.medianMs, t.minMs);
              row["median_ms"] = t.medianMs;
              row["min_ms"] = t.minMs;
            } else {
              std::printf("%9d^2 %10s %7d %8s %2d %12s (skipped: %s)\n", size, bufferName, slices,
                          lookName.c_str(), k, "-", t.skipped.c_str());
              row["skipped"] = t.skipped;
            }
            std::fflush(stdout);
            rows.push_back(row);
          }
        }
      }
    }
  }
  renderer.setSlicesPerFragment(0);
  return {};
}

Result<nlohmann::json> runBenchmarks(const Context& context, const BenchOptions& options) {
  LIC3D_TRY_ASSIGN(const std::vector<int> sizes, parseIntList(options.sizes, "--sizes", 4, 4096));
  LIC3D_TRY_ASSIGN(const std::vector<int> lengths,
                   parseIntList(options.lengths, "--lengths", 0, kMaxLicLength));
  LIC3D_TRY_ASSIGN(const std::vector<int> frameSizes,
                   parseIntList(options.frameSizes, "--frame-sizes", 16, 16384));
  const auto fieldKind = parseEnum<AnalyticField>(options.field);
  if (!fieldKind) return inputError("bench: --field must be an analytic field");

  const DeviceInfo& device = context.deviceInfo();
  const double memory = static_cast<double>(device.deviceLocalBytes);
  double budgetLeft = options.budgetSeconds;
  nlohmann::json report = newReport(context);
  report["field"] = options.field;
  report["repeats"] = options.repeats;
  report["warmup"] = options.warmup;

  std::printf("lic3d bench on %s (%s, %s), %s\n", device.name.c_str(), deviceTypeName(device.type),
              device.driver.c_str(), report["date"].get<std::string>().c_str());
  const LicParams defaults;
  std::printf(
      "LIC compute: %s field, rk2 (%s scheme), box kernel, h = 0.5, trilinear noise, %s "
      "field texture; median of %d after %d warm-up (GPU timestamps)\n",
      options.field.c_str(), std::string(enumName(defaults.scheme)).c_str(),
      std::string(fieldTextureFormatName(resolvePrecision(context, options.precision))).c_str(),
      options.repeats, options.warmup);
  std::printf("%8s %6s %12s %12s %14s\n", "volume", "L", "median ms", "min ms", "Gsamples/s");

  LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, {options.precision}));
  LIC3D_TRY_ASSIGN(const GpuTimer timer, benchTimer(context));
  const FieldPrecision precision = renderer.fieldPrecision();
  report["field_precision"] = fieldTextureFormatName(precision);
  report["scheme"] = enumName(defaults.scheme);
  report["lic"] = nlohmann::json::array();
  for (const int n : sizes) {
    if (residentBytes(n, precision) > 0.8 * memory) {
      // Larger than the device: in bricks, once (a run takes seconds).
      for (const int length : lengths) {
        LIC3D_TRY_ASSIGN(nlohmann::json row, benchBricked(context, options, n, length));
        report["lic"].push_back(std::move(row));
      }
      continue;
    }
    LIC3D_TRY(setVolume(renderer, *fieldKind, n, options.seed));
    for (const int length : lengths) {
      LicParams params;
      params.length = length;
      LIC3D_TRY_ASSIGN(const Timing t, measure(options, budgetLeft, [&] {
                         return timeLic(context, renderer, timer, params);
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
  std::printf("\nFrame: %d^3 volume, view-aligned slices (%d = one per voxel), default camera\n", n,
              n);
  std::printf("(K: slices per fragment, 0 the device's choice: %d on a GPU, %d on a CPU driver)\n",
              SlicePass::kSlicesPerFragmentGpu, SlicePass::kSlicesPerFragmentCpu);
  std::printf("%12s %10s %7s %8s %2s %12s %12s\n", "image", "buffer", "slices", "look", "K",
              "median ms", "min ms");
  report["frame"] = {{"volume", n}, {"slices", n}, {"rows", nlohmann::json::array()}};
  if (residentBytes(n, precision) > 0.8 * memory) {
    report["frame"]["skipped"] = "device memory";
  } else {
    LIC3D_TRY(setVolume(renderer, *fieldKind, n, options.seed));
    LIC3D_TRY_ASSIGN([[maybe_unused]] const double ms,
                     timeLic(context, renderer, timer, LicParams{}));
    LIC3D_TRY(frameRows(context, options, budgetLeft, renderer, timer, n, frameSizes,
                        report["frame"]["rows"]));
  }
  return report;
}

struct Variant {
  const char* name;
  LicParams lic;
  ViewParams view;
};

// The thesis' Table 6.1 today: frame time of specialized pipelines against one shader deciding
// the same modes at run time.
Result<nlohmann::json> runVariants(const Context& context, const BenchOptions& options) {
  if (!hasRuntimeModeShaders())
    return unsupportedError(
        "bench --variants needs a build configured with "
        "-DLIC3D_BENCH_RUNTIME_MODES=ON (cmake --preset bench)");
  const auto fieldKind = parseEnum<AnalyticField>(options.field);
  if (!fieldKind) return inputError("bench: --field must be an analytic field");
  LIC3D_TRY_ASSIGN(const std::vector<int> frameSizes,
                   parseIntList(options.frameSizes, "--frame-sizes", 16, 16384));
  const int n = options.frameVolume;
  const int size = frameSizes.front();

  ViewParams base;
  base.width = base.height = size;
  base.slices = n;
  LicParams plain;
  LicParams sparse;
  sparse.sparsity.distribution = SparsityDistribution::Halton;
  std::vector<Variant> variants;
  variants.push_back({"grey", plain, base});
  Variant colour{"colour + magnitude opacity", plain, base};
  colour.view.color = ColorMode::Magnitude;
  colour.view.magnitudeOpacity = 1.0f;
  variants.push_back(colour);
  Variant sparseFog{"sparsity + fog", sparse, base};
  sparseFog.view.fog = true;
  variants.push_back(sparseFog);
  Variant region{"sphere ROI + clip + nearest", plain, base};
  region.view.roi = RoiShape::Sphere;
  region.view.roiSize = 0.8f;
  region.view.clipMax = glm::vec3(1.0f, 0.8f, 1.0f);
  region.view.filter = VolumeFilter::Nearest;
  variants.push_back(region);
  Variant lit{"Phong lighting + colour", plain, base};
  lit.view.lighting = Lighting::Phong;
  lit.view.color = ColorMode::Magnitude;
  variants.push_back(lit);
  Variant all{"all of the above", sparse, base};
  all.view.color = ColorMode::Magnitude;
  all.view.magnitudeOpacity = 1.0f;
  all.view.fog = true;
  all.view.roi = RoiShape::Sphere;
  all.view.roiSize = 0.8f;
  all.view.lighting = Lighting::Phong;
  variants.push_back(all);
  // The depth cues and the filters against facets (docs/LOOKS.md), each on the colour row.
  Variant halos{"colour + halos 0.3", plain, colour.view};
  halos.view.halo = 0.3f;
  variants.push_back(halos);
  Variant occlusion{"colour + occlusion 0.5", plain, colour.view};
  occlusion.view.occlusion = 0.5f;
  variants.push_back(occlusion);
  Variant gradient{"colour + gradient lighting", plain, colour.view};
  gradient.view.lighting = Lighting::Gradient;
  variants.push_back(gradient);
  Variant cubic{"colour + cubic filter", plain, colour.view};
  cubic.view.filter = VolumeFilter::Cubic;
  variants.push_back(cubic);
  Variant plainSlicing{"colour, linear, no jitter", plain, colour.view};
  plainSlicing.view.filter = VolumeFilter::Linear;
  plainSlicing.view.jitter = false;
  variants.push_back(plainSlicing);
  Variant jittered{"colour, linear, jitter", plain, colour.view};
  jittered.view.filter = VolumeFilter::Linear;
  variants.push_back(jittered);
  // The default look's view (its optical depth, halos, opacity floor), on this frame.
  Session seeThrough;
  applyLook(Look::SeeThrough, seeThrough);
  Variant look{"the see-through look", plain, seeThrough.view};
  look.view.width = look.view.height = size;
  look.view.slices = n;
  variants.push_back(look);

  const DeviceInfo& device = context.deviceInfo();
  std::printf("lic3d bench --variants on %s (%s), %s\n", device.name.c_str(), device.driver.c_str(),
              today().c_str());
  std::printf(
      "Frame %d^2, %d^3 volume, %d slices; median of %d after %d warm-up (GPU timestamps)\n", size,
      n, n, options.repeats, options.warmup);
  std::printf("%-30s %15s %15s %8s\n", "modes", "specialized ms", "runtime ms", "ratio");

  nlohmann::json report = newReport(context);
  report["image"] = size;
  report["volume"] = n;
  report["rows"] = nlohmann::json::array();
  RendererOptions runtimeOptions;
  runtimeOptions.fieldPrecision = options.precision;
  runtimeOptions.runtimeModes = true;
  LIC3D_TRY_ASSIGN(LicRenderer specialized, LicRenderer::create(context, {options.precision}));
  LIC3D_TRY_ASSIGN(LicRenderer runtime, LicRenderer::create(context, runtimeOptions));
  LIC3D_TRY(setVolume(specialized, *fieldKind, n, options.seed));
  LIC3D_TRY(setVolume(runtime, *fieldKind, n, options.seed));
  LIC3D_TRY_ASSIGN(const GpuTimer timer, benchTimer(context));
  LIC3D_TRY_ASSIGN(OffscreenTarget target,
                   OffscreenTarget::create(context, FramePrecision::Float16));
  double budgetLeft = options.budgetSeconds;
  for (const Variant& v : variants) {
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool a, specialized.updateLic(v.lic));
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool b, runtime.updateLic(v.lic));
    LIC3D_TRY_ASSIGN(const Timing fast, measure(options, budgetLeft, [&] {
                       return timeFrame(context, specialized, target, timer, v.view);
                     }));
    LIC3D_TRY_ASSIGN(const Timing slow, measure(options, budgetLeft, [&] {
                       return timeFrame(context, runtime, target, timer, v.view);
                     }));
    nlohmann::json row{{"modes", v.name}};
    if (fast.measured && slow.measured) {
      std::printf("%-30s %15.3f %15.3f %8.2f\n", v.name, fast.medianMs, slow.medianMs,
                  slow.medianMs / fast.medianMs);
      row["specialized_ms"] = fast.medianMs;
      row["runtime_ms"] = slow.medianMs;
    } else {
      std::printf("%-30s %15s (skipped: over the time budget)\n", v.name, "-");
      row["skipped"] = "over the time budget";
    }
    std::fflush(stdout);
    report["rows"].push_back(row);
  }
  return report;
}

// A sparsity change of distribution `d` end to end (wall clock) and the LIC pass alone; the
// first change is skipped when `predicted` seconds do not fit the budget left.
Result<nlohmann::json> recomputeRow(const Context& context, const BenchOptions& options,
                                    double& budgetLeft, LicRenderer& renderer,
                                    const GpuTimer& timer, SparsityDistribution d,
                                    std::string_view name, double predicted) {
  std::vector<double> wall;
  LicParams lic;
  lic.sparsity.distribution = d;
  for (int i = 0; i < options.repeats && budgetLeft > 0.0 && predicted <= budgetLeft; ++i) {
    lic.sparsity.seed = static_cast<std::uint64_t>(i + 2);  // a new mask every time
    const auto start = std::chrono::steady_clock::now();
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer.updateLic(lic));
    wall.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
    budgetLeft -= wall.back() / 1000.0;
    predicted = wall.back() / 1000.0;
  }
  nlohmann::json row{{"distribution", name}};
  if (wall.empty()) {
    std::printf("%-16s %14s %14s %14s (skipped: over the time budget)\n", std::string(name).c_str(),
                "-", "-", "-");
    row["skipped"] = "over the time budget";
  } else {
    // The pass on its own, warmed up like every other GPU time here: a single dispatch right
    // after the host made a mask meets a GPU whose clocks dropped while it idled (on the H100
    // that read 14-19 ms for a 3.4 ms pass).
    LIC3D_TRY_ASSIGN(const Timing pass, measure(options, budgetLeft, [&] {
                       return timeLic(context, renderer, timer, lic);
                     }));
    const double passMs = pass.measured ? pass.medianMs : 0.0;
    // Back to the first mask of the row, seen before: the cache's case for the masks made on the
    // CPU, a new mask on the GPU for the others (timeLic left the last mask in place).
    const std::uint64_t firstSeed = 2;
    if (lic.sparsity.seed == firstSeed) {
      lic.sparsity.seed = firstSeed + 1;
      LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer.updateLic(lic));
    }
    lic.sparsity.seed = firstSeed;
    const auto start = std::chrono::steady_clock::now();
    LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer.updateLic(lic));
    const double againMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::printf("%-16s %14.1f %14.1f %14.2f %8s\n", std::string(name).c_str(), median(wall),
                againMs, passMs, madeOnGpu(d) ? "GPU" : "CPU");
    row["wall_ms"] = median(wall);
    row["seen_again_ms"] = againMs;
    row["mask_made_on"] = madeOnGpu(d) ? "gpu" : "cpu";
    if (pass.measured) row["lic_ms"] = passMs;
  }
  return row;
}

// GPU milliseconds of making the mask of `params` with SparsityMaskPass (median of the repeats
// after one warm-up run).
Result<double> gpuMaskMs(const Context& context, const BenchOptions& options,
                         SparsityMaskPass& pass, const GpuTimer& timer,
                         const SparsityParams& params, Dims dims) {
  constexpr VkBufferUsageFlags kUsage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                        VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  LIC3D_TRY_ASSIGN(const Buffer bits,
                   Buffer::create(context, sparsityMaskWords(dims) * sizeof(std::uint32_t), kUsage,
                                  MemoryUse::DeviceLocal, "bench sparsity mask"));
  LIC3D_TRY_ASSIGN(const Buffer count, Buffer::create(context, sizeof(std::uint32_t), kUsage,
                                                      MemoryUse::DeviceLocal, "bench mask count"));
  std::vector<double> ms;
  for (int i = 0; i <= std::max(1, options.repeats); ++i) {
    Result<void> recorded;
    LIC3D_TRY(submitAndWait(
        context,
        [&](VkCommandBuffer cmd) {
          timer.reset(cmd, 0);
          timer.begin(cmd, 0);
          recorded = pass.record(cmd, params, dims, bits, count);
          timer.end(cmd, 0);
        },
        "bench sparsity mask"));
    LIC3D_TRY(recorded);
    LIC3D_TRY_ASSIGN(const double once, timer.milliseconds(0));
    if (i > 0) ms.push_back(once);
  }
  return median(ms);
}

// Thesis Figure 6.4 today: how long each distribution takes to make its points (and mask), and
// how long a sparsity change takes end to end (mask on the CPU, upload, LIC pass).
Result<nlohmann::json> runDistributions(const Context& context, const BenchOptions& options) {
  const int n = options.distributionVolume;
  const Dims dims(n);
  const double voxels = static_cast<double>(voxelCount(dims));
  const DeviceInfo& device = context.deviceInfo();
  nlohmann::json report = newReport(context);
  report["volume"] = n;
  report["generation"] = nlohmann::json::array();
  std::printf("lic3d bench --distributions, %d^3 volume, %s\n", n, today().c_str());
  std::printf(
      "Mask generation on the CPU (wall clock, one run each) and, for the distributions made on "
      "the GPU, on %s (GPU timestamps, median of %d):\n",
      device.name.c_str(), std::max(1, options.repeats));
  std::printf("%-16s %12s %14s %12s %12s\n", "distribution", "requested", "black voxels", "ms",
              "GPU ms");
  LIC3D_TRY_ASSIGN(SparsityMaskPass maskPass, SparsityMaskPass::create(context));
  LIC3D_TRY_ASSIGN(const GpuTimer maskTimer, benchTimer(context));
  double budgetLeft = options.budgetSeconds;
  // Per distribution, the largest row measured (points, ms): a row whose time, scaled from it by
  // the points, would not fit in what is left of the budget is skipped rather than started.
  std::map<SparsityDistribution, std::pair<double, double>> measured;
  const auto predictedSeconds = [&](SparsityDistribution d, double count) {
    const auto known = measured.find(d);
    if (known == measured.end() || known->second.first <= 0.0) return 0.0;
    return known->second.second / 1000.0 * std::max(1.0, count / known->second.first);
  };
  for (const auto& [d, name] : enumNames<SparsityDistribution>()) {
    if (d == SparsityDistribution::None) continue;
    for (const double count : {1e3, 1e4, 1e5, 1e6}) {
      SparsityParams p;
      p.distribution = d;
      switch (d) {
        case SparsityDistribution::Checkerboard:
          p.ratio = static_cast<float>(count / voxels);
          break;
        case SparsityDistribution::Jitter:
          p.radius = static_cast<float>(std::cbrt(kJitterDensity * voxels / count));
          break;
        default: p.points = static_cast<int>(count); break;
      }
      nlohmann::json row{{"distribution", name}, {"requested", count}};
      if (!validate(p, dims)) {
        std::printf("%-16s %12.0f %14s %12s (outside its limits)\n", std::string(name).c_str(),
                    count, "-", "-");
        row["skipped"] = "outside its limits";
        report["generation"].push_back(row);
        continue;
      }
      if (budgetLeft <= 0.0 || predictedSeconds(d, count) > budgetLeft) {
        std::printf("%-16s %12.0f %14s %12s (skipped: over the time budget)\n",
                    std::string(name).c_str(), count, "-", "-");
        row["skipped"] = "over the time budget";
        report["generation"].push_back(row);
        continue;
      }
      const auto start = std::chrono::steady_clock::now();
      LIC3D_TRY_ASSIGN(const SparsityMask mask, makeSparsityMask(p, dims));
      const double ms =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      budgetLeft -= ms / 1000.0;
      measured[d] = {count, ms};
      row["black"] = mask.blackCount;
      row["ms"] = ms;
      std::string gpuText = "-";
      if (madeOnGpu(d)) {
        LIC3D_TRY_ASSIGN(const double gpuMs,
                         gpuMaskMs(context, options, maskPass, maskTimer, p, dims));
        char text[32];
        std::snprintf(text, sizeof(text), "%.3f", gpuMs);
        gpuText = text;
        row["gpu_ms"] = gpuMs;
      }
      std::printf("%-16s %12.0f %14zu %12.1f %12s\n", std::string(name).c_str(), count,
                  mask.blackCount, ms, gpuText.c_str());
      std::fflush(stdout);
      report["generation"].push_back(row);
    }
  }

  std::printf(
      "\nA sparsity change end to end on %s (request, mask ready, LIC pass done: what the "
      "renderer does), automatic parameters, L = 20: a new mask (median of %d), back to a mask "
      "seen before (once); the LIC pass alone with that mask, after warm-up; where the mask is "
      "made\n",
      device.name.c_str(), options.repeats);
  std::printf("%-16s %14s %14s %14s %8s\n", "distribution", "new mask ms", "seen again ms",
              "LIC pass ms", "mask on");
  LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, {options.precision}));
  LIC3D_TRY_ASSIGN(const GpuTimer timer, benchTimer(context));
  const auto fieldKind = parseEnum<AnalyticField>(options.field);
  if (!fieldKind) return inputError("bench: --field must be an analytic field");
  LIC3D_TRY(setVolume(renderer, *fieldKind, n, options.seed));
  report["recompute"] = nlohmann::json::array();
  for (const auto& [d, name] : enumNames<SparsityDistribution>()) {
    if (d == SparsityDistribution::None) continue;
    // The automatic parameters blacken about kDefaultBlackFraction of the voxels: the first
    // change is predicted from the generation table, later ones from the changes measured.
    LIC3D_TRY_ASSIGN(const nlohmann::json row,
                     recomputeRow(context, options, budgetLeft, renderer, timer, d, name,
                                  predictedSeconds(d, kDefaultBlackFraction * voxels)));
    std::fflush(stdout);
    report["recompute"].push_back(row);
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
  contextOptions.pipelineStatistics = options.kernels;
  Result<Context> context = Context::create(contextOptions);
  if (!context) return reportError(context.error());
  const Result<nlohmann::json> report =
      options.variants             ? runVariants(*context, options)
      : options.distributions      ? runDistributions(*context, options)
      : options.kernels            ? runKernelBenchmarks(*context, options)
      : options.fidelity           ? runFidelityBenchmarks(*context, options)
      : options.visible            ? runVisibleBenchmarks(*context, options)
      : options.drag               ? runDragBenchmarks(*context, options)
      : !options.readField.empty() ? runReadRateBenchmarks(*context, options)
                                   : runBenchmarks(*context, options);
  if (!report) return reportError(report.error());
  if (!options.json.empty()) {
    if (auto r = writeFileAtomically(options.json, report->dump(2) + "\n"); !r)
      return reportError(r.error());
    if (!global.quiet) std::fprintf(stderr, "lic3d: wrote %s\n", options.json.c_str());
  }
  return kExitOk;
}

}  // namespace lic3d::cli
