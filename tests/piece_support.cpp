// SPDX-License-Identifier: BSD-3-Clause
#include "piece_support.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "lic/field_piece.h"
#include "lic/noise.h"

namespace lic3d::test {

PieceRun runInPieces(const VectorField& field, const LicParams& params, Dims split, int ghostLayers,
                     const PieceCompute& compute) {
  PieceRun run;
  const NoiseVolume noise = makeWhiteNoise(field.dims, 7);
  Result<ScalarVolume> whole = compute(field, noise, params);
  if (!whole) {
    run.error = "whole field: " + whole.error().message;
    return run;
  }
  ScalarVolume assembled;
  assembled.dims = field.dims;
  assembled.values.assign(voxelCount(field.dims), 0.0f);
  assembled.drawn.assign(voxelCount(field.dims), 1);
  for (int pz = 0; pz < split.z; ++pz)
    for (int py = 0; py < split.y; ++py)
      for (int px = 0; px < split.x; ++px) {
        const Dims index(px, py, pz);
        Dims ownLow, ownHigh, low, high;  // inclusive voxel boxes
        for (int a = 0; a < 3; ++a) {
          ownLow[a] = field.dims[a] * index[a] / split[a];
          ownHigh[a] = field.dims[a] * (index[a] + 1) / split[a] - 1;
          low[a] = std::max(ownLow[a] - ghostLayers, 0);
          high[a] = std::min(ownHigh[a] + ghostLayers, field.dims[a] - 1);
        }
        const Dims dims = high - low + 1;
        Result<VectorField> piece = cutFieldPiece(field, low, dims);
        if (!piece) {
          run.error = piece.error().message;
          return run;
        }
        const NoiseVolume pieceNoise = makeWhiteNoisePiece(field.dims, low, dims, 7);
        Result<ScalarVolume> lic = compute(*piece, pieceNoise, params);
        if (!lic) {
          run.error = "piece: " + lic.error().message;
          return run;
        }
        for (int k = ownLow.z; k <= ownHigh.z; ++k)
          for (int j = ownLow.y; j <= ownHigh.y; ++j)
            for (int i = ownLow.x; i <= ownHigh.x; ++i) {
              const std::size_t from = voxelIndex(dims, i - low.x, j - low.y, k - low.z);
              const std::size_t to = voxelIndex(field.dims, i, j, k);
              assembled.values[to] = lic->values[from];
              assembled.drawn[to] = lic->drawn.empty() ? 1 : lic->drawn[from];
            }
        ++run.pieces;
      }

  std::vector<double> differences;
  for (std::size_t i = 0; i < assembled.values.size(); ++i) {
    const bool drawnWhole = whole->drawn.empty() || whole->drawn[i] != 0;
    const bool drawnPieces = assembled.drawn[i] != 0;
    if (drawnWhole != drawnPieces) ++run.hiddenMismatches;
    if (!drawnWhole || !drawnPieces) continue;
    const double d = std::abs(static_cast<double>(whole->values[i]) - assembled.values[i]);
    if (d > run.difference.max) {
      run.difference.max = d;
      run.difference.argMax = i;
    }
    run.difference.mean += d;
    differences.push_back(d);
  }
  if (!differences.empty()) {
    run.difference.mean /= static_cast<double>(differences.size());
    const auto q = differences.begin() +
                   static_cast<std::ptrdiff_t>(0.999 * static_cast<double>(differences.size() - 1));
    std::nth_element(differences.begin(), q, differences.end());
    run.difference.quantile999 = *q;
  }
  run.ok = true;
  return run;
}

}  // namespace lic3d::test
