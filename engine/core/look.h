// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Looks: named sets of display parameters that show a field's inside without hand-tuning. A look
// sets relative parameters only (percentiles, optical depth, fractions of the data's ranges),
// which the renderer resolves against the data, so one look fits the tornado, a carotid artery
// and a magnetic field alike. Parameters given after the look override it.

#include <cstdint>

#include "core/enum_names.h"

namespace lic3d {

struct Session;
struct ValueHistogram;

enum class Look : std::uint32_t {
  Dense,        // the thesis' look: white noise, grey, constant-ish opacity; an opaque block
  SeeThrough,   // colour and opacity by speed: slow and empty space turn clear (the default)
  Streamlines,  // sparse seed noise, a percentile window, illuminated lines coloured by speed
  Sparse,       // a Poisson-disk mask hides half of the streamlines, brightness compensated
};
LIC3D_ENUM_NAMES(Look, {Look::Dense, "dense"}, {Look::SeeThrough, "see-through"},
                 {Look::Streamlines, "streamlines"}, {Look::Sparse, "sparse"})

// What `lic3d render` and the app show when neither a look nor a session is given.
inline constexpr Look kDefaultLook = Look::SeeThrough;

// Empty space, for the looks: voxels slower than this fraction of the field's fast speeds (the
// speed below which a fraction kLookRangeTail of the voxels lie above) are transparent, and seed
// noise places its seeds by the voxels faster than it. Zero, NaN (read as zero) and masked
// vectors lie below it on any field; the carotid's still tissue (97 % of its voxels under 1 %
// of the fast speeds) too.
inline constexpr float kEmptySpeedFraction = 0.02f;
inline constexpr float kLookRangeTail = 0.001f;
// The physical speed below which a field's voxels are empty space, from its speedHistogram
// (core/value_histogram.h): kEmptySpeedFraction of the speed a fraction kLookRangeTail of its
// voxels lie above. 0 for a field that is zero everywhere.
double emptySpaceSpeed(const ValueHistogram& speeds);

// Sets the look's parameters in `session` (its view, the noise, LIC sparsity and length) and
// session.look; everything else keeps its value.
void applyLook(Look look, Session& session);

}  // namespace lic3d
