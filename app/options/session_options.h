// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The flags shared by the subcommands (and the viewer), bound straight to a Session: the engine's
// parameter structs plus where the field and the noise come from; and the session every PNG of
// the CLI and the app carries (pngText).

#include <cstdint>
#include <initializer_list>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/enum_names.h"
#include "core/error.h"
#include "core/session.h"
#include "core/volume.h"
#include "io/png_writer.h"
#include "loading/session_inputs.h"

// CLI11 is heavy to compile: only the files that declare options include it (options/flags.h).
namespace CLI {
class App;
class Option;
class Validator;
}  // namespace CLI

namespace lic3d::cli {

enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitBadInput = 2, kExitResourceLimit = 3 };

// `lic3d --version`, and the "Software" text of every PNG lic3d writes.
inline constexpr char kVersionText[] = "lic3d 0.1.0";

// Bad input exits with 2; anything the user cannot fix by changing arguments exits with 1.
int exitCodeFor(const Error& error);
int reportError(const Error& error);
// --timings: the stages' seconds (core/stage_times.h) as a table on stderr, with the rest of
// `totalSeconds` as "other".
void printTimings(double totalSeconds);
// The error's message with the flag in place of the parameter's session key (Error::parameter):
// "--length must be in [0, 4096], got 5000".
std::string messageWithFlags(const Error& error);

struct GlobalOptions {
  std::string device;
  bool validation = false;
  bool quiet = false;
  bool timings = false;  // --timings: the stages' times as a table on stderr
  unsigned threads = 0;  // --threads: at most this many CPU threads (0: the affinity mask's)
};

// Flags whose text needs parsing after CLI11 (lists, colours, on/off). Each is applied only if
// given, so that values from --session survive unless a flag overrides them.
struct TextOption {
  std::string text;
  CLI::Option* option = nullptr;
  bool given() const;
};

// Whether `option` was given on the command line (not only filled from a session file).
bool given(const CLI::Option* option);

struct SessionOptions {
  Session session;
  std::string sessionFile;
  TextOption grid;
  CLI::Option* time = nullptr;  // --time, to tell a given time from the session's
  bool planar = false;          // 2D LIC is possible: --grid also takes NX,NY
  bool looks = false;           // --look is offered (render, the app)
  std::string lookName;         // applied before the other flags (preloadSession)
  // view flags (render and the viewer only)
  TextOption background, window, contrast, colorRange, clip, roiCenter, roiRotate, fog, fogColor;
  TextOption colormap, transferFunction, clipPlane, windowPercentiles;
  TextOption jitter;
  CLI::Option* colorBy = nullptr;  // to tell a given --color-by from the session's
  CLI::Option* opacityBy = nullptr;
  float scale = 1.0f;       // --scale: the picture's sizes times this (scaledView), after the rest
  CLI::App* app = nullptr;  // the command the flags belong to: which were given (flag_rules.cpp)
};

// An error about a parameter the session file set, not a flag of the command line, names the
// file and the session's key ("run.json: field.source 'x' is neither ..."); others are returned
// as they are (reportError names the flag).
Error fromSessionFile(Error error, const SessionOptions& options);

struct ComputeOptions {
  SessionOptions inputs;
  bool cpu = false;
  std::uint64_t memoryBudget = 0;  // --memory-budget: at most this many bytes of device memory
  std::string devices;             // --devices: all, or indices or name parts (empty: --device)
  std::string output;
  CLI::Option* outputOption = nullptr;  // to tell a given -o from the default
};

void addGlobalOptions(CLI::App& app, GlobalOptions& options);
// --session, the field and noise flags, the LIC flags, --field-precision, --time and
// --time-steps. `planar`: the command makes 2D LIC (render2d, the app), whose --field also
// takes the 2D fields; `volume`: it makes LIC volumes (not render2d), so --resolution applies.
void addInputOptions(CLI::App& app, SessionOptions& options, bool planar = false,
                     bool volume = true);
void addComputeOptions(CLI::App& app, ComputeOptions& options, const char* defaultOutput);
// --look NAME (core/look.h): applied by preloadSession before the other flags; the default
// look when neither --look nor --session is given.
void addLookOption(CLI::App& app, SessionOptions& options);
// Every ViewParams flag.
void addViewOptions(CLI::App& app, SessionOptions& options);
// The picture flags of 2D LIC (render2d): the image size (into session.plane), the plane of a 3D
// field, and the grey and colour flags of ViewParams.
struct PlaneOptions {
  TextOption slice;    // AXIS[:INDEX]
  TextOption oblique;  // --plane PX,PY,PZ,NX,NY,NZ
};
void addPlaneOptions(CLI::App& app, SessionOptions& options, PlaneOptions& plane);
// Applies --slice to session.plane (InvalidInput naming the flag).
Result<void> finishPlaneOptions(const PlaneOptions& plane, Session& session);

// Parses `argv` for a front end that prints nothing (the Python module): a refused flag or
// value is an InvalidInput error with CLI11's message; help and the version are not offered.
Result<void> parseArguments(CLI::App& app, int argc, char** argv,
                            std::initializer_list<SessionOptions*> sessions);

// Parses the command line once the session files it names are read into `sessions` (flags
// given then override them). Nothing when the program goes on; else its exit status: help and
// the version are printed (0), a bad flag is named with `hint` (kExitBadInput).
std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv, const char* program,
                                    const char* hint,
                                    std::initializer_list<SessionOptions*> sessions);

// WxH with each side in [min, max] (InvalidInput naming `flag`).
Result<glm::ivec2> parseSize(const std::string& text, const char* flag, int min, int max);

// Looks for --session FILE among the arguments and loads it into `options.session` before
// CLI11 parses them, so that explicit flags override the file.
Result<void> preloadSession(int argc, const char* const* argv, SessionOptions& options);
// Flags given win over what a look or session set (--alpha turns the optical depth off, ...);
// a flag that acts only with another is refused naming it (flag_rules.cpp).
Result<void> applyFlagRules(SessionOptions& options);
// Applies the text flags to the session and checks it (InvalidInput naming the flag).
Result<void> finishSessionOptions(SessionOptions& options, bool withView);

// N, NX,NY,NZ, or with `planar` also NX,NY (one voxel along z).
Result<Dims> parseGrid(const std::string& text, bool planar = false);
Result<glm::vec3> parseColor(const std::string& text, const char* flag);
Result<std::vector<int>> parseIntList(const std::string& text, const char* flag, int min, int max);
Result<std::vector<float>> parseFloatList(const std::string& text, const char* flag,
                                          std::size_t count);

// The output must have `extension` and lie in an existing folder: checked before any work.
Result<void> checkOutputPath(const std::string& path, const char* extension);

// The PNG text of a picture made from `session` for the PNG `path`, in every PNG lic3d and the
// app write: kPngSessionKey (sessionToJson, its file paths relative to the PNG's folder) and
// "Software". An error when the session cannot be written as JSON (a file name that is not
// UTF-8).
Result<PngText> pngText(const Session& session, const std::string& path);

}  // namespace lic3d::cli
