// SPDX-License-Identifier: BSD-3-Clause
#include "core/look.h"

#include "core/session.h"

namespace lic3d {
namespace {

// Ray optical depth the looks aim at: about a third of the light crosses a typical ray through
// the whole volume (exp(-1.1)), so the inside shows and the structure still reads as solid.
constexpr float kSeeThroughDepth = 1.1f;

}  // namespace

void applyLook(Look look, Session& session) {
  ViewParams& v = session.view;
  LicParams& lic = session.lic;
  const ViewParams defaults;
  session.look = look;
  // What every look sets: start from the thesis' dense look.
  v.color = defaults.color;
  v.colormap = defaults.colormap;
  v.divergingWhenSigned = defaults.divergingWhenSigned;
  v.colorBy = defaults.colorBy;
  v.opacityBy = defaults.opacityBy;
  v.rangeTail = defaults.rangeTail;
  v.alpha = defaults.alpha;
  v.opticalDepth = defaults.opticalDepth;
  v.opacityMode = defaults.opacityMode;
  v.contrast = defaults.contrast;
  v.percentileWindow = defaults.percentileWindow;
  v.windowPercentiles = defaults.windowPercentiles;
  v.manualWindow = defaults.manualWindow;
  v.magnitudeOpacity = defaults.magnitudeOpacity;
  v.magnitudeThreshold = defaults.magnitudeThreshold;
  v.lighting = defaults.lighting;
  v.filter = defaults.filter;
  session.noise.seedSpots = 0;
  session.noise.seedFraction = 0.0f;
  lic.sparsity = SparsityParams{};
  if (look == Look::Dense) return;

  // Colour and opacity follow speed; a ray meets a fixed optical depth whatever the data's
  // speeds; empty space (below 2 % of the speed range) vanishes; the fastest 0.1 % saturate.
  v.color = ColorMode::Magnitude;
  v.colormap = Colormap::Viridis;
  v.rangeTail = kLookRangeTail;
  v.opticalDepth = kSeeThroughDepth;
  v.magnitudeOpacity = 1.5f;
  v.magnitudeThreshold = kEmptySpeedFraction;
  if (look == Look::Streamlines) {
    // A seed in about every 700th flowing voxel: streamlines 10 voxels long each way seldom
    // overlap. Most voxels meet no seed and stay black, so the window comes from the top of the
    // LIC values (about 6 % of the voxels are lit on the tornado).
    session.noise.seedFraction = 0.0015f;
    v.percentileWindow = true;
    v.windowPercentiles = {0.85f, 0.95f};
    v.magnitudeOpacity = 0.5f;
    v.lighting = Lighting::Lines;
  } else if (look == Look::Sparse) {
    lic.sparsity.distribution = SparsityDistribution::Poisson;
    lic.sparsity.amount = 0.5f;
    v.magnitudeOpacity = 0.5f;
    // Thesis 6.4: nearest sampling keeps the drawn voxels apart; trilinear sampling smears the
    // drawn flag over the hidden neighbours and the volume turns dark.
    v.filter = VolumeFilter::Nearest;
  }
}

}  // namespace lic3d
