#include "cli_options.h"

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include <unistd.h>

#include "analytic_fields.h"
#include "field_io.h"
#include "noise.h"

namespace lic3d::cli {
namespace {

template <class T>
Result<T> parseNumber(std::string_view text, const char* flag) {
  T value{};
  const char* begin = text.data();
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(begin, end, value);
  if (ec != std::errc() || ptr != end)
    return inputError(std::string(flag) + ": '" + std::string(text) + "' is not a number");
  return value;
}

std::vector<std::string_view> splitCommas(std::string_view text) {
  std::vector<std::string_view> parts;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = text.find(',', start);
    parts.push_back(text.substr(start, comma - start));
    if (comma == std::string_view::npos) break;
    start = comma + 1;
  }
  return parts;
}

std::string fieldNameList() {
  std::string names;
  for (std::string_view n : analyticFieldNames()) names += (names.empty() ? "" : "|") + std::string(n);
  return names;
}

}  // namespace

int exitCodeFor(const Error& error) {
  return error.kind == ErrorKind::InvalidInput ? kExitBadInput : kExitFailure;
}

int reportError(const Error& error) {
  std::fprintf(stderr, "lic3d: error: %s\n", error.message.c_str());
  return exitCodeFor(error);
}

void addGlobalOptions(CLI::App& app, GlobalOptions& options) {
  app.add_option("--device", options.device,
                 "Vulkan device: an index or part of a name from `lic3d devices` (default: "
                 "discrete GPU, then integrated, then CPU)");
  app.add_flag("--validation", options.validation,
               "Enable the Khronos validation layer with synchronization validation; any "
               "message makes the command fail (also LIC3D_VALIDATION=1)");
  app.add_flag("-q,--quiet", options.quiet, "Print nothing but errors");
}

void addFieldOptions(CLI::App& app, FieldOptions& options) {
  app.add_option("--field", options.field,
                 "Vector field: an analytic field (" + fieldNameList() +
                     ") or a file (.nrrd, .vtk)")
      ->capture_default_str();
  options.gridOption =
      app.add_option("--grid", options.grid,
                     "Grid of an analytic field: N for N^3, or NX,NY,NZ (1..2048 each)")
          ->capture_default_str();
  app.add_option("--noise", options.noise,
                 "Noise volume (.nrrd: uchar, ushort or float) on the field's grid (default: "
                 "seeded white noise)");
  app.add_option("--seed", options.seed, "Seed of the white noise")->capture_default_str();
}

void addLicParamsOptions(CLI::App& app, LicParams& params) {
  app.add_option("-L,--length", params.length, "Streamline steps each way (L)")
      ->check(CLI::Range(0, kMaxLicLength))
      ->capture_default_str();
  app.add_option("--step", params.step, "Step length h in voxels")
      ->check(CLI::Range(1e-3, 8.0))
      ->capture_default_str();
  app.add_option("--bias", params.bias, "Integer bias: L-B steps backward, L+B forward, |B| <= L")
      ->capture_default_str();
  const std::map<std::string, Integrator> integrators{
      {"euler", Integrator::Euler}, {"rk2", Integrator::Rk2}, {"rk4", Integrator::Rk4}};
  app.add_option("--integrator", params.integrator, "Streamline integrator: euler|rk2|rk4")
      ->transform(CLI::CheckedTransformer(integrators).description(""))
      ->default_str("rk2");
  const std::map<std::string, Kernel> kernels{
      {"box", Kernel::Box}, {"hann", Kernel::Hann}, {"gauss", Kernel::Gauss}};
  app.add_option("--kernel", params.kernel, "Convolution kernel: box|hann|gauss")
      ->transform(CLI::CheckedTransformer(kernels).description(""))
      ->default_str("box");
  const std::map<std::string, NoiseFilter> filters{{"nearest", NoiseFilter::Nearest},
                                                   {"linear", NoiseFilter::Linear}};
  app.add_option("--noise-filter", params.noiseFilter,
                 "Noise lookup along streamlines: nearest|linear")
      ->transform(CLI::CheckedTransformer(filters).description(""))
      ->default_str("linear");
  const std::map<std::string, DirectionMode> directions{
      {"normalized", DirectionMode::Normalized}, {"magnitude", DirectionMode::Magnitude}};
  app.add_option("--direction", params.direction,
                 "Step direction: normalized (v/|v|) or magnitude (v/max|v|, shorter "
                 "streamlines where the flow is slow)")
      ->transform(CLI::CheckedTransformer(directions).description(""))
      ->default_str("normalized");
}

void addLicOptions(CLI::App& app, LicParams& params) { addLicParamsOptions(app, params); }

void addPrecisionOption(CLI::App& app, FieldPrecision& precision) {
  const std::map<std::string, FieldPrecision> precisions{{"auto", FieldPrecision::Auto},
                                                         {"half", FieldPrecision::Half},
                                                         {"float", FieldPrecision::Float}};
  app.add_option("--field-precision", precision,
                 "Precision of the field and noise texture on the device: auto (float on CPU "
                 "drivers, half on GPUs), half (RGBA16F) or float (RGBA32F)")
      ->transform(CLI::CheckedTransformer(precisions).description(""))
      ->default_str("auto");
}

void addComputeOptions(CLI::App& app, ComputeOptions& options, const char* defaultOutput) {
  addFieldOptions(app, options.input);
  addLicOptions(app, options.lic);
  addPrecisionOption(app, options.precision);
  app.add_flag("--cpu", options.cpu,
               "Compute the LIC volume with the CPU reference (multi-threaded, double "
               "precision) instead of the GPU");
  options.output = defaultOutput;
  app.add_option("-o,--output", options.output, "Output file")->capture_default_str();
}

void addViewOptions(CLI::App& app, RenderOptions& options) {
  ViewParams& view = options.view;
  app.add_option("--width", view.width, "Image width in pixels")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  app.add_option("--height", view.height, "Image height in pixels")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  app.add_option("--slices", view.slices,
                 "Number of slices (0: one per voxel along the view direction)")
      ->check(CLI::Range(0, 16384))
      ->capture_default_str();
  const std::map<std::string, Slicing> slicings{{"view", Slicing::ViewAligned},
                                                {"axis", Slicing::AxisAligned}};
  app.add_option("--slicing", view.slicing,
                 "Slice planes: view (perpendicular to the view direction) or axis (perpendicular "
                 "to the grid axis closest to it)")
      ->transform(CLI::CheckedTransformer(slicings).description(""))
      ->default_str("view");
  app.add_option("--azimuth", view.camera.azimuth, "Camera azimuth in degrees around +z")
      ->capture_default_str();
  app.add_option("--elevation", view.camera.elevation, "Camera elevation in degrees")
      ->check(CLI::Range(-90.0, 90.0))
      ->capture_default_str();
  app.add_option("--distance", view.camera.distance,
                 "Camera distance from the volume centre (the longest box side is 1; 0 fits the "
                 "whole volume)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  app.add_option("--fov", view.camera.fovY, "Vertical field of view in degrees")
      ->check(CLI::Range(1.0, 170.0))
      ->capture_default_str();
  app.add_flag("--ortho", view.camera.orthographic, "Orthographic projection");
  app.add_option("--alpha", view.alpha,
                 "Opacity per voxel of depth, corrected for the slice spacing (0: invisible)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  const std::map<std::string, OpacityMode> opacities{{"constant", OpacityMode::Constant},
                                                     {"intensity", OpacityMode::Intensity}};
  app.add_option("--opacity", view.opacityMode,
                 "Opacity transfer: constant (alpha everywhere) or intensity (alpha x grey, so "
                 "dark gaps between streamlines turn clear)")
      ->transform(CLI::CheckedTransformer(opacities).description(""))
      ->default_str("intensity");
  const std::map<std::string, VolumeFilter> filters{{"nearest", VolumeFilter::Nearest},
                                                    {"linear", VolumeFilter::Linear}};
  app.add_option("--filter", view.filter, "Sampling of the LIC volume by the slices: nearest|linear")
      ->transform(CLI::CheckedTransformer(filters).description(""))
      ->default_str("linear");
  app.add_option("--background", options.background,
                 "Background colour R,G,B: components in 0..1, or 0..255 if any exceeds 1")
      ->capture_default_str();
  app.add_option("--window", options.window,
                 "Intensity window mapped to black..white: auto (the volume's 3rd and 97th "
                 "percentiles) or LO,HI in 0..1")
      ->capture_default_str();
  app.add_option("--gain", view.contrast, "Contrast: scales grey values around mid-grey")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--brightness", view.brightness, "Added to grey values (-1..1)")
      ->check(CLI::Range(-1.0, 1.0))
      ->capture_default_str();
}

Result<Dims> parseGrid(const std::string& text) {
  const std::vector<std::string_view> parts = splitCommas(text);
  if (parts.size() != 1 && parts.size() != 3)
    return inputError("--grid: expected N or NX,NY,NZ, got '" + text + "'");
  Dims dims(0);
  for (int a = 0; a < 3; ++a) {
    LIC3D_TRY_ASSIGN(dims[a], parseNumber<int>(parts[parts.size() == 1 ? 0 : a], "--grid"));
    if (dims[a] < 1 || dims[a] > 2048)
      return inputError("--grid: each size must be in 1..2048, got '" + text + "'");
  }
  return dims;
}

Result<glm::vec3> parseColor(const std::string& text, const char* flag) {
  const std::vector<std::string_view> parts = splitCommas(text);
  if (parts.size() != 3) return inputError(std::string(flag) + ": expected R,G,B, got '" + text + "'");
  glm::vec3 color(0.0f);
  for (int c = 0; c < 3; ++c) {
    LIC3D_TRY_ASSIGN(color[c], parseNumber<float>(parts[c], flag));
    if (!(color[c] >= 0.0f && color[c] <= 255.0f))
      return inputError(std::string(flag) + ": components must be in 0..1 or 0..255, got '" +
                        text + "'");
  }
  if (color.r > 1.0f || color.g > 1.0f || color.b > 1.0f) color /= 255.0f;
  return color;
}

Result<std::vector<int>> parseIntList(const std::string& text, const char* flag, int min, int max) {
  std::vector<int> values;
  for (std::string_view part : splitCommas(text)) {
    LIC3D_TRY_ASSIGN(const int v, parseNumber<int>(part, flag));
    if (v < min || v > max)
      return inputError(std::string(flag) + ": " + std::to_string(v) + " is outside " +
                        std::to_string(min) + ".." + std::to_string(max));
    values.push_back(v);
  }
  return values;
}

Result<void> finishViewOptions(RenderOptions& options) {
  LIC3D_TRY_ASSIGN(options.view.background, parseColor(options.background, "--background"));
  if (options.window == "auto") {
    options.view.autoWindow = true;
  } else {
    const std::vector<std::string_view> parts = splitCommas(options.window);
    if (parts.size() != 2) return inputError("--window: expected auto or LO,HI, got '" + options.window + "'");
    LIC3D_TRY_ASSIGN(options.view.windowLow, parseNumber<float>(parts[0], "--window"));
    LIC3D_TRY_ASSIGN(options.view.windowHigh, parseNumber<float>(parts[1], "--window"));
    if (!(options.view.windowLow >= 0.0f && options.view.windowHigh <= 1.0f &&
          options.view.windowLow < options.view.windowHigh))
      return inputError("--window: need 0 <= LO < HI <= 1, got '" + options.window + "'");
    options.view.autoWindow = false;
  }
  return {};
}

Result<void> checkHostMemory(Dims dims) {
  // The field (12 bytes per voxel), the noise (1) and the packed texels with their staging copy
  // (up to 32) live in host memory at once.
  const double needed = static_cast<double>(voxelCount(dims)) * 45.0;
  const double available = static_cast<double>(sysconf(_SC_PHYS_PAGES)) *
                           static_cast<double>(sysconf(_SC_PAGE_SIZE));
  if (available > 0.0 && needed > 0.9 * available)
    return inputError("a " + std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" +
                      std::to_string(dims.z) + " grid needs about " +
                      std::to_string(static_cast<long long>(needed / (1 << 30))) +
                      " GiB of memory; this machine has " +
                      std::to_string(static_cast<long long>(available / (1 << 30))) + " GiB");
  return {};
}

Result<VectorField> loadField(const FieldOptions& options) {
  if (const auto analytic = parseAnalyticField(options.field)) {
    LIC3D_TRY_ASSIGN(const Dims dims, parseGrid(options.grid));
    LIC3D_TRY(checkHostMemory(dims));
    return makeAnalyticField(*analytic, dims);
  }
  if (options.gridOption && options.gridOption->count() > 0)
    return inputError("--grid applies to analytic fields only; " + options.field +
                      " has its own grid");
  const std::filesystem::path path(options.field);
  if (!path.has_extension())
    return inputError("--field: '" + options.field + "' is neither an analytic field (" +
                      fieldNameList() + ") nor a file name with an extension");
  return readVectorField(path);
}

Result<NoiseVolume> loadNoise(const FieldOptions& options, Dims dims) {
  if (options.noise.empty()) return makeWhiteNoise(dims, options.seed);
  LIC3D_TRY_ASSIGN(NoiseVolume noise, readNoise(options.noise));
  if (noise.dims != dims)
    return inputError(options.noise + ": the noise grid " + std::to_string(noise.dims.x) + "x" +
                      std::to_string(noise.dims.y) + "x" + std::to_string(noise.dims.z) +
                      " does not match the field grid " + std::to_string(dims.x) + "x" +
                      std::to_string(dims.y) + "x" + std::to_string(dims.z));
  return noise;
}

Result<void> checkOutputPath(const std::string& path, const char* extension) {
  const std::filesystem::path p(path);
  if (p.extension() != extension)
    return inputError("output " + path + ": expected a " + extension + " file name");
  const std::filesystem::path folder = p.parent_path().empty() ? "." : p.parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    return inputError("output " + path + ": folder " + folder.string() + " does not exist");
  if (std::filesystem::is_directory(p, ec))
    return inputError("output " + path + " is a folder");
  return {};
}

}  // namespace lic3d::cli
