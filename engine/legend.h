#pragma once
// Annotations drawn into finished pictures on the CPU: text and the colour legend (a colour bar
// with its value range), so CLI images carry their own key.

#include <string_view>

#include <glm/vec4.hpp>

#include "colormap.h"
#include "rgba_image.h"

namespace lic3d {

// Text in stb's easy font (about 6x12 pixels per character at scale 1), top-left at (x, y).
void drawText(RgbaImage& image, int x, int y, std::string_view text, glm::u8vec4 color, int scale);
int textWidth(std::string_view text, int scale);

struct LegendBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the colour bar's pixels: [x0,x1) x [y0,y1)
};

// A vertical colour bar at the right edge, `low` at the bottom and `high` at the top, labelled
// with the values and `title`. Text is white or black, whichever stands out from `background`.
LegendBox drawLegend(RgbaImage& image, Colormap map, float low, float high,
                     std::string_view title, glm::vec3 background);

}  // namespace lic3d
