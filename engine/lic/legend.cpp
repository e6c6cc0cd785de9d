// SPDX-License-Identifier: BSD-3-Clause
#include "lic/legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <glm/geometric.hpp>
#include <string>
#include <vector>

namespace lic3d {
namespace {

// Blends `color` over [x0,x1) x [y0,y1), cut to the image.
void fillRect(RgbaImage& image, int x0, int y0, int x1, int y1, glm::u8vec4 color) {
  x0 = std::clamp(x0, 0, image.width);
  x1 = std::clamp(x1, 0, image.width);
  y0 = std::clamp(y0, 0, image.height);
  y1 = std::clamp(y1, 0, image.height);
  const float a = color.a / 255.0f;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      std::uint8_t* p = &image.pixels[4 * (static_cast<std::size_t>(y) * image.width + x)];
      for (int k = 0; k < 3; ++k)
        p[k] = static_cast<std::uint8_t>(color[k] * a + p[k] * (1.0f - a) + 0.5f);
    }
}

// A line `width` pixels wide from a to b with round ends, anti-aliased: each pixel covered by the
// part of its square within width / 2 of the segment (to a pixel's accuracy). Only the pixels
// near the line are visited, column by column or row by row along its longer direction.
void drawLine(RgbaImage& image, glm::vec2 a, glm::vec2 b, float width, glm::u8vec4 color) {
  const bool steep = std::abs(b.y - a.y) > std::abs(b.x - a.x);
  const int major = steep ? 1 : 0, minor = 1 - major;
  if (a[major] > b[major]) std::swap(a, b);
  const glm::vec2 d = b - a;
  const float length2 = glm::dot(d, d);
  const float reach = 0.5f * width + 1.0f;
  // Across the line, the band of pixels within `reach` of it is reach / cos wide.
  const float across = reach * std::sqrt(length2) / std::max(std::abs(d[major]), 1e-6f);
  const int extent[2] = {image.width, image.height};
  const int m0 = std::max(0, static_cast<int>(std::floor(a[major] - reach)));
  const int m1 = std::min(extent[major], static_cast<int>(std::ceil(b[major] + reach)));
  for (int m = m0; m < m1; ++m) {
    const float at = static_cast<float>(m) + 0.5f;
    const float t =
        std::abs(d[major]) > 1e-6f ? std::clamp((at - a[major]) / d[major], 0.0f, 1.0f) : 0.0f;
    const float centre = a[minor] + t * d[minor];
    const int n0 = std::max(0, static_cast<int>(std::floor(centre - across - reach)));
    const int n1 = std::min(extent[minor], static_cast<int>(std::ceil(centre + across + reach)));
    for (int n = n0; n < n1; ++n) {
      glm::vec2 p;
      p[major] = at;
      p[minor] = static_cast<float>(n) + 0.5f;
      const float s = length2 > 0.0f ? std::clamp(glm::dot(p - a, d) / length2, 0.0f, 1.0f) : 0.0f;
      const float coverage =
          std::clamp(0.5f * width + 0.5f - glm::length(p - (a + s * d)), 0.0f, 1.0f);
      if (coverage <= 0.0f) continue;
      const int x = steep ? n : m, y = steep ? m : n;
      fillRect(image, x, y, x + 1, y + 1,
               glm::u8vec4(color.r, color.g, color.b,
                           static_cast<std::uint8_t>(color.a * coverage + 0.5f)));
    }
  }
}

std::string formatValue(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", static_cast<double>(v));
  return text;
}

// The size at which `text` fits `width` pixels: `size`, or smaller.
float fittedSize(std::string_view text, float size, int width) {
  const int needed = measureText(text, size).width;
  return needed <= width || needed == 0
             ? size
             : std::max(1.0f, size * static_cast<float>(width) / static_cast<float>(needed));
}

// The top of a line box whose digits are centred on row `y`: DejaVu Sans's digits are 0.73 em
// high on the baseline.
int topForCentre(float y, const TextExtent& extent, float size) {
  return static_cast<int>(std::lround(y - static_cast<float>(extent.ascent) + 0.365f * size));
}

bool overlaps(const glm::ivec4& a, const glm::ivec4& b) {
  return a.x < b.z && b.x < a.z && a.y < b.w && b.y < a.w;
}

}  // namespace

AnnotationStyle annotationStyle(float fontSize, int height) {
  AnnotationStyle style;
  style.fontSize =
      fontSize > 0.0f ? fontSize : std::max(10.0f, std::round(static_cast<float>(height) / 50.0f));
  const float em = style.fontSize;
  style.lineWidth = std::max(1.0f, em / 20.0f);
  style.tickLength = 0.35f * em;
  style.tickGap = 0.5f * em;
  style.margin = static_cast<int>(std::lround(0.5f * em));
  return style;
}

glm::u8vec4 inkFor(glm::vec3 background, std::uint8_t alpha) {
  const float luminance = 0.2126f * background.r + 0.7152f * background.g + 0.0722f * background.b;
  return luminance > 0.5f ? glm::u8vec4(0, 0, 0, alpha) : glm::u8vec4(255, 255, 255, alpha);
}

std::string legendTitle(std::string_view quantity, std::string_view unit) {
  std::string title(quantity);
  if (!unit.empty()) title += " [" + std::string(unit) + "]";
  return title;
}

std::vector<double> niceTicks(double low, double high, int count) {
  if (!(high > low) || !std::isfinite(low) || !std::isfinite(high)) return {low};
  // Of the steps 1, 2 and 5 times a power of ten around (high - low) / count, the one whose
  // ticks come closest to `count`, with at least two where any step gives two.
  const double base = std::floor(std::log10((high - low) / std::max(count, 1)));
  std::vector<double> best;
  for (double exponent = base - 1.0; exponent <= base + 1.0; exponent += 1.0)
    for (const double multiple : {1.0, 2.0, 5.0}) {
      const double step = multiple * std::pow(10.0, exponent);
      // k * multiple is a whole number; dividing by 10^-exponent (exact for the usual
      // exponents) gives 0.6 where 6 * 0.1 would give 0.6000000000000001.
      const auto value = [&](double k) {
        return exponent < 0.0 ? k * multiple / std::pow(10.0, -exponent) : k * step;
      };
      std::vector<double> ticks;
      for (double k = std::ceil(low / step - 1e-9); value(k) <= high + 1e-9 * step; k += 1.0) {
        ticks.push_back(k == 0.0 ? 0.0 : value(k));
        if (ticks.size() > 64) break;
      }
      const auto cost = [&](const std::vector<double>& t) {
        const int n = static_cast<int>(t.size());
        return (n < 2 ? 1000 : 0) + std::abs(n - count) + (n > count ? 1 : 0);
      };
      if (best.empty() || cost(ticks) < cost(best)) best = std::move(ticks);
    }
  return best;
}

namespace {

constexpr float kTitleScale = 1.25f;  // the picture's title against the other text

// The legend's geometry in a column of `height` pixels, shared by the layout (its width) and the
// drawing: from the column's left, a margin, the bar (an em wide), the tick marks, the gap and the
// labels; the title above, smaller where it is wider than `maxWidth` allows.
struct LegendMetrics {
  int bar = 0;
  int labelsX = 0;  // where the labels start, from the column's left
  int width = 0;
  int titleTop = 0, barTop = 0, barBottom = 0;  // from the column's top
  float titleSize = 0.0f;
  std::vector<double> ticks;
};

LegendMetrics legendMetrics(const LegendSpec& legend, const AnnotationStyle& style, int height,
                            int maxWidth) {
  LegendMetrics m;
  const float em = style.fontSize;
  const int line = measureText("0", em).height;
  m.bar = static_cast<int>(std::lround(em));
  m.labelsX =
      style.margin + m.bar + static_cast<int>(std::lround(style.tickLength + style.tickGap));
  const int room = std::max(height / 10, style.margin);
  m.titleTop = room;
  m.titleSize = em;
  const int titleWidth = legend.title.empty() ? 0 : measureText(legend.title, em).width;
  const int titleHeight = legend.title.empty() ? 0 : measureText(legend.title, em).height;
  m.barTop = m.titleTop + titleHeight + static_cast<int>(std::lround(0.85f * em));
  m.barBottom = height - room - static_cast<int>(std::lround(0.65f * em));
  // Labels at least 1.6 lines apart where the bar is long enough for two.
  const int count = std::clamp((m.barBottom - m.barTop) * 10 / (16 * std::max(line, 1)) + 1, 2, 6);
  m.ticks = niceTicks(legend.low, legend.high, count);
  int labels = 0;
  for (const double t : m.ticks)
    labels = std::max(labels, measureText(formatValue(static_cast<float>(t)), em).width);
  m.width =
      std::min(maxWidth, std::max(m.labelsX + labels, titleWidth + style.margin) + style.margin);
  m.titleSize = fittedSize(legend.title, em, m.width - 2 * style.margin);
  return m;
}

int titleBand(std::string_view title, const AnnotationStyle& style, int height) {
  if (title.empty()) return 0;
  const float size = kTitleScale * style.fontSize;
  return std::min(height / 4,
                  measureText(title, size).height + static_cast<int>(std::lround(style.fontSize)));
}

}  // namespace

PictureLayout pictureLayout(int width, int height, const LegendSpec* legend, std::string_view title,
                            float fontSize) {
  PictureLayout layout;
  layout.style = annotationStyle(fontSize, height);
  const int top = titleBand(title, layout.style, height);
  if (top > 0) layout.title = {0, 0, width, top};
  int right = 0;
  if (legend) {
    right = legendMetrics(*legend, layout.style, height - top, width / 2).width;
    layout.legend = {width - right, top, right, height - top};
  }
  layout.picture = {0, top, std::max(width - right, 1), std::max(height - top, 1)};
  return layout;
}

LegendBox drawLegend(RgbaImage& image, const PictureLayout& layout, const LegendSpec& legend,
                     glm::vec3 background) {
  const AnnotationStyle& style = layout.style;
  const float em = style.fontSize;
  const glm::u8vec4 ink = inkFor(background, 255);
  const glm::ivec4 area = layout.legend;
  const LegendMetrics m = legendMetrics(legend, style, area.w, area.z);
  LegendBox box;
  box.x0 = area.x + style.margin;
  box.x1 = box.x0 + m.bar;
  box.y0 = area.y + m.barTop;
  box.y1 = area.y + m.barBottom;
  if (box.y1 - box.y0 < 8) return box;

  for (int y = box.y0; y < box.y1; ++y) {
    const float t = 1.0f - static_cast<float>(y - box.y0) / static_cast<float>(box.y1 - box.y0 - 1);
    const glm::vec3 c = glm::clamp(legend.color(t), 0.0f, 1.0f);
    fillRect(image, box.x0, y, box.x1, y + 1, glm::u8vec4(glm::vec3(c * 255.0f + 0.5f), 255));
  }
  // A frame in the text colour keeps the bar readable on any background.
  const int line = static_cast<int>(std::lround(style.lineWidth));
  fillRect(image, box.x0 - line, box.y0 - line, box.x1 + line, box.y0, ink);
  fillRect(image, box.x0 - line, box.y1, box.x1 + line, box.y1 + line, ink);
  fillRect(image, box.x0 - line, box.y0, box.x0, box.y1, ink);
  fillRect(image, box.x1, box.y0, box.x1 + line, box.y1, ink);

  // Tick marks out of the bar's right edge, joined to its frame, and the labels half an em
  // beyond their ends.
  const double span = legend.high - legend.low;
  const int tickEnd = box.x1 + line + static_cast<int>(std::lround(style.tickLength));
  for (const double tick : m.ticks) {
    const double t = span > 0.0 ? (tick - legend.low) / span : 0.5;
    const float y = static_cast<float>(box.y1) - 0.5f -
                    static_cast<float>(t) * static_cast<float>(box.y1 - box.y0 - 1);
    const std::string text = formatValue(static_cast<float>(tick));
    const TextExtent extent = measureText(text, em);
    const int x = area.x + m.labelsX + line;
    const int top = topForCentre(y, extent, em);
    const glm::ivec4 placed{x, top, x + extent.width, top + extent.height};
    if (!box.texts.empty() && overlaps(placed, box.texts.back().box)) continue;
    const int row = static_cast<int>(std::floor(y + 0.5f - 0.5f * static_cast<float>(line)));
    fillRect(image, box.x1, row, tickEnd, row + line, ink);
    drawText(image, x, top, text, ink, em);
    box.texts.push_back({placed, text});
  }
  if (!legend.title.empty()) {
    const TextExtent extent = measureText(legend.title, m.titleSize);
    const int x = area.x + style.margin, y = area.y + m.titleTop;
    drawText(image, x, y, legend.title, ink, m.titleSize);
    box.texts.push_back({{x, y, x + extent.width, y + extent.height}, legend.title});
  }
  return box;
}

std::vector<PlacedText> drawTitle(RgbaImage& image, const PictureLayout& layout,
                                  std::string_view title, glm::vec3 background) {
  if (title.empty() || layout.title.z == 0) return {};
  const AnnotationStyle& style = layout.style;
  const float size =
      fittedSize(title, kTitleScale * style.fontSize, layout.title.z - 2 * style.margin);
  const TextExtent extent = measureText(title, size);
  const int x =
      std::max(layout.title.x + style.margin, layout.title.x + (layout.title.z - extent.width) / 2);
  const int y = layout.title.y + (layout.title.w - extent.height) / 2;
  drawText(image, x, y, title, inkFor(background, 255), size);
  return {{{x, y, x + extent.width, y + extent.height}, std::string(title)}};
}

RgbaImage annotatedPicture(const RgbaImage& picture, const LegendSpec* legend,
                           std::string_view title, glm::vec3 background, float fontSize) {
  if (!legend && title.empty()) return picture;
  // The text's size from the picture's height, which the canvas then grows around: by the
  // legend's column and the title's band.
  const float size = annotationStyle(fontSize, picture.height).fontSize;
  const PictureLayout probe = pictureLayout(picture.width * 2, picture.height, legend, title, size);
  const int height = picture.height + probe.title.w;
  const PictureLayout sized = pictureLayout(picture.width * 2, height, legend, title, size);
  const int width = picture.width + sized.legend.z;
  const PictureLayout layout = pictureLayout(width, height, legend, title, size);
  RgbaImage canvas;
  canvas.width = width;
  canvas.height = height;
  canvas.pixels.resize(static_cast<std::size_t>(width) * height * 4);
  const glm::u8vec4 fill(glm::vec3(glm::clamp(background, 0.0f, 1.0f) * 255.0f + 0.5f), 255);
  for (std::size_t i = 0; i < canvas.pixels.size(); i += 4)
    for (int k = 0; k < 4; ++k) canvas.pixels[i + static_cast<std::size_t>(k)] = fill[k];
  for (int y = 0; y < picture.height && layout.picture.y + y < height; ++y)
    std::copy_n(&picture.pixels[4 * static_cast<std::size_t>(y) * picture.width],
                4 * static_cast<std::size_t>(std::min(picture.width, width)),
                &canvas.pixels[4 * (static_cast<std::size_t>(layout.picture.y + y) * width)]);
  if (legend) drawLegend(canvas, layout, *legend, background);
  drawTitle(canvas, layout, title, background);
  return canvas;
}

namespace {

// The convex hull of `points`, counter-clockwise in y-down pixels (Andrew's monotone chain).
std::vector<glm::vec2> convexHull(std::vector<glm::vec2> points) {
  std::sort(points.begin(), points.end(),
            [](glm::vec2 a, glm::vec2 b) { return a.x < b.x || (a.x == b.x && a.y < b.y); });
  const auto cross = [](glm::vec2 o, glm::vec2 a, glm::vec2 b) {
    return (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x);
  };
  std::vector<glm::vec2> hull(2 * points.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    while (k >= 2 && cross(hull[k - 2], hull[k - 1], points[i]) <= 0.0f) --k;
    hull[k++] = points[i];
  }
  for (std::size_t i = points.size(), lower = k + 1; i-- > 1;) {
    while (k >= lower && cross(hull[k - 2], hull[k - 1], points[i - 1]) <= 0.0f) --k;
    hull[k++] = points[i - 1];
  }
  hull.resize(k > 1 ? k - 1 : k);
  return hull;
}

}  // namespace

BoxAxes projectBoxAxes(const CameraMatrices& camera, bool orthographic, glm::vec3 halfExtent,
                       Dims dims, const GridGeometry& geometry, glm::ivec4 area,
                       float tickSpacing) {
  BoxAxes axes;
  axes.area = area;
  auto corner = [&](int i) {
    return glm::vec3(i & 1 ? halfExtent.x : -halfExtent.x, i & 2 ? halfExtent.y : -halfExtent.y,
                     i & 4 ? halfExtent.z : -halfExtent.z);
  };
  // Pixels of a world point; false behind the camera.
  auto project = [&](glm::vec3 p, glm::vec2& pixel) {
    const glm::vec4 clip = camera.viewProjection * glm::vec4(p, 1.0f);
    if (clip.w <= 1e-6f) return false;
    pixel = glm::vec2(
        static_cast<float>(area.x) + (clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(area.z),
        static_cast<float>(area.y) + (clip.y / clip.w * 0.5f + 0.5f) * static_cast<float>(area.w));
    return true;
  };
  // Whether the face with outward normal `normal` (an axis, signed) faces the camera.
  auto facesCamera = [&](int axis, float side) {
    glm::vec3 normal(0.0f), centre(0.0f);
    normal[axis] = side;
    centre[axis] = side * halfExtent[axis];
    const glm::vec3 toEye = orthographic ? camera.toViewer : camera.eye - centre;
    return glm::dot(normal, toEye) > 0.0f;
  };
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis) {
      const int j = i | (1 << axis);
      if (j == i) continue;
      // The edge along `axis` lies on one face of each of the other two axes.
      const int a1 = (axis + 1) % 3, a2 = (axis + 2) % 3;
      const bool front = facesCamera(a1, i & (1 << a1) ? 1.0f : -1.0f) ||
                         facesCamera(a2, i & (1 << a2) ? 1.0f : -1.0f);
      glm::vec2 a, b;
      if (front && project(corner(i), a) && project(corner(j), b)) axes.edges.push_back({a, b});
    }
  std::vector<glm::vec2> corners;
  for (int i = 0; i < 8; ++i) {
    glm::vec2 p;
    if (!project(corner(i), p)) return axes;  // the camera inside the box's reach: no axes
    corners.push_back(p);
  }
  axes.outline = convexHull(corners);
  const char* names[3] = {"x", "y", "z"};
  glm::vec2 centre;
  if (!project(glm::vec3(0.0f), centre)) return axes;
  // Whether every corner lies on one side of the line through a and b: an edge of the outline.
  const auto onOutline = [&](glm::vec2 a, glm::vec2 b) {
    const glm::vec2 d = b - a;
    if (glm::length(d) < 1e-3f) return false;
    const glm::vec2 normal = glm::normalize(glm::vec2(-d.y, d.x));
    float low = 0.0f, high = 0.0f;
    for (const glm::vec2 p : corners) {
      low = std::min(low, glm::dot(p - a, normal));
      high = std::max(high, glm::dot(p - a, normal));
    }
    return low > -0.5f || high < 0.5f;
  };
  for (int axis = 0; axis < 3; ++axis) {
    // Of the four edges along this axis, label one on the outline, so the text sits beside the
    // volume rather than over it; of those, the one farthest from the centre, bottom and left
    // winning (the usual place of axes).
    bool found = false, foundOnOutline = false;
    glm::vec3 bestLow{0.0f}, bestHigh{0.0f};
    float bestScore = 0.0f;
    for (int k = 0; k < 4; ++k) {
      glm::vec3 low =
          corner((k & 1 ? 1 : 0) << ((axis + 1) % 3) | (k & 2 ? 1 : 0) << ((axis + 2) % 3));
      glm::vec3 high = low;
      low[axis] = -halfExtent[axis];
      high[axis] = halfExtent[axis];
      glm::vec2 at, a, b;
      if (!project(0.5f * (low + high), at) || !project(low, a) || !project(high, b)) continue;
      const bool outline = onOutline(a, b);
      const float score =
          glm::length(at - centre) + 0.25f * (at.y - centre.y) - 0.25f * (at.x - centre.x);
      if (!found || (outline && !foundOnOutline) ||
          (outline == foundOnOutline && score > bestScore)) {
        bestScore = score;
        bestLow = low;
        bestHigh = high;
        foundOnOutline = outline;
      }
      found = true;
    }
    glm::vec2 a, b, middle;
    if (!found || !project(bestLow, a) || !project(bestHigh, b) ||
        !project(0.5f * (bestLow + bestHigh), middle))
      continue;
    // The edge's normal on screen, away from the box.
    const glm::vec2 d = b - a;
    glm::vec2 outward =
        glm::length(d) > 1e-3f ? glm::normalize(glm::vec2(-d.y, d.x)) : glm::vec2(0.0f, 1.0f);
    if (glm::dot(outward, middle - centre) < 0.0f) outward = -outward;
    const double first = geometry.origin[axis];
    const double last = first + geometry.spacing[axis] * (dims[axis] - 1);
    const float pixels = glm::length(b - a);
    const int count = std::clamp(static_cast<int>(pixels / std::max(tickSpacing, 1.0f)), 2, 6);
    for (const double value : niceTicks(first, last, count)) {
      const float t = last > first ? static_cast<float>((value - first) / (last - first)) : 0.5f;
      axes.ticks.push_back(
          {a + t * (b - a), outward, formatValue(static_cast<float>(value)), axis});
    }
    // The name at the edge's middle (drawn beyond its tick labels): labelled edges often meet at
    // their ends, where two names would share a corner.
    axes.labels.push_back({middle, outward, names[axis], outward.x < 0.0f, {a, b}, axis});
  }
  return axes;
}

std::vector<PlacedText> drawBoxAxes(RgbaImage& image, const BoxAxes& axes, glm::vec3 background,
                                    const AnnotationStyle& style) {
  const float em = style.fontSize;
  const glm::u8vec4 line = inkFor(background, 160);
  // The box reaches beyond the picture when the camera is close: its edges are cut at the
  // picture's border (Liang-Barsky), so they never cross the legend's column or the title.
  const glm::vec2 areaLow(axes.area.x, axes.area.y);
  const glm::vec2 areaHigh = areaLow + glm::vec2(axes.area.z, axes.area.w);
  for (const auto& [a, b] : axes.edges) {
    const glm::vec2 d = b - a;
    float t0 = 0.0f, t1 = 1.0f;
    bool visible = true;
    const auto clip = [&](float p, float q) {  // keep where p t <= q
      if (p == 0.0f) {
        visible = visible && q >= 0.0f;
      } else if (p < 0.0f) {
        t0 = std::max(t0, q / p);
      } else {
        t1 = std::min(t1, q / p);
      }
    };
    clip(-d.x, a.x - areaLow.x);
    clip(d.x, areaHigh.x - a.x);
    clip(-d.y, a.y - areaLow.y);
    clip(d.y, areaHigh.y - a.y);
    if (visible && t0 < t1) drawLine(image, a + t0 * d, a + t1 * d, style.lineWidth, line);
  }
  const glm::u8vec4 ink = inkFor(background, 255);
  std::vector<PlacedText> placed;
  // The box of a text centred on the line from `at` along `outward`, `distance` from `at` to
  // its nearest side.
  const auto boxBeyond = [](glm::vec2 at, glm::vec2 outward, float distance, TextExtent extent) {
    const glm::vec2 size(static_cast<float>(extent.width), static_cast<float>(extent.height));
    const float half = 0.5f * (std::abs(outward.x) * size.x + std::abs(outward.y) * size.y);
    const glm::vec2 low = at + (distance + half) * outward - 0.5f * size;
    const int x = static_cast<int>(std::lround(low.x)), y = static_cast<int>(std::lround(low.y));
    return glm::ivec4(x, y, x + extent.width, y + extent.height);
  };
  const auto inside = [&](const glm::ivec4& r) {
    return r.x >= std::max(1, axes.area.x) && r.y >= std::max(1, axes.area.y) &&
           r.z <= std::min(image.width - 1, axes.area.x + axes.area.z) &&
           r.w <= std::min(image.height - 1, axes.area.y + axes.area.w);
  };
  const auto unoccupied = [&](const glm::ivec4& r) {
    return std::none_of(placed.begin(), placed.end(),
                        [&](const PlacedText& p) { return overlaps(p.box, r); });
  };
  for (const AxisTick& tick : axes.ticks) {
    // A value that would leave the image (the box reaches beyond it when the camera is close) or
    // cover another is left out with its mark rather than moved away from it.
    const TextExtent extent = measureText(tick.text, em);
    const glm::ivec4 box =
        boxBeyond(tick.at, tick.outward, style.tickLength + style.tickGap, extent);
    if (!inside(box) || !unoccupied(box)) continue;
    drawLine(image, tick.at, tick.at + style.tickLength * tick.outward, style.lineWidth, ink);
    drawText(image, box.x, box.y, tick.text, ink, em);
    placed.push_back({box, tick.text});
  }
  for (const AxisLabel& label : axes.labels) {
    // Beyond the band of the edge's tick labels, on the line through the edge's normal: nearer
    // its own edge than any other, and not read as one of the values.
    const TextExtent extent = measureText(label.text, em);
    float band = 0.0f;
    for (const AxisTick& tick : axes.ticks)
      if (tick.axis == label.axis) {
        const TextExtent e = measureText(tick.text, em);
        band = std::max(band, std::abs(tick.outward.x) * static_cast<float>(e.width) +
                                  std::abs(tick.outward.y) * static_cast<float>(e.height));
      }
    float distance = style.tickLength + 2.0f * style.tickGap + band;
    glm::ivec4 box = boxBeyond(label.at, label.outward, distance, extent);
    for (int step = 0; step < 64 && !unoccupied(box); ++step) {
      distance += 0.25f * em;
      box = boxBeyond(label.at, label.outward, distance, extent);
    }
    if (!inside(box)) {
      const int x = std::clamp(box.x, 1, std::max(1, image.width - 1 - extent.width));
      const int y = std::clamp(box.y, 1, std::max(1, image.height - 1 - extent.height));
      box = {x, y, x + extent.width, y + extent.height};
    }
    drawText(image, box.x, box.y, label.text, ink, em);
    placed.push_back({box, label.text});
  }
  return placed;
}

}  // namespace lic3d
