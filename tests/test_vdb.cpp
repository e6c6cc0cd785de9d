// SPDX-License-Identifier: BSD-3-Clause
// OpenVDB output (`lic3d compute -o x.vdb`, io/vdb_write.h), read back with OpenVDB's own library
// and compared with the NRRD of the same run: the grids, their transform, which voxels are active
// and their values. Built only where lic3d is built with OpenVDB (LIC3D_OPENVDB).
#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "cli_test_support.h"
#include "io/nrrd.h"
#include "io/vdb_write.h"

namespace lic3d::test {
namespace {

class VdbTest : public CliTest {
 protected:
  static void SetUpTestSuite() { openvdb::initialize(); }
};

// A field with empty space: zero vectors for x < 8, elsewhere a swirl about the z axis whose
// speed grows from 0.6 to 1 with z. Non-uniform spacing and an origin away from 0.
constexpr Dims kDims{32, 24, 20};
const GridGeometry kGeometry{.spacing = {0.5, 1.0, 2.0}, .origin = {-3.0, 5.0, 10.0}};

VectorField swirlWithEmptySpace() {
  VectorField field{.dims = kDims, .geometry = kGeometry};
  field.vectors.resize(voxelCount(kDims));
  for (int k = 0; k < kDims.z; ++k)
    for (int j = 0; j < kDims.y; ++j)
      for (int i = 0; i < kDims.x; ++i) {
        if (i < 8) continue;
        const glm::vec3 around(12.0f - static_cast<float>(j), static_cast<float>(i) - 20.0f, 4.0f);
        field.vectors[voxelIndex(kDims, i, j, k)] =
            glm::normalize(around) * (0.6f + 0.4f * static_cast<float>(k) / (kDims.z - 1));
      }
  return field;
}

ScalarVolume pressureOf(const VectorField& field) {
  ScalarVolume pressure{.dims = field.dims, .geometry = field.geometry};
  pressure.values.resize(voxelCount(field.dims));
  for (std::size_t i = 0; i < pressure.values.size(); ++i)
    pressure.values[i] = 0.25f * static_cast<float>(i % 977) - 3.0f;
  return pressure;
}

openvdb::FloatGrid::Ptr floatGrid(const openvdb::GridPtrVecPtr& grids, const std::string& name) {
  for (const openvdb::GridBase::Ptr& grid : *grids)
    if (grid->getName() == name) return openvdb::gridPtrCast<openvdb::FloatGrid>(grid);
  return nullptr;
}

TEST_F(VdbTest, ComputeWritesTheNrrdsLicWithSpeedAndColourGridsEmptySpaceInactive) {
  const VectorField field = swirlWithEmptySpace();
  ASSERT_TRUE(writeVectorFieldNrrd(path("field.nrrd"), field).ok());
  const ScalarVolume pressure = pressureOf(field);
  ASSERT_TRUE(writeScalarNrrd(path("pressure.nrrd"), pressure, "pressure").ok());
  const std::string flags =
      "compute --field field.nrrd --length 8 --sparsity halton --sparsity-points 40 -q";
  const CommandRun nrrd = run(flags + " -o lic.nrrd");
  ASSERT_EQ(nrrd.status, 0) << nrrd.output;
  const CommandRun vdb = run(flags + " -o lic.vdb --color-by pressure.nrrd");
  ASSERT_EQ(vdb.status, 0) << vdb.output;

  const Result<ScalarVolume> lic = readScalarNrrd(path("lic.nrrd"));
  ASSERT_TRUE(lic.ok()) << lic.error().message;
  openvdb::io::File file(path("lic.vdb").string());
  file.open();
  const openvdb::GridPtrVecPtr grids = file.getGrids();
  file.close();
  ASSERT_EQ(grids->size(), 3u);
  const openvdb::FloatGrid::Ptr licGrid = floatGrid(grids, "LIC");
  const openvdb::FloatGrid::Ptr speedGrid = floatGrid(grids, "speed");
  const openvdb::FloatGrid::Ptr pressureGrid = floatGrid(grids, "pressure");
  ASSERT_TRUE(licGrid && speedGrid && pressureGrid);
  EXPECT_EQ(licGrid->getGridClass(), openvdb::GRID_FOG_VOLUME);
  EXPECT_EQ(licGrid->background(), 0.0f);

  // Index (i,j,k) lies at origin + (i,j,k) * spacing, one spacing per axis.
  for (const openvdb::FloatGrid::Ptr& grid : {licGrid, speedGrid, pressureGrid}) {
    const openvdb::Vec3d size = grid->voxelSize();
    EXPECT_DOUBLE_EQ(size.x(), 0.5);
    EXPECT_DOUBLE_EQ(size.y(), 1.0);
    EXPECT_DOUBLE_EQ(size.z(), 2.0);
    for (const openvdb::Coord ijk :
         {openvdb::Coord(0, 0, 0), openvdb::Coord(31, 23, 19), openvdb::Coord(7, 3, 11)}) {
      const openvdb::Vec3d world = grid->transform().indexToWorld(ijk);
      EXPECT_DOUBLE_EQ(world.x(), -3.0 + 0.5 * ijk.x());
      EXPECT_DOUBLE_EQ(world.y(), 5.0 + 1.0 * ijk.y());
      EXPECT_DOUBLE_EQ(world.z(), 10.0 + 2.0 * ijk.z());
    }
  }

  // Active exactly where the NRRD has a drawn voxel (not NaN) that is not empty space; there
  // the values of the NRRD, the field's speed and the colour scalar.
  const auto licAt = licGrid->getConstAccessor();
  const auto speedAt = speedGrid->getConstAccessor();
  const auto pressureAt = pressureGrid->getConstAccessor();
  openvdb::Index64 drawn = 0, hidden = 0, empty = 0;
  for (int k = 0; k < kDims.z; ++k)
    for (int j = 0; j < kDims.y; ++j)
      for (int i = 0; i < kDims.x; ++i) {
        const std::size_t index = voxelIndex(kDims, i, j, k);
        const openvdb::Coord ijk(i, j, k);
        const float value = lic->values[index];
        const float speed = glm::length(field.vectors[index]);
        const bool active = !std::isnan(value) && speed > 0.0f;
        hidden += std::isnan(value) ? 1 : 0;
        empty += speed == 0.0f ? 1 : 0;
        ASSERT_EQ(licAt.isValueOn(ijk), active) << i << "," << j << "," << k;
        ASSERT_EQ(speedAt.isValueOn(ijk), active);
        ASSERT_EQ(pressureAt.isValueOn(ijk), active);
        if (!active) {
          EXPECT_EQ(licAt.getValue(ijk), 0.0f);
          continue;
        }
        ++drawn;
        ASSERT_EQ(licAt.getValue(ijk), value) << i << "," << j << "," << k;
        ASSERT_NEAR(speedAt.getValue(ijk), speed, 1e-6f);
        ASSERT_EQ(pressureAt.getValue(ijk), pressure.values[index]);
      }
  EXPECT_GT(hidden, 0u);  // the sparsity mask hid some voxels
  EXPECT_EQ(empty, voxelCount({8, kDims.y, kDims.z}));
  EXPECT_EQ(licGrid->activeVoxelCount(), drawn);
  EXPECT_EQ(speedGrid->activeVoxelCount(), drawn);
  EXPECT_LT(drawn, voxelCount(kDims) * 3 / 4);
}

TEST_F(VdbTest, ASessionColouredByAScalarAddsItsGrid) {
  const CommandRun render = run(
      "render --field tornado --grid 16 --color-by vorticity --width 32 --height 32 -q -o a.png");
  ASSERT_EQ(render.status, 0) << render.output;
  const CommandRun compute = run("compute --session a.png -q -o s.vdb");
  ASSERT_EQ(compute.status, 0) << compute.output;
  openvdb::io::File file(path("s.vdb").string());
  file.open();
  const openvdb::GridPtrVecPtr grids = file.getGrids();
  const openvdb::FloatGrid::Ptr vorticity = floatGrid(grids, "vorticity");
  ASSERT_TRUE(vorticity);
  EXPECT_EQ(vorticity->activeVoxelCount(), floatGrid(grids, "LIC")->activeVoxelCount());
  float largest = 0.0f;
  for (auto v = vorticity->cbeginValueOn(); v; ++v) {
    ASSERT_GE(*v, 0.0f);  // |curl v|
    largest = std::max(largest, *v);
  }
  EXPECT_GT(largest, 0.0f);
}

TEST_F(VdbTest, ColourScalarsOnlyForVdbAndFailedWritesLeaveNothing) {
  const CommandRun nrrd = run("compute --field tornado --grid 16 -o x.nrrd --color-by vorticity");
  EXPECT_EQ(nrrd.status, 2) << nrrd.output;
  EXPECT_NE(nrrd.output.find("-o FILE.vdb"), std::string::npos) << nrrd.output;

  // A grid that does not match, or names that repeat: refused naming the file, nothing written.
  const std::vector<float> values(8, 0.5f);
  const std::vector<float> fewer(7, 0.5f);
  VdbVolume volume{.dims = {2, 2, 2}};
  volume.grids = {{.name = "a", .values = values}, {.name = "b", .values = fewer}};
  Result<void> written = writeVdb(path("bad.vdb"), volume);
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find("bad.vdb"), std::string::npos);
  volume.grids = {{.name = "a", .values = values}, {.name = "a", .values = values}};
  EXPECT_FALSE(writeVdb(path("bad.vdb"), volume).ok());
  // A folder that does not exist.
  volume.grids = {{.name = "a", .values = values}};
  written = writeVdb(path("missing/x.vdb"), volume);
  ASSERT_FALSE(written.ok());
  EXPECT_NE(written.error().message.find("missing/x.vdb"), std::string::npos);
  EXPECT_TRUE(listFolder().empty());
  // All voxels active without a mask.
  ASSERT_TRUE(writeVdb(path("dense.vdb"), volume).ok());
  openvdb::io::File file(path("dense.vdb").string());
  file.open();
  EXPECT_EQ(file.getGrids()->front()->activeVoxelCount(), 8u);
  EXPECT_EQ(listFolder(), std::vector<std::string>{"dense.vdb"});

  // The free-space check's bound holds for values that do not compress, every voxel active.
  const Dims dims{37, 20, 9};
  std::vector<float> noise(voxelCount(dims));
  std::uint32_t state = 12345;
  for (float& v : noise) v = static_cast<float>((state = state * 1664525u + 1013904223u) >> 8);
  VdbVolume noisy{.dims = dims, .geometry = kGeometry};
  noisy.grids = {{.name = "x", .values = noise}, {.name = "y", .values = noise}};
  ASSERT_TRUE(writeVdb(path("noise.vdb"), noisy).ok());
  EXPECT_LE(std::filesystem::file_size(path("noise.vdb")), vdbFileBytesBound(dims, 2));
  EXPECT_GT(std::filesystem::file_size(path("noise.vdb")), 2 * voxelCount(dims) * sizeof(float));
  EXPECT_LE(std::filesystem::file_size(path("dense.vdb")), vdbFileBytesBound({2, 2, 2}, 1));
}

}  // namespace
}  // namespace lic3d::test
