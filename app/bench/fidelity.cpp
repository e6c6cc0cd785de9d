// SPDX-License-Identifier: BSD-3-Clause
// `lic3d bench --fidelity`: how far each RK2 scheme's LIC lies from a converged one (RK4 at h/8 on
// the CPU, convergedLicAtVoxel), on the analytic fields and on files, for the scheme's own CPU
// reference and for the device's volume with each texture precision. The default scheme is the
// fastest whose error is no worse than the exact scheme's (docs/LIC_SEMANTICS.md, "Fidelity").
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "bench/bench.h"
#include "core/parallel.h"
#include "core/volume_compare.h"
#include "io/field_io.h"
#include "lic/analytic_fields.h"
#include "lic/lic_reference.h"
#include "lic/noise.h"
#include "render/lic_renderer.h"

namespace lic3d::cli {
namespace {

// Voxels judged per field: enough that the means hold to about a percent.
constexpr std::size_t kVoxelsPerField = 4000;

struct Error {
  double mean = 0.0;  // mean |value - converged|
  double r = 0.0;     // correlation with the converged values
};

Error errorOf(const std::vector<double>& values, const std::vector<double>& converged) {
  double sum = 0.0;
  for (std::size_t i = 0; i < values.size(); ++i) sum += std::abs(values[i] - converged[i]);
  return {sum / static_cast<double>(values.size()), correlation(values, converged)};
}

// A fixed random choice of voxels (the same for every scheme).
std::vector<glm::ivec3> pickVoxels(Dims dims, std::uint64_t seed) {
  std::vector<glm::ivec3> voxels;
  std::mt19937_64 random(seed);
  const std::size_t count = std::min<std::size_t>(kVoxelsPerField, voxelCount(dims));
  for (std::size_t k = 0; k < count; ++k)
    voxels.emplace_back(static_cast<int>(random() % static_cast<std::uint64_t>(dims.x)),
                        static_cast<int>(random() % static_cast<std::uint64_t>(dims.y)),
                        static_cast<int>(random() % static_cast<std::uint64_t>(dims.z)));
  return voxels;
}

struct NamedField {
  std::string name;
  VectorField field;
};

Result<std::vector<NamedField>> fieldsToJudge(const BenchOptions& options) {
  LIC3D_TRY_ASSIGN(const std::vector<int> sizes, parseIntList(options.sizes, "--sizes", 4, 512));
  const Dims dims(sizes.front());
  std::vector<NamedField> fields;
  for (const AnalyticField kind :
       {AnalyticField::Tornado, AnalyticField::Corner, AnalyticField::Abc, AnalyticField::Vortex,
        AnalyticField::Solenoidal})
    fields.push_back({std::string(enumName(kind)), makeAnalyticField(kind, dims)});
  std::string list = options.fidelityFiles;
  while (!list.empty()) {
    const std::size_t comma = list.find(',');
    const std::string path = list.substr(0, comma);
    list = comma == std::string::npos ? "" : list.substr(comma + 1);
    if (path.empty()) continue;
    Result<VectorField> field = readVectorField(path);
    if (!field) return field.error();
    fields.push_back({std::filesystem::path(path).filename().string(), std::move(*field)});
  }
  return fields;
}

struct Judged {
  StepScheme scheme;
  FieldPrecision precision;  // Auto: the CPU reference of the scheme, in double
};

}  // namespace

Result<nlohmann::json> runFidelityBenchmarks(const Context& context, const BenchOptions& options) {
  LIC3D_TRY_ASSIGN(const std::vector<int> lengths,
                   parseIntList(options.lengths, "--lengths", 1, kMaxLicLength));
  LIC3D_TRY_ASSIGN(const std::vector<NamedField> fields, fieldsToJudge(options));
  const FieldPrecision automatic = resolvePrecision(context, FieldPrecision::Auto);
  const std::vector<Judged> judged{
      {StepScheme::Exact, FieldPrecision::Auto},
      {StepScheme::Ab2, FieldPrecision::Auto},
      {StepScheme::Fused, FieldPrecision::Auto},
      {StepScheme::Exact, automatic},
      {StepScheme::Ab2, automatic},
      {StepScheme::Fused, automatic},
      {StepScheme::Exact, FieldPrecision::Byte},
      {StepScheme::Fused, FieldPrecision::Byte},
  };
  auto label = [](const Judged& j) {
    return std::string(enumName(j.scheme)) + ", " +
           (j.precision == FieldPrecision::Auto ? std::string("CPU double")
                                                : std::string(fieldTextureFormatName(j.precision)));
  };

  nlohmann::json report = newReport(context);
  report["rows"] = nlohmann::json::array();
  const int length = lengths.back();
  std::printf("lic3d bench --fidelity on %s, %s\n", context.deviceInfo().name.c_str(),
              today().c_str());
  std::printf(
      "RK2, box kernel, h = 0.5, L = %d, trilinear noise; error against RK4 at h/8 (CPU) over %zu "
      "random voxels per field: mean |LIC - converged| and correlation r\n",
      length, kVoxelsPerField);
  std::printf("%-24s %-18s %12s %9s %14s\n", "field", "scheme, texture", "mean |diff|", "r",
              "x exact's");
  for (const NamedField& f : fields) {
    const NoiseVolume noise = makeWhiteNoise(f.field.dims, options.seed);
    const FieldSampler sampler(f.field);
    const std::vector<glm::ivec3> voxels = pickVoxels(f.field.dims, options.seed);
    LicParams params;
    params.length = length;
    std::vector<double> converged(voxels.size());
    parallelFor(voxels.size(), 0, [&](std::size_t k) {
      converged[k] = convergedLicAtVoxel(sampler, noise, params, voxels[k]);
    });
    std::optional<LicRenderer> renderer;
    FieldPrecision uploaded = FieldPrecision::Auto;
    double exactCpu = 0.0, exactDevice = 0.0;
    for (const Judged& j : judged) {
      LicParams p = params;
      p.scheme = j.scheme;
      std::vector<double> values(voxels.size());
      if (j.precision == FieldPrecision::Auto) {
        parallelFor(voxels.size(), 0,
                    [&](std::size_t k) { values[k] = licAtVoxel(sampler, noise, p, voxels[k]); });
      } else {
        if (!renderer || uploaded != j.precision) {
          renderer.reset();
          LIC3D_TRY_ASSIGN(LicRenderer made, LicRenderer::create(context, {j.precision}));
          LIC3D_TRY(made.setInputs(f.field, noise));
          renderer = std::move(made);
          uploaded = j.precision;
        }
        LIC3D_TRY_ASSIGN([[maybe_unused]] const bool ran, renderer->updateLic(p));
        LIC3D_TRY_ASSIGN(const ScalarVolume volume, renderer->readLicVolume());
        for (std::size_t k = 0; k < voxels.size(); ++k)
          values[k] = volume.values[voxelIndex(volume.dims, voxels[k].x, voxels[k].y, voxels[k].z)];
      }
      const Error e = errorOf(values, converged);
      const bool cpu = j.precision == FieldPrecision::Auto;
      if (j.scheme == StepScheme::Exact && cpu) exactCpu = e.mean;
      if (j.scheme == StepScheme::Exact && j.precision == automatic) exactDevice = e.mean;
      const double relative = e.mean / (cpu ? exactCpu : exactDevice);
      const std::string name = label(j);
      std::printf("%-24s %-18s %12.3e %9.5f %14.2f\n", f.name.c_str(), name.c_str(), e.mean, e.r,
                  relative);
      std::fflush(stdout);
      report["rows"].push_back(
          {{"field", f.name},
           {"dims", {f.field.dims.x, f.field.dims.y, f.field.dims.z}},
           {"scheme", enumName(j.scheme)},
           {"texture", cpu ? "CPU double" : fieldTextureFormatName(j.precision)},
           {"mean_abs_error", e.mean},
           {"correlation", e.r},
           {"relative_to_exact", relative}});
    }
  }
  return report;
}

}  // namespace lic3d::cli
