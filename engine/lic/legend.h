#pragma once
// Annotations drawn into finished pictures on the CPU: text and the colour legend (a colour bar
// with its value range), so CLI images carry their own key.

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/colormap.h"
#include "core/rgba_image.h"
#include "core/volume.h"

namespace lic3d {

// Text in stb's easy font (about 6x12 pixels per character at scale 1), top-left at (x, y).
void drawText(RgbaImage& image, int x, int y, std::string_view text, glm::u8vec4 color, int scale);
int textWidth(std::string_view text, int scale);

struct LegendBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the colour bar's pixels: [x0,x1) x [y0,y1)
};

// A vertical colour bar at the right edge, `low` at the bottom and `high` at the top, labelled
// with the values and `title`. Text is white or black, whichever stands out from `background`.
LegendBox drawLegend(RgbaImage& image, Colormap map, float low, float high, std::string_view title,
                     glm::vec3 background);

// The volume's box as the camera sees it: 12 edges in pixels, and a label per axis at the middle
// of the outline edge that runs along it, e.g. "x 0 .. 2.35".
struct AxisLabel {
  glm::vec2 at{0.0f};  // the middle of the labelled edge
  std::string text;
  bool leftOfBox = false;  // the edge is left of the box's centre: put the text to its left
};
struct BoxAxes {
  std::vector<std::pair<glm::vec2, glm::vec2>> edges;
  std::vector<AxisLabel> labels;
};
// `viewProjection` maps the box (centred at the origin, half extent `halfExtent`) to Vulkan clip
// space; the picture is width x height pixels. Edges behind the camera are left out.
// `keepRightFree` (a legend is there) labels outline edges left of the box's centre.
BoxAxes projectBoxAxes(const glm::mat4& viewProjection, glm::vec3 halfExtent, Dims dims,
                       const GridGeometry& geometry, int width, int height,
                       bool keepRightFree = false);
// Draws them into the image, light or dark to stand out from `background`.
void drawBoxAxes(RgbaImage& image, const BoxAxes& axes, glm::vec3 background);

}  // namespace lic3d
