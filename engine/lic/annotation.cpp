// SPDX-License-Identifier: BSD-3-Clause
#include "lic/annotation.h"

#include "core/camera.h"
#include "core/slice_geometry.h"

namespace lic3d {

std::optional<LegendSpec> viewLegend(const ViewParams& view, const TransferFacts& facts,
                                     std::string_view colorName, std::string_view colorUnit) {
  if (!view.legend || view.color != ColorMode::Magnitude) return std::nullopt;
  const ColorRange range = colorRange(view, facts);
  return LegendSpec{[shown = shownView(view, facts)](float t) { return viewColor(shown, t); },
                    range.low, range.high, legendTitle(colorName, colorUnit)};
}

PictureLayout viewLayout(const ViewParams& view, const LegendSpec* legend) {
  const int width = view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width;
  return pictureLayout(width, view.height, legend, view.title);
}

void annotatePicture(RgbaImage& image, const ViewParams& view, const LegendSpec* legend, Dims dims,
                     const GridGeometry& geometry) {
  const PictureLayout layout = viewLayout(view, legend);
  if (legend) drawLegend(image, layout, *legend, view.background);
  drawTitle(image, layout, view.title, view.background);
  if (!view.axes || view.stereo == StereoMode::SideBySide) return;
  const glm::ivec4 area = layout.picture;
  // The camera of the mono frame the slices were drawn with (makeSliceFrame).
  const glm::vec3 halfExtent = boxHalfExtent(dims, geometry);
  const CameraMatrices camera = computeCamera(
      view.camera, halfExtent, static_cast<float>(area.z) / static_cast<float>(area.w));
  drawBoxAxes(image,
              projectBoxAxes(camera, view.camera.orthographic, halfExtent, dims, geometry, area),
              view.background);
}

}  // namespace lic3d
