// SPDX-License-Identifier: BSD-3-Clause
#include "core/look.h"

#include "core/session.h"
#include "core/value_histogram.h"

namespace lic3d {
namespace {

// Ray optical depth the looks aim at: about 60 % of the light crosses a typical ray through the
// whole volume (exp(-0.5)), so a layer of flow behind another still shows (docs/LOOKS.md).
constexpr float kSeeThroughDepth = 0.5f;
// The least opacity weight of flow above the empty-space threshold: the magnetic mirror's
// central field lines, at a tenth of the coils' |B|, stay in the picture.
constexpr float kWeakFlowOpacity = 0.15f;
// Depth cues, chosen by rendering every gallery field with and without (docs/LOOKS.md).
constexpr float kSeeThroughHalo = 0.3f;
constexpr float kStreamlinesHalo = 0.4f;

}  // namespace

double emptySpaceSpeed(const ValueHistogram& speeds) {
  return kEmptySpeedFraction * speeds.percentile(1.0 - kLookRangeTail);
}

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
  v.opacityFloor = defaults.opacityFloor;
  v.halo = defaults.halo;
  v.occlusion = defaults.occlusion;
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
  v.opacityFloor = kWeakFlowOpacity;
  v.halo = kSeeThroughHalo;
  if (look == Look::Streamlines) {
    // A seed in about every 700th flowing voxel: streamlines 10 voxels long each way seldom
    // overlap. Most voxels meet no seed and stay black, so the window comes from the top of the
    // LIC values (about 6 % of the voxels are lit on the tornado).
    session.noise.seedFraction = 0.0015f;
    v.percentileWindow = true;
    v.windowPercentiles = {0.85f, 0.95f};
    v.magnitudeOpacity = 0.5f;
    v.lighting = Lighting::Lines;
    v.halo = kStreamlinesHalo;
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
