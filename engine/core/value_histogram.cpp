// SPDX-License-Identifier: BSD-3-Clause
#include "core/value_histogram.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>

#include "core/parallel.h"

namespace lic3d {
namespace {

template <class Values>
ValueHistogram build(std::size_t n, const Values& valueAt) {
  // Two passes over the values, chunk by chunk on the available threads: their range, then the
  // counts. Min, max and integer sums do not depend on the order: the same histogram as one
  // thread makes.
  ValueHistogram h;
  h.counts.assign(ValueHistogram::kBins, 0);
  std::mutex mutex;
  double lo = std::numeric_limits<double>::max(), hi = std::numeric_limits<double>::lowest();
  parallelChunks(n, [&](std::size_t begin, std::size_t end) {
    double low = std::numeric_limits<double>::max(), high = std::numeric_limits<double>::lowest();
    for (std::size_t i = begin; i < end; ++i) {
      const double v = valueAt(i);
      if (std::isnan(v)) continue;
      low = std::min(low, v);
      high = std::max(high, v);
    }
    const std::scoped_lock lock(mutex);
    lo = std::min(lo, low);
    hi = std::max(hi, high);
  });
  if (lo > hi) return h;
  h.min = lo;
  h.max = hi;
  const double scale = hi > lo ? ValueHistogram::kBins / (hi - lo) : 0.0;
  parallelChunks(n, [&](std::size_t begin, std::size_t end) {
    std::vector<std::uint64_t> counts(ValueHistogram::kBins, 0);
    for (std::size_t i = begin; i < end; ++i) {
      const double v = valueAt(i);
      if (std::isnan(v)) continue;
      const auto bin = static_cast<std::size_t>((v - lo) * scale);
      ++counts[std::min(bin, std::size_t{ValueHistogram::kBins - 1})];
    }
    const std::scoped_lock lock(mutex);
    for (std::size_t b = 0; b < counts.size(); ++b) h.counts[b] += counts[b];
  });
  return h;
}

}  // namespace

std::uint64_t ValueHistogram::total() const {
  std::uint64_t n = 0;
  for (const std::uint64_t c : counts) n += c;
  return n;
}

double ValueHistogram::percentile(double fraction) const {
  const std::uint64_t n = total();
  if (n == 0 || max <= min) return min;
  const double target = std::clamp(fraction, 0.0, 1.0) * static_cast<double>(n);
  const int bins = static_cast<int>(counts.size());
  const double width = (max - min) / bins;
  double below = 0.0;
  for (int b = 0; b < bins; ++b) {
    const double count = static_cast<double>(counts[static_cast<std::size_t>(b)]);
    if (below + count >= target && count > 0.0) return min + width * (b + (target - below) / count);
    below += count;
  }
  return max;
}

double ValueHistogram::mean(const std::function<double(double)>& f) const {
  const std::uint64_t n = total();
  if (n == 0) return 0.0;
  const int bins = static_cast<int>(counts.size());
  const double width = (max - min) / bins;
  double sum = 0.0;
  for (int b = 0; b < bins; ++b)
    if (counts[static_cast<std::size_t>(b)] > 0)
      sum += static_cast<double>(counts[static_cast<std::size_t>(b)]) * f(min + width * (b + 0.5));
  return sum / static_cast<double>(n);
}

ValueHistogram ValueHistogram::blend(const ValueHistogram& a, const ValueHistogram& b, double w) {
  if (a.total() == 0) return b;
  if (b.total() == 0) return a;
  // Blend the two quantile functions: the value of rank q is (1 - w) a(q) + w b(q).
  std::vector<float> quantiles(kBins);
  for (int i = 0; i < kBins; ++i) {
    const double q = (i + 0.5) / kBins;
    quantiles[static_cast<std::size_t>(i)] =
        static_cast<float>((1.0 - w) * a.percentile(q) + w * b.percentile(q));
  }
  ValueHistogram h = histogramOf(quantiles);
  // Scale the counts back to the voxels' number.
  const double scale = static_cast<double>(a.total()) / kBins;
  for (std::uint64_t& c : h.counts)
    c = static_cast<std::uint64_t>(std::llround(static_cast<double>(c) * scale));
  return h;
}

ValueHistogram histogramOf(std::span<const float> values) {
  return build(values.size(), [&](std::size_t i) { return static_cast<double>(values[i]); });
}

ValueHistogram histogramOfCounts(std::span<const std::uint32_t> counts, double min, double max) {
  ValueHistogram h;
  h.min = min;
  h.max = max;
  h.counts.assign(counts.begin(), counts.end());
  return h;
}

ValueHistogram speedHistogram(const VectorField& field) {
  return build(field.vectors.size(), [&](std::size_t i) {
    const glm::vec3& v = field.vectors[i];
    const double x = v.x, y = v.y, z = v.z;
    return std::sqrt(x * x + y * y + z * z);
  });
}

}  // namespace lic3d
