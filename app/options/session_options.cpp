// SPDX-License-Identifier: BSD-3-Clause
#include "options/session_options.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <exception>
#include <filesystem>
#include <limits>
#include <map>
#include <sstream>

#include "core/enum_names.h"
#include "core/parameter_ranges.h"
#include "core/stage_times.h"
#include "core/text.h"
#include "io/session_file.h"
#include "lic/analytic_fields.h"
#include "options/flags.h"

namespace lic3d::cli {

bool given(const CLI::Option* option) { return option && option->count() > 0; }

bool TextOption::given() const { return cli::given(option); }

int exitCodeFor(const Error& error) {
  switch (error.kind) {
    case ErrorKind::InvalidInput: return kExitBadInput;
    case ErrorKind::ResourceLimit: return kExitResourceLimit;
    default: return kExitFailure;
  }
}

std::string messageWithFlags(const Error& error) { return rewriteKeys(error, flagNames()); }

Error fromSessionFile(Error error, const SessionOptions& options) {
  if (options.sessionFile.empty() || error.parameter.empty() || !options.app) return error;
  const auto flag = flagNames().find(error.parameter);
  if (flag != flagNames().end() && given(options.app->get_option_no_throw(flag->second)))
    return error;
  error.message = options.sessionFile + ": " + error.message;
  error.parameter.clear();
  return error;
}

int reportError(const Error& error) {
  // A message quotes what it was given (a path, a value): cut, so that no input fills the
  // terminal or a job's log.
  std::fprintf(stderr, "lic3d: error: %s\n", cutMessage(messageWithFlags(error), 1000).c_str());
  return exitCodeFor(error);
}

void printTimings(double totalSeconds) {
  // What the stages do not cover (option parsing, waiting for input) is the rest.
  double covered = 0.0;
  std::fprintf(stderr, "lic3d: timings (wall clock, seconds)\n");
  for (const auto& [stage, seconds] : stageTimings()) {
    // A stage that moved bytes (a volume written) shows them and its rate.
    const std::uint64_t bytes = stageBytes(stage);
    if (bytes > 0 && seconds > 0.0)
      std::fprintf(stderr, "  %-24s %9.4f  (%llu bytes, %.2f GB/s)\n", stage.c_str(), seconds,
                   static_cast<unsigned long long>(bytes),
                   static_cast<double>(bytes) / seconds / 1e9);
    else
      std::fprintf(stderr, "  %-24s %9.4f\n", stage.c_str(), seconds);
    covered += seconds;
  }
  std::fprintf(stderr, "  %-24s %9.4f\n  %-24s %9.4f\n", "other",
               std::max(totalSeconds - covered, 0.0), "total", totalSeconds);
  if (covered > totalSeconds)
    std::fprintf(stderr,
                 "  (stages on worker threads, such as PNG writes of an animation, ran beside "
                 "the others)\n");
}

CLI::Validator wholeNumberText() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        // Only digits, and within 64 bits: CLI11 would take 99999999999999999999999 as 2^64 - 1.
        std::uint64_t value = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
        if (!text.empty() && text.find_first_not_of("0123456789") == std::string::npos &&
            error == std::errc() && end == text.data() + text.size())
          return {};
        return "must be a whole number from 0 to 18446744073709551615, got " + text;
      },
      "");
}

// --memory-budget: BYTES with an optional unit (kB, MB, GB, TB in 1000s; KiB, MiB, GiB, TiB in
// 1024s; any case), from 1 byte to 2^64 - 1. CLI11's AsSizeValue took 0, -1 (as 2^64 - 1) and
// 2^64 (as 0) alike as "no budget".
CLI::Validator memorySizeText() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        const std::string given = text;
        const std::string range =
            "must be a size from 1 byte to 18446744073709551615 bytes (BYTES, or with kB, MB, GB, "
            "TB or KiB, MiB, GiB, TiB), got '" +
            given + "'";
        const std::size_t digits = text.find_first_not_of("0123456789");
        std::uint64_t number = 0;
        const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), number);
        if (digits == 0 || error != std::errc() ||
            end != text.data() + (digits == std::string::npos ? text.size() : digits))
          return range;
        std::string unit = asciiLowerCase(text.substr(end - text.data()));
        while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
        static const std::map<std::string, std::uint64_t> kUnits = {
            {"", 1},
            {"b", 1},
            {"k", 1000},
            {"kb", 1000},
            {"m", 1000'000},
            {"mb", 1000'000},
            {"g", 1000'000'000},
            {"gb", 1000'000'000},
            {"t", 1000'000'000'000},
            {"tb", 1000'000'000'000},
            {"kib", std::uint64_t{1} << 10},
            {"mib", std::uint64_t{1} << 20},
            {"gib", std::uint64_t{1} << 30},
            {"tib", std::uint64_t{1} << 40}};
        const auto scale = kUnits.find(unit);
        if (scale == kUnits.end() || number == 0 ||
            number > std::numeric_limits<std::uint64_t>::max() / scale->second)
          return range;
        text = std::to_string(number * scale->second);
        return {};
      },
      "SIZE");
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
  app.add_option("--threads", options.threads,
                 "At most this many CPU threads for the CPU work (the field, noise, masks, the CPU "
                 "reference, files); default: the CPUs the process may run on (its affinity mask)")
      ->check(rangeCheck(0, 4096));
  nameFlag("threads", "--threads");
  app.add_flag("--timings", options.timings,
               "Print where the time went, stage by stage (reading or making the field, noise, "
               "mask, uploads, LIC, frames, read-backs, writing), as a table on stderr; the "
               "summary line has them as \"timings\"");
}

void addInputOptions(CLI::App& app, SessionOptions& options, bool planar, bool volume) {
  Session& s = options.session;
  options.planar = planar;
  options.app = &app;
  app.add_option("--session", options.sessionFile,
                 "Start from a session file (JSON, as the viewer saves it); other flags override "
                 "its values");
  app.add_option(
         "--field", s.field.field,
         planar ? "Vector field: a 2D analytic field (" + enumChoices<AnalyticField2D>() +
                      "), a plane of a 3D one (" + enumChoices<AnalyticField>() +
                      ", see --slice), a file (.vtk, .vti, .pvti, .nrrd, .nhdr, .raw; 2D, or a "
                      "plane of a 3D one), or a time series of files: step_%03d.vti or "
                      "'step_*.vti' (docs/TIME.md)"
                : "Vector field: an analytic field (" + enumChoices<AnalyticField>() +
                      "), a file (.vtk, .vti, .pvti, .nrrd, .nhdr, .raw), or a time series of "
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
  app.add_option("--seed", s.noise.seed, "Seed of the white noise")
      ->check(wholeNumberText())
      ->capture_default_str();
  addRanged(app, "--seed-noise", s.noise.seedSpots, ranges::kSeedSpots,
            "Sparse seed noise instead of white noise: N bright spots on black, placed by "
            "Poisson-disk sampling (streamlines become distinct lines)");
  addRanged(app, "--seed-fraction", s.noise.seedFraction, ranges::kSeedFraction,
            "Seed noise with this fraction of the voxels as spots (of the flowing voxels for a "
            "file; the streamlines look's 0.0015); --seed-noise N takes precedence");
  if (volume)
    app.add_option("--resolution", s.field.resolution,
                   "LIC grid of a file's field, finer than the file's: N (voxels along the "
                   "longest axis, the others in proportion), NX,NY,NZ, or a factor such as 2x; "
                   "the field is sampled trilinearly and the noise made on that grid");
  nameFlag("field.resolution", "--resolution");

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
                "directions already fetched: one fetch per sample) or fused (RK2 steps of 2h "
                "whose midpoint is itself a sample: one fetch per sample)");

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
  addRanged(app, "--sparsity-amount", sparsity.amount, ranges::kSparsityAmount,
            "Fraction of the LIC voxels to hide, in [0,0.99) (0: the distribution's own "
            "parameters): sets the black fraction f of the mask from the streamline length n "
            "in voxels, (1-f)^n = 1-amount, and the automatic points, radius or checkerboard "
            "ratio from f; the fraction actually hidden is reported");
  app.add_option("--sparsity-seed", sparsity.seed, "Seed of the random sparsity distributions")
      ->check(wholeNumberText())
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
  app.add_option("--memory-budget", options.memoryBudget,
                 "At most this much device memory: BYTES, or with kB, MB, GB (1000s) or KiB, "
                 "MiB, GiB (1024s); a LIC that does not fit is made in bricks with ghost layers, "
                 "and render draws a reduced copy of one too large to draw (docs/SCALE.md) "
                 "(default: what the device has)")
      ->transform(memorySizeText());
  app.add_option("--devices", options.devices,
                 "Spread the LIC over several devices: all (every GPU of the best kind) or "
                 "indices or name parts of `lic3d devices`, separated by commas; the grid goes "
                 "out in bricks, at least one a device (docs/SCALE.md); not with --device")
      ->check(CLI::Validator(
          [](const std::string& text) -> std::string {
            // An empty list would silently mean --device's one device.
            return text.empty() ? "needs 'all' or device indices or names, got ''" : "";
          },
          ""));
  options.output = defaultOutput;
  const bool picture = std::string_view(defaultOutput).ends_with(".png");
  options.outputOption =
      app.add_option(
             "-o,--output", options.output,
             picture ? "Output PNG; for --turntable or --animate-bias a pattern with one "
                       "%d or %0Nd for the frame number (default then lic3d_%04d.png)"
                     : "Output: the LIC volume as .nrrd, .vti or .raw (float32; .raw with a JSON "
                       "sidecar), as .vdb (OpenVDB for Blender and Houdini: grids LIC and speed, "
                       "empty space inactive), or one slice as .png with --slice")
          ->capture_default_str();
}

namespace {

// The option `flag` names in the subcommand being parsed, else in `app`.
const CLI::Option* findOption(const CLI::App& app, const std::string& flag) {
  for (const CLI::App* sub : app.get_subcommands())
    if (const CLI::Option* option = findOption(*sub, flag)) return option;
  return app.get_option_no_throw(flag);
}

// CLI11's message for a refused value, with the flag, the value and what the flag takes instead
// of CLI11's words: "Could not convert: --length = abc" becomes "--length: expected a whole
// number in [0, 4096], got 'abc'". Other messages are kept (cut to a line: CLI11 echoes the
// argument it refused, which may be megabytes long).
std::string parseErrorMessage(const CLI::ParseError& error, const CLI::App& app) {
  constexpr std::string_view kPrefix = "Could not convert: ";
  const std::string message = error.what();
  const std::size_t equals = message.find(" = ");
  if (!message.starts_with(kPrefix) || equals == std::string::npos) return cutMessage(message);
  const std::string flag = message.substr(kPrefix.size(), equals - kPrefix.size());
  const CLI::Option* option = findOption(app, flag);
  if (!option) return cutMessage(message);
  const std::string type = option->get_type_name();
  const std::size_t colon = type.find(':');
  const std::string base = type.substr(0, colon);
  // The validator's description is the range ("in [0, 4096]", rangeCheck).
  const std::string range = colon == std::string::npos ? "" : type.substr(colon + 1);
  const bool ranged = range.starts_with("in ");
  const std::string kind = base == "INT"              ? "a whole number"
                           : base == "UINT" && ranged ? "a whole number"
                           : base == "UINT"           ? "a whole number from 0"
                           : base == "FLOAT"          ? "a number"
                                                      : base;
  return flag + ": expected " + kind + (ranged ? " " + range : "") + ", got '" +
         cutMessage(message.substr(equals + 3), 60) + "'";
}

}  // namespace

Result<void> parseArguments(CLI::App& app, int argc, char** argv,
                            std::initializer_list<SessionOptions*> sessions) {
  try {
    for (SessionOptions* options : sessions) LIC3D_TRY(preloadSession(argc, argv, *options));
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return inputError(parseErrorMessage(e, app));
  }
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
    std::fprintf(stderr, "%s: error: %s\n%s\n", program, parseErrorMessage(e, app).c_str(), hint);
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

namespace {

// The value of `--name VALUE` or `--name=VALUE` among the arguments, if given.
std::optional<std::string> findValue(int argc, const char* const* argv, const std::string& name) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == name && i + 1 < argc) return std::string(argv[i + 1]);
    if (arg.rfind(name + "=", 0) == 0) return arg.substr(name.size() + 1);
  }
  return std::nullopt;
}

}  // namespace

Result<void> preloadSession(int argc, const char* const* argv, SessionOptions& options) {
  if (const std::optional<std::string> file = findValue(argc, argv, "--session")) {
    LIC3D_TRY_ASSIGN(options.session, readSession(*file));
    options.sessionFile = *file;
  }
  if (!options.looks) return {};
  // A look sets the display parameters the flags then refine; without a session or a look,
  // the default look.
  if (const std::optional<std::string> name = findValue(argc, argv, "--look")) {
    const std::optional<Look> look = parseEnum<Look>(*name);
    if (!look) return {};  // CLI11 names the bad value
    applyLook(*look, options.session);
  } else if (options.sessionFile.empty()) {
    applyLook(kDefaultLook, options.session);
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
    const Result<int> size = parseNumber<int>(parts[parts.size() == 1 ? 0 : a], "--grid");
    if (!size || !ranges::kGrid.contains(*size))
      return inputError("--grid: each size must be a whole number in " + ranges::kGrid.text() +
                        ", got '" + text + "'");
    dims[a] = *size;
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

Result<void> finishSessionOptions(SessionOptions& options, bool withView) {
  Session& s = options.session;
  if (options.grid.given()) {
    LIC3D_TRY_ASSIGN(s.field.grid, parseGrid(options.grid.text, options.planar));
  }
  if (withView) LIC3D_TRY(applyViewOptions(options));
  LIC3D_TRY(applyFlagRules(options));
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
  // Writable before any work: a file is made and removed in the folder, which is what the final
  // write will need (permissions, read-only or pseudo file systems, quotas on inodes). A run
  // that cannot write one output then writes none.
  const std::filesystem::path probe =
      folder / (".lic3d-write-check-" + std::to_string(static_cast<long>(::getpid())));
  const int fd = ::open(probe.c_str(), O_CREAT | O_EXCL | O_WRONLY | O_CLOEXEC, 0600);
  if (fd < 0) {
    const int error = errno;
    if (error != EEXIST)
      return inputError("output " + path + ": cannot write in folder " + folder.string() + ": " +
                        std::strerror(error));
  } else {
    ::close(fd);
    ::unlink(probe.c_str());
  }
  return {};
}

Result<PngText> pngText(const Session& session, const std::string& path) {
  PngText text;
  try {
    text.emplace_back(kPngSessionKey, sessionToJson(sessionForFolder(
                                          session, std::filesystem::path(path).parent_path())));
  } catch (const std::exception& e) {
    return inputError(std::string("cannot record the parameters in the PNG as JSON: ") + e.what());
  }
  text.emplace_back("Software", kVersionText);
  return text;
}

}  // namespace lic3d::cli
