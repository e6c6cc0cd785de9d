// SPDX-License-Identifier: BSD-3-Clause
// What a flag given on the command line does to the parameters a look or a session set, and the
// flags that act only with another: each acts, or is refused naming the flag it needs, before
// any work (docs/LOOKS.md, "Flags that need another").
#include <string>

#include "options/flags.h"
#include "options/session_options.h"

namespace lic3d::cli {
namespace {

bool givenFlag(const SessionOptions& options, const char* flag) {
  return options.app && given(options.app->get_option_no_throw(flag));
}

Result<void> needs(const SessionOptions& options, const char* flag, bool satisfied,
                   const std::string& need) {
  if (!givenFlag(options, flag) || satisfied) return {};
  return inputError(std::string(flag) + " acts only " + need);
}

Result<void> notBoth(const SessionOptions& options, const char* a, const char* b,
                     const std::string& why) {
  if (givenFlag(options, a) && givenFlag(options, b))
    return inputError(std::string(a) + " and " + b + " both " + why + ": give one");
  return {};
}

// Flags that would be ignored without another, or beside another.
Result<void> checkFlagNeeds(const SessionOptions& options) {
  const Session& s = options.session;
  const ViewParams& v = s.view;
  using D = SparsityDistribution;
  const D d = s.lic.sparsity.distribution;
  const bool mask = d != D::None;
  for (const char* flag : {"--sparsity-amount", "--sparsity-points", "--sparsity-radius",
                           "--sparsity-ratio", "--sparsity-seed"})
    LIC3D_TRY(needs(options, flag, mask, "with a sparsity mask: add --sparsity DISTRIBUTION"));
  LIC3D_TRY(needs(options, "--sparsity-points", !mask || (d != D::Checkerboard && d != D::Jitter),
                  "with --sparsity poisson, poisson-approx, halton or hammersley"));
  LIC3D_TRY(needs(options, "--sparsity-radius", !mask || d == D::Poisson || d == D::Jitter,
                  "with --sparsity poisson or jitter"));
  LIC3D_TRY(needs(options, "--sparsity-ratio", !mask || d == D::Checkerboard,
                  "with --sparsity checkerboard"));
  for (const char* flag : {"--sparsity-points", "--sparsity-radius", "--sparsity-ratio"})
    LIC3D_TRY(notBoth(options, "--sparsity-amount", flag, "set how much the mask hides"));

  const bool fileNoise = !s.noise.file.empty();
  LIC3D_TRY(needs(options, "--seed", !fileNoise, "with noise lic3d makes, not with --noise FILE"));
  LIC3D_TRY(needs(options, "--seed-fraction", !fileNoise,
                  "with noise lic3d makes, not with --noise FILE"));
  LIC3D_TRY(notBoth(options, "--seed-noise", "--seed-fraction", "choose the seed noise"));

  LIC3D_TRY(needs(options, "--fog-color", v.fog, "with depth cueing: add --fog START,END"));
  for (const char* flag : {"--eye-separation", "--zero-parallax"})
    LIC3D_TRY(needs(options, flag, v.stereo != StereoMode::None,
                    "with stereo: add --stereo anaglyph or side-by-side"));
  for (const char* flag : {"--roi-center", "--roi-size", "--roi-rotate", "--roi-outside"})
    LIC3D_TRY(needs(options, flag, v.roi != RoiShape::None,
                    "with a region of interest: add --roi sphere, cube or cylinder"));
  LIC3D_TRY(needs(options, "--halo-radius", v.halo > 0.0f, "with halos: add --halo S"));
  LIC3D_TRY(
      needs(options, "--opacity-floor", v.magnitudeOpacity > 0.0f || v.magnitudeThreshold > 0.0f,
            "with opacity by a scalar: add --magnitude-opacity E or --magnitude-threshold T"));
  LIC3D_TRY(notBoth(options, "--alpha", "--optical-depth", "set the opacity per voxel"));
  LIC3D_TRY(notBoth(options, "--window", "--window-percentiles", "set the grey window"));
  LIC3D_TRY(notBoth(options, "--contrast", "--window-percentiles", "set the grey window"));
  LIC3D_TRY(notBoth(options, "--contrast", "--window", "set the grey window"));
  const bool tfOpacities = !v.transfer.opacities.empty() && givenFlag(options, "--tf");
  for (const char* flag : {"--magnitude-opacity", "--magnitude-threshold"})
    if (givenFlag(options, flag) && tfOpacities)
      return inputError(std::string(flag) + ": the --tf opacities replace it; give one");
  if (givenFlag(options, "--colormap") && givenFlag(options, "--tf") && !v.transfer.colors.empty())
    return inputError("--colormap and --tf both set the colours: give one");
  // applyViewOptions has made the colour Magnitude for --color-by: the flag's own text tells.
  if (givenFlag(options, "--color-by") && givenFlag(options, "--color") &&
      options.app->get_option("--color")->as<ColorMode>() == ColorMode::None)
    return inputError("--color-by colours by a scalar: not with --color none");
  return {};
}

}  // namespace

Result<void> applyFlagRules(SessionOptions& options) {
  LIC3D_TRY(checkFlagNeeds(options));
  Session& s = options.session;
  ViewParams& v = s.view;
  // A flag given wins over the look (or the session) that set what it overrides.
  if (givenFlag(options, "--alpha")) v.opticalDepth = 0.0f;
  if (givenFlag(options, "--contrast")) v.percentileWindow = false;
  if (givenFlag(options, "--seed-noise")) s.noise.seedFraction = 0.0f;
  // Colouring by a quantity makes the opacity follow it unless --opacity-by says otherwise.
  if (givenFlag(options, "--color-by") && !givenFlag(options, "--opacity-by"))
    v.opacityBy = v.colorBy;
  // A colour map or transfer function chosen is drawn as chosen, signed scalar or not.
  if (givenFlag(options, "--colormap") || givenFlag(options, "--tf")) v.divergingWhenSigned = false;
  return {};
}

}  // namespace lic3d::cli
