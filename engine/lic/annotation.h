// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What a rendered picture carries besides the volume, drawn on the CPU into the finished frame:
// the colour legend, the title and the volume's box with its axes, laid out as the view asks.

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/rgba_image.h"
#include "core/view_params.h"
#include "core/volume.h"
#include "lic/legend.h"

namespace lic3d {

// The legend's title: the view's legendTitle where given, else the quantity and its unit
// ("speed [m/s]").
std::string viewLegendTitle(const ViewParams& view, std::string_view quantity,
                            std::string_view unit);

// The legend of `view` (colour by magnitude and a legend asked for) over the colour range the
// view takes from `facts`; `colorName` and `colorUnit` name what the colour shows.
std::optional<LegendSpec> viewLegend(const ViewParams& view, const TransferFacts& facts,
                                     std::string_view colorName, std::string_view colorUnit);

// Where the volume, the legend and the title go in a picture of the view's size (twice as wide
// for side-by-side stereo), with text of the view's font size.
PictureLayout viewLayout(const ViewParams& view, const LegendSpec* legend);

// Draws the legend (if any), the title and, where asked and not side by side, the box axes of a
// volume of `dims` and `geometry` into `image`, the frame rendered with viewLayout's picture.
// The boxes of the texts drawn.
std::vector<PlacedText> annotatePicture(RgbaImage& image, const ViewParams& view,
                                        const LegendSpec* legend, Dims dims,
                                        const GridGeometry& geometry);

}  // namespace lic3d
