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
  app.add_option("--seed-noise", options.seedNoiseSpots,
                 "Sparse seed noise instead of white noise: N bright spots on black, placed by "
                 "Poisson-disk sampling (streamlines become distinct lines)")
      ->check(CLI::Range(0, 1 << 30))
      ->capture_default_str();
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

  std::map<std::string, SparsityDistribution> distributions;
  std::string distributionNames;
  for (std::string_view name : sparsityDistributionNames()) {
    distributions.emplace(std::string(name), *parseSparsityDistribution(name));
    distributionNames += (distributionNames.empty() ? "" : "|") + std::string(name);
  }
  SparsityParams& sparsity = params.sparsity;
  app.add_option("--sparsity", sparsity.distribution,
                 "Sparsity mask (thesis 5.1.4): voxels whose streamline touches a black point are "
                 "not drawn; points from " + distributionNames)
      ->transform(CLI::CheckedTransformer(distributions).description(""))
      ->default_str("none");
  app.add_option("--sparsity-points", sparsity.points,
                 "Black points for poisson, poisson-approx, halton, hammersley (0: automatic)")
      ->check(CLI::Range(0, 1 << 30))
      ->capture_default_str();
  app.add_option("--sparsity-radius", sparsity.radius,
                 "Minimum distance between black points in voxels, for poisson and jitter (0: "
                 "automatic)")
      ->check(CLI::Range(0.0, 4096.0))
      ->capture_default_str();
  app.add_option("--sparsity-ratio", sparsity.ratio,
                 "Fraction of black voxels of the checkerboard, in (0,1)")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();
  app.add_option("--sparsity-seed", sparsity.seed, "Seed of the random sparsity distributions")
      ->capture_default_str();
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
  app.add_option("--filter", view.filter,
                 "Sampling of the LIC volume by the slices: nearest|linear (thesis 6.4)")
      ->transform(CLI::CheckedTransformer(filters).description(""))
      ->default_str("linear");
  app.add_option("--background", options.background,
                 "Background colour R,G,B: components in 0..1, or 0..255 if any exceeds 1")
      ->capture_default_str();

  app.add_option("--contrast", options.contrast,
                 "on: stretch the drawn voxels' LIC values to mean 0.5 and deviation 0.25 (a "
                 "histogram stretch); off: grey = LIC value")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  app.add_option("--window", options.window,
                 "Intensity window mapped to black..white instead of the contrast stretch: auto "
                 "or LO,HI in 0..1")
      ->capture_default_str();
  app.add_option("--gain", view.gain, "Scales grey values around mid-grey")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--brightness", view.brightness, "Added to grey values (-1..1)")
      ->check(CLI::Range(-1.0, 1.0))
      ->capture_default_str();

  const std::map<std::string, ColorMode> colors{{"none", ColorMode::None},
                                                {"magnitude", ColorMode::Magnitude}};
  app.add_option("--color", view.color,
                 "none: grey LIC; magnitude: colour by |v| through --colormap, the LIC intensity "
                 "modulating it (thesis 5.1.2)")
      ->transform(CLI::CheckedTransformer(colors).description(""))
      ->default_str("none");
  std::map<std::string, Colormap> colormaps;
  for (std::string_view name : colormapNames())
    colormaps.emplace(std::string(name), *parseColormap(name));
  app.add_option("--colormap", view.colormap,
                 "thesis (blue-yellow-red), viridis or coolwarm")
      ->transform(CLI::CheckedTransformer(colormaps).description(""))
      ->default_str("thesis");
  app.add_option("--color-range", options.colorRange,
                 "|v| mapped to the ends of the colour map: auto (the field's min and max) or "
                 "MIN,MAX")
      ->capture_default_str();
  app.add_flag("--legend", view.legend,
               "Draw the colour legend into the image (with --color magnitude)");
  app.add_option("--magnitude-opacity", view.magnitudeOpacity,
                 "Opacity x (normalised |v|)^E so slow regions fade (thesis 5.1.3); 0 is off")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--magnitude-threshold", view.magnitudeThreshold,
                 "Voxels whose normalised |v| is below this vanish")
      ->check(CLI::Range(0.0, 1.0))
      ->capture_default_str();

  app.add_option("--clip", options.clip,
                 "Keep X0..X1, Y0..Y1, Z0..Z1 of the box, as fractions (thesis 5.2.1)")
      ->capture_default_str();
  const std::map<std::string, RoiShape> shapes{{"none", RoiShape::None},
                                               {"sphere", RoiShape::Sphere},
                                               {"cube", RoiShape::Cube},
                                               {"cylinder", RoiShape::Cylinder}};
  app.add_option("--roi", view.roi, "Region of interest: none|sphere|cube|cylinder (thesis 5.2.2)")
      ->transform(CLI::CheckedTransformer(shapes).description(""))
      ->default_str("none");
  app.add_option("--roi-center", options.roiCenter, "Centre X,Y,Z as fractions of the box")
      ->capture_default_str();
  app.add_option("--roi-size", view.roiSize,
                 "Diameter (sphere, cylinder) or side (cube) as a fraction of the longest box side")
      ->check(CLI::Range(1e-3, 10.0))
      ->capture_default_str();
  app.add_option("--roi-rotate", options.roiRotate,
                 "Rotation AX,AY,AZ in degrees (about x, then y, then z)")
      ->capture_default_str();
  app.add_flag("--roi-outside", view.roiOutside, "Keep the outside of the region instead");

  app.add_option("--fog", options.fog,
                 "Depth cueing START,END: fog grows linearly from START to END, fractions of the "
                 "depth from the volume's nearest to its farthest point (thesis 5.3.1)");
  app.add_option("--fog-color", options.fogColor, "Fog colour R,G,B (default: the background)");

  const std::map<std::string, StereoMode> stereo{{"none", StereoMode::None},
                                                 {"anaglyph", StereoMode::Anaglyph},
                                                 {"side-by-side", StereoMode::SideBySide}};
  app.add_option("--stereo", view.stereo,
                 "none, anaglyph (red left, cyan right) or side-by-side (left|right, twice the "
                 "width) with an off-axis frustum (thesis 5.3.2)")
      ->transform(CLI::CheckedTransformer(stereo).description(""))
      ->default_str("none");
  app.add_option("--eye-separation", view.eyeSeparation,
                 "Distance between the eyes in box units (0: zero-parallax distance / 30)")
      ->check(CLI::Range(0.0, 100.0))
      ->capture_default_str();
  app.add_option("--zero-parallax", view.zeroParallax,
                 "Distance from the eye of the plane that shows no disparity (0: the volume "
                 "centre)")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();

  const std::map<std::string, Lighting> lighting{{"none", Lighting::None},
                                                 {"phong", Lighting::Phong},
                                                 {"lines", Lighting::Lines}};
  app.add_option("--lighting", view.lighting,
                 "none, phong (normals from the streamline's TNB frame, thesis 5.3.3) or lines "
                 "(illuminated lines: lit from the tangent alone)")
      ->transform(CLI::CheckedTransformer(lighting).description(""))
      ->default_str("none");
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

Result<std::vector<float>> parseFloatList(const std::string& text, const char* flag,
                                          std::size_t count) {
  const std::vector<std::string_view> parts = splitCommas(text);
  if (parts.size() != count)
    return inputError(std::string(flag) + ": expected " + std::to_string(count) +
                      " comma-separated numbers, got '" + text + "'");
  std::vector<float> values;
  for (std::string_view part : parts) {
    LIC3D_TRY_ASSIGN(const float v, parseNumber<float>(part, flag));
    values.push_back(v);
  }
  return values;
}

Result<void> finishViewOptions(RenderOptions& options) {
  ViewParams& view = options.view;
  LIC3D_TRY_ASSIGN(view.background, parseColor(options.background, "--background"));
  view.contrast = options.contrast == "on";
  if (options.window != "auto") {
    LIC3D_TRY_ASSIGN(const std::vector<float> w, parseFloatList(options.window, "--window", 2));
    if (!(w[0] >= 0.0f && w[1] <= 1.0f && w[0] < w[1]))
      return inputError("--window: need 0 <= LO < HI <= 1, got '" + options.window + "'");
    view.manualWindow = true;
    view.windowLow = w[0];
    view.windowHigh = w[1];
  }
  if (options.colorRange != "auto") {
    LIC3D_TRY_ASSIGN(const std::vector<float> r,
                     parseFloatList(options.colorRange, "--color-range", 2));
    if (!(r[0] < r[1]))
      return inputError("--color-range: need MIN < MAX, got '" + options.colorRange + "'");
    view.autoColorRange = false;
    view.colorLow = r[0];
    view.colorHigh = r[1];
  }
  if (view.legend && view.color != ColorMode::Magnitude)
    return inputError("--legend shows the colour map: use it with --color magnitude");
  LIC3D_TRY_ASSIGN(const std::vector<float> clip, parseFloatList(options.clip, "--clip", 6));
  view.clipMin = {clip[0], clip[2], clip[4]};
  view.clipMax = {clip[1], clip[3], clip[5]};
  LIC3D_TRY_ASSIGN(const std::vector<float> centre,
                   parseFloatList(options.roiCenter, "--roi-center", 3));
  view.roiCenter = {centre[0], centre[1], centre[2]};
  LIC3D_TRY_ASSIGN(const std::vector<float> rotate,
                   parseFloatList(options.roiRotate, "--roi-rotate", 3));
  view.roiRotation = {rotate[0], rotate[1], rotate[2]};
  if (!options.fog.empty()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> fog, parseFloatList(options.fog, "--fog", 2));
    view.fog = true;
    view.fogStart = fog[0];
    view.fogEnd = fog[1];
  }
  if (!options.fogColor.empty()) {
    LIC3D_TRY_ASSIGN(view.fogColor, parseColor(options.fogColor, "--fog-color"));
    view.fogColorFromBackground = false;
  }
  return validate(view);
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
  if (options.seedNoiseSpots > 0 && !options.noise.empty())
    return inputError("--seed-noise and --noise both choose the noise: give one");
  if (options.seedNoiseSpots > 0) {
    if (static_cast<std::size_t>(options.seedNoiseSpots) > voxelCount(dims))
      return inputError("--seed-noise: more spots than voxels");
    return makeSeedNoise(dims, static_cast<std::size_t>(options.seedNoiseSpots), options.seed);
  }
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
