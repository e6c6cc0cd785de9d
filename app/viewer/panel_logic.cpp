// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/panel_logic.h"

#include <algorithm>
#include <cstdio>

#include "core/colormap.h"
#include "core/enum_names.h"
#include "core/look.h"
#include "core/parameter_ranges.h"

namespace lic3d::viewer {
namespace {

// ImGui's default font has no ellipsis glyph.
constexpr std::string_view kEllipsis = "...";

// The longest `text.substr(0, n)` (from the front) or `text.substr(size - n)` (from the back)
// with `textWidth(prefix + part + suffix) <= width`.
std::size_t fitting(std::string_view text, bool front, const std::string& prefix,
                    const std::string& suffix, float width, const TextWidth& textWidth) {
  std::size_t low = 0, high = text.size();
  while (low < high) {  // the widths grow with n: bisect
    const std::size_t n = (low + high + 1) / 2;
    const std::string_view part = front ? text.substr(0, n) : text.substr(text.size() - n);
    if (textWidth(prefix + std::string(part) + suffix) <= width)
      low = n;
    else
      high = n - 1;
  }
  return low;
}

}  // namespace

std::string elidePath(const std::string& path, float width, const TextWidth& textWidth) {
  if (textWidth(path) <= width) return path;
  const std::size_t slash = path.find_last_of('/');
  const std::string name = slash == std::string::npos ? path : path.substr(slash);
  const std::string dir = slash == std::string::npos ? std::string() : path.substr(0, slash);
  const std::string ellipsis(kEllipsis);
  if (dir.empty() || textWidth(ellipsis + name) > width) {
    // The file name alone is too wide: its start and its end (the extension) stay.
    const std::string_view bare = std::string_view(name).substr(name.front() == '/' ? 1 : 0);
    const std::size_t tail = std::min<std::size_t>(
        fitting(bare, false, ellipsis, "", 0.45f * width, textWidth), bare.size());
    const std::string end(bare.substr(bare.size() - tail));
    const std::size_t head =
        fitting(bare.substr(0, bare.size() - tail), true, "", ellipsis + end, width, textWidth);
    return std::string(bare.substr(0, head)) + ellipsis + end;
  }
  // The nearest folders, whole, in about half of what the file name leaves.
  std::string tail = name;
  std::size_t cut = dir.size();
  const float nearWidth = textWidth(ellipsis + name) + 0.5f * (width - textWidth(ellipsis + name));
  while (cut > 0) {
    const std::size_t previous = dir.find_last_of('/', cut - 1);
    const std::size_t from = previous == std::string::npos ? 0 : previous;
    const std::string longer = dir.substr(from, cut - from) + tail;
    if (from == 0 || textWidth(ellipsis + longer) > nearWidth) break;
    tail = longer;
    cut = from;
  }
  // Then as much of the start as fits.
  const std::string_view rest = std::string_view(dir).substr(0, cut);
  const std::size_t head = fitting(rest, true, "", ellipsis + tail, width, textWidth);
  return std::string(rest.substr(0, head)) + ellipsis + tail;
}

OpacitySource opacitySource(const ViewParams& view) {
  return view.opticalDepth > 0.0f ? OpacitySource::OpticalDepth : OpacitySource::Alpha;
}

void setOpacitySource(ViewParams& view, OpacitySource source, float resolvedAlpha,
                      float& lastDepth) {
  if (opacitySource(view) == source) return;
  if (source == OpacitySource::Alpha) {
    lastDepth = view.opticalDepth;
    if (resolvedAlpha >= 0.0f)
      view.alpha = std::clamp(resolvedAlpha, static_cast<float>(ranges::kAlpha.min),
                              static_cast<float>(ranges::kAlpha.max));
    view.opticalDepth = 0.0f;
  } else if (lastDepth > 0.0f) {
    view.opticalDepth = lastDepth;
  } else {
    Session seeThrough;  // the depth of the default look
    applyLook(Look::SeeThrough, seeThrough);
    view.opticalDepth = seeThrough.view.opticalDepth;
  }
}

std::string opacityCaption(const ViewParams& view, float resolvedAlpha) {
  char text[160];
  if (opacitySource(view) == OpacitySource::Alpha) {
    std::snprintf(text, sizeof text, "alpha %.3f per voxel sets the opacity",
                  static_cast<double>(view.alpha));
  } else if (resolvedAlpha >= 0.0f) {
    std::snprintf(text, sizeof text,
                  "optical depth %.2f sets the opacity: alpha %.3f per voxel, chosen from the data",
                  static_cast<double>(view.opticalDepth), static_cast<double>(resolvedAlpha));
  } else {
    std::snprintf(text, sizeof text,
                  "optical depth %.2f sets the opacity: alpha is chosen from the data",
                  static_cast<double>(view.opticalDepth));
  }
  return text;
}

std::string startupPresetFile(const cli::SessionOptions& inputs) {
  // --tf is applied after --colormap (options/view_options.cpp) and wins.
  if (inputs.transferFunction.given()) return inputs.transferFunction.text;
  if (inputs.colormap.given() && !parseEnum<Colormap>(inputs.colormap.text))
    return inputs.colormap.text;
  return {};
}

}  // namespace lic3d::viewer
