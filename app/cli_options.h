#pragma once
// The flags shared by the subcommands (and the viewer), bound straight to a Session: the engine's
// parameter structs plus where the field and the noise come from.

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "enum_names.h"
#include "error.h"
#include "session.h"
#include "volume.h"
#include "volume_io.h"

namespace lic3d {
class Context;
}

namespace lic3d::cli {

enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitBadInput = 2, kExitResourceLimit = 3 };

// `lic3d --version`, and the "Software" text of every PNG lic3d writes.
inline constexpr char kVersionText[] = "lic3d 0.1.0";

// Bad input exits with 2; anything the user cannot fix by changing arguments exits with 1.
int exitCodeFor(const Error& error);
int reportError(const Error& error);

struct GlobalOptions {
  std::string device;
  bool validation = false;
  bool quiet = false;
};

// Flags whose text needs parsing after CLI11 (lists, colours, on/off). Each is applied only if
// given, so that values from --session survive unless a flag overrides them.
struct TextOption {
  std::string text;
  CLI::Option* option = nullptr;
  bool given() const { return option && option->count() > 0; }
};

struct SessionOptions {
  Session session;
  std::string sessionFile;
  TextOption grid;
  // view flags (render and the viewer only)
  TextOption background, window, contrast, colorRange, clip, roiCenter, roiRotate, fog, fogColor;
};

struct ComputeOptions {
  SessionOptions inputs;
  bool cpu = false;
  std::string output;
  CLI::Option* outputOption = nullptr;  // to tell a given -o from the default
};

// An option taking one of the names of E (enum_names.h).
template <class E>
CLI::Option* addEnumOption(CLI::App& app, const std::string& flag, E& value,
                           const std::string& help) {
  std::map<std::string, E> names;
  for (const EnumName<E>& n : enumNames<E>()) names.emplace(std::string(n.name), n.value);
  return app.add_option(flag, value, help + ": " + enumChoices<E>())
      ->transform(CLI::CheckedTransformer(names).description(""))
      ->default_str(std::string(enumName(value)));
}

void addGlobalOptions(CLI::App& app, GlobalOptions& options);
// --session, the field and noise flags, the LIC flags and --field-precision.
void addInputOptions(CLI::App& app, SessionOptions& options);
void addComputeOptions(CLI::App& app, ComputeOptions& options, const char* defaultOutput);
// Every ViewParams flag.
void addViewOptions(CLI::App& app, SessionOptions& options);

// Looks for --session FILE among the arguments and loads it into `options.session` before
// CLI11 parses them, so that explicit flags override the file.
Result<void> preloadSession(int argc, const char* const* argv, SessionOptions& options);
// Applies the text flags to the session and checks it (InvalidInput naming the flag).
Result<void> finishSessionOptions(SessionOptions& options, bool withView);

Result<Dims> parseGrid(const std::string& text);
Result<glm::vec3> parseColor(const std::string& text, const char* flag);
Result<std::vector<int>> parseIntList(const std::string& text, const char* flag, int min, int max);
Result<std::vector<float>> parseFloatList(const std::string& text, const char* flag,
                                          std::size_t count);

// Refuses grids whose host-side arrays would not fit this machine's memory.
Result<void> checkHostMemory(Dims dims);

// What a command keeps resident besides the field, the noise and one LIC volume.
struct RequestShape {
  bool doubleBuffered = false;  // the app's second LIC volume
  bool volumeReadback = false;  // `compute` reads the volume back
  bool frame = false;           // a frame of the session's size (or frameWidth x frameHeight)
  int frameWidth = 0;
  int frameHeight = 0;
};
// ResourceLimit error (exit status 3) if the request does not fit the device and the host:
// checked before anything of it is allocated on the device.
Result<void> checkRequestMemory(const Context& context, const Session& session, Dims dims,
                                const RequestShape& shape);
// A file field also fills `info` (when given): the array read, the file's vector arrays and the
// count of NaN or infinite vectors read as zero.
Result<VectorField> loadField(const FieldSource& source, bool gridGiven,
                              FieldReadInfo* info = nullptr);
Result<NoiseVolume> loadNoise(const NoiseSource& source, Dims dims);
// The output must have `extension` and lie in an existing folder: checked before any work.
Result<void> checkOutputPath(const std::string& path, const char* extension);

}  // namespace lic3d::cli
