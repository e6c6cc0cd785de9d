// SPDX-License-Identifier: BSD-3-Clause
#include "core/parameter_ranges.h"

#include "core/text.h"

namespace lic3d {

std::string ParameterRange::text() const {
  return (minExclusive ? "(" : "[") + formatNumber(min) + ", " + formatNumber(max) +
         (maxExclusive ? ")" : "]");
}

Result<void> checkRange(const ParameterRange& range, double value) {
  if (range.contains(value)) return {};
  return parameterError(range.key, "must be in " + range.text() + ", got " + formatNumber(value));
}

}  // namespace lic3d
