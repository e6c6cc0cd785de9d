// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// How the values of a scalar over a grid are spread (speed, vorticity, an array of a file): what
// automatic colour ranges, opacity and looks are tuned from, so that they follow the data rather
// than constants that fit one field.

#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "core/volume.h"

namespace lic3d {

struct ValueHistogram {
  static constexpr int kBins = 4096;  // of the histograms made here
  double min = 0.0;
  double max = 0.0;
  std::vector<std::uint64_t> counts;  // equal bins over [min, max]; NaN is not counted

  std::uint64_t total() const;
  // The value below which `fraction` of the values lie (linear within a bin); min for 0, max for 1.
  double percentile(double fraction) const;
  // The mean of f(value) over the values, each taken at its bin's centre.
  double mean(const std::function<double(double)>& f) const;
  // The histogram of a blend: each count moved to (1 - w) x + w y of the two histograms' bins at
  // the same rank. An approximation for fields blended on the GPU (time series).
  static ValueHistogram blend(const ValueHistogram& a, const ValueHistogram& b, double w);
};

ValueHistogram histogramOf(std::span<const float> values);
// Counts already binned over [min, max] (the GPU's histogram of the LIC values over [0, 1]).
ValueHistogram histogramOfCounts(std::span<const std::uint32_t> counts, double min, double max);
// Of |v| over the field's voxels.
ValueHistogram speedHistogram(const VectorField& field);

}  // namespace lic3d
