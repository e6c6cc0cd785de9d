// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The project's one random-number hash, shared by the noise and the point samplers: a pure
// function of (seed, index), so every volume and point set is identical on every machine.

#include <cstdint>

namespace lic3d {

// SplitMix64 (Steele, Lea, Flood 2014) of the seed-offset voxel index: a counter-based generator
// with full 64-bit avalanche, integer arithmetic only.
inline std::uint64_t noiseHash(std::uint64_t seed, std::uint64_t index) {
  std::uint64_t z = seed * 0xD1B54A32D192ED03ull + index * 0x9E3779B97F4A7C15ull;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

}  // namespace lic3d
