#pragma once
// Seeded white noise, the input texture of LIC (the thesis' positional noise): each voxel's value
// is a hash of (seed, voxel index), so it is bit-identical on every machine and compiler and
// independent of the order voxels are generated in.

#include <cstdint>

#include "volume.h"

namespace lic3d {

// SplitMix64 (Steele, Lea, Flood 2014) of the seed-offset voxel index: a counter-based generator
// with full 64-bit avalanche, integer arithmetic only.
std::uint64_t noiseHash(std::uint64_t seed, std::uint64_t index);

// Uniform 8-bit white noise: the top byte of noiseHash, read as [0,1] by value()/255.
NoiseVolume makeWhiteNoise(Dims dims, std::uint64_t seed);

}  // namespace lic3d
