// SPDX-License-Identifier: BSD-3-Clause
#include "viewer/ui.h"

#include <imgui.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/common.hpp>
#include <map>
#include <string_view>

#include "core/colormap.h"
#include "core/enum_names.h"
#include "core/key_names.h"
#include "core/look.h"
#include "core/parameter_ranges.h"
#include "lic/analytic_fields.h"
#include "viewer/panel_logic.h"

namespace lic3d::viewer {
namespace {

void tip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// The session keys the engine names parameters by, and the widgets that set them: uiMessage shows
// the widget where an error message has the key. Filled as the widgets are drawn.
KeyNames& widgetNames() {
  static KeyNames names;
  return names;
}

void nameWidget(std::string_view key, const char* label) {
  widgetNames().try_emplace(std::string(key), std::string("'") + label + "'");
}

// Sliders over a parameter's slider range (core/parameter_ranges.h); ctrl+click types a value
// outside it, which validate() then checks against the accepted range.
bool slider(const char* label, float& value, const ParameterRange& range,
            const char* format = "%.3f") {
  nameWidget(range.key, label);
  return ImGui::SliderFloat(label, &value, static_cast<float>(range.sliderMin),
                            static_cast<float>(range.sliderMax), format);
}
bool slider(const char* label, int& value, const ParameterRange& range) {
  nameWidget(range.key, label);
  return ImGui::SliderInt(label, &value, static_cast<int>(range.sliderMin),
                          static_cast<int>(range.sliderMax));
}
bool slider3(const char* label, glm::vec3& value, const ParameterRange& range,
             const char* format = "%.3f") {
  nameWidget(range.key, label);
  return ImGui::SliderFloat3(label, &value.x, static_cast<float>(range.sliderMin),
                             static_cast<float>(range.sliderMax), format);
}
// Two ends of an interval of one parameter (a window, a clip range) over its slider range.
bool interval(const char* label, float& low, float& high, float speed,
              const ParameterRange& range) {
  nameWidget(range.key, label);
  return ImGui::DragFloatRange2(label, &low, &high, speed, static_cast<float>(range.sliderMin),
                                static_cast<float>(range.sliderMax));
}

bool text(const char* label, std::string& value, const char* help) {
  std::array<char, 1024> buffer{};
  std::snprintf(buffer.data(), buffer.size(), "%s", value.c_str());
  const bool changed = ImGui::InputText(label, buffer.data(), buffer.size());
  tip(help);
  if (changed) value = buffer.data();
  return changed;
}

}  // namespace

bool pathText(const char* label, std::string& value, const char* help) {
  // The box being edited; it edits the whole path until it loses the keyboard.
  static ImGuiID editing = 0;
  static bool focusPending = false;
  const ImGuiID id = ImGui::GetID(label);
  // A path takes the panel's width beside the longest path label, so that more of it is read
  // without eliding and the path boxes end in one column.
  const ImGuiStyle& style = ImGui::GetStyle();
  const float boxWidth = std::max(ImGui::CalcItemWidth(), ImGui::GetContentRegionAvail().x -
                                                              ImGui::CalcTextSize("noise file").x -
                                                              style.ItemInnerSpacing.x);
  const float room = boxWidth - 2.0f * style.FramePadding.x;
  const auto width = [](std::string_view t) {
    return ImGui::CalcTextSize(t.data(), t.data() + t.size()).x;
  };
  if (editing != id && width(value) > room) {
    std::array<char, 1024> shown{};
    std::snprintf(shown.data(), shown.size(), "%s", elidePath(value, room, width).c_str());
    ImGui::SetNextItemWidth(boxWidth);
    ImGui::InputText((std::string(label) + "##shown").c_str(), shown.data(), shown.size(),
                     ImGuiInputTextFlags_ReadOnly);
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s\n\n%s", value.c_str(), help);
    if (ImGui::IsItemActivated()) {  // edited from the next frame on
      editing = id;
      focusPending = true;
    }
    return false;
  }
  const bool focusing = editing == id && focusPending;
  if (focusing) {
    ImGui::SetKeyboardFocusHere();
    focusPending = false;
  }
  ImGui::SetNextItemWidth(boxWidth);
  const bool changed = text(label, value, help);
  if (editing == id && !focusing && !ImGui::IsItemActive()) editing = 0;
  return changed;
}

namespace {

template <class E>
bool combo(const char* label, E& value, const char* help) {
  bool changed = false;
  if (ImGui::BeginCombo(label, std::string(enumName(value)).c_str())) {
    for (const EnumName<E>& n : enumNames<E>()) {
      const bool selected = n.value == value;
      if (ImGui::Selectable(std::string(n.name).c_str(), selected)) {
        value = n.value;
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  tip(help);
  return changed;
}

void fieldPanel(Session& session, UiState& ui, Actions& actions) {
  if (!ImGui::CollapsingHeader("Field and noise", ImGuiTreeNodeFlags_DefaultOpen)) return;
  int mode = session.twoD ? 1 : 0;
  ImGui::RadioButton("3D volume", &mode, 0);
  ImGui::SameLine();
  ImGui::RadioButton("2D plane", &mode, 1);
  tip("2D LIC of a plane (thesis chapter 3): a 2D field, or a plane of the 3D field");
  session.twoD = mode == 1;
  FieldSource& f = ui.pendingField;
  const bool analytic = parseEnum<AnalyticField>(f.field) || parseEnum<AnalyticField2D>(f.field);
  if (ImGui::BeginCombo("analytic", analytic ? f.field.c_str() : "(file)")) {
    for (const auto& [value, name] : enumNames<AnalyticField>())
      if (ImGui::Selectable(std::string(name).c_str(), f.field == name)) f.field = name;
    if (session.twoD)
      for (const auto& [value, name] : enumNames<AnalyticField2D>())
        if (ImGui::Selectable(std::string(name).c_str(), f.field == name)) f.field = name;
    ImGui::EndCombo();
  }
  tip("An analytic field: tornado (Crawfis), corner (thesis 4.5), solenoidal (thesis 6.2), "
      "vortex, ABC flow; in 2D also circle (thesis Figure 3.7), saddle and the time-varying "
      "wave (thesis 3.5)");
  pathText("file", f.field,
           "Or a field file: .vtk, .vti, .nrrd, or a time series step_%03d.vti / step_*.vti "
           "(press Load)");
  if (parseEnum<AnalyticField>(f.field) && timePeriod(*parseEnum<AnalyticField>(f.field)) > 0.0 &&
      !session.twoD) {
    ImGui::InputInt("time steps", &ui.pendingTimeSteps);
    ui.pendingTimeSteps = std::clamp(ui.pendingTimeSteps, 0, 4096);
    if (ui.pendingTimeSteps == 1) ui.pendingTimeSteps = 2;
    tip("The tornado as a series of steps over its period, blended on the GPU (0: 64)");
  }
  // A file brings its own grid: the grid is edited for analytic fields only.
  if (parseEnum<AnalyticField>(f.field)) {
    ImGui::InputInt3("grid", &f.grid.x);
    f.grid = glm::clamp(f.grid, glm::ivec3(1), glm::ivec3(2048));
    tip("Voxels of an analytic field along x, y, z");
  }
  text("array", f.array, "The vector array to read from a file with several (empty: the first)");
  NoiseSource& n = ui.pendingNoise;
  int seed = static_cast<int>(n.seed);
  if (ImGui::InputInt("noise seed", &seed)) n.seed = static_cast<std::uint64_t>(std::max(seed, 0));
  tip("Seed of the white noise (and of the seed noise's spots)");
  ImGui::InputInt("seed spots", &n.seedSpots);
  nameWidget(ranges::kSeedSpots.key, "seed spots");
  n.seedSpots = std::max(n.seedSpots, 0);
  tip("Sparse seed noise: this many bright spots on black instead of white noise (0: white "
      "noise)");
  pathText("noise file", n.file,
           "A noise volume (.nrrd) on the field's grid instead (empty: generated)");
  if (ImGui::Button("Load")) actions.reloadField = true;
  tip("Load the field and noise above (the LIC volume is recomputed)");
  if (!session.twoD) return;
  PlaneParams& p = session.plane;
  const char* axes[3] = {"x", "y", "z"};
  ImGui::Combo("plane across", &p.axis, axes, 3);
  tip("A 3D field is cut across this axis");
  ImGui::InputInt("layer", &p.index);
  p.index = std::max(p.index, -1);
  tip("The voxel layer of the plane (-1: the middle)");
  ImGui::InputInt2("image size", &p.width);
  p.width = std::clamp(p.width, 0, 16384);
  p.height = std::clamp(p.height, 0, 16384);
  tip("The LIC image in pixels: noise at this size, finer than the field stays sharp (0: the "
      "view's size, one image pixel per screen pixel, made again when the window is resized; one "
      "side alone keeps the grid's aspect)");
}

void timePanel(Session& session, UiState& ui, const Stats& stats) {
  if (!stats.timeDependent) return;
  if (!ImGui::CollapsingHeader("Time", ImGuiTreeNodeFlags_DefaultOpen)) return;
  double time = session.time;
  const double low = 0.0, high = stats.timeEnd;
  ImGui::SliderScalar("time", ImGuiDataType_Double, &time, &low, &high, "%.3f");
  session.time = time;
  tip(stats.timePeriodic
          ? "The field's time; it repeats after this range (the field between steps is blended "
            "on the GPU in 3D)"
          : "The position in the series of files: 1.5 is halfway between the second and the "
            "third step, blended on the GPU");
  ImGui::Checkbox("play time", &ui.playingTime);
  tip("Run the time through its range (with the bias animation too, both loop)");
  ImGui::SliderFloat("seconds per cycle", &ui.timeSeconds, 1.0f, 120.0f, "%.0f s");
}

// Whether the widget just drawn is held: its drag shows a coarse LIC (viewer/drag.h).
void noteDrag(UiState& ui) { ui.licDragging = ui.licDragging || ImGui::IsItemActive(); }

void licPanel(Session& s, UiState& ui) {
  if (!ImGui::CollapsingHeader("LIC", ImGuiTreeNodeFlags_DefaultOpen)) return;
  LicParams& l = s.lic;
  slider("length L", l.length, ranges::kLength);
  noteDrag(ui);
  tip("Streamline steps each way: longer streaks, more blur (thesis 4.4.3)");
  slider("step h", l.step, ranges::kStep, "%.2f voxels");
  noteDrag(ui);
  tip("Step length in voxels");
  ImGui::SliderInt("bias", &l.bias, -l.length, l.length);
  noteDrag(ui);
  nameWidget("lic.bias", "bias");
  l.bias = std::clamp(l.bias, -l.length, l.length);
  tip("L - bias steps backward, L + bias forward: moving it animates the flow (thesis 3.3.3)");
  combo("integrator", l.integrator, "Euler, midpoint RK2 or classical RK4");
  combo("kernel", l.kernel, "Weights along the streamline: box, Hann or Gaussian");
  combo("noise filter", l.noiseFilter, "Noise looked up at the nearest voxel or trilinearly");
  combo("direction", l.direction,
        "normalized: unit steps; magnitude: steps scaled by |v| / max |v|");
  combo("scheme", l.scheme,
        "How rk2 steps. exact: every step an RK2 step (two texture fetches per sample); ab2: "
        "Adams-Bashforth steps from the directions already fetched (one fetch per sample); fused: "
        "RK2 steps of 2h whose midpoint is a sample (one fetch per sample)");
  combo("precision", s.precision,
        "Field texture on the device: float on CPU drivers, half on GPUs (auto); byte: RGBA8, "
        "8-bit direction and noise, a quarter of the memory of float");
}

void sparsityPanel(Session& s, UiState& ui, const Stats& stats) {
  if (!ImGui::CollapsingHeader("Sparsity")) return;
  SparsityParams& p = s.lic.sparsity;
  combo("distribution", p.distribution,
        "Black points of the mask (thesis 5.1.4): a voxel whose streamline touches one is not "
        "drawn");
  slider("amount", p.amount, ranges::kSparsityAmount, "%.2f");
  noteDrag(ui);
  tip("The fraction of voxels to hide, mapped to the distribution's points, radius or ratio "
      "(0: the distribution's own parameters below)");
  if (stats.hiddenFraction >= 0.0)
    ImGui::Text("the mask hides %.1f %% of the voxels", 100.0 * stats.hiddenFraction);
  ImGui::InputInt("points", &p.points, 1000, 10000);
  nameWidget(ranges::kSparsityPoints.key, "points");
  p.points = std::max(p.points, 0);
  tip("Black points for poisson, poisson-approx, halton, hammersley (0: automatic)");
  slider("radius", p.radius, ranges::kSparsityRadius, "%.2f voxels");
  noteDrag(ui);
  tip("Minimum distance between black points for poisson and jitter (0: automatic)");
  slider("ratio", p.ratio, ranges::kSparsityRatio);
  noteDrag(ui);
  tip("Fraction of black voxels of the checkerboard");
  int seed = static_cast<int>(p.seed);
  if (ImGui::InputInt("mask seed", &seed)) p.seed = static_cast<std::uint64_t>(std::max(seed, 0));
  tip("Seed of the random distributions");
}

// A look sets many parameters at once (core/look.h); a look that changes the noise reads it
// again.
void lookPanel(Session& session, UiState& ui, Actions& actions) {
  Look look = session.look;
  if (!combo("look", look,
             "dense: the thesis' opaque block; see-through: colour and opacity by speed, empty "
             "space clear; streamlines: seed noise, lit lines; sparse: a Poisson-disk mask "
             "hides half of the streamlines"))
    return;
  applyLook(look, session);
  if (!(ui.pendingNoise == session.noise)) {
    ui.pendingNoise = session.noise;
    actions.reloadField = true;
  }
}

// Colour or opacity by speed, a derived quantity or a point scalar of the field's file.
void scalarCombo(const char* label, std::string& value, const Stats& stats, const char* help) {
  if (ImGui::BeginCombo(label, value.c_str())) {
    for (const std::string& name : stats.scalarChoices)
      if (ImGui::Selectable(name.c_str(), name == value)) value = name;
    ImGui::EndCombo();
  }
  tip(help);
}

// What sets the alpha per voxel: an optical depth (alpha chosen from the data, the looks' way) or
// the alpha slider. Only the control that acts is shown, and a line says which it is.
void opacityControls(ViewParams& v, UiState& ui, const Stats& stats) {
  int source = opacitySource(v) == OpacitySource::OpticalDepth ? 0 : 1;
  ImGui::AlignTextToFramePadding();
  ImGui::TextUnformatted("opacity from");
  ImGui::SameLine();
  bool switched = ImGui::RadioButton("optical depth##source", &source, 0);
  ImGui::SameLine();
  switched |= ImGui::RadioButton("alpha##source", &source, 1);
  tip("optical depth: alpha is chosen from the data so that a ray through the volume meets this "
      "optical depth (what the looks set); alpha: a fixed opacity per voxel of depth. Switching "
      "keeps the alpha in use");
  if (switched)
    setOpacitySource(v, source == 0 ? OpacitySource::OpticalDepth : OpacitySource::Alpha,
                     stats.resolvedAlpha, ui.lastOpticalDepth);
  if (opacitySource(v) == OpacitySource::OpticalDepth) {
    slider("optical depth", v.opticalDepth, ranges::kOpticalDepth, "%.2f");
    // Dragged to 0 the depth would hand the opacity to alpha while the slider is held: the
    // switch above does that.
    v.opticalDepth = std::max(v.opticalDepth, 0.01f);
    tip("Alpha is chosen from the data so that a ray through the volume meets this optical depth "
        "(1: about a third of the light crosses it)");
  } else {
    slider("alpha", v.alpha, ranges::kAlpha);
    tip("Opacity per voxel of depth, corrected for the slice spacing (thesis 5.1.1)");
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyleColorVec4(ImGuiCol_TextDisabled));
  ImGui::TextWrapped("%s", opacityCaption(v, stats.resolvedAlpha).c_str());
  ImGui::PopStyleColor();
}

void colourPanel(ViewParams& v, UiState& ui, const Stats& stats) {
  if (!ImGui::CollapsingHeader("Colour and opacity", ImGuiTreeNodeFlags_DefaultOpen)) return;
  opacityControls(v, ui, stats);
  combo("opacity", v.opacityMode, "constant alpha, or alpha x grey (dark gaps turn clear)");
  combo("color", v.color, "Colour by a scalar, modulated by the LIC intensity (thesis 5.1.2)");
  nameWidget("view.color_by", "color by");
  scalarCombo("color by", v.colorBy, stats,
              "speed |v|, vorticity |curl v|, helicity v . curl v, or a scalar of the file");
  nameWidget("view.opacity_by", "opacity by");
  scalarCombo("opacity by", v.opacityBy, stats,
              "The scalar the magnitude opacity and the opacity transfer function follow");
  combo("colormap", v.colormap, "The thesis' blue-yellow-red, viridis, or cool-warm");
  ImGui::Checkbox("auto range", &v.autoColorRange);
  tip("Colour range from the field's min and max |v|");
  if (!v.autoColorRange) {
    ImGui::DragFloatRange2("range", &v.colorLow, &v.colorHigh, 0.005f * stats.maxMagnitude, 0.0f,
                           2.0f * stats.maxMagnitude, "%.4g", "%.4g");
    if (v.colorHigh <= v.colorLow) v.colorHigh = v.colorLow + 1e-6f;
    tip("|v| at the two ends of the colour map");
  }
  ImGui::Checkbox("legend", &v.legend);
  tip("Show the colour legend beside the volume");
  ImGui::Checkbox("axes", &v.axes);
  tip("The box's edges, each axis labelled with its physical range (origin, spacing)");
  slider("magnitude opacity", v.magnitudeOpacity, ranges::kMagnitudeOpacity);
  tip("Opacity x (normalised |v|)^E: slow regions fade (thesis 5.1.3); 0 is off");
  slider("threshold", v.magnitudeThreshold, ranges::kMagnitudeThreshold);
  tip("Voxels whose normalised |v| is below this vanish");
  ImGui::Checkbox("percentile window", &v.percentileWindow);
  tip("LIC values mapped to black..white between two percentiles of the drawn voxels' values "
      "(sparse volumes, seed noise)");
  if (v.percentileWindow)
    interval("percentiles", v.windowPercentiles.x, v.windowPercentiles.y, 0.002f,
             ranges::kWindowPercentiles);
  ImGui::Checkbox("contrast stretch", &v.contrast);
  tip("Stretch the drawn voxels' LIC values to mean 0.5 and deviation 0.25");
  ImGui::Checkbox("manual window", &v.manualWindow);
  if (v.manualWindow) {
    interval("window", v.windowLow, v.windowHigh, 0.002f, ranges::kWindow);
    if (v.windowHigh <= v.windowLow) v.windowHigh = v.windowLow + 1e-3f;
  }
  tip("LIC values mapped to black..white instead of the stretch");
  slider("gain", v.gain, ranges::kGain);
  tip("Scales grey values around mid-grey");
  slider("brightness", v.brightness, ranges::kBrightness);
  tip("Added to grey values");
  ImGui::ColorEdit3("background", &v.background.x);
  tip("Background colour");
  text("title", v.title, "A title above the picture (empty: none)");
}

void localPanel(ViewParams& v) {
  if (!ImGui::CollapsingHeader("Clip planes and region")) return;
  const char* axes[3] = {"clip x", "clip y", "clip z"};
  for (int a = 0; a < 3; ++a) {
    interval(axes[a], v.clipMin[a], v.clipMax[a], 0.005f, ranges::kClipMin);
    if (v.clipMax[a] <= v.clipMin[a]) v.clipMax[a] = std::min(1.0f, v.clipMin[a] + 0.01f);
    if (v.clipMax[a] <= v.clipMin[a]) v.clipMin[a] = v.clipMax[a] - 0.01f;
    tip("The part of the box kept along this axis (thesis 5.2.1)");
  }
  combo("region", v.roi, "A region of interest: only its inside (or outside) is drawn (5.2.2)");
  if (v.roi != RoiShape::None) {
    slider3("centre", v.roiCenter, ranges::kRoiCenter);
    tip("Centre as fractions of the box");
    slider("size", v.roiSize, ranges::kRoiSize);
    tip("Diameter or side as a fraction of the longest box side");
    slider3("rotate", v.roiRotation, ranges::kRoiRotation, "%.0f deg");
    tip("The region turns with its own frame (x, then y, then z)");
    ImGui::Checkbox("outside", &v.roiOutside);
    tip("Keep the outside of the region instead");
  }
}

void depthPanel(ViewParams& v) {
  if (!ImGui::CollapsingHeader("Depth: halos, occlusion, fog, lighting, stereo")) return;
  slider("halos", v.halo, ranges::kHalo);
  tip("Dark borders around streaks in the background colour, so a near streak cuts the far ones "
      "it crosses (0: off)");
  if (v.halo > 0.0f) {
    slider("halo radius", v.haloRadius, ranges::kHaloRadius, "%.2f voxels");
  }
  slider("occlusion", v.occlusion, ranges::kOcclusion);
  tip("Each slice darkened by the opacity in front of it, spread over a cone towards the viewer "
      "(slices drawn front to back; 0: off)");
  ImGui::Checkbox("fog", &v.fog);
  tip("Intensity depth cueing (thesis 5.3.1)");
  if (v.fog) {
    interval("fog range", v.fogStart, v.fogEnd, 0.005f, ranges::kFogRange);
    if (v.fogEnd <= v.fogStart) v.fogEnd = v.fogStart + 0.01f;
    tip("Start and end, as fractions of the depth from the nearest to the farthest point");
    ImGui::Checkbox("fog = background", &v.fogColorFromBackground);
    if (!v.fogColorFromBackground) ImGui::ColorEdit3("fog colour", &v.fogColor.x);
  }
  combo("lighting", v.lighting,
        "phong: normals from the streamline's TNB frame (5.3.3); lines: lit from the tangent; "
        "gradient: Phong with the streak's normal, the LIC gradient across the flow");
  if (v.lighting != Lighting::None) {
    slider("ambient", v.light.ambient, ranges::kAmbient);
    slider("diffuse", v.light.diffuse, ranges::kDiffuse);
    slider("specular", v.light.specular, ranges::kSpecular);
    slider("shininess", v.light.shininess, ranges::kShininess);
  }
  nameWidget("view.stereo", "stereo");
  combo("stereo", v.stereo,
        "Off-axis stereo (5.3.2): red/cyan anaglyph or side by side; quad-buffered stereo is not "
        "offered by Vulkan surfaces here");
  if (v.stereo != StereoMode::None) {
    slider("eye separation", v.eyeSeparation, ranges::kEyeSeparation);
    tip("Box units; 0 is a thirtieth of the zero-parallax distance");
    slider("zero parallax", v.zeroParallax, ranges::kZeroParallax, "%.2f");
    tip("Distance of the plane without disparity; 0 is the volume centre");
  }
}

void renderingPanel(ViewParams& v, UiState& ui, Actions& actions) {
  if (!ImGui::CollapsingHeader("Slices and camera")) return;
  combo("slicing", v.slicing, "view-aligned planes, or the thesis' axis-aligned planes (4.1.2)");
  slider("slices", v.slices, ranges::kSlices);
  tip("Number of slices (0: one per voxel along the view direction)");
  combo("filter", v.filter,
        "Nearest keeps neighbouring streamlines apart, linear smooths (6.4), cubic is smooth "
        "across voxel faces; auto: cubic where a voxel covers more than 6 pixels");
  ImGui::Checkbox("jitter", &v.jitter);
  tip("Offset each pixel's samples along its ray by part of a slice spacing (no wood grain)");
  ImGui::Checkbox("orthographic", &v.camera.orthographic);
  nameWidget("view.camera.orthographic", "orthographic");
  slider("field of view", v.camera.fovY, ranges::kFov, "%.0f deg");
  slider("azimuth", v.camera.azimuth, ranges::kAzimuth, "%.1f deg");
  slider("elevation", v.camera.elevation, ranges::kElevation, "%.1f deg");
  if (ImGui::Button("Reset view (R)")) actions.resetView = true;
  ImGui::Checkbox("play bias (Space)", &ui.playing);
  tip("Cycle the bias so the texture flows along the streamlines (thesis 3.3.3)");
  ImGui::SliderFloat("speed", &ui.animationSpeed, 1.0f, 60.0f, "%.0f steps/s");
}

void filesPanel(UiState& ui, Actions& actions) {
  if (!ImGui::CollapsingHeader("Session and images")) return;
  pathText("session", ui.sessionPath, "JSON file with every parameter");
  if (ImGui::Button("Save session")) actions.saveSession = true;
  ImGui::SameLine();
  if (ImGui::Button("Load session")) actions.loadSession = true;
  if (ImGui::Button("Screenshot (F12)")) actions.screenshot = true;
  tip("The window as it is, UI included, to lic3d-screenshot-N.png. It carries the session of "
      "the picture without the panels: `lic3d render --session` remakes it");
  pathText("image", ui.imagePath, "PNG file for the image below");
  ImGui::InputInt2("size", &ui.imageWidth);
  ui.imageWidth = std::clamp(ui.imageWidth, 16, 16384);
  ui.imageHeight = std::clamp(ui.imageHeight, 16, 16384);
  if (ImGui::Button("Render image")) actions.renderImage = true;
  tip("The volume alone at this size, as `lic3d render --session` remakes it from the PNG");
}

// The app's state at the top of the panel: speed, the volume, the device, work in progress and
// the last message.
void statusSection(const Stats& stats) {
  ImGui::Text("%.1f fps   draw %.2f ms (GPU)", static_cast<double>(stats.fps), stats.frameMs);
  ImGui::TextUnformatted(stats.frameTimes.c_str());
  tip("CPU: the time between frames; GPU: the frame's LIC work and volume draw (timestamps)");
  if (!stats.licTimes.empty()) ImGui::TextUnformatted(stats.licTimes.c_str());
  tip("GPU time of the last LIC volume, summed over its frames; coarse while a LIC slider is "
      "dragged (every 2nd, 4th or 8th voxel), full when it is let go");
  if (stats.picture2D)
    ImGui::Text("%dx%d picture", stats.dims.x, stats.dims.y);
  else
    ImGui::Text("%dx%dx%d volume, %.1f MiB on the device", stats.dims.x, stats.dims.y, stats.dims.z,
                stats.volumeMiB);
  ImGui::TextUnformatted(stats.device.c_str());
  if (stats.loading) ImGui::TextColored(ImVec4(1, 0.8f, 0.2f, 1), "loading the field...");
  if (stats.waitingForMask)
    ImGui::TextColored(ImVec4(1, 0.8f, 0.2f, 1), "making the sparsity mask...");
  else if (stats.computing)
    ImGui::TextColored(ImVec4(1, 0.8f, 0.2f, 1), "computing LIC %3.0f %%",
                       100.0 * stats.computeFraction);
  if (!stats.scriptText.empty()) {
    ImGui::PushStyleColor(ImGuiCol_PlotHistogram, ImGui::GetStyleColorVec4(ImGuiCol_Header));
    ImGui::ProgressBar(stats.scriptFraction, ImVec2(-1.0f, 0.0f), stats.scriptText.c_str());
    ImGui::PopStyleColor();
    tip("--frames: the run quits after this many frames, once the picture is complete");
  }
  if (!stats.message.empty()) ImGui::TextWrapped("%s", stats.message.c_str());
  ImGui::Separator();
}

void helpPanel(UiState& ui) {
  if (!ui.help) return;
  ImGui::SetNextWindowSize(ImVec2(360, 0), ImGuiCond_FirstUseEver);
  if (ImGui::Begin("Help", &ui.help)) {
    ImGui::TextUnformatted(
        "Mouse\n"
        "  left drag            orbit\n"
        "  middle / shift+left  pan\n"
        "  wheel                zoom\n"
        "Keys\n"
        "  R          reset the view\n"
        "  Space      play / pause the bias animation\n"
        "  F12        screenshot of the window\n"
        "  H or Tab   show / hide the panels\n"
        "  F1         this help\n"
        "  Esc        quit\n"
        "\n"
        "View changes redraw at once. LIC changes recompute the\n"
        "volume in the background; the last volume stays on\n"
        "screen until the new one is complete.");
  }
  ImGui::End();
}

}  // namespace

// A request the app refused (e.g. a field too large for the device) or a lost device, until
// dismissed; shown even with the panels hidden.
void alertDialog(const Stats& stats, Actions& actions) {
  if (stats.alert.empty()) return;
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  ImGui::SetNextWindowPos(ImVec2(0.5f * display.x, 0.5f * display.y), ImGuiCond_Always,
                          ImVec2(0.5f, 0.5f));
  ImGui::SetNextWindowSize(ImVec2(ImGui::GetFontSize() * 32.0f, 0.0f), ImGuiCond_Always);
  const std::string title = (stats.alertTitle.empty() ? "lic3d" : stats.alertTitle) + "###alert";
  if (ImGui::Begin(title.c_str(), nullptr,
                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings)) {
    ImGui::TextWrapped("%s", stats.alert.c_str());
    if (ImGui::Button("OK")) actions.dismissAlert = true;
  }
  ImGui::End();
}

float panelWidth(const UiState& ui, float displayWidth) {
  if (!ui.visible) return 0.0f;
  return std::floor(std::min(380.0f, 0.45f * displayWidth));
}

Actions drawUi(Session& session, UiState& ui, const Stats& stats) {
  Actions actions;
  ui.licDragging = false;
  alertDialog(stats, actions);
  if (!ui.visible) return actions;
  helpPanel(ui);
  // Docked at the right, the full height: the volume is drawn in what is left (viewer/app.cpp).
  const ImVec2 display = ImGui::GetIO().DisplaySize;
  const float width = panelWidth(ui, display.x);
  ImGui::SetNextWindowPos(ImVec2(display.x - width, 0.0f), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(width, display.y), ImGuiCond_Always);
  const ImGuiWindowFlags flags = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                 ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings;
  if (ImGui::Begin("lic3d", nullptr, flags)) {
    ImGui::PushItemWidth(std::min(180.0f, 0.45f * width));
    statusSection(stats);
    if (!session.twoD) lookPanel(session, ui, actions);
    fieldPanel(session, ui, actions);
    timePanel(session, ui, stats);
    licPanel(session, ui);
    if (!session.twoD) sparsityPanel(session, ui, stats);
    colourPanel(session.view, ui, stats);
    if (!session.twoD) transferFunctionPanel(session.view, ui, stats);
    if (!session.twoD) {
      localPanel(session.view);
      depthPanel(session.view);
    }
    renderingPanel(session.view, ui, actions);
    filesPanel(ui, actions);
    ImGui::PopItemWidth();
    if (ImGui::Button("Help (F1)")) ui.help = !ui.help;
  }
  ImGui::End();
  return actions;
}

std::string uiMessage(const Error& error) { return rewriteKeys(error, widgetNames()); }

}  // namespace lic3d::viewer
