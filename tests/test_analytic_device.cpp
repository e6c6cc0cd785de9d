// The analytic fields made on the device (passes/analytic_field_pass.h) against the CPU oracle
// in double precision (lic/analytic_fields.h).
#include <gtest/gtest.h>

#include <algorithm>
#include <glm/geometric.hpp>

#include "core/enum_names.h"
#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "passes/analytic_field_pass.h"

namespace lic3d {
namespace {

using test::GpuTest;

TEST_F(GpuTest, AnalyticFieldsOnTheDeviceMatchTheCpuOracle) {
  // An odd grid, several slabs' worth of layers, the tornado at a time off its start.
  const Dims dims{37, 29, 41};
  for (const auto& [field, name] : enumNames<AnalyticField>()) {
    const double time = field == AnalyticField::Tornado ? 123.4 : 0.0;
    const VectorField cpu = makeAnalyticField(field, dims, time);
    const Result<VectorField> gpu = makeAnalyticFieldOnDevice(context(), field, dims, time);
    ASSERT_TRUE(gpu) << gpu.error().message;
    ASSERT_EQ(gpu->dims, dims);
    EXPECT_EQ(gpu->geometry, cpu.geometry) << name;
    const double largest = maxMagnitude(cpu);
    // Float against double: the tornado's published formula jumps where |r - d| = r2, and a
    // voxel within rounding of that seam may land on the other side.
    std::size_t off = 0;
    double worst = 0.0;
    for (std::size_t i = 0; i < cpu.vectors.size(); ++i) {
      const double d = glm::length(glm::dvec3(gpu->vectors[i]) - glm::dvec3(cpu.vectors[i]));
      if (d > 1e-4 * largest)
        ++off;
      else
        worst = std::max(worst, d);
    }
    EXPECT_LE(off, cpu.vectors.size() / 10000) << name << ": voxels off the oracle";
    EXPECT_LT(worst, 1e-4 * largest) << name;
  }
}

}  // namespace
}  // namespace lic3d
