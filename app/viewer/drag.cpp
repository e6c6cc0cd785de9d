// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/drag.h"

#include <algorithm>
#include <cstdio>

#include "core/parameter_ranges.h"
#include "render/lic_volume_job.h"

namespace lic3d::viewer {

void RecentMedian::add(double value) {
  if (values_.size() < kCapacity) {
    values_.push_back(value);
  } else {
    values_[next_] = value;
  }
  next_ = (next_ + 1) % kCapacity;
}

double RecentMedian::median() const {
  if (values_.empty()) return 0.0;
  std::vector<double> sorted = values_;
  const std::size_t half = sorted.size() / 2;
  const auto middle = sorted.begin() + static_cast<std::ptrdiff_t>(half);
  std::nth_element(sorted.begin(), middle, sorted.end());
  const double upper = *middle;
  if (sorted.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(sorted.begin(), middle));
}

std::string frameTimeText(double cpuMs, double gpuMs, std::size_t frames) {
  char text[96];
  std::snprintf(text, sizeof text, "frame %.1f ms CPU, %.2f ms GPU (median of %zu)", cpuMs, gpuMs,
                frames);
  return text;
}

std::string licTimeText(double licMs, int stride, Dims grid) {
  char text[96];
  std::snprintf(text, sizeof text, "LIC %.2f ms GPU, %s %dx%dx%d", licMs,
                stride > 1 ? "coarse" : "full", grid.x, grid.y, grid.z);
  return text;
}

std::optional<int> LicDrag::request(bool changed, bool dragging, double fullLicMs) {
  const bool dragEnded = !dragging && requested_ != 1;
  if (!changed && !dragEnded) return std::nullopt;
  const int coarse =
      forcedStride_ > 0 ? forcedStride_ : std::max(coarseLicStride(fullLicMs), floor_);
  requested_ = changed && dragging ? coarse : 1;
  return requested_;
}

void LicDrag::noteCoarse(int stride, double ms) {
  floor_ = std::max(floor_, nextCoarseStride(stride, ms));
}

bool ScriptedDrag::step(bool ready, LicParams& lic) {
  if (done() || (held_ == 0 && !ready)) return false;
  ++held_;
  lic.length = std::min(lic.length + 1, static_cast<int>(ranges::kLength.sliderMax));
  return true;
}

}  // namespace lic3d::viewer
