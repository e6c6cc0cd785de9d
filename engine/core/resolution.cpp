// SPDX-License-Identifier: BSD-3-Clause
#include "core/resolution.h"

#include <algorithm>
#include <charconv>
#include <cmath>

#include "core/parameter_ranges.h"
#include "core/text.h"

namespace lic3d {
namespace {

constexpr double kMaxResolutionFactor = 16.0;

bool parseFactor(std::string_view text, double& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size() && std::isfinite(value);
}

Error resolutionError(std::string_view text, const std::string& problem) {
  return parameterError(ranges::kResolution.key, "'" + std::string(text) + "': " + problem);
}

}  // namespace

Result<Resolution> parseResolution(std::string_view text) {
  Resolution resolution;
  if (text.empty()) return resolution;
  const std::string limits = "[2, " + std::to_string(kMaxGridSize) + "]";
  if (text.back() == 'x') {
    if (!parseFactor(text.substr(0, text.size() - 1), resolution.factor) ||
        !(resolution.factor > 0.0 && resolution.factor <= kMaxResolutionFactor))
      return resolutionError(text, "a factor must be a number in (0, 16] followed by x, as 2x");
    return resolution;
  }
  const std::size_t comma = text.find(',');
  if (comma == std::string_view::npos) {
    if (!parseInt(text, resolution.longest) || resolution.longest < 2 ||
        resolution.longest > kMaxGridSize)
      return resolutionError(text, "expected N (voxels along the longest axis) in " + limits +
                                       ", NX,NY,NZ or a factor such as 2x");
    return resolution;
  }
  const std::size_t second = text.find(',', comma + 1);
  if (second == std::string_view::npos || !parseInt(text.substr(0, comma), resolution.dims.x) ||
      !parseInt(text.substr(comma + 1, second - comma - 1), resolution.dims.y) ||
      !parseInt(text.substr(second + 1), resolution.dims.z))
    return resolutionError(text, "expected NX,NY,NZ, N or a factor such as 2x");
  for (int a = 0; a < 3; ++a)
    if (resolution.dims[a] < 1 || resolution.dims[a] > kMaxGridSize)
      return resolutionError(text,
                             "each axis must be in [1, " + std::to_string(kMaxGridSize) + "]");
  return resolution;
}

Dims resolvedGrid(const Resolution& resolution, Dims fileDims) {
  if (resolution.dims.x > 0) return resolution.dims;
  if (!resolution.given()) return fileDims;
  const int longest = std::max({fileDims.x, fileDims.y, fileDims.z});
  // Voxel counts scale with the spacing: (n - 1) intervals become (n - 1) * factor.
  const double factor = resolution.longest > 0
                            ? static_cast<double>(resolution.longest - 1) / std::max(longest - 1, 1)
                            : resolution.factor;
  Dims out{0};
  for (int a = 0; a < 3; ++a) {
    if (fileDims[a] == 1) {
      out[a] = 1;
      continue;
    }
    const double n = std::round(static_cast<double>(fileDims[a] - 1) * factor) + 1.0;
    out[a] = static_cast<int>(std::clamp(n, 2.0, static_cast<double>(kMaxGridSize)));
  }
  return out;
}

Result<Dims> resolveGrid(const Resolution& resolution, Dims fileDims, std::string_view text) {
  if (resolution.dims.x > 0 || !resolution.given()) return resolvedGrid(resolution, fileDims);
  const int longest = std::max({fileDims.x, fileDims.y, fileDims.z});
  const double factor = resolution.longest > 0
                            ? static_cast<double>(resolution.longest - 1) / std::max(longest - 1, 1)
                            : resolution.factor;
  for (int a = 0; a < 3; ++a) {
    if (fileDims[a] == 1) continue;
    const double n = std::round(static_cast<double>(fileDims[a] - 1) * factor) + 1.0;
    if (!(n >= 2.0 && n <= static_cast<double>(kMaxGridSize)))
      return resolutionError(
          text, "gives the file's " + gridText(fileDims) + " grid " + formatNumber(n) +
                    " voxels along " + std::string(1, static_cast<char>('x' + a)) +
                    "; each axis must be in [2, " + std::to_string(kMaxGridSize) + "]");
  }
  return resolvedGrid(resolution, fileDims);
}

}  // namespace lic3d
