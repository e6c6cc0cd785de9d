// SPDX-License-Identifier: BSD-3-Clause
#include "lic/annotation.h"

#include "core/camera.h"
#include "core/slice_geometry.h"

namespace lic3d {

std::string viewLegendTitle(const ViewParams& view, std::string_view quantity,
                            std::string_view unit) {
  return view.legendTitle.empty() ? legendTitle(quantity, unit) : view.legendTitle;
}

std::optional<LegendSpec> viewLegend(const ViewParams& view, const TransferFacts& facts,
                                     std::string_view colorName, std::string_view colorUnit) {
  if (!view.legend || view.color != ColorMode::Magnitude) return std::nullopt;
  const ColorRange range = colorRange(view, facts);
  return LegendSpec{[shown = shownView(view, facts)](float t) { return viewColor(shown, t); },
                    range.low, range.high, viewLegendTitle(view, colorName, colorUnit)};
}

PictureLayout viewLayout(const ViewParams& view, const LegendSpec* legend) {
  const int width = view.stereo == StereoMode::SideBySide ? 2 * view.width : view.width;
  return pictureLayout(width, view.height, legend, view.title, view.fontSize);
}

std::vector<PlacedText> annotatePicture(RgbaImage& image, const ViewParams& view,
                                        const LegendSpec* legend, Dims dims,
                                        const GridGeometry& geometry) {
  const PictureLayout layout = viewLayout(view, legend);
  std::vector<PlacedText> texts;
  if (legend) texts = drawLegend(image, layout, *legend, view.background).texts;
  for (PlacedText& t : drawTitle(image, layout, view.title, view.background))
    texts.push_back(std::move(t));
  if (!view.axes || view.stereo == StereoMode::SideBySide) return texts;
  const glm::ivec4 area = layout.picture;
  // The camera of the mono frame the slices were drawn with (makeSliceFrame).
  const glm::vec3 halfExtent = boxHalfExtent(dims, geometry);
  const CameraMatrices camera = computeCamera(
      view.camera, halfExtent, static_cast<float>(area.z) / static_cast<float>(area.w));
  for (PlacedText& t :
       drawBoxAxes(image,
                   projectBoxAxes(camera, view.camera.orthographic, halfExtent, dims, geometry,
                                  area, 3.5f * layout.style.fontSize),
                   view.background, layout.style))
    texts.push_back(std::move(t));
  return texts;
}

}  // namespace lic3d
