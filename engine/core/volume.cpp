// SPDX-License-Identifier: BSD-3-Clause
#include "core/volume.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>

#include "core/parallel.h"
#include "core/text.h"

namespace lic3d {

std::string gridText(Dims d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

std::string sizeText(Dims d) { return std::to_string(d.x) + "x" + std::to_string(d.y); }

namespace {

// The largest (or, with `smallest`, the smallest) |v| of the field, chunk by chunk on the
// available threads: min and max do not depend on the order.
double extremeMagnitude(const VectorField& field, bool smallest) {
  std::mutex mutex;
  const double identity = smallest ? std::numeric_limits<double>::max() : 0.0;
  double result = identity;
  parallelChunks(field.vectors.size(), [&](std::size_t begin, std::size_t end) {
    double local = identity;  // not `result`: other threads write it under the lock
    for (std::size_t i = begin; i < end; ++i) {
      const glm::vec3& v = field.vectors[i];
      const double x = v.x, y = v.y, z = v.z;
      const double length = std::sqrt(x * x + y * y + z * z);
      local = smallest ? std::min(local, length) : std::max(local, length);
    }
    const std::scoped_lock lock(mutex);
    result = smallest ? std::min(result, local) : std::max(result, local);
  });
  return result;
}

}  // namespace

Result<void> checkGridGeometry(const GridGeometry& geometry) {
  const glm::dvec3 s = geometry.spacing;
  for (int a = 0; a < 3; ++a) {
    if (!(s[a] >= kMinSpacing && s[a] <= kMaxSpacing))
      return inputError("the grid's spacing along " + std::string(1, static_cast<char>('x' + a)) +
                        " is " + formatNumber(s[a]) + "; lic3d draws spacings in [1e-30, 1e30]");
    if (!(std::abs(geometry.origin[a]) <= kMaxSpacing))
      return inputError("the grid's origin along " + std::string(1, static_cast<char>('x' + a)) +
                        " is " + formatNumber(geometry.origin[a]) +
                        "; lic3d draws origins within +-1e30");
  }
  const double ratio = std::max({s.x, s.y, s.z}) / std::min({s.x, s.y, s.z});
  if (ratio > kMaxSpacingRatio)
    return inputError("the grid's spacings (" + formatNumber(s.x) + ", " + formatNumber(s.y) +
                      ", " + formatNumber(s.z) + ") differ by a factor of " + formatNumber(ratio) +
                      "; lic3d draws at most 1e6 between axes");
  return {};
}

double maxMagnitude(const VectorField& field) { return extremeMagnitude(field, false); }

double minMagnitude(const VectorField& field) {
  if (field.vectors.empty()) return 0.0;
  return extremeMagnitude(field, true);
}

std::size_t bytesPerValue(NoiseType type) {
  switch (type) {
    case NoiseType::UInt8: return 1;
    case NoiseType::UInt16: return 2;
    case NoiseType::Float32: return 4;
  }
  return 1;
}

Result<void> finishFloatNoise(NoiseVolume& noise) {
  if (noise.type != NoiseType::Float32) return {};
  const std::size_t count = noise.bytes.size() / 4;
  float low = 0.0f;
  float high = 0.0f;
  for (std::size_t i = 0; i < count; ++i) {
    float value;
    std::memcpy(&value, noise.bytes.data() + 4 * i, 4);
    if (!std::isfinite(value))
      return inputError("float noise at voxel " + voxelText(noise.dims, i) + " is NaN or infinite");
    low = i == 0 ? value : std::min(low, value);
    high = i == 0 ? value : std::max(high, value);
  }
  if (low >= 0.0f && high <= 1.0f) return {};
  if (low == high)
    return inputError("float noise is the constant " + formatDouble(low) +
                      ", outside [0,1], and cannot be rescaled to [0,1]");
  const double range = static_cast<double>(high) - static_cast<double>(low);
  for (std::size_t i = 0; i < count; ++i) {
    float value;
    std::memcpy(&value, noise.bytes.data() + 4 * i, 4);
    const double scaled = (static_cast<double>(value) - static_cast<double>(low)) / range;
    value = static_cast<float>(std::clamp(scaled, 0.0, 1.0));
    std::memcpy(noise.bytes.data() + 4 * i, &value, 4);
  }
  return {};
}

float NoiseVolume::value(std::size_t index) const {
  switch (type) {
    case NoiseType::UInt8: return static_cast<float>(bytes[index]) / 255.0f;
    case NoiseType::UInt16: {
      std::uint16_t v;
      std::memcpy(&v, bytes.data() + 2 * index, 2);
      return static_cast<float>(v) / 65535.0f;
    }
    case NoiseType::Float32: {
      float v;
      std::memcpy(&v, bytes.data() + 4 * index, 4);
      return v;
    }
  }
  return 0.0f;
}

void markHiddenVoxels(ScalarVolume& volume) {
  for (std::size_t i = 0; i < volume.drawn.size(); ++i)
    if (!volume.drawn[i]) volume.values[i] = std::numeric_limits<float>::quiet_NaN();
}

}  // namespace lic3d
