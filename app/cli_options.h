#pragma once
// The flags shared by the subcommands, bound straight to the engine's parameter structs.

#include <cstdint>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "error.h"
#include "lic_params.h"
#include "view_params.h"
#include "volume.h"
#include "volume_textures.h"

namespace lic3d::cli {

enum ExitCode : int { kExitOk = 0, kExitFailure = 1, kExitBadInput = 2 };

// Bad input exits with 2; anything the user cannot fix by changing arguments exits with 1.
int exitCodeFor(const Error& error);
int reportError(const Error& error);

struct GlobalOptions {
  std::string device;
  bool validation = false;
  bool quiet = false;
};

struct FieldOptions {
  std::string field = "tornado";
  std::string grid = "128";
  std::string noise;
  std::uint64_t seed = 1;
  int seedNoiseSpots = 0;  // > 0: sparse seed noise with this many spots instead of white noise
  CLI::Option* gridOption = nullptr;
};

struct ComputeOptions {
  FieldOptions input;
  LicParams lic;
  FieldPrecision precision = FieldPrecision::Auto;
  bool cpu = false;
  std::string output;
};

// View flags whose text is parsed after CLI11 is done (lists, colours, on/off).
struct RenderOptions {
  ComputeOptions compute;
  ViewParams view;
  std::string background = "0,0,0";
  std::string window = "auto";
  std::string contrast = "on";
  std::string colorRange = "auto";
  std::string clip = "0,1,0,1,0,1";
  std::string roiCenter = "0.5,0.5,0.5";
  std::string roiRotate = "0,0,0";
  std::string fog;
  std::string fogColor;
};

void addGlobalOptions(CLI::App& app, GlobalOptions& options);
void addFieldOptions(CLI::App& app, FieldOptions& options);
void addLicOptions(CLI::App& app, LicParams& params);
void addPrecisionOption(CLI::App& app, FieldPrecision& precision);
void addComputeOptions(CLI::App& app, ComputeOptions& options, const char* defaultOutput);
void addViewOptions(CLI::App& app, RenderOptions& options);

Result<Dims> parseGrid(const std::string& text);
Result<glm::vec3> parseColor(const std::string& text, const char* flag);
Result<std::vector<int>> parseIntList(const std::string& text, const char* flag, int min, int max);
Result<std::vector<float>> parseFloatList(const std::string& text, const char* flag,
                                          std::size_t count);
// Applies the text-valued view flags (colours, lists, on/off) to options.view and checks it.
Result<void> finishViewOptions(RenderOptions& options);

// Refuses grids whose host-side arrays would not fit this machine's memory.
Result<void> checkHostMemory(Dims dims);
Result<VectorField> loadField(const FieldOptions& options);
Result<NoiseVolume> loadNoise(const FieldOptions& options, Dims dims);
// The output must have `extension` and lie in an existing folder: checked before any work.
Result<void> checkOutputPath(const std::string& path, const char* extension);

}  // namespace lic3d::cli
