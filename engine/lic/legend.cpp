// SPDX-License-Identifier: BSD-3-Clause
#include "lic/legend.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#include <stb_easy_font.h>
#pragma GCC diagnostic pop

namespace lic3d {
namespace {

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

std::string formatValue(float v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", static_cast<double>(v));
  return text;
}

}  // namespace

int textWidth(std::string_view text, int scale) {
  std::string copy(text);
  return stb_easy_font_width(copy.data()) * scale;
}

glm::u8vec4 inkFor(glm::vec3 background, std::uint8_t alpha) {
  const float luminance = 0.2126f * background.r + 0.7152f * background.g + 0.0722f * background.b;
  return luminance > 0.5f ? glm::u8vec4(0, 0, 0, alpha) : glm::u8vec4(255, 255, 255, alpha);
}

void drawText(RgbaImage& image, int x, int y, std::string_view text, glm::u8vec4 color, int scale) {
  std::string copy(text);
  // 4 vertices of 16 bytes per quad. stb's "about 270 bytes per character" is an average: an
  // '8' takes 9 quads (576 bytes), and a short buffer silently drops the last strokes (0.008 was
  // drawn as 0.003). 16 quads per character is more than any glyph has.
  std::vector<char> buffer(16 * 64 * (copy.size() + 1));
  const int quads = stb_easy_font_print(0.0f, 0.0f, copy.data(), nullptr, buffer.data(),
                                        static_cast<int>(buffer.size()));
  for (int q = 0; q < quads; ++q) {
    const float* v0 = reinterpret_cast<const float*>(&buffer[static_cast<std::size_t>(q) * 64]);
    const float* v2 =
        reinterpret_cast<const float*>(&buffer[static_cast<std::size_t>(q) * 64 + 32]);
    fillRect(image, x + static_cast<int>(v0[0]) * scale, y + static_cast<int>(v0[1]) * scale,
             x + static_cast<int>(v2[0]) * scale, y + static_cast<int>(v2[1]) * scale, color);
  }
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

constexpr int kCharHeight = 12;  // stb_easy_font's line height at scale 1

int textScale(int height) { return std::max(1, height / 360); }

// Legend geometry shared by the layout and the drawing: the bar's width and the gap to its
// labels, and the labels (at the ticks).
struct LegendMetrics {
  int margin = 0, bar = 0, gap = 0, labelWidth = 0, width = 0;
  std::vector<double> ticks;
};

LegendMetrics legendMetrics(const LegendSpec& legend, int height, int scale) {
  LegendMetrics m;
  m.margin = 10 * scale;
  m.bar = std::max(10, height / 36);
  m.gap = 4 * scale;
  m.ticks = niceTicks(legend.low, legend.high, 6);
  for (const double t : m.ticks)
    m.labelWidth = std::max(m.labelWidth, textWidth(formatValue(static_cast<float>(t)), scale));
  // stb's width is the pen advance; a character's width spare keeps the last glyph inside.
  const int labels = m.bar + m.gap + m.labelWidth + textWidth("0", scale);
  m.width = 2 * m.margin + std::max(labels, textWidth(legend.title, scale) + textWidth("0", scale));
  return m;
}

}  // namespace

PictureLayout pictureLayout(int width, int height, const LegendSpec* legend,
                            std::string_view title) {
  PictureLayout layout;
  layout.scale = textScale(height);
  int top = 0;
  if (!title.empty()) {
    top = std::min(height / 4, (kCharHeight + 12) * layout.scale);
    layout.title = {0, 0, width, top};
  }
  int right = 0;
  if (legend) {
    right = std::min(width / 2, legendMetrics(*legend, height - top, layout.scale).width);
    layout.legend = {width - right, top, right, height - top};
  }
  layout.picture = {0, top, std::max(width - right, 1), std::max(height - top, 1)};
  return layout;
}

LegendBox drawLegend(RgbaImage& image, const PictureLayout& layout, const LegendSpec& legend,
                     glm::vec3 background) {
  const int scale = layout.scale;
  const glm::u8vec4 ink = inkFor(background, 255);
  const glm::ivec4 area = layout.legend;
  const LegendMetrics m = legendMetrics(legend, area.w, scale);
  LegendBox box;
  box.x0 = area.x + m.margin;
  box.x1 = box.x0 + m.bar;
  box.y0 = area.y + area.w / 6 + 2 * kCharHeight * scale;
  box.y1 = area.y + area.w - area.w / 6;
  if (box.y1 - box.y0 < 8) return box;

  for (int y = box.y0; y < box.y1; ++y) {
    const float t = 1.0f - static_cast<float>(y - box.y0) / static_cast<float>(box.y1 - box.y0 - 1);
    const glm::vec3 c = glm::clamp(legend.color(t), 0.0f, 1.0f);
    fillRect(image, box.x0, y, box.x1, y + 1, glm::u8vec4(glm::vec3(c * 255.0f + 0.5f), 255));
  }
  // A thin frame in the text colour keeps the bar readable on any background.
  fillRect(image, box.x0 - 1, box.y0 - 1, box.x1 + 1, box.y0, ink);
  fillRect(image, box.x0 - 1, box.y1, box.x1 + 1, box.y1 + 1, ink);
  fillRect(image, box.x0 - 1, box.y0, box.x0, box.y1, ink);
  fillRect(image, box.x1, box.y0, box.x1 + 1, box.y1, ink);

  const int half = 5 * scale;  // half a character height: centre labels on their ticks
  const double span = legend.high - legend.low;
  for (const double tick : m.ticks) {
    const double t = span > 0.0 ? (tick - legend.low) / span : 0.5;
    const int y = box.y1 - 1 - static_cast<int>(std::lround(t * (box.y1 - box.y0 - 1)));
    fillRect(image, box.x1, y, box.x1 + m.gap / 2 + scale, y + std::max(1, scale / 2 + 1), ink);
    drawText(image, box.x1 + m.gap + scale, y - half, formatValue(static_cast<float>(tick)), ink,
             scale);
  }
  drawText(image, area.x + m.margin, box.y0 - 2 * kCharHeight * scale, legend.title, ink, scale);
  return box;
}

void drawTitle(RgbaImage& image, const PictureLayout& layout, std::string_view title,
               glm::vec3 background) {
  if (title.empty() || layout.title.z == 0) return;
  const int scale = layout.scale;
  const int x = std::max(2, layout.title.x + (layout.title.z - textWidth(title, scale)) / 2);
  const int y = layout.title.y + (layout.title.w - 10 * scale) / 2;
  drawText(image, x, y, title, inkFor(background, 255), scale);
}

RgbaImage annotatedPicture(const RgbaImage& picture, const LegendSpec* legend,
                           std::string_view title, glm::vec3 background) {
  if (!legend && title.empty()) return picture;
  // The canvas grows by the legend's column and the title's band around the picture's size.
  const PictureLayout probe = pictureLayout(picture.width * 2, picture.height, legend, title);
  const int height = picture.height + probe.title.w;
  const PictureLayout sized = pictureLayout(picture.width * 2, height, legend, title);
  const int width = picture.width + sized.legend.z;
  const PictureLayout layout = pictureLayout(width, height, legend, title);
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

BoxAxes projectBoxAxes(const CameraMatrices& camera, bool orthographic, glm::vec3 halfExtent,
                       Dims dims, const GridGeometry& geometry, glm::ivec4 area) {
  BoxAxes axes;
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
  const char* names[3] = {"x", "y", "z"};
  glm::vec2 centre;
  if (!project(glm::vec3(0.0f), centre)) return axes;
  for (int axis = 0; axis < 3; ++axis) {
    // Of the four edges along this axis, label the one on the outline: farthest from the centre
    // on screen, so the text sits beside the volume rather than over it.
    bool found = false;
    glm::vec3 bestLow{0.0f}, bestHigh{0.0f};
    float bestScore = 0.0f;
    for (int k = 0; k < 4; ++k) {
      glm::vec3 low =
          corner((k & 1 ? 1 : 0) << ((axis + 1) % 3) | (k & 2 ? 1 : 0) << ((axis + 2) % 3));
      glm::vec3 high = low;
      low[axis] = -halfExtent[axis];
      high[axis] = halfExtent[axis];
      glm::vec2 at;
      if (!project(0.5f * (low + high), at)) continue;
      // Bottom and left outline edges win: the usual place of axes.
      const float score =
          glm::length(at - centre) + 0.25f * (at.y - centre.y) - 0.25f * (at.x - centre.x);
      if (!found || score > bestScore) {
        bestScore = score;
        bestLow = low;
        bestHigh = high;
      }
      found = true;
    }
    glm::vec2 a, b, middle;
    if (!found || !project(bestLow, a) || !project(bestHigh, b) ||
        !project(0.5f * (bestLow + bestHigh), middle))
      continue;
    glm::vec2 outward = middle - centre;
    outward = glm::length(outward) > 1e-3f ? glm::normalize(outward) : glm::vec2(0.0f, 1.0f);
    const double first = geometry.origin[axis];
    const double last = first + geometry.spacing[axis] * (dims[axis] - 1);
    const float pixels = glm::length(b - a);
    const int count = std::clamp(static_cast<int>(pixels / 70.0f), 2, 6);
    for (const double value : niceTicks(first, last, count)) {
      const float t = last > first ? static_cast<float>((value - first) / (last - first)) : 0.5f;
      axes.ticks.push_back(
          {a + t * (b - a), outward, formatValue(static_cast<float>(value)), axis});
    }
    const glm::vec2 end = b + 0.04f * (b - a);
    axes.labels.push_back({end, names[axis], end.x < centre.x});
  }
  return axes;
}

void drawBoxAxes(RgbaImage& image, const BoxAxes& axes, glm::vec3 background) {
  const int scale = std::max(1, image.height / 360);
  const glm::u8vec4 line = inkFor(background, 160);
  for (const auto& [a, b] : axes.edges) {
    const glm::vec2 d = b - a;
    const int steps = static_cast<int>(std::ceil(std::max(std::abs(d.x), std::abs(d.y)))) + 1;
    for (int k = 0; k <= steps; ++k) {
      const glm::vec2 p = a + d * (static_cast<float>(k) / static_cast<float>(steps));
      const int x = static_cast<int>(std::floor(p.x)), y = static_cast<int>(std::floor(p.y));
      fillRect(image, x, y, x + scale, y + scale, line);
    }
  }
  const glm::u8vec4 ink = inkFor(background, 255);
  std::vector<glm::ivec4> placed;  // x0, y0, x1, y1 of the labels drawn so far
  for (const AxisTick& tick : axes.ticks) {
    const int width = textWidth(tick.text, scale), height = 10 * scale;
    const glm::vec2 to = tick.at + static_cast<float>(8 * scale) * tick.outward;
    // The text's box on the side the mark points to. A tick whose value would not fit in the
    // image (the box reaches beyond it when the camera is close) is left out rather than moved
    // away from its mark.
    const int x = static_cast<int>(to.x) - (tick.outward.x < -0.3f  ? width
                                            : tick.outward.x > 0.3f ? 0
                                                                    : width / 2);
    const int y = static_cast<int>(to.y) - (tick.outward.y < -0.3f  ? height
                                            : tick.outward.y > 0.3f ? 0
                                                                    : height / 2);
    if (x < 1 || y < 1 || x + width > image.width - 1 || y + height > image.height - 1) continue;
    bool overlaps = false;
    for (const glm::ivec4& r : placed)
      overlaps = overlaps || (x < r.z && r.x < x + width && y < r.w && r.y < y + height);
    if (overlaps) continue;
    // A short mark away from the box, the value beyond it.
    for (int k = 0; k <= 5 * scale; ++k) {
      const glm::vec2 p = tick.at + static_cast<float>(k) * tick.outward;
      fillRect(image, static_cast<int>(p.x), static_cast<int>(p.y), static_cast<int>(p.x) + scale,
               static_cast<int>(p.y) + scale, ink);
    }
    drawText(image, x, y, tick.text, ink, scale);
    placed.push_back({x, y, x + width, y + height});
  }
  for (const AxisLabel& label : axes.labels) {
    const int width = textWidth(label.text, scale);
    const int height = 12 * scale;
    const int x = std::clamp(label.leftOfBox ? static_cast<int>(label.at.x) - width - 6 * scale
                                             : static_cast<int>(label.at.x) + 6 * scale,
                             2, std::max(2, image.width - width - 2));
    int y = static_cast<int>(label.at.y) - 5 * scale;
    // Labels of edges that meet would overlap: move this one down until it is clear.
    for (bool moved = true; moved;) {
      moved = false;
      for (const glm::ivec4& r : placed)
        if (x < r.z && r.x < x + width && y < r.w && r.y < y + height) {
          y = r.w + scale;
          moved = true;
        }
    }
    drawText(image, x, y, label.text, ink, scale);
    placed.push_back({x, y, x + width, y + height});
  }
}

}  // namespace lic3d
