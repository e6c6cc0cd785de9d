// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The legend, the title and the box axes over the app's picture, drawn by the engine as `lic3d
// render` draws them (lic/annotation.h), so that a screenshot and the picture its session
// remakes have the same pixels. The engine draws into a finished picture; the app's picture is
// on the GPU, so the annotation becomes a layer of pixel runs, each a colour and a coverage,
// that Dear ImGui blends over the picture.

#include <cstdint>
#include <glm/vec4.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/rgba_image.h"
#include "core/view_params.h"
#include "core/volume.h"
#include "lic/legend.h"

namespace lic3d::viewer {

// Pixels [x0, x1) of row y, each blended as colour * a + beneath * (1 - a) with a = color.a / 255.
struct OverlayRun {
  int x0 = 0, x1 = 0, y = 0;
  glm::u8vec4 color{0};
  bool operator==(const OverlayRun&) const = default;
};

// The annotation of a picture of view.width x view.height (annotatePicture) as runs: drawn over
// any picture they give annotatePicture's pixels within a level. The engine blends each line and
// glyph in turn; together they are one affine map per pixel, read off by drawing onto black and
// onto white.
std::vector<OverlayRun> annotationRuns(const ViewParams& view, const LegendSpec* legend, Dims dims,
                                       const GridGeometry& geometry);

// Blends `runs` into `image` as the GPU does (8-bit colour and alpha, one rounding).
void blendRuns(RgbaImage& image, const std::vector<OverlayRun>& runs);

// annotationRuns, made again only when what they depend on changes.
class AnnotationLayer {
 public:
  const std::vector<OverlayRun>& runs(const ViewParams& view, const LegendSpec* legend, Dims dims,
                                      const GridGeometry& geometry);

 private:
  struct Key {
    ViewParams view;
    std::optional<LegendSpec> legend;  // its colours follow `view`
    Dims dims;
    GridGeometry geometry;
    bool operator==(const Key& other) const;
  };
  std::optional<Key> key_;
  std::vector<OverlayRun> runs_;
};

}  // namespace lic3d::viewer
