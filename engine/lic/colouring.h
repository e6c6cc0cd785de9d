// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// LIC values as colours on the CPU, with the grey transfer and colour by magnitude that the 3D
// slices draw (ViewParams, core/view_params.h): the 2D LIC picture and the RGBA volume.

#include <cstdint>
#include <vector>

#include "core/rgba_image.h"
#include "core/view_params.h"
#include "core/volume.h"
#include "io/field_io.h"
#include "io/volume_io.h"

namespace lic3d {

// Per pixel: grey = the grey transfer of the LIC value (contrast stretch of the image's own mean
// and deviation, or the window; then gain and brightness); with colour by magnitude, the colour
// map at |v| (the field bilinearly interpolated at the pixel, physical units, over the colour
// range: by default the field's min and max |v| over its voxels) times grey. Opaque; rows from
// the top, so the highest y is the top row. With a legend asked for (and colour), it is drawn
// at the right edge. `lic` is the image of computeLic2DReference or Lic2DPass on `field`.
// `outside` (a plane at any orientation, lic/field_plane.h) marks the plane's points outside the
// field's box: their pixels are the background and do not count in the contrast stretch.
RgbaImage colourLic2D(const ScalarVolume& lic, const VectorField& field, const ViewParams& view,
                      const std::vector<std::uint8_t>& outside = {});

// The scalars colour and opacity follow when not the speed (loading/scalars.h), on the LIC grid;
// null for the speed.
struct VolumeScalars {
  const PointScalars* color = nullptr;
  const PointScalars* opacity = nullptr;
};

// The colour-mapped LIC volume as 8-bit RGBA, per voxel what the slice shader assigns before
// lighting, fog, clipping and the region of interest: grey = the grey transfer (contrast,
// window, gain, brightness) of the LIC value; RGB = grey, or with colour the colour map (or the
// transfer function's colours) at the colour scalar over the colour range times grey; A = the
// opacity per voxel of depth: alpha (times grey with intensity opacity, times the opacity weight
// of the opacity scalar), 0 where sparsity hides the voxel or a scalar is NaN. Not
// premultiplied. `facts` are those the slices drew the volume with.
RgbaVolume colourLicVolume(const ScalarVolume& lic, const VectorField& field,
                           const ViewParams& view, const TransferFacts& facts,
                           const VolumeScalars& scalars = {});

}  // namespace lic3d
