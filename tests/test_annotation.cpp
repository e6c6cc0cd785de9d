// SPDX-License-Identifier: BSD-3-Clause
// The text of pictures, measured on the CPU: where the legend, the title and the axes put their
// texts at small and poster sizes, the size and anti-aliasing of the glyphs, the room between a
// tick mark and its label, and which edge each axis name sits at.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/camera.h"
#include "core/slice_geometry.h"
#include "lic/annotation.h"
#include "lic/font.h"
#include "lic/legend.h"

namespace lic3d {
namespace {

RgbaImage blankImage(int width, int height) {
  RgbaImage image;
  image.width = width;
  image.height = height;
  image.pixels.assign(4 * static_cast<std::size_t>(width) * height, 0);
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;
  return image;
}

bool inked(const RgbaImage& image, int x, int y) {
  const glm::u8vec4 p = image.at(x, y);
  return p.r > 0 || p.g > 0 || p.b > 0;
}

bool overlap(const glm::ivec4& a, const glm::ivec4& b) {
  return a.x < b.z && b.x < a.z && a.y < b.w && b.y < a.w;
}

// Whether the rectangle [x0,x1) x [y0,y1) and the convex polygon share any area: a corner of
// one inside the other, or crossing edges.
bool rectangleMeetsPolygon(const glm::ivec4& r, const std::vector<glm::vec2>& polygon) {
  const glm::vec2 lo(r.x, r.y), hi(r.z, r.w);
  const auto insidePolygon = [&](glm::vec2 p) {
    float sign = 0.0f;
    for (std::size_t i = 0; i < polygon.size(); ++i) {
      const glm::vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
      const float c = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
      if (c * sign < 0.0f) return false;
      if (c != 0.0f) sign = c;
    }
    return true;
  };
  for (const glm::vec2 p : polygon)
    if (p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y) return true;
  for (const glm::vec2 c : {lo, hi, glm::vec2(lo.x, hi.y), glm::vec2(hi.x, lo.y)})
    if (insidePolygon(c)) return true;
  // An edge of the polygon crossing the rectangle: sampled finely along it.
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const glm::vec2 a = polygon[i], b = polygon[(i + 1) % polygon.size()];
    for (int k = 0; k <= 256; ++k) {
      const glm::vec2 p = a + (b - a) * (static_cast<float>(k) / 256.0f);
      if (p.x > lo.x && p.x < hi.x && p.y > lo.y && p.y < hi.y) return true;
    }
  }
  return false;
}

float distanceToSegment(glm::vec2 p, glm::vec2 a, glm::vec2 b) {
  const glm::vec2 d = b - a;
  const float t = glm::clamp(glm::dot(p - a, d) / std::max(glm::dot(d, d), 1e-12f), 0.0f, 1.0f);
  return glm::length(p - (a + t * d));
}

struct Annotated {
  ViewParams view;
  LegendSpec legend;
  RgbaImage image;
  std::vector<PlacedText> texts;
  PictureLayout layout;
  BoxAxes axes;
};

// A size x size picture of a 48^3 box (blank: only the annotation is drawn) with legend, title
// and axes, as `render` annotates it.
Annotated annotate(int size, float fontSize = 0.0f, float azimuth = -60.0f,
                   float elevation = 25.0f) {
  Annotated a;
  a.view.width = a.view.height = size;
  a.view.color = ColorMode::Magnitude;
  a.view.legend = true;
  a.view.axes = true;
  a.view.title = "Tornado";
  a.view.fontSize = fontSize;
  a.view.camera.azimuth = azimuth;
  a.view.camera.elevation = elevation;
  a.legend = {[](float t) { return glm::vec3(t, 0.5f, 1.0f - t); }, 0.0f, 0.3f, "speed [m/s]"};
  a.image = blankImage(size, size);
  const Dims dims{48, 48, 48};
  const GridGeometry geometry;
  a.texts = annotatePicture(a.image, a.view, &a.legend, dims, geometry);
  a.layout = viewLayout(a.view, &a.legend);
  const glm::ivec4 area = a.layout.picture;
  const glm::vec3 half = boxHalfExtent(dims, geometry);
  a.axes = projectBoxAxes(
      computeCamera(a.view.camera, half, static_cast<float>(area.z) / static_cast<float>(area.w)),
      false, half, dims, geometry, area, 3.5f * a.layout.style.fontSize);
  return a;
}

bool isAxisName(const std::string& text) { return text == "x" || text == "y" || text == "z"; }

// The legend's and the title's texts lie beside the picture, the axes' beside the box's outline;
// none leaves the image or covers another, and each box holds ink.
TEST(Annotation, TextBoxesStayInsideTheImageAndApartAtSmallAndPosterSizes) {
  for (const int size : {512, 4096}) {
    SCOPED_TRACE(size);
    const Annotated a = annotate(size);
    int legendTexts = 0, names = 0, tickLabels = 0;
    for (std::size_t i = 0; i < a.texts.size(); ++i) {
      const PlacedText& t = a.texts[i];
      SCOPED_TRACE(t.text);
      EXPECT_GE(t.box.x, 0);
      EXPECT_GE(t.box.y, 0);
      EXPECT_LE(t.box.z, size);
      EXPECT_LE(t.box.w, size);
      for (std::size_t j = i + 1; j < a.texts.size(); ++j)
        EXPECT_FALSE(overlap(t.box, a.texts[j].box)) << "covers " << a.texts[j].text;
      const bool fromAxes = overlap(t.box, a.layout.picture);
      if (fromAxes) {
        EXPECT_FALSE(rectangleMeetsPolygon(t.box, a.axes.outline)) << "over the volume's box";
        (isAxisName(t.text) ? names : tickLabels) += 1;
      } else {
        ++legendTexts;
      }
      bool ink = false;
      for (int y = t.box.y; y < t.box.w && !ink; ++y)
        for (int x = t.box.x; x < t.box.z && !ink; ++x) ink = inked(a.image, x, y);
      EXPECT_TRUE(ink) << "an empty text box";
    }
    EXPECT_GE(legendTexts, 4);  // the title, the legend's title and at least two labels
    EXPECT_EQ(names, 3);
    EXPECT_GE(tickLabels, 6);
  }
}

// The rows the title's glyphs ink, in the title's band.
int titleInkRows(const Annotated& a) {
  int first = -1, last = -1;
  for (int y = a.layout.title.y; y < a.layout.title.y + a.layout.title.w; ++y)
    for (int x = 0; x < a.image.width; ++x)
      if (inked(a.image, x, y)) {
        if (first < 0) first = y;
        last = y;
        break;
      }
  return first < 0 ? 0 : last - first + 1;
}

TEST(Annotation, ABiggerFontSizeGivesTallerText) {
  const int small = titleInkRows(annotate(512, 12.0f));
  const int large = titleInkRows(annotate(512, 24.0f));
  EXPECT_GT(small, 5);
  EXPECT_GT(large, small * 3 / 2) << small << " rows at 12 px, " << large << " at 24 px";
  // The automatic size follows the picture's height: a poster's text is as tall for its size.
  EXPECT_GT(titleInkRows(annotate(2048)), titleInkRows(annotate(512)) * 3);
}

// Glyph edges are blended by coverage: many inked pixels lie between the background and the ink.
TEST(Annotation, TextIsAntiAliased) {
  RgbaImage image = blankImage(200, 60);
  drawText(image, 4, 4, "0.008 speed [m/s]", glm::u8vec4(255), 20.0f);
  int full = 0, partial = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const int v = image.at(x, y).r;
      full += v == 255;
      partial += v > 0 && v < 255;
    }
  EXPECT_GT(full, 50);
  EXPECT_GT(partial, full / 4) << full << " full, " << partial << " partial pixels";
}

// Left of a value on its rows, within 0.4 em, there is no ink but other text: no tick mark sits
// where it would read as a minus sign. In the legend (ticks on the bar's right edge) and on the
// axes (where an edge's labels lie right of their ticks).
TEST(Annotation, NoTickMarkSitsJustLeftOfALabel) {
  for (const float azimuth : {-60.0f, 30.0f, 120.0f}) {
    SCOPED_TRACE(azimuth);
    const Annotated a = annotate(1024, 0.0f, azimuth);
    const int gap = static_cast<int>(0.4f * a.layout.style.fontSize);
    const auto inText = [&](int x, int y) {
      return std::any_of(a.texts.begin(), a.texts.end(), [&](const PlacedText& t) {
        return x >= t.box.x && x < t.box.z && y >= t.box.y && y < t.box.w;
      });
    };
    int checkedRows = 0;
    for (const PlacedText& t : a.texts) {
      if (t.text.empty() ||
          !(std::isdigit(static_cast<unsigned char>(t.text[0])) || t.text[0] == '-'))
        continue;
      for (int y = t.box.y; y < t.box.w; ++y) {
        int left = -1;
        for (int x = t.box.x; x < t.box.z && left < 0; ++x)
          if (inked(a.image, x, y)) left = x;
        if (left < 0) continue;
        ++checkedRows;
        for (int x = left - 1; x >= std::max(0, left - gap); --x)
          if (inked(a.image, x, y) && !inText(x, y)) {
            ADD_FAILURE() << "ink " << left - x << " px left of '" << t.text << "' at row " << y;
            break;
          }
      }
    }
    EXPECT_GT(checkedRows, 100);
  }
}

// Each axis name sits at its own labelled edge: nearer it than the other axes' labelled edges,
// whichever way the box is seen, so two names never share a corner.
TEST(Annotation, EachAxisNameIsNearestItsOwnEdge) {
  for (const float azimuth : {-60.0f, 30.0f, 120.0f, 210.0f})
    for (const float elevation : {25.0f, -20.0f, 60.0f}) {
      SCOPED_TRACE(testing::Message() << azimuth << ", " << elevation);
      const Annotated a = annotate(1024, 0.0f, azimuth, elevation);
      ASSERT_EQ(a.axes.labels.size(), 3u);
      for (const AxisLabel& label : a.axes.labels) {
        const auto drawn = std::find_if(a.texts.begin(), a.texts.end(),
                                        [&](const PlacedText& t) { return t.text == label.text; });
        ASSERT_NE(drawn, a.texts.end()) << label.text;
        const glm::vec2 centre =
            0.5f * glm::vec2(drawn->box.x + drawn->box.z, drawn->box.y + drawn->box.w);
        const float own = distanceToSegment(centre, label.edge.first, label.edge.second);
        for (const AxisLabel& other : a.axes.labels) {
          if (other.axis == label.axis) continue;
          EXPECT_LT(own, distanceToSegment(centre, other.edge.first, other.edge.second))
              << label.text << " is nearer the " << other.text << " edge";
        }
      }
    }
}

}  // namespace
}  // namespace lic3d
