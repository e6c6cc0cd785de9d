#include "core/volume_compare.h"

#include <cmath>

namespace lic3d {

double correlation(const ScalarVolume& a, const ScalarVolume& b,
                   const std::function<bool(std::size_t)>& keep) {
  const std::size_t n = a.values.size();
  double ma = 0.0, mb = 0.0, count = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (keep && !keep(i)) continue;
    ma += a.values[i];
    mb += b.values[i];
    ++count;
  }
  if (count == 0.0) return 1.0;
  ma /= count;
  mb /= count;
  double ab = 0.0, aa = 0.0, bb = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (keep && !keep(i)) continue;
    const double da = a.values[i] - ma, db = b.values[i] - mb;
    ab += da * db;
    aa += da * da;
    bb += db * db;
  }
  return aa > 0.0 && bb > 0.0 ? ab / std::sqrt(aa * bb) : 1.0;
}

}  // namespace lic3d
