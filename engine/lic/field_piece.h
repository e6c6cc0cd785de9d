// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Pieces of a field for distributed runs (the ParaView plugin under MPI): each process computes
// LIC on its part of the grid widened by ghost layers, and keeps the voxels of its own part.
//
// A piece's streamlines stop where the piece ends. Where that is the whole grid's face they stop
// exactly as on the whole grid; elsewhere the ghost layers must hold every position a streamline
// of a kept voxel reaches, plus one voxel for trilinear interpolation, for the piece to give the
// whole grid's values there (docs/LIC_SEMANTICS.md, "Pieces").

#include "core/error.h"
#include "core/lic_params.h"
#include "core/volume.h"

namespace lic3d {

// Ghost layers (voxels on each side) a piece needs: ceil(max(Lb, Lf) * h) + 1, with Lb = L - bias
// and Lf = L + bias steps of h voxels. No step is longer than h: normalized steps are exactly h,
// magnitude steps h * |u| / max|u| with the whole field's max|u|.
int licGhostLayers(const LicParams& params);

// The voxels [offset, offset + dims) of `whole` as a piece of it (VectorField::piece set, with
// the whole field's max|u|). InvalidInput unless the box lies inside the whole grid.
Result<VectorField> cutFieldPiece(const VectorField& whole, Dims offset, Dims dims);
// The same with the whole field's max|u| given (maxVoxelSpeedOverVoxels), for many pieces of it.
Result<VectorField> cutFieldPiece(const VectorField& whole, Dims offset, Dims dims,
                                  double wholeMaxVoxelSpeed);

// The voxels [offset, offset + dims) of a volume on a piece's or the whole grid.
Result<ScalarVolume> cutVolume(const ScalarVolume& volume, Dims offset, Dims dims);

}  // namespace lic3d
