// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What `lic3d bench` measures, as its flags fill it (options/command_line.cpp declares them).

#include <cstdint>
#include <string>

#include "core/field_precision.h"

namespace lic3d::cli {

struct BenchOptions {
  std::string field = "tornado";
  std::uint64_t seed = 1;
  FieldPrecision precision = FieldPrecision::Auto;
  std::string sizes = "64,128,256,512";
  std::string lengths = "10,20";
  std::string frameSizes = "512,1024,2048";
  int frameVolume = 256;
  std::string frameBuffers = "rgba16f,rgba16,rgb10a2,rgba8";
  std::string frameLooks = "plain";     // plain: ViewParams' defaults; default: the default look
  std::string slicesPerFragment = "0";  // K of each frame row; 0: the device's choice
  int repeats = 7;
  int warmup = 2;
  double budgetSeconds = 120.0;
  std::string json;
  bool variants = false;       // specialized pipelines against runtime mode switches
  bool distributions = false;  // sparsity point generation and mask + LIC recompute
  bool kernels = false;        // the naive LIC kernel against each shipped one
  bool fidelity = false;       // each scheme's error against a converged LIC
  std::string fidelityFiles;   // fields judged besides the analytic ones (comma-separated)
  int distributionVolume = 256;
  bool visible = false;           // the full LIC pass against visible work
  std::string visibleFiles;       // fields --visible times instead of the analytic --field
  std::string resolution = "1x";  // of the --visible-files (as render's --resolution)
  bool drag = false;              // the app's frames while a LIC slider is dragged
  int dragPicture = 1024;         // of --drag: the square picture's size
  int dragSlices = 256;           // of --drag: the slices drawn
  int dragFrames = 60;            // of --drag: frames timed
  std::string writeDir;           // a bricked row also writes its NRRD into this folder
  std::string readField;          // a field file read by pieces: read and packing rates
};

}  // namespace lic3d::cli
