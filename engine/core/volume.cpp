#include "core/volume.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace lic3d {

std::string gridText(Dims d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

std::string sizeText(Dims d) { return std::to_string(d.x) + "x" + std::to_string(d.y); }

double maxMagnitude(const VectorField& field) {
  double largest = 0.0;
  for (const glm::vec3& v : field.vectors) {
    const double x = v.x, y = v.y, z = v.z;
    largest = std::max(largest, std::sqrt(x * x + y * y + z * z));
  }
  return largest;
}

double minMagnitude(const VectorField& field) {
  if (field.vectors.empty()) return 0.0;
  double smallest = std::numeric_limits<double>::max();
  for (const glm::vec3& v : field.vectors) {
    const double x = v.x, y = v.y, z = v.z;
    smallest = std::min(smallest, std::sqrt(x * x + y * y + z * z));
  }
  return smallest;
}

std::size_t bytesPerValue(NoiseType type) {
  switch (type) {
    case NoiseType::UInt8: return 1;
    case NoiseType::UInt16: return 2;
    case NoiseType::Float32: return 4;
  }
  return 1;
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

}  // namespace lic3d
