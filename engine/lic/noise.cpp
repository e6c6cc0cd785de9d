// SPDX-License-Identifier: BSD-3-Clause
#include "lic/noise.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "core/parallel.h"
#include "lic/point_sets.h"

namespace lic3d {

NoiseVolume makeWhiteNoise(Dims dims, std::uint64_t seed) {
  NoiseVolume noise;
  noise.dims = dims;
  noise.type = NoiseType::UInt8;
  resizeLarge(noise.bytes, voxelCount(dims));
  parallelChunks(noise.bytes.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      noise.bytes[i] = static_cast<std::uint8_t>(noiseHash(seed, i) >> 56);
  });
  return noise;
}

NoiseVolume makeWhiteNoisePiece(Dims wholeDims, Dims offset, Dims dims, std::uint64_t seed) {
  NoiseVolume noise;
  noise.dims = dims;
  noise.type = NoiseType::UInt8;
  resizeLarge(noise.bytes, voxelCount(dims));
  // Layers on the available threads: each voxel's value depends on its whole-grid index only.
  parallelFor(static_cast<std::size_t>(dims.z), 0, [&](std::size_t layer) {
    const int k = static_cast<int>(layer);
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) {
        const std::size_t whole = voxelIndex(wholeDims, offset.x + i, offset.y + j, offset.z + k);
        noise.bytes[voxelIndex(dims, i, j, k)] =
            static_cast<std::uint8_t>(noiseHash(seed, whole) >> 56);
      }
  });
  return noise;
}

NoiseVolume makeSeedNoise(Dims dims, std::size_t spots, std::uint64_t seed) {
  NoiseVolume noise;
  noise.dims = dims;
  noise.type = NoiseType::UInt8;
  noise.bytes.assign(voxelCount(dims), 0);
  for (const glm::vec3& p : poissonDiskPointsByCount(dims, spots, seed)) {
    const glm::ivec3 v = glm::clamp(glm::ivec3(glm::floor(p)), glm::ivec3(0), dims - 1);
    noise.bytes[voxelIndex(dims, v.x, v.y, v.z)] = 255;
  }
  return noise;
}

}  // namespace lic3d
