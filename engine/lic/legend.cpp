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

glm::u8vec4 inkFor(glm::vec3 background, std::uint8_t alpha) {
  const float luminance = 0.2126f * background.r + 0.7152f * background.g + 0.0722f * background.b;
  return luminance > 0.5f ? glm::u8vec4(0, 0, 0, alpha) : glm::u8vec4(255, 255, 255, alpha);
}

}  // namespace

int textWidth(std::string_view text, int scale) {
  std::string copy(text);
  return stb_easy_font_width(copy.data()) * scale;
}

void drawText(RgbaImage& image, int x, int y, std::string_view text, glm::u8vec4 color, int scale) {
  std::string copy(text);
  // 4 vertices of 16 bytes per quad; 270 bytes per character is stb's documented worst case.
  std::vector<char> buffer(270 * (copy.size() + 1));
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

LegendBox drawLegend(RgbaImage& image, Colormap map, float low, float high, std::string_view title,
                     glm::vec3 background) {
  const int scale = std::max(1, image.height / 360);
  const glm::u8vec4 ink = inkFor(background, 255);

  const std::string labels[3] = {formatValue(high), formatValue(0.5f * (low + high)),
                                 formatValue(low)};
  int labelWidth = textWidth(title, scale);
  for (const std::string& l : labels) labelWidth = std::max(labelWidth, textWidth(l, scale));
  // stb's width is the pen advance; keep a character's width spare so the last glyph fits.
  const int margin = 8 * scale + textWidth("0", scale);
  const int barWidth = std::max(8, image.width / 40);
  LegendBox box;
  box.x1 = image.width - margin - labelWidth - 4 * scale;
  box.x0 = box.x1 - barWidth;
  box.y0 = image.height / 4;
  box.y1 = image.height - image.height / 4;

  for (int y = box.y0; y < box.y1; ++y) {
    const float t = 1.0f - static_cast<float>(y - box.y0) / static_cast<float>(box.y1 - box.y0 - 1);
    const glm::vec3 c = sampleColormap(map, t);
    fillRect(image, box.x0, y, box.x1, y + 1, glm::u8vec4(glm::vec3(c * 255.0f + 0.5f), 255));
  }
  // A thin frame in the text colour keeps the bar readable on any background.
  fillRect(image, box.x0 - 1, box.y0 - 1, box.x1 + 1, box.y0, ink);
  fillRect(image, box.x0 - 1, box.y1, box.x1 + 1, box.y1 + 1, ink);
  fillRect(image, box.x0 - 1, box.y0, box.x0, box.y1, ink);
  fillRect(image, box.x1, box.y0, box.x1 + 1, box.y1, ink);

  const int textX = box.x1 + 4 * scale;
  const int half = 5 * scale;  // half a character height: centre labels on their ticks
  drawText(image, textX, box.y0 - half, labels[0], ink, scale);
  drawText(image, textX, (box.y0 + box.y1) / 2 - half, labels[1], ink, scale);
  drawText(image, textX, box.y1 - half, labels[2], ink, scale);
  drawText(image, box.x0, box.y0 - 3 * half - margin, title, ink, scale);
  return box;
}

BoxAxes projectBoxAxes(const glm::mat4& viewProjection, glm::vec3 halfExtent, Dims dims,
                       const GridGeometry& geometry, int width, int height, bool keepRightFree) {
  BoxAxes axes;
  auto corner = [&](int i) {
    return glm::vec3(i & 1 ? halfExtent.x : -halfExtent.x, i & 2 ? halfExtent.y : -halfExtent.y,
                     i & 4 ? halfExtent.z : -halfExtent.z);
  };
  // Pixels of a world point; false behind the camera.
  auto project = [&](glm::vec3 p, glm::vec2& pixel) {
    const glm::vec4 clip = viewProjection * glm::vec4(p, 1.0f);
    if (clip.w <= 1e-6f) return false;
    pixel = glm::vec2((clip.x / clip.w * 0.5f + 0.5f) * static_cast<float>(width),
                      (clip.y / clip.w * 0.5f + 0.5f) * static_cast<float>(height));
    return true;
  };
  for (int i = 0; i < 8; ++i)
    for (int axis = 0; axis < 3; ++axis) {
      const int j = i | (1 << axis);
      if (j == i) continue;
      glm::vec2 a, b;
      if (project(corner(i), a) && project(corner(j), b)) axes.edges.push_back({a, b});
    }
  const char* names[3] = {"x", "y", "z"};
  glm::vec2 centre;
  if (!project(glm::vec3(0.0f), centre)) return axes;
  for (int axis = 0; axis < 3; ++axis) {
    // Of the four edges along this axis, label the one on the outline: farthest from the centre
    // on screen, so the text sits beside the volume rather than over it.
    bool found = false;
    glm::vec2 best{0.0f};
    for (int k = 0; k < 4; ++k) {
      glm::vec3 middle =
          corner((k & 1 ? 1 : 0) << ((axis + 1) % 3) | (k & 2 ? 1 : 0) << ((axis + 2) % 3));
      middle[axis] = 0.0f;
      glm::vec2 at;
      if (!project(middle, at)) continue;
      // With a legend at the right edge, outline edges left of the centre win.
      auto score = [&](glm::vec2 p) {
        return glm::length(p - centre) - (keepRightFree && p.x > centre.x ? 1e6f : 0.0f);
      };
      if (!found || score(at) > score(best)) best = at;
      found = true;
    }
    if (!found) continue;
    const double first = geometry.origin[axis];
    const double last = first + geometry.spacing[axis] * (dims[axis] - 1);
    char text[96];
    std::snprintf(text, sizeof text, "%s %.4g .. %.4g", names[axis], first, last);
    axes.labels.push_back({best, text, best.x < centre.x});
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
