// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Annotations drawn into finished pictures on the CPU: text and the colour legend (a colour bar
// with its value range), so CLI images carry their own key.

#include <functional>
#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec4.hpp>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/camera.h"
#include "core/colormap.h"
#include "core/rgba_image.h"
#include "core/volume.h"

namespace lic3d {

// Black or white, whichever stands out from `background` (display RGB in [0, 1]): the ink of
// every annotation, in images and in the app.
glm::u8vec4 inkFor(glm::vec3 background, std::uint8_t alpha);

// Text in stb's easy font (about 6x12 pixels per character at scale 1), top-left at (x, y).
void drawText(RgbaImage& image, int x, int y, std::string_view text, glm::u8vec4 color, int scale);
int textWidth(std::string_view text, int scale);

struct LegendBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the colour bar's pixels: [x0,x1) x [y0,y1)
};

// What a colour legend shows: the colours over t in [0, 1] (the view's colour map or transfer
// function), the values at its ends, and what they are ("speed [m/s]").
struct LegendSpec {
  std::function<glm::vec3(float)> color;
  float low = 0.0f;
  float high = 1.0f;
  std::string title;
};

// The legend's title: the quantity, then its unit in brackets where one is known.
std::string legendTitle(std::string_view quantity, std::string_view unit);

// Up to about `count` round values (1, 2 or 5 times a power of ten apart) in [low, high]; the
// ends themselves when the range is empty.
std::vector<double> niceTicks(double low, double high, int count);

// Where the parts of an annotated picture of width x height go, so that no annotation lies over
// the data: the title in a band across the top, the legend in a column at the right (as wide as
// its labels need), the picture in what is left. Rectangles are x, y, width, height in pixels,
// y down; an absent part has width 0. `scale` is the text's pixel scale.
struct PictureLayout {
  glm::ivec4 picture{0};
  glm::ivec4 legend{0};
  glm::ivec4 title{0};
  int scale = 1;
};
PictureLayout pictureLayout(int width, int height, const LegendSpec* legend,
                            std::string_view title);

// Draws the legend into layout.legend (a vertical colour bar, `high` at the top, labelled at
// round values, the title above it) and the title into layout.title, centred. Text is white or
// black, whichever stands out from `background`; all of it inside the image.
LegendBox drawLegend(RgbaImage& image, const PictureLayout& layout, const LegendSpec& legend,
                     glm::vec3 background);
void drawTitle(RgbaImage& image, const PictureLayout& layout, std::string_view title,
               glm::vec3 background);

// `picture` on a canvas with room for the legend and the title (pictureLayout of the canvas that
// holds the picture at its own size), both drawn; the picture itself unchanged.
RgbaImage annotatedPicture(const RgbaImage& picture, const LegendSpec* legend,
                           std::string_view title, glm::vec3 background);

// The volume's box as the camera sees it: its edges in pixels (those behind the volume left out,
// so the box does not cross the data), and per axis an outline edge with ticks at round values of
// the physical coordinate and the axis' name.
struct AxisTick {
  glm::vec2 at{0.0f};       // on the edge
  glm::vec2 outward{0.0f};  // unit screen direction away from the box
  std::string text;
  int axis = 0;
};
struct AxisLabel {
  glm::vec2 at{0.0f};  // the end of the labelled edge
  std::string text;
  bool leftOfBox = false;  // the edge is left of the box's centre: put the text to its left
};
struct BoxAxes {
  std::vector<std::pair<glm::vec2, glm::vec2>> edges;
  std::vector<AxisLabel> labels;
  std::vector<AxisTick> ticks;
};
// `camera` maps the box (centred at the origin, half extent `halfExtent`) to Vulkan clip space;
// the picture is `area` (x, y, width, height) of the image. An edge is behind the volume when
// both faces that meet at it face away from the camera. Edges behind the camera are left out.
BoxAxes projectBoxAxes(const CameraMatrices& camera, bool orthographic, glm::vec3 halfExtent,
                       Dims dims, const GridGeometry& geometry, glm::ivec4 area);
// Draws them into the image, light or dark to stand out from `background`.
void drawBoxAxes(RgbaImage& image, const BoxAxes& axes, glm::vec3 background);

}  // namespace lic3d
