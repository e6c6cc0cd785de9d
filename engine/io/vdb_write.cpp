// SPDX-License-Identifier: BSD-3-Clause
// io/vdb_write.h with OpenVDB: the only file that includes its headers (they compile slowly).
#include "io/vdb_write.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <algorithm>
#include <exception>
#include <set>

#include "core/parallel.h"
#include "io/file_util.h"

namespace lic3d {
namespace {

// Slabs of this many z layers (a leaf node's depth, so that no two slabs share a leaf) are built
// apart on all threads, one tree each, then merged.
constexpr int kSlabDepth = openvdb::FloatTree::LeafNodeType::DIM;

// vdbFileBytesBound counts the nodes of this layout.
static_assert(openvdb::FloatTree::LeafNodeType::DIM == 8);
static_assert(openvdb::FloatTree::RootNodeType::ChildNodeType::ChildNodeType::DIM == 128);
static_assert(openvdb::FloatTree::RootNodeType::ChildNodeType::DIM == 4096);

Result<void> checkVdbVolume(const std::filesystem::path& path, const VdbVolume& volume) {
  const std::size_t count = voxelCount(volume.dims);
  if (count == 0) return fileError(path, "the grid " + gridText(volume.dims) + " is empty");
  if (!volume.active.empty() && volume.active.size() != count)
    return fileError(path, "the active mask has " + std::to_string(volume.active.size()) +
                               " voxels, the grid " + std::to_string(count));
  LIC3D_TRY(checkGridGeometry(volume.geometry));
  std::set<std::string> names;
  for (const VdbGrid& grid : volume.grids) {
    if (grid.name.empty()) return fileError(path, "a grid has no name");
    if (!names.insert(grid.name).second)
      return fileError(path, "two grids are named '" + grid.name + "'");
    if (grid.values.size() != count)
      return fileError(path, "the grid '" + grid.name + "' has " +
                                 std::to_string(grid.values.size()) + " voxels, the grid " +
                                 std::to_string(count));
  }
  return {};
}

// Index (i,j,k) to world origin + (i,j,k) * spacing, a scale per axis: OpenVDB's voxel centres
// lie at integer index coordinates, as lic3d's grid points do (core/volume.h).
openvdb::math::Transform::Ptr gridTransform(const GridGeometry& geometry) {
  openvdb::math::Mat4d matrix = openvdb::math::Mat4d::identity();
  matrix.setToScale(openvdb::Vec3d(geometry.spacing.x, geometry.spacing.y, geometry.spacing.z));
  matrix.setTranslation(openvdb::Vec3d(geometry.origin.x, geometry.origin.y, geometry.origin.z));
  return openvdb::math::Transform::createLinearTransform(matrix);
}

openvdb::FloatGrid::Ptr makeGrid(const VdbVolume& volume, const VdbGrid& source) {
  const Dims d = volume.dims;
  const int slabs = (d.z + kSlabDepth - 1) / kSlabDepth;
  std::vector<openvdb::FloatTree::Ptr> trees(static_cast<std::size_t>(slabs));
  parallelFor(trees.size(), 0, [&](std::size_t slab) {
    auto tree = std::make_shared<openvdb::FloatTree>(0.0f);
    openvdb::tree::ValueAccessor<openvdb::FloatTree> accessor(*tree);
    const int zEnd = std::min(d.z, static_cast<int>(slab + 1) * kSlabDepth);
    for (int k = static_cast<int>(slab) * kSlabDepth; k < zEnd; ++k)
      for (int j = 0; j < d.y; ++j)
        for (int i = 0; i < d.x; ++i) {
          const std::size_t index = voxelIndex(d, i, j, k);
          if (!volume.active.empty() && !volume.active[index]) continue;
          accessor.setValueOn(openvdb::Coord(i, j, k), source.values[index]);
        }
    trees[slab] = std::move(tree);
  });
  openvdb::FloatGrid::Ptr grid = openvdb::FloatGrid::create(0.0f);
  for (const openvdb::FloatTree::Ptr& tree : trees)
    grid->tree().merge(*tree, openvdb::MERGE_ACTIVE_STATES);
  grid->setTransform(gridTransform(volume.geometry));
  grid->setName(source.name);
  grid->setGridClass(source.fog ? openvdb::GRID_FOG_VOLUME : openvdb::GRID_UNKNOWN);
  if (!volume.creator.empty()) grid->setCreator(volume.creator);
  if (!source.description.empty())
    grid->insertMeta("description", openvdb::StringMetadata(source.description));
  if (!source.unit.empty()) grid->insertMeta("units", openvdb::StringMetadata(source.unit));
  return grid;
}

}  // namespace

bool openVdbAvailable() { return true; }

Result<void> writeVdb(const std::filesystem::path& path, const VdbVolume& volume) {
  LIC3D_TRY(checkVdbVolume(path, volume));
  openvdb::initialize();
  openvdb::GridPtrVec grids;
  for (const VdbGrid& source : volume.grids) grids.push_back(makeGrid(volume, source));
  // OpenVDB writes through its own stream, to the temporary file, which commit() syncs and
  // renames into place.
  LIC3D_TRY_ASSIGN(TemporaryOutput output, TemporaryOutput::create(path));
  try {
    openvdb::io::File file(output.temporaryPath().string());
    file.write(grids);
    file.close();
  } catch (const std::exception& e) {
    return runtimeError(path.string() + ": OpenVDB could not write it: " + e.what());
  }
  return output.commit();
}

}  // namespace lic3d
