// SPDX-License-Identifier: BSD-3-Clause
// `lic3d bench --visible`: the full LIC pass against visible work (docs/VISIBLE_WORK.md), the
// classification of the bricks a view can show and the LIC over them, from nothing made, timed
// with GPU timestamps, for the default look and for a clip plane that removes half the box.
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench/bench.h"
#include "core/look.h"
#include "core/session.h"
#include "gpu/submit.h"
#include "gpu/timer.h"
#include "io/field_io.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "loading/session_inputs.h"
#include "passes/lic_pass.h"
#include "passes/visible_bricks_pass.h"
#include "render/lic_renderer.h"

namespace lic3d::cli {
namespace {

struct NamedField {
  std::string name;
  VectorField field;
};

// The analytic --field at each of --sizes, then each of --visible-files at --resolution.
Result<std::vector<NamedField>> fieldsToTime(const BenchOptions& options) {
  std::vector<NamedField> fields;
  if (options.visibleFiles.empty()) {
    const std::optional<AnalyticField> kind = parseEnum<AnalyticField>(options.field);
    if (!kind) return inputError("bench --visible: --field must be an analytic field");
    LIC3D_TRY_ASSIGN(const std::vector<int> sizes, parseIntList(options.sizes, "--sizes", 4, 2048));
    for (const int n : sizes)
      fields.push_back(
          {options.field + " " + std::to_string(n) + "^3", makeAnalyticField(*kind, Dims(n))});
  }
  std::string list = options.visibleFiles;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    const std::string path = list.substr(0, comma);
    list = comma == std::string::npos ? "" : list.substr(comma + 1);
    if (path.empty()) continue;
    LIC3D_TRY_ASSIGN(VectorField file, readVectorField(path));
    FieldSource source;
    source.resolution = options.resolution;
    LIC3D_TRY_ASSIGN(VectorField field, atResolution(std::move(file), source));
    fields.push_back({std::filesystem::path(path).filename().string() + " " + options.resolution,
                      std::move(field)});
  }
  return fields;
}

// What the LIC of one field is timed with: the passes and an output volume (no mask: visible
// work is off with sparsity).
struct VisibleRig {
  LicPass lic;
  VisibleBricksPass bricks;
  Image output;
};

Result<VisibleRig> makeRig(const Context& context, Dims dims) {
  VisibleRig rig;
  LIC3D_TRY_ASSIGN(rig.lic, LicPass::create(context));
  LIC3D_TRY_ASSIGN(rig.bricks, VisibleBricksPass::create(context));
  LIC3D_TRY(rig.bricks.reserve(dims));
  ImageDesc desc;
  desc.format = kLicVolumeFormat;
  desc.extent = extentOf(dims);
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT;
  desc.name = "bench lic volume";
  LIC3D_TRY_ASSIGN(rig.output, Image::create(context, desc));
  return rig;
}

// GPU milliseconds of the full pass (`visible` null) or of forgetting the made bricks,
// classifying for `visible` and the LIC over the listed bricks.
Result<double> timeOnce(const Context& context, VisibleRig& rig, const GpuTimer& timer,
                        const FieldTexture& field, const LicParams& params,
                        const VisibleBricksSetup* visible) {
  Result<void> recorded;
  LIC3D_TRY(submitAndWait(
      context,
      [&](VkCommandBuffer cmd) {
        imageBarrier(cmd, rig.output.handle(), VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_NONE,
                     VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        if (visible) rig.bricks.recordForget(cmd);
        timer.reset(cmd, 0);
        timer.begin(cmd, 0);
        if (!visible) {
          recorded = rig.lic.record(cmd, field, nullptr, {}, rig.output, params, 0, field.dims.z);
        } else {
          recorded = rig.bricks.record(cmd, field, *visible);
          if (recorded)
            recorded = rig.lic.recordBricks(cmd, field, nullptr, {}, rig.output, params, rig.bricks,
                                            0, rig.bricks.bricks().z);
        }
        timer.end(cmd, 0);
        if (visible) {
          memoryBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                        VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT,
                        VK_ACCESS_2_TRANSFER_READ_BIT);
          rig.bricks.recordReadback(cmd);
        }
      },
      "visible work timing"));
  LIC3D_TRY(std::move(recorded));
  return timer.milliseconds(0);
}

}  // namespace

Result<nlohmann::json> runVisibleBenchmarks(const Context& context, const BenchOptions& options) {
  if (!context.supportsTimestamps())
    return unsupportedError("bench --visible: the device has no timestamp queries");
  LIC3D_TRY_ASSIGN(const std::vector<NamedField> fields, fieldsToTime(options));
  LIC3D_TRY_ASSIGN(const GpuTimer timer, GpuTimer::create(context, 1, "visible timestamps"));
  nlohmann::json report = newReport(context);
  report["rows"] = nlohmann::json::array();
  double budgetLeft = options.budgetSeconds;
  Session session;
  applyLook(kDefaultLook, session);
  std::printf(
      "Visible work on %s: the full LIC pass against classification + LIC of the visible "
      "bricks (from none made), the default look, a %dx%d view; median of %d after %d warm-up "
      "(GPU timestamps)\n",
      context.deviceInfo().name.c_str(), session.view.width, session.view.height, options.repeats,
      options.warmup);
  std::printf("%-22s %-16s %14s %13s %12s %12s %8s %s\n", "field", "view", "grid", "visible bricks",
              "full ms", "visible ms", "ratio", "renderer takes");
  for (const NamedField& named : fields) {
    const Dims dims = named.field.dims;
    RendererOptions rendererOptions{options.precision};
    rendererOptions.visibleWork = true;
    LIC3D_TRY_ASSIGN(LicRenderer renderer, LicRenderer::create(context, rendererOptions));
    LIC3D_TRY(renderer.setInputs(named.field, makeWhiteNoise(dims, options.seed)));
    LIC3D_TRY_ASSIGN(VisibleRig rig, makeRig(context, dims));
    const FieldTexture& texture = renderer.fieldTextures().field();
    ViewParams halfBox = session.view;
    halfBox.clipPlane = true;
    halfBox.clipPlanePoint = glm::vec3(0.5f);
    halfBox.clipPlaneNormal = glm::vec3(1.0f, 0.0f, 0.0f);
    const std::pair<const char*, const ViewParams*> views[] = {{"default look", &session.view},
                                                               {"half-box clip plane", &halfBox}};
    for (const auto& [viewName, view] : views) {
      LIC3D_TRY_ASSIGN(const std::optional<VisibleBricksSetup> setup,
                       renderer.visibleBricksFor(*view));
      if (!setup) return unsupportedError("bench --visible: no visible work on this device");
      LIC3D_TRY_ASSIGN(const Timing full, measure(options, budgetLeft, [&] {
                         return timeOnce(context, rig, timer, texture, session.lic, nullptr);
                       }));
      LIC3D_TRY_ASSIGN(const Timing visible, measure(options, budgetLeft, [&] {
                         return timeOnce(context, rig, timer, texture, session.lic, &*setup);
                       }));
      std::uint64_t shown = 0, listed = 0;
      const std::vector<std::uint32_t> flags = rig.bricks.visibleFlags();
      for (const std::uint32_t flag : flags) shown += flag;
      for (const std::vector<std::uint32_t>& layer : rig.bricks.listedBricks())
        listed += layer.size();
      const double fraction = static_cast<double>(shown) / static_cast<double>(flags.size());
      const bool measured = full.measured && visible.measured;
      const char* takes = fraction >= kVisibleFullPassShare ? "full pass" : "bricks";
      if (measured) {
        std::printf("%-22s %-16s %14s %12.1f%% %12.3f %12.3f %8.3f %s\n", named.name.c_str(),
                    viewName, gridText(dims).c_str(), 100.0 * fraction, full.medianMs,
                    visible.medianMs, visible.medianMs / full.medianMs, takes);
      } else {
        std::printf("%-22s %-16s %14s %12.1f%% skipped: %s\n", named.name.c_str(), viewName,
                    gridText(dims).c_str(), 100.0 * fraction,
                    (full.measured ? visible : full).skipped.c_str());
      }
      std::fflush(stdout);
      nlohmann::json row;
      row["field"] = named.name;
      row["view"] = viewName;
      row["grid"] = gridText(dims);
      row["visible_brick_fraction"] = fraction;
      row["listed_bricks"] = listed;
      row["renderer_takes"] = takes;
      if (measured) {
        row["full_ms"] = full.medianMs;
        row["visible_ms"] = visible.medianMs;
        row["ratio"] = visible.medianMs / full.medianMs;
      }
      report["rows"].push_back(row);
    }
  }
  return report;
}

}  // namespace lic3d::cli
