#include "cli_options.h"

#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>

#include "core/enum_names.h"
#include "core/parameter_ranges.h"
#include "io/session_file.h"
#include "lic/analytic_fields.h"

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

// The session keys the engine names parameters by (Error::parameter), and the flags that set
// them: reportError shows the flag where the message has the key. Filled as the options are
// added.
std::map<std::string, std::string, std::less<>>& flagNames() {
  static std::map<std::string, std::string, std::less<>> names;
  return names;
}

// "--length" of "-L,--length".
std::string longName(const std::string& flags) {
  const std::size_t comma = flags.rfind(',');
  return comma == std::string::npos ? flags : flags.substr(comma + 1);
}

void nameFlag(std::string_view key, const std::string& flags) {
  flagNames().emplace(std::string(key), longName(flags));
}

bool isKeyCharacter(char c) {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.';
}

TextOption& addText(CLI::App& app, const std::string& flag, TextOption& option,
                    const std::string& help, const std::string& shownDefault = "",
                    std::string_view key = {}) {
  option.option = app.add_option(flag, option.text, help);
  if (!shownDefault.empty()) option.option->default_str(shownDefault);
  if (!key.empty()) nameFlag(key, flag);
  return option;
}

// CLI11's check of a value against its range of core/parameter_ranges.h.
CLI::Validator rangeCheck(const ParameterRange& range) {
  return CLI::Validator(
      [range](std::string& text) -> std::string {
        double value = 0.0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (error != std::errc() || end != text.data() + text.size()) return {};  // CLI11 says
        return range.contains(value) ? std::string() : "must be in " + range.text();
      },
      "in " + range.text(), "RANGE");
}

// A numeric option with its range, whose key error messages name.
template <class T>
CLI::Option* addRanged(CLI::App& app, const std::string& flags, T& value,
                       const ParameterRange& range, const std::string& help) {
  nameFlag(range.key, flags);
  return app.add_option(flags, value, help)->check(rangeCheck(range))->capture_default_str();
}

}  // namespace

int exitCodeFor(const Error& error) {
  switch (error.kind) {
    case ErrorKind::InvalidInput: return kExitBadInput;
    case ErrorKind::ResourceLimit: return kExitResourceLimit;
    default: return kExitFailure;
  }
}

std::string messageWithFlags(const Error& error) {
  std::string text = error.message;
  if (error.parameter.empty()) return text;
  // The key the message starts with, then every other key with a dot that it mentions.
  const auto named = flagNames().find(error.parameter);
  if (named != flagNames().end() && text.starts_with(error.parameter))
    text.replace(0, error.parameter.size(), named->second);
  for (const auto& [key, flag] : flagNames()) {
    if (key.find('.') == std::string::npos) continue;
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at)) {
      const std::size_t end = at + key.size();
      const bool whole = (at == 0 || !isKeyCharacter(text[at - 1])) &&
                         (end == text.size() || !isKeyCharacter(text[end]));
      if (!whole) {
        at = end;
        continue;
      }
      text.replace(at, key.size(), flag);
      at += flag.size();
    }
  }
  return text;
}

int reportError(const Error& error) {
  std::fprintf(stderr, "lic3d: error: %s\n", messageWithFlags(error).c_str());
  return exitCodeFor(error);
}

void addGlobalOptions(CLI::App& app, GlobalOptions& options) {
  app.add_option("--device", options.device,
                 "Vulkan device: an index or part of a name from `lic3d devices` (default: "
                 "discrete GPU, then integrated, then CPU)");
  nameFlag("device", "--device");
  app.add_flag("--validation", options.validation,
               "Enable the Khronos validation layer with synchronization validation; any "
               "message makes the command fail (also LIC3D_VALIDATION=1)");
  app.add_flag("-q,--quiet", options.quiet,
               "Print nothing but errors and warnings about the input (no progress, no summary)");
}

void addInputOptions(CLI::App& app, SessionOptions& options, bool planar) {
  Session& s = options.session;
  options.planar = planar;
  app.add_option("--session", options.sessionFile,
                 "Start from a session file (JSON, as the viewer saves it); other flags override "
                 "its values");
  app.add_option("--field", s.field.field,
                 planar ? "Vector field: a 2D analytic field (" + enumChoices<AnalyticField2D>() +
                              "), a plane of a 3D one (" + enumChoices<AnalyticField>() +
                              ", see --slice), a file (.vtk, .vti, .nrrd, .nhdr, .raw; 2D, or a "
                              "plane of a 3D one), or a time series of files: step_%03d.vti or "
                              "'step_*.vti' (docs/TIME.md)"
                        : "Vector field: an analytic field (" + enumChoices<AnalyticField>() +
                              "), a file (.vtk, .vti, .nrrd, .nhdr, .raw), or a time series of "
                              "files: step_%03d.vti or 'step_*.vti' (docs/TIME.md)")
      ->capture_default_str();
  nameFlag("field.source", "--field");
  nameFlag("field.array", "--array");
  app.add_option("--array", s.field.array,
                 "The vector array of a .vtk or .vti file with several (default: the active or "
                 "first one; the others are listed)");
  addText(app, "--grid", options.grid,
          planar ? "Grid of an analytic field: N (N^2 for a 2D field, N^3 for a 3D one), NX,NY "
                   "(2D) or NX,NY,NZ (3D), 1..2048 each"
                 : "Grid of an analytic field: N for N^3, or NX,NY,NZ (1..2048 each)",
          "128", "field.grid");
  app.add_option("--noise", s.noise.file,
                 "Noise volume (.nrrd: uchar, ushort or float) on the field's grid (default: "
                 "seeded white noise)");
  nameFlag("noise.file", "--noise");
  app.add_option("--seed", s.noise.seed, "Seed of the white noise")->capture_default_str();
  addRanged(app, "--seed-noise", s.noise.seedSpots, ranges::kSeedSpots,
            "Sparse seed noise instead of white noise: N bright spots on black, placed by "
            "Poisson-disk sampling (streamlines become distinct lines)");

  LicParams& params = s.lic;
  addRanged(app, "-L,--length", params.length, ranges::kLength, "Streamline steps each way (L)");
  addRanged(app, "--step", params.step, ranges::kStep, "Step length h in voxels");
  app.add_option("--bias", params.bias, "Integer bias: L-B steps backward, L+B forward, |B| <= L")
      ->capture_default_str();
  nameFlag("lic.bias", "--bias");
  addEnumOption(app, "--integrator", params.integrator, "Streamline integrator");
  addEnumOption(app, "--kernel", params.kernel, "Convolution kernel");
  addEnumOption(app, "--noise-filter", params.noiseFilter, "Noise lookup along streamlines");
  addEnumOption(app, "--direction", params.direction,
                "Step direction: normalized (v/|v|) or magnitude (v/max|v|, shorter streamlines "
                "where the flow is slow)");
  addEnumOption(app, "--scheme", params.scheme,
                "How rk2 steps: exact (every step an RK2 step: two texture fetches per sample) or "
                "ab2 (a first RK2 step, then two-step Adams-Bashforth steps of h from the "
                "directions already fetched: one fetch per sample)");

  SparsityParams& sparsity = params.sparsity;
  addEnumOption(app, "--sparsity", sparsity.distribution,
                "Sparsity mask (thesis 5.1.4): voxels whose streamline touches a black point are "
                "not drawn; points from");
  nameFlag("lic.sparsity.distribution", "--sparsity");
  addRanged(app, "--sparsity-points", sparsity.points, ranges::kSparsityPoints,
            "Black points for poisson, poisson-approx, halton, hammersley (0: automatic)");
  addRanged(app, "--sparsity-radius", sparsity.radius, ranges::kSparsityRadius,
            "Minimum distance between black points in voxels, for poisson and jitter (0: "
            "automatic)");
  addRanged(app, "--sparsity-ratio", sparsity.ratio, ranges::kSparsityRatio,
            "Fraction of black voxels of the checkerboard, in (0,1)");
  app.add_option("--sparsity-seed", sparsity.seed, "Seed of the random sparsity distributions")
      ->capture_default_str();
  options.time =
      addRanged(app, "--time", s.time, ranges::kTime,
                "Time of an unsteady field (docs/TIME.md): the tornado's and the wave's time "
                "parameter, or for a series of files the position in steps (1.5: halfway "
                "between the second and the third file)");
  addRanged(app, "--time-steps", s.timeSteps, ranges::kTimeSteps,
            "A time-dependent analytic field (tornado) as a series of K steps over its "
            "period, blended on the GPU as a series of files is (0: sampled at each time "
            "exactly)");
  addEnumOption(app, "--field-precision", s.precision,
                "Precision of the field and noise texture on the device: auto (float on CPU "
                "drivers, half on GPUs), half (RGBA16F), float (RGBA32F) or byte (RGBA8: 8-bit "
                "direction with square-root magnitude, 8-bit noise; a quarter of float's memory)");
}

void addComputeOptions(CLI::App& app, ComputeOptions& options, const char* defaultOutput) {
  addInputOptions(app, options.inputs);
  app.add_flag("--cpu", options.cpu,
               "Compute the LIC volume with the CPU reference (multi-threaded, double "
               "precision) instead of the GPU");
  options.output = defaultOutput;
  const bool picture = std::string_view(defaultOutput).ends_with(".png");
  options.outputOption =
      app.add_option("-o,--output", options.output,
                     picture ? "Output PNG; for --turntable or --animate-bias a pattern with one "
                               "%d or %0Nd for the frame number (default then lic3d_%04d.png)"
                             : "Output: the LIC volume as .nrrd or .vti (float32), or one slice "
                               "as .png with --slice")
          ->capture_default_str();
}

namespace {

// Grey mapping and colour, the same for the volume (`render`) and the 2D image (`render2d`):
// `what` names what the contrast stretch measures, `colorNote` ends the --color help.
void addGreyAndColorOptions(CLI::App& app, SessionOptions& options, const char* what,
                            const char* colorNote) {
  ViewParams& view = options.session.view;
  addText(app, "--contrast", options.contrast,
          std::string("on: stretch ") + what +
              " LIC values to mean 0.5 and deviation 0.25 (a histogram stretch); off: grey = "
              "LIC value",
          "on")
      .option->check(CLI::IsMember({"on", "off"}));
  addText(app, "--window", options.window,
          "Intensity window mapped to black..white instead of the contrast stretch: auto or "
          "LO,HI in 0..1",
          "auto", "view.window");
  addRanged(app, "--gain", view.gain, ranges::kGain, "Scales grey values around mid-grey");
  addRanged(app, "--brightness", view.brightness, ranges::kBrightness,
            "Added to grey values (-1..1)");
  addEnumOption(app, "--color", view.color,
                std::string("none: grey LIC; magnitude: colour by |v| through --colormap, the LIC "
                            "intensity modulating it") +
                    colorNote);
  addEnumOption(app, "--colormap", view.colormap, "Colour map");
  addText(app, "--color-range", options.colorRange,
          "|v| mapped to the ends of the colour map: auto (the field's min and max) or MIN,MAX",
          "auto", "view.color_range");
  app.add_flag("--legend", view.legend,
               "Draw the colour legend into the image (with --color magnitude)");
}

}  // namespace

void addViewOptions(CLI::App& app, SessionOptions& options) {
  ViewParams& view = options.session.view;
  addRanged(app, "--width", view.width, ranges::kImageWidth, "Image width in pixels");
  addRanged(app, "--height", view.height, ranges::kImageHeight, "Image height in pixels");
  addRanged(app, "--slices", view.slices, ranges::kSlices,
            "Number of slices (0: one per voxel along the view direction)");
  addEnumOption(app, "--slicing", view.slicing,
                "Slice planes: view (perpendicular to the view direction) or axis (perpendicular "
                "to the grid axis closest to it)");
  addRanged(app, "--azimuth", view.camera.azimuth, ranges::kAzimuth,
            "Camera azimuth in degrees around +z");
  addRanged(app, "--elevation", view.camera.elevation, ranges::kElevation,
            "Camera elevation in degrees");
  addRanged(app, "--distance", view.camera.distance, ranges::kDistance,
            "Camera distance from the volume centre (the longest box side is 1; 0 fits the "
            "whole volume)");
  addRanged(app, "--fov", view.camera.fovY, ranges::kFov, "Vertical field of view in degrees");
  app.add_flag("--ortho", view.camera.orthographic, "Orthographic projection");
  nameFlag("view.camera.orthographic", "--ortho");
  addRanged(app, "--alpha", view.alpha, ranges::kAlpha,
            "Opacity per voxel of depth, corrected for the slice spacing (0: invisible)");
  addEnumOption(app, "--opacity", view.opacityMode,
                "Opacity transfer: constant (alpha everywhere) or intensity (alpha x grey, so "
                "dark gaps between streamlines turn clear)");
  addEnumOption(app, "--filter", view.filter,
                "Sampling of the LIC volume by the slices (thesis 6.4)");
  addText(app, "--background", options.background,
          "Background colour R,G,B: components in 0..1, or 0..255 if any exceeds 1", "0,0,0",
          "view.background");

  addGreyAndColorOptions(app, options, "the drawn voxels'", " (thesis 5.1.2)");
  app.add_flag("--axes", view.axes,
               "Draw the box's edges and label each axis with its physical range (the grid's "
               "origin and spacing)");
  addRanged(app, "--magnitude-opacity", view.magnitudeOpacity, ranges::kMagnitudeOpacity,
            "Opacity x (normalised |v|)^E so slow regions fade (thesis 5.1.3); 0 is off");
  addRanged(app, "--magnitude-threshold", view.magnitudeThreshold, ranges::kMagnitudeThreshold,
            "Voxels whose normalised |v| is below this vanish");

  addText(app, "--clip", options.clip,
          "Keep X0..X1, Y0..Y1, Z0..Z1 of the box, as fractions (thesis 5.2.1)", "0,1,0,1,0,1",
          "view.clip_min");
  nameFlag("view.clip_max", "--clip");
  addEnumOption(app, "--roi", view.roi, "Region of interest (thesis 5.2.2)");
  addText(app, "--roi-center", options.roiCenter, "Centre X,Y,Z as fractions of the box",
          "0.5,0.5,0.5", "view.roi_center");
  addRanged(app, "--roi-size", view.roiSize, ranges::kRoiSize,
            "Diameter (sphere, cylinder) or side (cube) as a fraction of the longest box side");
  addText(app, "--roi-rotate", options.roiRotate,
          "Rotation AX,AY,AZ in degrees (about x, then y, then z)", "0,0,0", "view.roi_rotation");
  app.add_flag("--roi-outside", view.roiOutside, "Keep the outside of the region instead");

  addText(app, "--fog", options.fog,
          "Depth cueing START,END: fog grows linearly from START to END, fractions of the depth "
          "from the volume's nearest to its farthest point (thesis 5.3.1)",
          "", "view.fog_range");
  addText(app, "--fog-color", options.fogColor, "Fog colour R,G,B (default: the background)", "",
          "view.fog_color");

  addEnumOption(app, "--stereo", view.stereo,
                "Stereo with an off-axis frustum (thesis 5.3.2): anaglyph is red left, cyan "
                "right; side-by-side is left|right, twice the width");
  nameFlag("view.stereo", "--stereo");
  addRanged(app, "--eye-separation", view.eyeSeparation, ranges::kEyeSeparation,
            "Distance between the eyes in box units (0: zero-parallax distance / 30)");
  addRanged(app, "--zero-parallax", view.zeroParallax, ranges::kZeroParallax,
            "Distance from the eye of the plane that shows no disparity (0: the volume "
            "centre)");
  addEnumOption(app, "--lighting", view.lighting,
                "phong: normals from the streamline's TNB frame (thesis 5.3.3); lines: "
                "illuminated lines, lit from the tangent alone");
}

void addPlaneOptions(CLI::App& app, SessionOptions& options, PlaneOptions& plane) {
  PlaneParams& p = options.session.plane;
  addRanged(app, "--width", p.width, ranges::kPlaneWidth.atLeast(1),
            "Width of the LIC image in pixels (default: the field's grid; with --height alone, "
            "keeping the grid's aspect). Larger than the grid, the noise is finer than "
            "the field and the picture stays sharp");
  addRanged(app, "--height", p.height, ranges::kPlaneHeight.atLeast(1),
            "Height of the LIC image in pixels (see --width)");
  addText(app, "--slice", plane.slice,
          "The plane of a 3D field (analytic or file): AXIS or AXIS:INDEX, x, y or z, INDEX in "
          "voxels (default z, the middle layer)",
          "", "plane.index");
  nameFlag("plane.axis", "--slice");
  addGreyAndColorOptions(app, options, "the image's", "");
  addText(app, "--background", options.background,
          "Background colour R,G,B the legend's text is set against (0..1, or 0..255)", "0,0,0",
          "view.background");
}

Result<void> finishPlaneOptions(const PlaneOptions& plane, Session& session) {
  if (!plane.slice.given()) return {};
  const std::size_t colon = plane.slice.text.find(':');
  const std::string axis = plane.slice.text.substr(0, colon);
  int index = -1;
  if (axis != "x" && axis != "y" && axis != "z")
    return inputError("--slice: expected AXIS or AXIS:INDEX with AXIS x, y or z, got '" +
                      plane.slice.text + "'");
  if (colon != std::string::npos) {
    LIC3D_TRY_ASSIGN(
        index, parseNumber<int>(std::string_view(plane.slice.text).substr(colon + 1), "--slice"));
    if (index < 0)
      return inputError("--slice: the index of '" + plane.slice.text + "' must be 0 or more");
  }
  session.plane.axis = axis[0] - 'x';
  session.plane.index = index;
  return {};
}

std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv, const char* program,
                                    const char* hint,
                                    std::initializer_list<SessionOptions*> sessions) {
  try {
    for (SessionOptions* options : sessions)
      if (auto r = preloadSession(argc, argv, *options); !r) return reportError(r.error());
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "%s: error: %s\n%s\n", program, e.what(), hint);
    return kExitBadInput;
  }
  return std::nullopt;
}

Result<glm::ivec2> parseSize(const std::string& text, const char* flag, int min, int max) {
  int w = 0, h = 0;
  char rest = 0;
  if (std::sscanf(text.c_str(), "%dx%d%c", &w, &h, &rest) != 2 || w < min || h < min || w > max ||
      h > max)
    return inputError(std::string(flag) + ": expected WxH between " + std::to_string(min) +
                      " and " + std::to_string(max) + ", got '" + text + "'");
  return glm::ivec2(w, h);
}

Result<void> preloadSession(int argc, const char* const* argv, SessionOptions& options) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    std::string file;
    if (arg == "--session" && i + 1 < argc)
      file = argv[i + 1];
    else if (arg.rfind("--session=", 0) == 0)
      file = arg.substr(10);
    else
      continue;
    LIC3D_TRY_ASSIGN(options.session, readSession(file));
    options.sessionFile = file;
    return {};
  }
  return {};
}

Result<Dims> parseGrid(const std::string& text, bool planar) {
  const std::vector<std::string_view> parts = splitCommas(text);
  if (parts.size() != 1 && parts.size() != 3 && !(planar && parts.size() == 2))
    return inputError(std::string("--grid: expected N") + (planar ? ", NX,NY" : "") +
                      " or NX,NY,NZ, got '" + text + "'");
  Dims dims(0);
  for (int a = 0; a < 3; ++a) {
    // NX,NY is a 2D grid: one voxel along z.
    if (parts.size() == 2 && a == 2) {
      dims[a] = 1;
      continue;
    }
    LIC3D_TRY_ASSIGN(dims[a], parseNumber<int>(parts[parts.size() == 1 ? 0 : a], "--grid"));
    if (!ranges::kGrid.contains(dims[a]))
      return inputError("--grid: each size must be in " + ranges::kGrid.text() + ", got '" + text +
                        "'");
  }
  return dims;
}

Result<glm::vec3> parseColor(const std::string& text, const char* flag) {
  const std::vector<std::string_view> parts = splitCommas(text);
  if (parts.size() != 3)
    return inputError(std::string(flag) + ": expected R,G,B, got '" + text + "'");
  glm::vec3 color(0.0f);
  for (int c = 0; c < 3; ++c) {
    LIC3D_TRY_ASSIGN(color[c], parseNumber<float>(parts[c], flag));
    if (!(color[c] >= 0.0f && color[c] <= 255.0f))
      return inputError(std::string(flag) + ": components must be in 0..1 or 0..255, got '" + text +
                        "'");
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

namespace {

// The view flags whose text needs parsing, into the session (checked with it afterwards).
Result<void> applyViewOptions(SessionOptions& options) {
  Session& s = options.session;

  ViewParams& view = s.view;
  if (options.background.given()) {
    LIC3D_TRY_ASSIGN(view.background, parseColor(options.background.text, "--background"));
  }
  if (options.contrast.given()) view.contrast = options.contrast.text == "on";
  if (options.window.given()) {
    view.manualWindow = options.window.text != "auto";
    if (view.manualWindow) {
      LIC3D_TRY_ASSIGN(const std::vector<float> w,
                       parseFloatList(options.window.text, "--window", 2));
      view.windowLow = w[0];
      view.windowHigh = w[1];
    }
  }
  if (options.colorRange.given()) {
    view.autoColorRange = options.colorRange.text == "auto";
    if (!view.autoColorRange) {
      LIC3D_TRY_ASSIGN(const std::vector<float> r,
                       parseFloatList(options.colorRange.text, "--color-range", 2));
      view.colorLow = r[0];
      view.colorHigh = r[1];
    }
  }
  if (view.legend && view.color != ColorMode::Magnitude)
    return inputError("--legend shows the colour map: use it with --color magnitude");
  if (options.clip.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> clip, parseFloatList(options.clip.text, "--clip", 6));
    view.clipMin = {clip[0], clip[2], clip[4]};
    view.clipMax = {clip[1], clip[3], clip[5]};
  }
  if (options.roiCenter.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> c,
                     parseFloatList(options.roiCenter.text, "--roi-center", 3));
    view.roiCenter = {c[0], c[1], c[2]};
  }
  if (options.roiRotate.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> r,
                     parseFloatList(options.roiRotate.text, "--roi-rotate", 3));
    view.roiRotation = {r[0], r[1], r[2]};
  }
  if (options.fog.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> fog, parseFloatList(options.fog.text, "--fog", 2));
    view.fog = true;
    view.fogStart = fog[0];
    view.fogEnd = fog[1];
  }
  if (options.fogColor.given()) {
    LIC3D_TRY_ASSIGN(view.fogColor, parseColor(options.fogColor.text, "--fog-color"));
    view.fogColorFromBackground = false;
  }
  return {};
}

}  // namespace

Result<void> finishSessionOptions(SessionOptions& options, bool withView) {
  Session& s = options.session;
  if (options.grid.given()) {
    LIC3D_TRY_ASSIGN(s.field.grid, parseGrid(options.grid.text, options.planar));
  }
  if (withView) LIC3D_TRY(applyViewOptions(options));
  // The CLI's one validation of the session: every parameter against its range
  // (core/parameter_ranges.h), the flags named by reportError.
  return validate(s);
}

Result<void> checkOutputPath(const std::string& path, const char* extension) {
  const std::filesystem::path p(path);
  if (p.extension() != extension)
    return inputError("output " + path + ": expected a " + extension + " file name");
  const std::filesystem::path folder = p.parent_path().empty() ? "." : p.parent_path();
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    return inputError("output " + path + ": folder " + folder.string() + " does not exist");
  if (std::filesystem::is_directory(p, ec)) return inputError("output " + path + " is a folder");
  return {};
}

}  // namespace lic3d::cli
