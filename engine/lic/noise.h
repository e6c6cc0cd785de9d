// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Seeded white noise, the input texture of LIC (the thesis' positional noise): each voxel's value
// is a hash of (seed, voxel index), so it is bit-identical on every machine and compiler and
// independent of the order voxels are generated in.

#include <cstdint>

#include "core/volume.h"
#include "lic/random.h"  // noiseHash

namespace lic3d {

// Uniform 8-bit white noise: the top byte of noiseHash, read as [0,1] by value()/255.
NoiseVolume makeWhiteNoise(Dims dims, std::uint64_t seed);

// The part of makeWhiteNoise(wholeDims, seed) that a piece of `dims` at `offset` covers: each
// voxel hashes its index in the whole grid, so the pieces of a distributed run agree with the
// whole and with each other where their ghost layers overlap.
NoiseVolume makeWhiteNoisePiece(Dims wholeDims, Dims offset, Dims dims, std::uint64_t seed);

// Sparse seed noise (Helgeland & Andreassen's "seed LIC"; the alternative the thesis points to
// for sparsity): black everywhere but about `spots` white voxels, spread evenly by Poisson-disk
// sampling, so LIC turns each spot into one distinct streamline segment.
NoiseVolume makeSeedNoise(Dims dims, std::size_t spots, std::uint64_t seed);

}  // namespace lic3d
