// SPDX-License-Identifier: BSD-3-Clause
// The view flags of `render` and the app (ViewParams), the look, and the picture flags of
// `render2d`.
#include <map>
#include <string>

#include "core/look.h"
#include "io/session_file.h"
#include "options/flags.h"
#include "options/session_options.h"

namespace lic3d::cli {

namespace {

// Grey mapping and colour, the same for the volume (`render`) and the 2D image (`render2d`):
// `what` names what the contrast stretch measures, `colorNote` ends the --color help.
void addGreyAndColorOptions(CLI::App& app, SessionOptions& options, const char* what,
                            const char* colorNote) {
  ViewParams& view = options.session.view;
  addText(app, "--contrast", options.contrast,
          std::string("on: stretch ") + what +
              " LIC values to mean 0.5 and deviation 0.25 (a histogram stretch); off: grey = "
              "LIC value",
          "on")
      .option->check(CLI::IsMember({"on", "off"}));
  addText(app, "--window", options.window,
          "Intensity window mapped to black..white instead of the contrast stretch: auto or "
          "LO,HI in 0..1",
          "auto", "view.window");
  addText(app, "--window-percentiles", options.windowPercentiles,
          "Intensity window from percentiles of the drawn voxels' LIC values instead: LO,HI "
          "fractions in 0..1 (the streamlines look's 0.85,0.95, which the contrast stretch also "
          "takes when the LIC values are those of seed noise)",
          "", "view.window_percentiles");
  addRanged(app, "--gain", view.gain, ranges::kGain, "Scales grey values around mid-grey");
  addRanged(app, "--brightness", view.brightness, ranges::kBrightness,
            "Added to grey values (-1..1)");
  addEnumOption(app, "--color", view.color,
                std::string("none: grey LIC; magnitude: colour by |v| through --colormap, the LIC "
                            "intensity modulating it") +
                    colorNote);
  addText(app, "--colormap", options.colormap,
          "Colour map: " + enumChoices<Colormap>() +
              ", or a ParaView colour-map preset (.json, its RGBPoints; as --tf without the "
              "opacities)",
          std::string(enumName(view.colormap)), "view.colormap");
  addText(app, "--color-range", options.colorRange,
          "Values mapped to the ends of the colour map: auto (the colour scalar's min and max, "
          "or its percentiles with a look) or MIN,MAX",
          "auto", "view.color_range");
  app.add_flag("--legend", view.legend,
               "Draw the colour legend into the image (with --color magnitude)");
}

// The size of the annotation's text and the legend's title (render, render2d and the app);
// `render` and the app also take --scale.
void addTextOptions(CLI::App& app, SessionOptions& options, bool scale = true) {
  ViewParams& view = options.session.view;
  addRanged(app, "--font-size", view.fontSize, ranges::kFontSize,
            "Size of the legend's, the title's and the axes' text in pixels (the em; lines and "
            "ticks follow it); 0: 1/50 of the picture's height, 20 at 1024");
  app.add_option(
      "--legend-title", view.legendTitle,
      "The legend's title, e.g. '|B| [T]' (default: the colour quantity and its unit where "
      "the file gives one, 'speed [m/s]')");
  nameFlag("view.legend_title", "--legend-title");
  if (scale)
    addRanged(app, "--scale", options.scale, ranges::kScale,
              "Make the picture this many times larger with the same layout: --width, --height "
              "and --font-size times it (a poster from a figure's settings; the session records "
              "the sizes it gives)");
}

}  // namespace

void addLookOption(CLI::App& app, SessionOptions& options) {
  options.looks = true;
  std::map<std::string, Look> names;
  for (const EnumName<Look>& n : enumNames<Look>()) names.emplace(std::string(n.name), n.value);
  app.add_option("--look", options.lookName,
                 "A set of display parameters tuned from the data, which later flags refine: "
                 "see-through (colour and opacity by speed; the default), dense (the thesis' "
                 "opaque block), streamlines (seed noise, illuminated lines), sparse (a Poisson "
                 "mask hides half of the streamlines): " +
                     enumChoices<Look>())
      ->check(CLI::IsMember(names))
      ->default_str(std::string(enumName(kDefaultLook)));
}

void addViewOptions(CLI::App& app, SessionOptions& options) {
  ViewParams& view = options.session.view;
  addRanged(app, "--width", view.width, ranges::kImageWidth, "Image width in pixels");
  addRanged(app, "--height", view.height, ranges::kImageHeight, "Image height in pixels");
  addRanged(app, "--slices", view.slices, ranges::kSlices,
            "Number of slices (0: one per voxel along the view direction)");
  addEnumOption(app, "--slicing", view.slicing,
                "Slice planes: view (perpendicular to the view direction) or axis (perpendicular "
                "to the grid axis closest to it)");
  addRanged(app, "--azimuth", view.camera.azimuth, ranges::kAzimuth,
            "Camera azimuth in degrees around +z");
  addRanged(app, "--elevation", view.camera.elevation, ranges::kElevation,
            "Camera elevation in degrees");
  addRanged(app, "--distance", view.camera.distance, ranges::kDistance,
            "Camera distance from the volume centre (the longest box side is 1; 0 fits the "
            "whole volume)");
  addRanged(app, "--fov", view.camera.fovY, ranges::kFov, "Vertical field of view in degrees");
  app.add_flag("--ortho", view.camera.orthographic, "Orthographic projection");
  nameFlag("view.camera.orthographic", "--ortho");
  addRanged(app, "--alpha", view.alpha, ranges::kAlpha,
            "Opacity per voxel of depth, corrected for the slice spacing (0: invisible); "
            "turns the look's --optical-depth off");
  addEnumOption(app, "--opacity", view.opacityMode,
                "Opacity transfer: constant (alpha everywhere) or intensity (alpha x grey, so "
                "dark gaps between streamlines turn clear)");
  addEnumOption(app, "--filter", view.filter,
                "Sampling of the LIC volume by the slices: nearest and linear (thesis 6.4), the "
                "cubic B-spline, or auto (cubic where a voxel covers more than 6 pixels)");
  addText(app, "--background", options.background,
          "Background colour R,G,B: components in 0..1, or 0..255 if any exceeds 1", "0,0,0",
          "view.background");

  addGreyAndColorOptions(app, options, "the drawn voxels'", " (thesis 5.1.2)");
  app.add_flag("--axes", view.axes,
               "Draw the box's edges and label each axis with its physical range (the grid's "
               "origin and spacing)");
  app.add_option("--title", view.title, "A title drawn above the picture");
  nameFlag("view.title", "--title");
  addTextOptions(app, options);
  options.colorBy =
      app.add_option(
             "--color-by", view.colorBy,
             "What the colour follows (implies --color magnitude; the opacity follows it too "
             "unless --opacity-by is given; a signed scalar takes coolwarm over a range "
             "symmetric about 0 unless --colormap, --tf or --color-range): speed, vorticity "
             "(|curl v|), helicity (v . curl v), a scalar array of the field's file by name "
             "(VTK SCALARS, a 1-component VTI array), or a scalar .nrrd on the field's grid")
          ->capture_default_str();
  nameFlag("view.color_by", "--color-by");
  options.opacityBy =
      app.add_option("--opacity-by", view.opacityBy,
                     "What the opacity follows (through --magnitude-opacity or the --tf opacities; "
                     "alone it implies --magnitude-opacity 1): the names of --color-by")
          ->capture_default_str();
  nameFlag("view.opacity_by", "--opacity-by");
  addText(app, "--tf", options.transferFunction,
          "Transfer function: a ParaView colour-map preset (.json: RGBPoints x r g b ..., "
          "Points x opacity midpoint sharpness ...), rescaled to the colour (and opacity) "
          "range; its colours replace --colormap, its opacities --magnitude-opacity",
          "", "view.transfer_function");
  addRanged(app, "--optical-depth", view.opticalDepth, ranges::kOpticalDepth,
            "Choose alpha from the data so a ray through the volume meets this optical depth "
            "(0: use --alpha)");
  addText(app, "--clip-plane", options.clipPlane,
          "Cut the volume with a plane at any orientation: PX,PY,PZ,NX,NY,NZ, a point as "
          "fractions of the box and a normal in box axes; the side the normal points into is "
          "removed",
          "", "view.clip_plane_point");
  nameFlag("view.clip_plane_normal", "--clip-plane");
  addRanged(app, "--magnitude-opacity", view.magnitudeOpacity, ranges::kMagnitudeOpacity,
            "Opacity x (normalised |v|)^E so slow regions fade (thesis 5.1.3); 0 is off");
  addRanged(app, "--magnitude-threshold", view.magnitudeThreshold, ranges::kMagnitudeThreshold,
            "Voxels whose normalised |v| is below this vanish");

  addText(app, "--clip", options.clip,
          "Keep X0..X1, Y0..Y1, Z0..Z1 of the box, as fractions (thesis 5.2.1)", "0,1,0,1,0,1",
          "view.clip_min");
  nameFlag("view.clip_max", "--clip");
  addEnumOption(app, "--roi", view.roi, "Region of interest (thesis 5.2.2)");
  addText(app, "--roi-center", options.roiCenter, "Centre X,Y,Z as fractions of the box",
          "0.5,0.5,0.5", "view.roi_center");
  addRanged(app, "--roi-size", view.roiSize, ranges::kRoiSize,
            "Diameter (sphere, cylinder) or side (cube) as a fraction of the longest box side");
  addText(app, "--roi-rotate", options.roiRotate,
          "Rotation AX,AY,AZ in degrees (about x, then y, then z)", "0,0,0", "view.roi_rotation");
  app.add_flag("--roi-outside", view.roiOutside, "Keep the outside of the region instead");

  addText(app, "--fog", options.fog,
          "Depth cueing START,END: fog grows linearly from START to END, fractions of the depth "
          "from the volume's nearest to its farthest point (thesis 5.3.1)",
          "", "view.fog_range");
  addText(app, "--fog-color", options.fogColor, "Fog colour R,G,B (default: the background)", "",
          "view.fog_color");

  addEnumOption(app, "--stereo", view.stereo,
                "Stereo with an off-axis frustum (thesis 5.3.2): anaglyph is red left, cyan "
                "right; side-by-side is left|right, twice the width");
  nameFlag("view.stereo", "--stereo");
  addRanged(app, "--eye-separation", view.eyeSeparation, ranges::kEyeSeparation,
            "Distance between the eyes in box units (0: zero-parallax distance / 30)");
  addRanged(app, "--zero-parallax", view.zeroParallax, ranges::kZeroParallax,
            "Distance from the eye of the plane that shows no disparity (0: the volume "
            "centre)");
  addEnumOption(app, "--lighting", view.lighting,
                "phong: normals from the streamline's TNB frame (thesis 5.3.3); lines: "
                "illuminated lines, lit from the tangent alone; gradient: Phong with the "
                "streak's normal, the LIC gradient across the flow");
  addRanged(app, "--opacity-floor", view.opacityFloor, ranges::kOpacityFloor,
            "The least opacity weight of flow above --magnitude-threshold, so weak flow stays "
            "visible (0: none)");
  addRanged(app, "--halo", view.halo, ranges::kHalo,
            "Halos: around each streak, up to this times its opacity in the background colour, "
            "so a near streak visibly crosses a far one (0: off)");
  addRanged(app, "--halo-radius", view.haloRadius, ranges::kHaloRadius,
            "How far the halos reach from a streak, in voxels");
  addRanged(app, "--occlusion", view.occlusion, ranges::kOcclusion,
            "Occlusion shading: each slice darkened by the opacity in front of it, spread over a "
            "cone towards the viewer, by up to this fraction (0: off)");
  addText(app, "--jitter", options.jitter,
          "on: each pixel's samples offset along its ray by part of a slice spacing (no "
          "wood-grain pattern); off: plain slicing",
          "on")
      .option->check(CLI::IsMember({"on", "off"}));
}

void addPlaneOptions(CLI::App& app, SessionOptions& options, PlaneOptions& plane) {
  PlaneParams& p = options.session.plane;
  addRanged(app, "--width", p.width, ranges::kPlaneWidth.atLeast(1),
            "Width of the LIC image in pixels (default: the field's grid; with --height alone, "
            "keeping the grid's aspect). Larger than the grid, the noise is finer than "
            "the field and the picture stays sharp");
  addRanged(app, "--height", p.height, ranges::kPlaneHeight.atLeast(1),
            "Height of the LIC image in pixels (see --width)");
  addText(app, "--slice", plane.slice,
          "The plane of a 3D field (analytic or file): AXIS or AXIS:INDEX, x, y or z, INDEX in "
          "voxels (default z, the middle layer)",
          "", "plane.index");
  nameFlag("plane.axis", "--slice");
  addText(app, "--plane", plane.oblique,
          "A plane at any orientation instead of --slice: PX,PY,PZ,NX,NY,NZ, a point as "
          "fractions of the box and a normal in box axes (0,0,1 is a z layer); the plane is "
          "sampled at the field's finest spacing, its part outside the box is background",
          "", "plane.point");
  nameFlag("plane.normal", "--plane");
  addGreyAndColorOptions(app, options, "the image's", "");
  addTextOptions(app, options, false);
  addText(app, "--background", options.background,
          "Background colour R,G,B the legend's text is set against (0..1, or 0..255)", "0,0,0",
          "view.background");
}

Result<void> finishPlaneOptions(const PlaneOptions& plane, Session& session) {
  if (plane.oblique.given()) {
    if (plane.slice.given())
      return inputError("--plane and --slice both choose the plane: give one");
    LIC3D_TRY_ASSIGN(const std::vector<float> p, parseFloatList(plane.oblique.text, "--plane", 6));
    session.plane.oblique = true;
    session.plane.point = {p[0], p[1], p[2]};
    session.plane.normal = {p[3], p[4], p[5]};
    return {};
  }
  if (!plane.slice.given()) return {};
  const std::size_t colon = plane.slice.text.find(':');
  const std::string axis = plane.slice.text.substr(0, colon);
  int index = -1;
  if (axis != "x" && axis != "y" && axis != "z")
    return inputError("--slice: expected AXIS or AXIS:INDEX with AXIS x, y or z, got '" +
                      plane.slice.text + "'");
  if (colon != std::string::npos) {
    LIC3D_TRY_ASSIGN(
        index, parseNumber<int>(std::string_view(plane.slice.text).substr(colon + 1), "--slice"));
    if (index < 0)
      return inputError("--slice: the index of '" + plane.slice.text + "' must be 0 or more");
  }
  session.plane.axis = axis[0] - 'x';
  session.plane.index = index;
  return {};
}

Result<void> applyViewOptions(SessionOptions& options) {
  Session& s = options.session;

  ViewParams& view = s.view;
  if (options.background.given()) {
    LIC3D_TRY_ASSIGN(view.background, parseColor(options.background.text, "--background"));
  }
  if (options.contrast.given()) view.contrast = options.contrast.text == "on";
  if (options.jitter.given()) view.jitter = options.jitter.text == "on";
  if (options.window.given()) {
    view.manualWindow = options.window.text != "auto";
    if (view.manualWindow) {
      LIC3D_TRY_ASSIGN(const std::vector<float> w,
                       parseFloatList(options.window.text, "--window", 2));
      view.windowLow = w[0];
      view.windowHigh = w[1];
    }
  }
  if (options.colormap.given()) {
    if (const std::optional<Colormap> map = parseEnum<Colormap>(options.colormap.text)) {
      view.colormap = *map;
      view.transfer.colors.clear();
    } else {
      LIC3D_TRY_ASSIGN(const TransferFunction tf, readTransferFunction(options.colormap.text));
      if (tf.colors.empty())
        return inputError("--colormap " + options.colormap.text + ": the preset has no RGBPoints");
      view.transfer.name = tf.name;
      view.transfer.colors = tf.colors;
    }
  }
  if (options.transferFunction.given()) {
    LIC3D_TRY_ASSIGN(view.transfer, readTransferFunction(options.transferFunction.text));
  }
  if (options.colorBy && options.colorBy->count() > 0 && view.color == ColorMode::None)
    view.color = ColorMode::Magnitude;
  if (options.opacityBy && options.opacityBy->count() > 0 && view.magnitudeOpacity == 0.0f &&
      view.transfer.opacities.empty())
    view.magnitudeOpacity = 1.0f;
  if (options.clipPlane.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> c,
                     parseFloatList(options.clipPlane.text, "--clip-plane", 6));
    view.clipPlane = true;
    view.clipPlanePoint = {c[0], c[1], c[2]};
    view.clipPlaneNormal = {c[3], c[4], c[5]};
  }
  if (options.windowPercentiles.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> w,
                     parseFloatList(options.windowPercentiles.text, "--window-percentiles", 2));
    view.percentileWindow = true;
    view.manualWindow = false;
    view.windowPercentiles = {w[0], w[1]};
  }
  if (options.colorRange.given()) {
    view.autoColorRange = options.colorRange.text == "auto";
    if (!view.autoColorRange) {
      LIC3D_TRY_ASSIGN(const std::vector<float> r,
                       parseFloatList(options.colorRange.text, "--color-range", 2));
      view.colorLow = r[0];
      view.colorHigh = r[1];
    }
  }
  if (view.legend && view.color != ColorMode::Magnitude)
    return inputError("--legend shows the colour map: use it with --color magnitude");
  if (options.clip.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> clip, parseFloatList(options.clip.text, "--clip", 6));
    view.clipMin = {clip[0], clip[2], clip[4]};
    view.clipMax = {clip[1], clip[3], clip[5]};
  }
  if (options.roiCenter.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> c,
                     parseFloatList(options.roiCenter.text, "--roi-center", 3));
    view.roiCenter = {c[0], c[1], c[2]};
  }
  if (options.roiRotate.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> r,
                     parseFloatList(options.roiRotate.text, "--roi-rotate", 3));
    view.roiRotation = {r[0], r[1], r[2]};
  }
  if (options.fog.given()) {
    LIC3D_TRY_ASSIGN(const std::vector<float> fog, parseFloatList(options.fog.text, "--fog", 2));
    view.fog = true;
    view.fogStart = fog[0];
    view.fogEnd = fog[1];
  }
  if (options.fogColor.given()) {
    LIC3D_TRY_ASSIGN(view.fogColor, parseColor(options.fogColor.text, "--fog-color"));
    view.fogColorFromBackground = false;
  }
  if (options.scale != 1.0f) {
    view = scaledView(view, options.scale);
    if (view.width > kMaxImageSize || view.height > kMaxImageSize)
      return parameterError("scale", "makes the picture " + std::to_string(view.width) + "x" +
                                         std::to_string(view.height) + ", more than " +
                                         std::to_string(kMaxImageSize) + " pixels a side");
  }
  return {};
}

}  // namespace lic3d::cli
