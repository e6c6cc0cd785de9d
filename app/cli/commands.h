// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The subcommands. Each returns the process exit status.

#include <string>

#include "cli/batch.h"
#include "options/session_options.h"

namespace lic3d::cli {

int runDevices(const GlobalOptions& global);
int runCompute(const GlobalOptions& global, const ComputeOptions& options,
               const BatchOptions& batch);
int runRender(const GlobalOptions& global, const ComputeOptions& options,
              const BatchOptions& batch);
// 2D LIC of a plane (thesis chapter 3): a PNG, or the frames of a bias or time animation.
int runRender2D(const GlobalOptions& global, const ComputeOptions& options,
                const BatchOptions& batch);

}  // namespace lic3d::cli
