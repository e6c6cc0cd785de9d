// SPDX-License-Identifier: BSD-3-Clause
#include "cli/compute_vdb.h"

#include "core/look.h"
#include "core/parallel.h"
#include "core/stage_times.h"
#include "core/value_histogram.h"
#include "io/file_util.h"
#include "io/vdb_write.h"
#include "lic/derived_fields.h"
#include "loading/scalars.h"

namespace lic3d::cli {

bool isVdbOutput(const std::string& output) { return lowerCaseExtension(output) == ".vdb"; }

Result<VdbScalars> loadVdbScalars(const ComputeOptions& options, SessionInputs& inputs) {
  const Session& session = options.inputs.session;
  VdbScalars scalars;
  {
    const StageTimer timer("scalars");
    const bool hostField = !inputs.series && !inputs.field.vectors.empty();
    std::optional<VectorField> blended;
    if (!hostField) {
      LIC3D_TRY_ASSIGN(blended, hostFieldAt(inputs, session, session.time));
    }
    const VectorField& field = hostField ? inputs.field : *blended;
    scalars.speed = derivedScalars(field, DerivedQuantity::Speed, inputs.info.unit);
    scalars.emptySpeed = emptySpaceSpeed(speedHistogram(field));
  }
  const ViewParams& view = session.view;
  if (view.color == ColorMode::Magnitude || given(options.inputs.colorBy)) {
    LIC3D_TRY_ASSIGN(scalars.color, loadScalars(view.colorBy, "view.color_by", session, inputs));
  }
  if (scalars.color && scalars.color->name.empty()) scalars.color->name = view.colorBy;
  return scalars;
}

std::vector<std::uint8_t> vdbActiveVoxels(const ScalarVolume& lic, const VdbScalars& scalars) {
  std::vector<std::uint8_t> active(voxelCount(lic.dims));
  const std::vector<float>& speed = scalars.speed.values;
  parallelChunks(active.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
      active[i] = (lic.drawn.empty() || lic.drawn[i]) && speed[i] > scalars.emptySpeed ? 1 : 0;
  });
  return active;
}

Result<void> writeLicVdb(const std::string& path, const ScalarVolume& lic,
                         const VdbScalars& scalars) {
  const StageTimer timer("volume write");
  const std::vector<std::uint8_t> active = vdbActiveVoxels(lic, scalars);
  VdbVolume volume{.dims = lic.dims, .geometry = lic.geometry, .active = active};
  volume.creator = kVersionText;
  volume.grids.push_back({.name = std::string(kLicArrayName),
                          .values = lic.values,
                          .description = "line integral convolution of noise along the field, "
                                         "values in [0, 1]",
                          .fog = true});
  volume.grids.push_back({.name = scalars.speed.name,
                          .values = scalars.speed.values,
                          .unit = scalars.speed.unit,
                          .description = "speed |v| of the field"});
  if (scalars.color) {
    // A scalar array that happens to share a grid's name keeps its own under a prefix.
    std::string name = scalars.color->name;
    for (const VdbGrid& grid : volume.grids)
      if (grid.name == name) name = "color_" + name;
    volume.grids.push_back({.name = name,
                            .values = scalars.color->values,
                            .unit = scalars.color->unit,
                            .description = "the scalar the colour follows"});
  }
  return writeVdb(path, volume);
}

}  // namespace lic3d::cli
