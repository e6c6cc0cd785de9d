// SPDX-License-Identifier: BSD-3-Clause
#include "gpu_test_support.h"

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "lic/noise.h"

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

LicRenderer rendererWithVolume(const Context& context, Dims dims,
                               const std::function<float(int, int, int)>& value,
                               const VectorField* field) {
  VectorField alongX;
  if (!field) {
    alongX.dims = dims;
    alongX.vectors.assign(voxelCount(dims), glm::vec3(1.0f, 0.0f, 0.0f));
    field = &alongX;
  }
  ScalarVolume volume;
  volume.dims = dims;
  volume.values.resize(voxelCount(dims));
  for (int k = 0; k < dims.z; ++k)
    for (int j = 0; j < dims.y; ++j)
      for (int i = 0; i < dims.x; ++i) volume.values[voxelIndex(dims, i, j, k)] = value(i, j, k);
  Result<LicRenderer> renderer = LicRenderer::create(context);
  EXPECT_TRUE(renderer.ok()) << renderer.error().message;
  EXPECT_TRUE(renderer->setInputs(*field, makeWhiteNoise(dims, 1)).ok());
  EXPECT_TRUE(renderer->setLicVolume(volume, LicParams{}).ok());
  return std::move(renderer).value();
}

ViewParams opaqueView(int size) {
  ViewParams view;
  view.width = view.height = size;
  view.background = kBackground;
  view.alpha = 1.0f;
  view.opacityMode = OpacityMode::Constant;
  view.contrast = false;  // grey = intensity
  return view;
}

bool isBackground(glm::u8vec4 pixel) { return pixel == kBackground8; }

double ProjectedBox::signedDistance(glm::vec2 p) const {
  double inside = 1e30;
  for (std::size_t i = 0; i < hull.size(); ++i) {
    const glm::vec2 a = hull[i], b = hull[(i + 1) % hull.size()];
    const glm::vec2 edge = glm::normalize(b - a);
    // The hull runs counter-clockwise in pixel coordinates with y down: inside is to the right.
    const double d = edge.x * (p.y - a.y) - edge.y * (p.x - a.x);
    inside = std::min(inside, d);
  }
  return inside;
}

ProjectedBox projectBox(const ViewParams& view, Dims dims, glm::vec3 min, glm::vec3 max) {
  VolumeFacts facts;
  facts.dims = dims;
  const SliceFrame frame = makeSliceFrame(
      view, facts, Eye::Mono,
      {static_cast<std::uint32_t>(view.width), static_cast<std::uint32_t>(view.height)});
  std::vector<glm::vec2> points;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 fraction(c & 1 ? max.x : min.x, c & 2 ? max.y : min.y, c & 4 ? max.z : min.z);
    const glm::vec3 corner = (fraction - 0.5f) * 2.0f * frame.halfExtent;
    const glm::vec4 clip = frame.camera.viewProjection * glm::vec4(corner, 1.0f);
    const glm::vec2 ndc = glm::vec2(clip) / clip.w;
    points.push_back({(ndc.x * 0.5f + 0.5f) * static_cast<float>(view.width),
                      (ndc.y * 0.5f + 0.5f) * static_cast<float>(view.height)});
  }
  // Gift wrapping: the hull of the 8 projected corners.
  std::size_t start = 0;
  for (std::size_t i = 1; i < points.size(); ++i)
    if (points[i].x < points[start].x) start = i;
  ProjectedBox box;
  std::size_t current = start;
  do {
    box.hull.push_back(points[current]);
    std::size_t next = (current + 1) % points.size();
    for (std::size_t i = 0; i < points.size(); ++i) {
      const glm::vec2 a = points[next] - points[current], b = points[i] - points[current];
      if (a.x * b.y - a.y * b.x < 0.0f) next = i;
    }
    current = next;
  } while (current != start && box.hull.size() <= points.size());
  return box;
}

double meanAbsoluteDifference(const RgbaImage& a, const RgbaImage& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i)
    sum += std::abs(static_cast<int>(a.pixels[i]) - static_cast<int>(b.pixels[i]));
  return sum / static_cast<double>(a.pixels.size()) / 255.0;
}

}  // namespace lic3d::test
