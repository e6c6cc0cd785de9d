// SPDX-License-Identifier: BSD-3-Clause
#include "core/volume_compare.h"

#include <cmath>

namespace lic3d {

namespace {

// Pearson correlation of a(i) and b(i) over the i < n that keep(i) accepts.
template <class A, class B, class Keep>
double pearson(std::size_t n, const A& a, const B& b, const Keep& keep) {
  double ma = 0.0, mb = 0.0, count = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep(i)) continue;
    ma += a(i);
    mb += b(i);
    ++count;
  }
  if (count == 0.0) return 1.0;
  ma /= count;
  mb /= count;
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!keep(i)) continue;
    const double da = a(i) - ma, db = b(i) - mb;
    ab += da * db;
    aa += da * da;
    bb += db * db;
  }
  return aa > 0.0 && bb > 0.0 ? ab / std::sqrt(aa * bb) : 1.0;
}

}  // namespace

double correlation(const ScalarVolume& a, const ScalarVolume& b,
                   const std::function<bool(std::size_t)>& keep) {
  return pearson(
      a.values.size(), [&](std::size_t i) { return double(a.values[i]); },
      [&](std::size_t i) { return double(b.values[i]); },
      [&](std::size_t i) { return !keep || keep(i); });
}

double correlation(std::span<const double> a, std::span<const double> b) {
  return pearson(
      a.size(), [&](std::size_t i) { return a[i]; }, [&](std::size_t i) { return b[i]; },
      [](std::size_t) { return true; });
}

}  // namespace lic3d
