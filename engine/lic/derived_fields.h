// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Scalars derived from the vector field, for colour and opacity (ViewParams::colorBy, opacityBy):
// speed, the vorticity magnitude and the helicity. Computed on the CPU once per field (the
// derivatives need the neighbours of every voxel, a pass the GPU would run once as well, and the
// automatic ranges need their histogram on the host anyway).

#include <optional>
#include <string_view>

#include "core/enum_names.h"
#include "core/volume.h"
#include "io/field_io.h"

namespace lic3d {

enum class DerivedQuantity {
  Speed,      // |v|
  Vorticity,  // |curl v|
  Helicity,   // v . curl v
};
LIC3D_ENUM_NAMES(DerivedQuantity, {DerivedQuantity::Speed, "speed"},
                 {DerivedQuantity::Vorticity, "vorticity"}, {DerivedQuantity::Helicity, "helicity"})

// The quantity a colour-by or opacity-by name asks for, if it is one of these names.
std::optional<DerivedQuantity> derivedQuantity(std::string_view name);

// The quantity at every voxel, in the file's units: derivatives by central differences over the
// physical spacing (one-sided on the faces; 0 along an axis of one voxel). `unit` is the vectors'
// unit (for speed; the others have none, since the length unit of the grid is not known).
// Threads: 0 = availableThreads().
PointScalars derivedScalars(const VectorField& field, DerivedQuantity quantity,
                            const std::string& unit = {}, unsigned threads = 0);

}  // namespace lic3d
