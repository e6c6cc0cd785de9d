// SPDX-License-Identifier: BSD-3-Clause
// The Halton and Hammersley sequences (thesis 5.1.4.2.2): even without random numbers, and
// computed as exact integers rounded once, so every machine and compiler gets the same points.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>

#include "lic/fixed_point.h"
#include "lic/point_sets.h"

namespace lic3d {
using namespace points;
namespace {

// phi_b(i) as one integer (the mirrored digits) over base^digits: a single rounding at the end,
// so the value is the same on every machine (no running floating-point sum to contract or
// reorder). Digits past a 64-bit denominator are worth less than base * 2^-64 and dropped.
// Halton and Hammersley call it with constant bases, where division becomes multiplication.
template <class Base>
double mirroredDigitsIn(Base base, std::uint64_t index) {
  std::uint64_t mirrored = 0, denominator = 1;
  const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() / base;
  while (index > 0 && denominator <= limit) {
    mirrored = mirrored * base + index % base;
    denominator *= base;
    index /= base;
  }
  return static_cast<double>(mirrored) / static_cast<double>(denominator);
}
template <std::uint64_t kBase>
double mirroredDigits(std::uint64_t index) {
  return mirroredDigitsIn(std::integral_constant<std::uint64_t, kBase>{}, index);
}
double mirroredDigits(std::uint64_t base, std::uint64_t index) {
  return mirroredDigitsIn(base, index);
}

// phi_b(1), phi_b(2), ... in order, for Halton and Hammersley: the mirrored digits of i as one
// integer over base^K (K digits hold every i <= count), updated like an odometer, O(1) per step
// on average. Both integers stay below 2^53, so the quotient is the same double as
// radicalInverse(b, i): the same rational, rounded once.
class MirroredCounter {
 public:
  MirroredCounter(std::uint64_t base, std::uint64_t count) : base_(base) {
    while (denominator_ <= count &&
           denominator_ <= std::numeric_limits<std::uint64_t>::max() / base) {
      denominator_ *= base;
      ++digits_;
    }
    std::uint64_t weight = denominator_;
    for (int j = 0; j < digits_; ++j) weights_[static_cast<std::size_t>(j)] = weight /= base;
  }

  double next() {
    step();
    return static_cast<double>(mirrored_) / static_cast<double>(denominator_);
  }
  // floor(n phi_b(i)) of the next index, exactly: the mirrored digits times n stay below 2^64
  // for every count and axis size validate() allows (b^K <= 5 * 2^25, n <= 2^14).
  std::uint32_t nextVoxel(std::uint64_t n) {
    step();
    return static_cast<std::uint32_t>(mirrored_ * n / denominator_);
  }

 private:
  static constexpr int kMaxDigits = 64;
  std::uint64_t base_;
  std::uint64_t denominator_ = 1;
  std::uint64_t mirrored_ = 0;
  int digits_ = 0;
  std::array<std::uint64_t, kMaxDigits> weights_{};
  std::array<std::uint64_t, kMaxDigits> indexDigits_{};

  void step() {
    for (std::size_t j = 0; j < static_cast<std::size_t>(digits_); ++j) {
      if (++indexDigits_[j] < base_) {
        mirrored_ += weights_[j];
        break;
      }
      indexDigits_[j] = 0;
      mirrored_ -= (base_ - 1) * weights_[j];
    }
  }
};

// A coordinate t * n with t in [0, 1], moved inside [0, n) if rounding (or t = 1) put it on the
// far face.
float insideAxis(double t, int n) {
  const auto v = static_cast<float>(t * static_cast<double>(n));
  const float limit = static_cast<float>(n);
  return v < limit ? v : std::nextafter(limit, 0.0f);
}

}  // namespace

double radicalInverse(std::uint32_t base, std::uint64_t index) {
  double value = 0.0;
  switch (base) {
    case 0:
    case 1: return 0.0;
    case 2: value = mirroredDigits<2>(index); break;
    case 3: value = mirroredDigits<3>(index); break;
    case 5: value = mirroredDigits<5>(index); break;
    default: value = mirroredDigits(base, index); break;
  }
  // Only indices near 2^64 round up to 1.
  return std::min(value, std::nextafter(1.0, 0.0));
}

std::vector<glm::vec3> haltonPoints(Dims dims, std::size_t count) {
  std::vector<glm::vec3> points;
  if (!validDims(dims)) return points;
  points.reserve(count);
  MirroredCounter phi2(2, count), phi3(3, count), phi5(5, count);
  for (std::size_t i = 1; i <= count; ++i)
    points.emplace_back(insideAxis(phi2.next(), dims.x), insideAxis(phi3.next(), dims.y),
                        insideAxis(phi5.next(), dims.z));
  return points;
}

std::vector<glm::vec3> hammersleyPoints(Dims dims, std::size_t count) {
  std::vector<glm::vec3> points;
  if (!validDims(dims)) return points;
  points.reserve(count);
  MirroredCounter phi2(2, count), phi3(3, count);
  for (std::size_t i = 1; i <= count; ++i)
    points.emplace_back(insideAxis(static_cast<double>(i) / static_cast<double>(count), dims.x),
                        insideAxis(phi2.next(), dims.y), insideAxis(phi3.next(), dims.z));
  return points;
}

std::vector<glm::ivec3> lowDiscrepancyVoxels(Dims dims, std::size_t count, bool halton) {
  std::vector<glm::ivec3> voxels;
  if (!validDims(dims)) return voxels;
  voxels.reserve(count);
  MirroredCounter first(2, count), second(halton ? 3 : 2, count), third(halton ? 5 : 3, count);
  const auto n = [&](int a) { return static_cast<std::uint64_t>(dims[a]); };
  for (std::size_t i = 1; i <= count; ++i) {
    // Hammersley's x = floor(n i / count), the last one kept inside.
    const std::uint64_t x = halton ? first.nextVoxel(n(0)) : std::min(i * n(0) / count, n(0) - 1);
    voxels.emplace_back(static_cast<int>(x), static_cast<int>(second.nextVoxel(n(1))),
                        static_cast<int>(third.nextVoxel(n(2))));
  }
  return voxels;
}

}  // namespace lic3d
