// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// LIC of a field computed piece by piece, each piece widened by ghost layers and keeping its own
// voxels, as the ParaView plugin computes it under MPI; compared with LIC of the whole field.

#include <cstddef>
#include <functional>
#include <string>

#include "core/error.h"
#include "core/lic_params.h"
#include "core/volume.h"

namespace lic3d::test {

using PieceCompute =
    std::function<Result<ScalarVolume>(const VectorField&, const NoiseVolume&, const LicParams&)>;

struct PieceRun {
  bool ok = false;
  std::string error;
  std::size_t pieces = 0;
  // Over the voxels drawn in both: |whole - pieces|.
  struct {
    double mean = 0.0;
    double max = 0.0;
    double quantile999 = 0.0;
    std::size_t argMax = 0;
  } difference;
  std::size_t hiddenMismatches = 0;  // voxels drawn in one result only
};

// `split` pieces per axis (sizes as even as possible), `ghostLayers` voxels of ghost layers on
// each side that is not the grid's face, white noise of seed 7 on the whole grid.
PieceRun runInPieces(const VectorField& field, const LicParams& params, Dims split, int ghostLayers,
                     const PieceCompute& compute);

}  // namespace lic3d::test
