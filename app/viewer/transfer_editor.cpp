// SPDX-License-Identifier: BSD-3-Clause
// The transfer function editor: colour and opacity control points (core/transfer_function.h)
// dragged over a histogram of the scalar they follow, and ParaView colour-map presets loaded
// and saved.

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <glm/common.hpp>
#include <vector>

#include "io/session_file.h"
#include "viewer/ui.h"

namespace lic3d::viewer {
namespace {

constexpr float kGrab = 6.0f;  // pixels around a control point that pick it

ImU32 colourOf(glm::vec3 c) {
  const glm::vec3 v = glm::clamp(c, 0.0f, 1.0f);
  return ImGui::ColorConvertFloat4ToU32(ImVec4(v.r, v.g, v.b, 1.0f));
}

// Log-scaled bars of `values` over the canvas [p0, p1] (the scalar's range left to right).
void histogramBars(ImDrawList* draw, ImVec2 p0, ImVec2 p1, const ValueHistogram* values) {
  draw->AddRectFilled(p0, p1, IM_COL32(30, 30, 34, 255));
  if (!values || values->counts.empty()) return;
  const int columns = std::max(1, static_cast<int>(p1.x - p0.x));
  std::vector<double> heights(columns, 0.0);
  const std::size_t bins = values->counts.size();
  for (std::size_t b = 0; b < bins; ++b) {
    const int c = static_cast<int>(static_cast<double>(b) * columns / static_cast<double>(bins));
    heights[std::min(c, columns - 1)] += static_cast<double>(values->counts[b]);
  }
  double top = 1.0;
  for (double& h : heights) top = std::max(top, h = std::log1p(h));
  for (int c = 0; c < columns; ++c) {
    const float h = static_cast<float>(heights[c] / top) * (p1.y - p0.y);
    draw->AddLine(ImVec2(p0.x + static_cast<float>(c) + 0.5f, p1.y),
                  ImVec2(p0.x + static_cast<float>(c) + 0.5f, p1.y - h),
                  IM_COL32(110, 110, 120, 255));
  }
}

// The colour points over a ramp: click picks a point, drag moves it along x, double-click adds
// one, right-click removes one (two stay).
bool colourPoints(TransferFunction& tf, Colormap colormap, UiState& ui,
                  const ValueHistogram* values) {
  if (tf.colors.empty()) {
    for (int i = 0; i <= 4; ++i) {
      const double x = i / 4.0;
      tf.colors.push_back({x, sampleColormap(colormap, static_cast<float>(x))});
    }
  }
  const float width = ImGui::GetContentRegionAvail().x;
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 p1(p0.x + width, p0.y + 70.0f);
  ImGui::InvisibleButton("colour points", ImVec2(width, 70.0f));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  histogramBars(draw, p0, ImVec2(p1.x, p1.y - 16.0f), values);
  for (int c = 0; c < static_cast<int>(width); ++c)
    draw->AddLine(ImVec2(p0.x + static_cast<float>(c) + 0.5f, p1.y - 14.0f),
                  ImVec2(p0.x + static_cast<float>(c) + 0.5f, p1.y),
                  colourOf(tf.color(static_cast<float>(c) / std::max(width - 1.0f, 1.0f))));
  const auto xOf = [&](double x) { return p0.x + static_cast<float>(x) * width; };
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  int& selected = ui.selectedColorPoint;
  bool changed = false;
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) {
    selected = -1;
    for (int i = 0; i < static_cast<int>(tf.colors.size()); ++i)
      if (std::abs(mouse.x - xOf(tf.colors[i].x)) < kGrab) selected = i;
  }
  if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
    const double x = std::clamp((mouse.x - p0.x) / width, 0.0f, 1.0f);
    tf.colors.push_back({x, tf.color(x)});
    changed = true;
  }
  if (ImGui::IsItemClicked(ImGuiMouseButton_Right) && tf.colors.size() > 2)
    for (int i = 0; i < static_cast<int>(tf.colors.size()); ++i)
      if (std::abs(mouse.x - xOf(tf.colors[i].x)) < kGrab) {
        tf.colors.erase(tf.colors.begin() + i);
        selected = -1;
        changed = true;
        break;
      }
  if (selected >= static_cast<int>(tf.colors.size())) selected = -1;
  if (selected >= 0 && ImGui::IsItemActive() && ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
    tf.colors[selected].x = std::clamp((mouse.x - p0.x) / width, 0.0f, 1.0f);
    changed = true;
  }
  if (changed) {
    const ColorPoint kept = selected >= 0 ? tf.colors[selected] : ColorPoint{};
    std::stable_sort(tf.colors.begin(), tf.colors.end(),
                     [](const ColorPoint& a, const ColorPoint& b) { return a.x < b.x; });
    if (selected >= 0)
      selected =
          static_cast<int>(std::find(tf.colors.begin(), tf.colors.end(), kept) - tf.colors.begin());
  }
  for (int i = 0; i < static_cast<int>(tf.colors.size()); ++i) {
    const float x = xOf(tf.colors[i].x);
    draw->AddTriangleFilled(ImVec2(x, p1.y - 16.0f), ImVec2(x - 5, p1.y - 24.0f),
                            ImVec2(x + 5, p1.y - 24.0f),
                            i == selected ? IM_COL32(255, 220, 60, 255) : IM_COL32_WHITE);
  }
  if (selected >= 0) changed |= ImGui::ColorEdit3("point colour", &tf.colors[selected].rgb.x);
  return changed;
}

// The opacity points as a polyline over the histogram: drag moves a point, double-click adds,
// right-click removes (one stays).
bool opacityPoints(TransferFunction& tf, const ValueHistogram* values) {
  const float width = ImGui::GetContentRegionAvail().x, height = 80.0f;
  const ImVec2 p0 = ImGui::GetCursorScreenPos();
  const ImVec2 p1(p0.x + width, p0.y + height);
  ImGui::InvisibleButton("opacity points", ImVec2(width, height));
  ImDrawList* draw = ImGui::GetWindowDrawList();
  histogramBars(draw, p0, p1, values);
  const auto at = [&](const OpacityPoint& p) {
    return ImVec2(p0.x + static_cast<float>(p.x) * width,
                  p1.y - static_cast<float>(p.alpha) * height);
  };
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  static int dragged = -1;
  bool changed = false;
  const auto pick = [&] {
    for (int i = 0; i < static_cast<int>(tf.opacities.size()); ++i) {
      const ImVec2 q = at(tf.opacities[i]);
      if (std::abs(mouse.x - q.x) < kGrab && std::abs(mouse.y - q.y) < kGrab) return i;
    }
    return -1;
  };
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left)) dragged = pick();
  if (!ImGui::IsItemActive()) dragged = -1;
  const double mx = std::clamp((mouse.x - p0.x) / width, 0.0f, 1.0f);
  const double my = std::clamp((p1.y - mouse.y) / height, 0.0f, 1.0f);
  if (ImGui::IsItemHovered() && ImGui::IsMouseDoubleClicked(ImGuiMouseButton_Left)) {
    tf.opacities.push_back({mx, my});
    changed = true;
  }
  if (ImGui::IsItemClicked(ImGuiMouseButton_Right) && tf.opacities.size() > 1)
    if (const int i = pick(); i >= 0) {
      tf.opacities.erase(tf.opacities.begin() + i);
      changed = true;
    }
  if (dragged >= static_cast<int>(tf.opacities.size())) dragged = -1;
  if (dragged >= 0 && ImGui::IsMouseDragging(ImGuiMouseButton_Left)) {
    tf.opacities[dragged] = {mx, my};
    changed = true;
  }
  if (changed) {
    const OpacityPoint kept = dragged >= 0 ? tf.opacities[dragged] : OpacityPoint{};
    std::stable_sort(tf.opacities.begin(), tf.opacities.end(),
                     [](const OpacityPoint& a, const OpacityPoint& b) { return a.x < b.x; });
    if (dragged >= 0)
      dragged = static_cast<int>(std::find(tf.opacities.begin(), tf.opacities.end(), kept) -
                                 tf.opacities.begin());
  }
  for (std::size_t i = 0; i + 1 < tf.opacities.size(); ++i)
    draw->AddLine(at(tf.opacities[i]), at(tf.opacities[i + 1]), IM_COL32(255, 220, 60, 255), 2);
  for (const OpacityPoint& p : tf.opacities) draw->AddCircleFilled(at(p), 4.0f, IM_COL32_WHITE);
  return changed;
}

}  // namespace

void transferFunctionPanel(ViewParams& view, UiState& ui, const Stats& stats) {
  if (!ImGui::CollapsingHeader("Transfer function")) return;
  TransferFunction& tf = view.transfer;
  ImGui::TextWrapped(
      "Over the colour range of '%s' (histogram, log counts): drag a point, "
      "double-click adds one, right-click removes one.",
      view.colorBy.c_str());
  bool editColours = !tf.colors.empty();
  if (ImGui::Checkbox("colours", &editColours) && !editColours) tf.colors.clear();
  if (editColours) colourPoints(tf, view.colormap, ui, stats.colorValues.get());
  bool editOpacity = !tf.opacities.empty();
  if (ImGui::Checkbox("opacities", &editOpacity)) {
    if (editOpacity)
      tf.opacities = {{0.0, 0.0}, {1.0, 1.0}};
    else
      tf.opacities.clear();
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip(
        "Opacity as a function of the opacity scalar ('%s'), replacing the "
        "magnitude opacity",
        view.opacityBy.c_str());
  if (editOpacity) opacityPoints(tf, stats.opacityValues.get());

  pathText("preset", ui.transferPath, "A ParaView colour-map preset (.json): RGBPoints and Points");
  if (ImGui::Button("Load preset")) {
    Result<TransferFunction> loaded = readTransferFunction(ui.transferPath);
    ui.transferMessage = loaded ? "loaded " + ui.transferPath : loaded.error().message;
    if (loaded) tf = std::move(*loaded);
  }
  ImGui::SameLine();
  if (ImGui::Button("Save preset")) {
    const Result<void> written = writeTransferFunction(ui.transferPath, tf);
    ui.transferMessage = written ? "wrote " + ui.transferPath : written.error().message;
  }
  ImGui::SameLine();
  if (ImGui::Button("Clear")) {
    tf = TransferFunction();
    ui.transferMessage.clear();
  }
  if (!ui.transferMessage.empty()) ImGui::TextWrapped("%s", ui.transferMessage.c_str());
}

}  // namespace lic3d::viewer
