// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Annotations drawn into finished pictures on the CPU: the colour legend (a colour bar with its
// value range), the title and the box's axes, so CLI images carry their own key.

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
#include "lic/font.h"

namespace lic3d {

// Black or white, whichever stands out from `background` (display RGB in [0, 1]): the ink of
// every annotation, in images and in the app.
glm::u8vec4 inkFor(glm::vec3 background, std::uint8_t alpha);

// The sizes of an annotation, all in proportion to its text's size (the em, in pixels), so that a
// picture made larger with its font (--scale) keeps its layout: lines, ticks and gaps grow with
// the text.
struct AnnotationStyle {
  float fontSize = 20.0f;
  float lineWidth = 1.0f;   // box edges, the legend's frame and tick marks: 1/20 em, at least 1
  float tickLength = 7.0f;  // 0.35 em
  // Between a tick mark's end and its label: half an em, five times the space between two
  // characters, so that a mark beside a value never reads as its minus sign.
  float tickGap = 10.0f;
  int margin = 10;  // around the legend and the title: half an em
};
// `fontSize` in pixels, or for 0 the automatic size of a picture `height` pixels high: 1/50 of it
// (20 px at 1024), at least 10.
AnnotationStyle annotationStyle(float fontSize, int height);

// A line of text an annotation drew: its line box (x0, y0, x1, y1: [x0,x1) x [y0,y1), pixels, y
// down) and the text.
struct PlacedText {
  glm::ivec4 box{0};
  std::string text;
};

struct LegendBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the colour bar's pixels: [x0,x1) x [y0,y1)
  std::vector<PlacedText> texts;       // the title and the tick labels
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
// y down; an absent part has width 0. `fontSize` as annotationStyle takes it (0: from `height`).
struct PictureLayout {
  glm::ivec4 picture{0};
  glm::ivec4 legend{0};
  glm::ivec4 title{0};
  AnnotationStyle style;
};
PictureLayout pictureLayout(int width, int height, const LegendSpec* legend, std::string_view title,
                            float fontSize = 0.0f);

// Draws the legend into layout.legend (a vertical colour bar, `high` at the top, labelled at
// round values, its tick marks on the bar's right edge, the title above it) and the title into
// layout.title, centred and 1.25 times the size of the other text. Text is white or black,
// whichever stands out from `background`; all of it inside the image, a text too wide for its
// place set smaller. The title's box, if drawn.
LegendBox drawLegend(RgbaImage& image, const PictureLayout& layout, const LegendSpec& legend,
                     glm::vec3 background);
std::vector<PlacedText> drawTitle(RgbaImage& image, const PictureLayout& layout,
                                  std::string_view title, glm::vec3 background);

// `picture` on a canvas with room for the legend and the title (pictureLayout of the canvas that
// holds the picture at its own size), both drawn; the picture itself unchanged.
// `fontSize` as annotationStyle takes it, the automatic size from the picture's height.
RgbaImage annotatedPicture(const RgbaImage& picture, const LegendSpec* legend,
                           std::string_view title, glm::vec3 background, float fontSize = 0.0f);

// The volume's box as the camera sees it: its edges in pixels (those behind the volume left out,
// so the box does not cross the data), its outline, and per axis an edge of the outline with ticks
// at round values of the physical coordinate and the axis' name at the edge's middle.
struct AxisTick {
  glm::vec2 at{0.0f};       // on the edge
  glm::vec2 outward{0.0f};  // unit screen normal of the edge, away from the box
  std::string text;
  int axis = 0;
};
struct AxisLabel {
  glm::vec2 at{0.0f};       // the middle of the labelled edge
  glm::vec2 outward{0.0f};  // as AxisTick's
  std::string text;
  bool leftOfBox = false;  // the edge is left of the box's centre: put the text to its left
  std::pair<glm::vec2, glm::vec2> edge;  // the labelled edge, from its low to its high end
  int axis = 0;
};
struct BoxAxes {
  glm::ivec4 area{0};  // the picture (x, y, width, height): nothing is drawn outside it
  std::vector<std::pair<glm::vec2, glm::vec2>> edges;
  std::vector<glm::vec2> outline;  // the convex hull of the box's corners on screen
  std::vector<AxisLabel> labels;
  std::vector<AxisTick> ticks;
};
// `camera` maps the box (centred at the origin, half extent `halfExtent`) to Vulkan clip space;
// the picture is `area` (x, y, width, height) of the image. An edge is behind the volume when
// both faces that meet at it face away from the camera. Edges behind the camera are left out.
// Ticks are about `tickSpacing` pixels apart (3.5 em of the annotation's text, as the picture
// scales), 2 to 6 per edge.
BoxAxes projectBoxAxes(const CameraMatrices& camera, bool orthographic, glm::vec3 halfExtent,
                       Dims dims, const GridGeometry& geometry, glm::ivec4 area,
                       float tickSpacing = 70.0f);
// Draws them into the image, light or dark to stand out from `background`, sized by `style`: each
// tick label beyond its mark, centred on the mark's line, left out where it would leave the image
// or cover another; each name beyond its edge's tick labels. The texts' boxes.
std::vector<PlacedText> drawBoxAxes(RgbaImage& image, const BoxAxes& axes, glm::vec3 background,
                                    const AnnotationStyle& style);

}  // namespace lic3d
