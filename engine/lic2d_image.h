#pragma once
// The 2D LIC image as a picture: the same grey transfer and colour by magnitude as the 3D
// slices draw (ViewParams), computed on the CPU from the image's values, with the legend.

#include "rgba_image.h"
#include "view_params.h"
#include "volume.h"

namespace lic3d {

// Per pixel: grey = the grey transfer of the LIC value (contrast stretch of the image's own mean
// and deviation, or the window; then gain and brightness); with colour by magnitude, the colour
// map at |v| (the field bilinearly interpolated at the pixel, physical units, over the colour
// range: by default the field's min and max |v| over its voxels) times grey. Opaque; rows from
// the top, so the highest y is the top row. With a legend asked for (and colour), it is drawn
// at the right edge. `lic` is the image of computeLic2DReference or Lic2DPass on `field`.
RgbaImage colourLic2D(const ScalarVolume& lic, const VectorField& field, const ViewParams& view);

}  // namespace lic3d
