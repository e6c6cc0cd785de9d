#include "gpu_test_support.h"

#include <algorithm>
#include <cmath>

namespace lic3d::test {

void GpuTest::SetUp() {
  ContextOptions options;
  options.validation = true;
  Result<Context> created = Context::create(options);
  ASSERT_TRUE(created.ok()) << created.error().message;
  context_.emplace(std::move(created).value());
}

void GpuTest::TearDown() {
  if (!context_) return;
  EXPECT_EQ(context_->validationMessageCount(), 0u) << [&] {
    std::string all;
    for (const std::string& m : context_->validationMessages()) all += m + "\n";
    return all;
  }();
}

VolumeDifference compareVolumes(const ScalarVolume& a, const ScalarVolume& b) {
  VolumeDifference d;
  std::vector<double> diffs(a.values.size());
  for (std::size_t i = 0; i < a.values.size(); ++i) {
    diffs[i] = std::abs(static_cast<double>(a.values[i]) - b.values[i]);
    d.mean += diffs[i];
    if (diffs[i] > d.max) {
      d.max = diffs[i];
      d.argMax = i;
    }
  }
  d.mean /= static_cast<double>(diffs.size());
  const std::size_t q = static_cast<std::size_t>(0.999 * static_cast<double>(diffs.size() - 1));
  std::nth_element(diffs.begin(), diffs.begin() + static_cast<std::ptrdiff_t>(q), diffs.end());
  d.quantile999 = diffs[q];
  return d;
}

}  // namespace lic3d::test
