// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the panels decide without ImGui, so that tests can check it: how a long path is shortened
// to fit its box, which control sets the opacity, and which preset file the transfer function
// came from.

#include <functional>
#include <string>
#include <string_view>

#include "core/view_params.h"
#include "options/session_options.h"

namespace lic3d::viewer {

// The width of a text in pixels (ImGui::CalcTextSize in the app).
using TextWidth = std::function<float(std::string_view)>;

// `path` as it fits in `width` pixels: the whole path when it fits; else its file name with the
// directory elided in the middle ("/home/.../data/carotid.vtk"): the file name whole, as many
// of the nearest folders as fit in about half of the rest, then as much of the start as fits.
// A file name that cannot fit alone keeps its start and its extension ("very_lo...name.vtk").
std::string elidePath(const std::string& path, float width, const TextWidth& textWidth);

// What sets the alpha per voxel of depth: an optical depth (ViewParams::opticalDepth > 0,
// the looks' choice: alpha is chosen from the data) or the alpha slider.
enum class OpacitySource { OpticalDepth, Alpha };
OpacitySource opacitySource(const ViewParams& view);

// Switches what sets the opacity, keeping the picture as it is where it can: to the alpha the
// optical depth resolved to (`resolvedAlpha`, < 0 when unknown: alpha stays), or back to the
// optical depth last used (`lastDepth`, which remembers the depth switched away from).
void setOpacitySource(ViewParams& view, OpacitySource source, float resolvedAlpha,
                      float& lastDepth);

// The line under the opacity controls that says what sets the opacity, e.g. "optical depth
// 1.10 sets the opacity: alpha 0.034 per voxel, chosen from the data".
std::string opacityCaption(const ViewParams& view, float resolvedAlpha);

// The preset file the session's transfer function was read from at the start: --tf, else a
// --colormap that names a preset file rather than a colour map; empty when neither was given.
std::string startupPresetFile(const cli::SessionOptions& inputs);

}  // namespace lic3d::viewer
