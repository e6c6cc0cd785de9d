// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/overlay.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "lic/annotation.h"

namespace lic3d::viewer {
namespace {

RgbaImage filled(int width, int height, std::uint8_t value) {
  RgbaImage image;
  image.width = width;
  image.height = height;
  image.pixels.assign(static_cast<std::size_t>(width) * height * 4, value);
  return image;
}

}  // namespace

std::vector<OverlayRun> annotationRuns(const ViewParams& view, const LegendSpec* legend, Dims dims,
                                       const GridGeometry& geometry) {
  const int width = view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width;
  const int height = view.height;
  std::vector<OverlayRun> runs;
  if (width <= 0 || height <= 0) return runs;
  // Each pixel ends as c + (1 - a) * beneath: c is what lands on black, 1 - a what white keeps.
  RgbaImage black = filled(width, height, 0), white = filled(width, height, 255);
  annotatePicture(black, view, legend, dims, geometry);
  annotatePicture(white, view, legend, dims, geometry);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      // Most pixels hold no annotation: black stays 0 and white 255 (the alpha byte included).
      const std::size_t i = 4 * (static_cast<std::size_t>(y) * width + x);
      std::uint32_t onBlack, onWhite;
      std::memcpy(&onBlack, &black.pixels[i], 4);
      std::memcpy(&onWhite, &white.pixels[i], 4);
      if (onBlack == 0u && onWhite == 0xffffffffu) continue;
      const glm::u8vec4 c = black.at(x, y), w = white.at(x, y);
      const float kept = (static_cast<float>(w.r - c.r) + static_cast<float>(w.g - c.g) +
                          static_cast<float>(w.b - c.b)) /
                         3.0f;
      const int alpha = std::clamp(static_cast<int>(std::lround(255.0f - kept)), 0, 255);
      if (alpha == 0) continue;
      glm::u8vec4 color(0, 0, 0, static_cast<std::uint8_t>(alpha));
      for (int k = 0; k < 3; ++k)
        color[k] = static_cast<std::uint8_t>(std::clamp(
            std::lround(255.0f * static_cast<float>(c[k]) / static_cast<float>(alpha)), 0L, 255L));
      if (!runs.empty() && runs.back().y == y && runs.back().x1 == x && runs.back().color == color)
        ++runs.back().x1;
      else
        runs.push_back({x, x + 1, y, color});
    }
  }
  return runs;
}

void blendRuns(RgbaImage& image, const std::vector<OverlayRun>& runs) {
  for (const OverlayRun& run : runs) {
    if (run.y < 0 || run.y >= image.height) continue;
    const float a = static_cast<float>(run.color.a) / 255.0f;
    for (int x = std::max(run.x0, 0); x < std::min(run.x1, image.width); ++x) {
      std::uint8_t* p = &image.pixels[4 * (static_cast<std::size_t>(run.y) * image.width + x)];
      for (int k = 0; k < 3; ++k)
        p[k] = static_cast<std::uint8_t>(std::lround(static_cast<float>(run.color[k]) * a +
                                                     static_cast<float>(p[k]) * (1.0f - a)));
    }
  }
}

bool AnnotationLayer::Key::operator==(const Key& other) const {
  const auto sameLegend = [](const std::optional<LegendSpec>& a,
                             const std::optional<LegendSpec>& b) {
    if (a.has_value() != b.has_value()) return false;
    return !a || (a->low == b->low && a->high == b->high && a->title == b->title);
  };
  return view == other.view && sameLegend(legend, other.legend) && dims == other.dims &&
         geometry == other.geometry;
}

const std::vector<OverlayRun>& AnnotationLayer::runs(const ViewParams& view,
                                                     const LegendSpec* legend, Dims dims,
                                                     const GridGeometry& geometry) {
  Key key{view, legend ? std::optional<LegendSpec>(*legend) : std::nullopt, dims, geometry};
  if (!view.axes) key.view.camera = {};  // an orbit moves nothing else of the annotation
  if (!key_ || !(*key_ == key)) {
    runs_ = annotationRuns(view, legend, dims, geometry);
    key_ = std::move(key);
  }
  return runs_;
}

}  // namespace lic3d::viewer
