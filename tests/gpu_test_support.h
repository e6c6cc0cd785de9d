// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// A fixture for tests that use the GPU: a Vulkan context with validation and synchronization
// validation on; any validation message fails the test.

#include <gtest/gtest.h>

#include <algorithm>
#include <functional>
#include <glm/geometric.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <glm/vec4.hpp>
#include <optional>
#include <vector>

#include "core/rgba_image.h"
#include "core/view_params.h"
#include "core/volume.h"
#include "gpu/vulkan_context.h"
#include "render/lic_renderer.h"

namespace lic3d::test {

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  const Context& context() const { return *context_; }

 private:
  std::optional<Context> context_;
};

struct VolumeDifference {
  double mean = 0.0;
  double max = 0.0;
  double quantile999 = 0.0;  // 99.9th percentile of |a - b|
  std::size_t argMax = 0;
};

VolumeDifference compareVolumes(const ScalarVolume& a, const ScalarVolume& b);

// Pictures with known content: a renderer whose LIC volume is given directly (the field points
// along +x unless one is passed), and a view that draws it opaque with grey = LIC value.
// The speed of each voxel of `field`: what the CPU rule of the visible bricks reads.
inline std::vector<float> speedsOf(const VectorField& field) {
  std::vector<float> speeds(field.vectors.size());
  std::transform(field.vectors.begin(), field.vectors.end(), speeds.begin(),
                 [](glm::vec3 v) { return glm::length(v); });
  return speeds;
}

inline constexpr glm::vec3 kBackground{0.2f, 0.4f, 0.6f};
inline constexpr glm::u8vec4 kBackground8{51, 102, 153, 255};
LicRenderer rendererWithVolume(const Context& context, Dims dims,
                               const std::function<float(int, int, int)>& value,
                               const VectorField* field = nullptr);
ViewParams opaqueView(int size);
bool isBackground(glm::u8vec4 pixel);

// The screen footprint of a box (fractions min..max of the volume's box) for a view: a convex
// polygon in pixel coordinates.
struct ProjectedBox {
  std::vector<glm::vec2> hull;
  // Distance in pixels from p to the polygon's edge, positive inside.
  double signedDistance(glm::vec2 p) const;
};
ProjectedBox projectBox(const ViewParams& view, Dims dims, glm::vec3 min = glm::vec3(0.0f),
                        glm::vec3 max = glm::vec3(1.0f));

double meanAbsoluteDifference(const RgbaImage& a, const RgbaImage& b);

}  // namespace lic3d::test
