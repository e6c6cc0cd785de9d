// SPDX-License-Identifier: BSD-3-Clause
// 2D vector fields from files (2D LIC, thesis chapter 3): NRRD and VTK XML image data on a grid
// of one layer, with 2- or 3-component vectors.
#include <gtest/gtest.h>

#include "io/field_io.h"
#include "lic/field_plane.h"
#include "test_support.h"

namespace lic3d {
namespace {

class Field2DFilesTest : public test::TempFolderTest {};

TEST_F(Field2DFilesTest, NrrdWithTwoComponentsOnATwoDimensionalGrid) {
  writeBytes("two.nrrd",
             "NRRD0005\ntype: double\ndimension: 3\nsizes: 2 3 2\nkinds: 2-vector domain domain\n"
             "encoding: ascii\nspace dimension: 2\nspace directions: none (0.5,0) (0,0.25)\n"
             "space origin: (1,2)\n\n");  // ascii is refused: the header alone must pass first
  writeBytes("two_raw.nhdr",
             "NRRD0005\ntype: float\ndimension: 3\nsizes: 2 3 2\nendian: little\nencoding: raw\n"
             "space dimension: 2\nspace directions: none (0.5,0) (0,0.25)\nspace origin: (1,2)\n"
             "data file: two.raw\n");
  std::string payload;
  for (int i = 0; i < 12; ++i) {
    const float v = static_cast<float>(i + 1);
    payload.append(reinterpret_cast<const char*>(&v), 4);
  }
  writeBytes("two.raw", payload);
  const Result<VectorField> field = readVectorField(path("two_raw.nhdr"));
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(3, 2, 1));
  EXPECT_EQ(field->at(1, 0, 0), glm::vec3(3.0f, 4.0f, 0.0f));
  EXPECT_EQ(field->at(2, 1, 0), glm::vec3(11.0f, 12.0f, 0.0f));
  EXPECT_EQ(field->geometry.spacing, glm::dvec3(0.5, 0.25, 1.0));
  EXPECT_EQ(field->geometry.origin, glm::dvec3(1.0, 2.0, 0.0));
  EXPECT_TRUE(planarField(*field, "two_raw.nhdr").ok());

  // Three components on a 2D grid are read as they are; two on a 3D grid are refused.
  writeBytes("three.nhdr",
             "NRRD0005\ntype: float\ndimension: 3\nsizes: 3 2 2\nendian: little\nencoding: raw\n"
             "data file: two.raw\n");
  const Result<VectorField> three = readVectorField(path("three.nhdr"));
  ASSERT_TRUE(three.ok()) << three.error().message;
  EXPECT_EQ(three->at(0, 1, 0), glm::vec3(7.0f, 8.0f, 9.0f));
  writeBytes("bad.nhdr",
             "NRRD0005\ntype: float\ndimension: 4\nsizes: 2 3 1 2\nendian: little\n"
             "encoding: raw\ndata file: two.raw\n");
  const Result<VectorField> bad = readVectorField(path("bad.nhdr"));
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("bad.nhdr"), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("sizes"), std::string::npos) << bad.error().message;
}

TEST_F(Field2DFilesTest, VtiWithTwoComponentsOnATwoDimensionalGrid) {
  const std::string head =
      R"(<?xml version="1.0"?><VTKFile type="ImageData" version="1.0" byte_order="LittleEndian">)";
  writeBytes("two.vti",
             head + R"(<ImageData WholeExtent="0 2 0 1 0 0" Origin="0 0 0" Spacing="1 1 1">
<Piece Extent="0 2 0 1 0 0"><PointData Vectors="flow">
<DataArray type="Float32" Name="flow" NumberOfComponents="2" format="ascii">
1 2 3 4 5 6 7 8 9 10 11 12</DataArray></PointData></Piece></ImageData></VTKFile>)");
  FieldReadInfo info;
  const Result<VectorField> field = readVectorField(path("two.vti"), {}, &info);
  ASSERT_TRUE(field.ok()) << field.error().message;
  EXPECT_EQ(field->dims, Dims(3, 2, 1));
  EXPECT_EQ(field->at(2, 1, 0), glm::vec3(11.0f, 12.0f, 0.0f));
  EXPECT_EQ(info.arrayName, "flow");

  writeBytes("volume.vti",
             head + R"(<ImageData WholeExtent="0 1 0 1 0 1" Origin="0 0 0" Spacing="1 1 1">
<Piece Extent="0 1 0 1 0 1"><PointData>
<DataArray type="Float32" Name="flow" NumberOfComponents="2" format="ascii">
1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16</DataArray></PointData></Piece></ImageData></VTKFile>)");
  const Result<VectorField> volume = readVectorField(path("volume.vti"));
  ASSERT_FALSE(volume.ok());
  EXPECT_NE(volume.error().message.find("2D grid"), std::string::npos) << volume.error().message;
}

}  // namespace
}  // namespace lic3d
