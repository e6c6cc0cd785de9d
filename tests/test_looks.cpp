// SPDX-License-Identifier: BSD-3-Clause
// What the looks are made of, on the CPU: transfer functions and their ParaView files, the
// built-in colour maps' tables, derived quantities, resampling to a finer LIC grid, the
// --resolution syntax, oblique planes and the looks' parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <glm/geometric.hpp>
#include <string>

#include "core/colormap.h"
#include "core/look.h"
#include "core/resolution.h"
#include "core/session.h"
#include "core/transfer_function.h"
#include "io/session_file.h"
#include "lic/analytic_fields.h"
#include "lic/derived_fields.h"
#include "lic/field_plane.h"
#include "lic/resample.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

// ---- transfer functions -------------------------------------------------------------------------

TEST(TransferFunction, ParaViewPresetsAreRescaledToTheColourRange) {
  // A preset over [-1, 3], as ParaView stores them: x r g b ..., opacity x a midpoint sharpness.
  const Result<TransferFunction> tf = transferFunctionFromJson(R"([{
    "Name": "Red to blue", "ColorSpace": "RGB",
    "RGBPoints": [-1, 1, 0, 0,  1, 0, 1, 0,  3, 0, 0, 1],
    "Points": [-1, 0, 0.5, 0,  3, 0.8, 0.5, 0]
  }])",
                                                               "preset.json");
  ASSERT_TRUE(tf) << tf.error().message;
  EXPECT_EQ(tf->name, "Red to blue");
  ASSERT_EQ(tf->colors.size(), 3u);
  EXPECT_DOUBLE_EQ(tf->colors[1].x, 0.5);
  EXPECT_EQ(tf->colors[2].rgb, glm::vec3(0, 0, 1));
  ASSERT_EQ(tf->opacities.size(), 2u);
  EXPECT_DOUBLE_EQ(tf->opacities[1].x, 1.0);
  // Linear between points, constant beyond them.
  EXPECT_NEAR(tf->color(0.25).r, 0.5f, 1e-6);
  EXPECT_NEAR(tf->color(0.25).g, 0.5f, 1e-6);
  EXPECT_EQ(tf->color(-1.0), glm::vec3(1, 0, 0));
  EXPECT_NEAR(tf->opacity(0.5), 0.4, 1e-12);
}

class TransferFunctionFile : public test::TempFolderTest {};

TEST_F(TransferFunctionFile, RoundTripsAndBadPresetsAreNamed) {
  TransferFunction tf;
  tf.name = "custom";
  tf.colors = {{0.0, {0.1f, 0.2f, 0.3f}}, {0.4, {1.0f, 0.5f, 0.0f}}, {1.0, {0.0f, 0.0f, 1.0f}}};
  tf.opacities = {{0.0, 0.0}, {0.7, 0.9}, {1.0, 0.25}};
  const fs::path file = path("tf.json");
  ASSERT_TRUE(writeTransferFunction(file, tf));
  const Result<TransferFunction> back = readTransferFunction(file);
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(*back, tf);

  // In a session too.
  Session session;
  session.view.transfer = tf;
  const Result<Session> again = sessionFromJson(sessionToJson(session), "s.json");
  ASSERT_TRUE(again) << again.error().message;
  EXPECT_EQ(again->view.transfer, tf);

  for (const char* bad : {R"({"RGBPoints": [0, 1, 0]})",    // not 4 numbers a point
                          R"({"Points": [0, 2, 0.5, 0]})",  // opacity above 1
                          R"({"Name": "none"})", R"([])", "not json"}) {
    const Result<TransferFunction> r = transferFunctionFromJson(bad, "bad.json");
    ASSERT_FALSE(r) << bad;
    EXPECT_NE(r.error().message.find("bad.json"), std::string::npos) << r.error().message;
  }
  const Result<TransferFunction> missing = readTransferFunction(path("none.json"));
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("none.json"), std::string::npos);
}

// ---- colour maps --------------------------------------------------------------------------------

TEST(Colormap, ViridisIsMatplotlibsTable) {
  // matplotlib's viridis at the table's entries 0, 64, 128, 192 and 255.
  const struct {
    int index;
    glm::vec3 rgb;
  } known[] = {{0, {0.267004f, 0.004874f, 0.329415f}},
               {64, {0.229739f, 0.322361f, 0.545706f}},
               {128, {0.127568f, 0.566949f, 0.550556f}},
               {192, {0.369214f, 0.788888f, 0.382914f}},
               {255, {0.993248f, 0.906157f, 0.143936f}}};
  for (const auto& k : known) {
    const glm::vec3 c = sampleColormap(Colormap::Viridis, static_cast<float>(k.index) / 255.0f);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(c[i], k.rgb[i], 0.5 / 255.0) << k.index << " " << i;
  }
}

// ---- derived quantities -------------------------------------------------------------------------

TEST(DerivedFields, VorticityAndHelicityOfKnownFlows) {
  // ABC flow is a Beltrami field: curl v = v, so |curl v| = |v| and v . curl v = |v|^2.
  const VectorField abc = makeAnalyticField(AnalyticField::Abc, Dims(48));
  const PointScalars vorticity = derivedScalars(abc, DerivedQuantity::Vorticity);
  const PointScalars helicity = derivedScalars(abc, DerivedQuantity::Helicity);
  const PointScalars speed = derivedScalars(abc, DerivedQuantity::Speed);
  ASSERT_EQ(vorticity.dims, abc.dims);
  double worstVorticity = 0.0, worstHelicity = 0.0;
  for (int z = 1; z < 47; ++z)
    for (int y = 1; y < 47; ++y)
      for (int x = 1; x < 47; ++x) {
        const std::size_t i = (static_cast<std::size_t>(z) * 48 + y) * 48 + x;
        const double v = glm::length(glm::dvec3(abc.vectors[i]));
        EXPECT_NEAR(speed.values[i], v, 1e-5);
        worstVorticity = std::max(worstVorticity, std::abs(vorticity.values[i] - v));
        worstHelicity = std::max(worstHelicity, std::abs(helicity.values[i] - v * v));
      }
  // Central differences at 48 points over 2 pi: relative error about (h^2 / 6) = 0.3 %.
  EXPECT_LT(worstVorticity, 0.03);
  EXPECT_LT(worstHelicity, 0.1);

  // Solid-body rotation about z with angular speed 3 on a grid of spacing 0.5: vorticity 2 x 3,
  // helicity 0, everywhere (the faces included: the field is linear).
  VectorField rotation;
  rotation.dims = {9, 7, 5};
  rotation.geometry.spacing = glm::dvec3(0.5);
  rotation.geometry.origin = {-2.0, -1.5, 0.0};
  rotation.vectors.resize(voxelCount(rotation.dims));
  for (int z = 0; z < 5; ++z)
    for (int y = 0; y < 7; ++y)
      for (int x = 0; x < 9; ++x) {
        const glm::dvec3 p =
            rotation.geometry.origin + rotation.geometry.spacing * glm::dvec3(x, y, z);
        rotation.vectors[(static_cast<std::size_t>(z) * 7 + y) * 9 + x] =
            glm::vec3(-3.0 * p.y, 3.0 * p.x, 0.0);
      }
  for (const float w : derivedScalars(rotation, DerivedQuantity::Vorticity).values)
    EXPECT_NEAR(w, 6.0f, 1e-4);
  for (const float h : derivedScalars(rotation, DerivedQuantity::Helicity).values)
    EXPECT_NEAR(h, 0.0f, 1e-4);
  EXPECT_EQ(derivedQuantity("vorticity"), DerivedQuantity::Vorticity);
  EXPECT_FALSE(derivedQuantity("pressure"));
}

// ---- LIC finer than the data --------------------------------------------------------------------

TEST(Resolution, ParsedAsALongestSideAGridOrAFactor) {
  const Dims file{76, 49, 45};
  const Result<Resolution> longest = parseResolution("152");
  ASSERT_TRUE(longest);
  EXPECT_EQ(resolvedGrid(*longest, file), Dims(152, 98, 90));
  const Result<Resolution> grid = parseResolution("100,60,50");
  ASSERT_TRUE(grid);
  EXPECT_EQ(resolvedGrid(*grid, file), Dims(100, 60, 50));
  // A factor divides the spacing: n - 1 intervals become 2 (n - 1).
  const Result<Resolution> factor = parseResolution("2x");
  ASSERT_TRUE(factor);
  EXPECT_EQ(resolvedGrid(*factor, file), Dims(151, 97, 89));
  const Result<Resolution> none = parseResolution("");
  ASSERT_TRUE(none);
  EXPECT_FALSE(none->given());
  for (const char* bad : {"0", "-3", "abc", "2x,3", "1,2", "0x", "1e9", "10,20,0"})
    EXPECT_FALSE(parseResolution(bad)) << bad;
}

TEST(Resample, ALinearFieldIsReproducedOnTheFinerGrid) {
  VectorField field;
  field.dims = {6, 5, 4};
  field.geometry.spacing = {1.0, 2.0, 0.5};
  field.geometry.origin = {1.0, -1.0, 3.0};
  field.vectors.resize(voxelCount(field.dims));
  const auto linear = [](glm::dvec3 p) {
    return glm::vec3(glm::dvec3(p.x + 2.0 * p.y, 3.0 - p.z, 0.5 * p.x - p.y + p.z));
  };
  const auto position = [](const VectorField& f, int x, int y, int z) {
    return f.geometry.origin + f.geometry.spacing * glm::dvec3(x, y, z);
  };
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 6; ++x)
        field.vectors[(static_cast<std::size_t>(z) * 5 + y) * 6 + x] =
            linear(position(field, x, y, z));
  const VectorField fine = resampleField(field, {11, 9, 7});
  ASSERT_EQ(fine.dims, Dims(11, 9, 7));
  // The same box: first and last voxel centres stay where they were.
  EXPECT_EQ(fine.geometry.origin, field.geometry.origin);
  const glm::dvec3 last = position(fine, 10, 8, 6), fileLast = position(field, 5, 4, 3);
  for (int a = 0; a < 3; ++a) EXPECT_NEAR(last[a], fileLast[a], 1e-12);
  for (int z = 0; z < 7; ++z)
    for (int y = 0; y < 9; ++y)
      for (int x = 0; x < 11; ++x) {
        const glm::vec3 expected = linear(position(fine, x, y, z));
        const glm::vec3 got = fine.vectors[(static_cast<std::size_t>(z) * 9 + y) * 11 + x];
        for (int a = 0; a < 3; ++a) EXPECT_NEAR(got[a], expected[a], 1e-5) << x << y << z;
      }
}

// ---- oblique planes -----------------------------------------------------------------------------

TEST(ObliquePlane, ProjectsTheFieldOntoThePlaneAndMarksWhatLiesOutsideTheBox) {
  // v = (6, 4, 0) = (1, -1, 0) in the plane of normal (1, 1, 0) plus 5 (1, 1, 0) across it: 2D
  // LIC follows the projection, of length sqrt(2), wherever the plane lies in the box.
  VectorField field;
  field.dims = Dims(16);
  field.vectors.assign(voxelCount(field.dims), glm::vec3(6.0f, 4.0f, 0.0f));
  const Result<ObliquePlane> plane = obliquePlane(field, {0.5, 0.5, 0.5}, {1.0, 1.0, 0.0});
  ASSERT_TRUE(plane) << plane.error().message;
  ASSERT_EQ(plane->outside.size(), voxelCount(plane->field.dims));
  std::size_t inside = 0, outside = 0;
  for (std::size_t i = 0; i < plane->outside.size(); ++i) {
    const float length = glm::length(plane->field.vectors[i]);
    if (plane->outside[i]) {
      ++outside;
      EXPECT_EQ(length, 0.0f) << i;
    } else {
      ++inside;
      EXPECT_NEAR(length, std::sqrt(2.0f), 1e-4f) << i;
    }
  }
  EXPECT_GT(inside, 0u);
  // The plane's cut through the cube is a rectangle, its bounding rectangle too: the axis-aligned
  // case has nothing outside. A plane across a corner cuts a triangle: about half is outside.
  EXPECT_EQ(outside, 0u);
  const Result<ObliquePlane> corner = obliquePlane(field, {0.8, 0.8, 0.8}, {1.0, 1.0, 1.0});
  ASSERT_TRUE(corner) << corner.error().message;
  std::size_t cornerOutside = 0;
  for (const std::uint8_t o : corner->outside) cornerOutside += o;
  EXPECT_GT(cornerOutside, corner->outside.size() / 4);
  EXPECT_FALSE(obliquePlane(field, {0.5, 0.5, 0.5}, {0.0, 0.0, 0.0}));
  EXPECT_FALSE(obliquePlane(field, {3.0, 0.5, 0.5}, {1.0, 0.0, 0.0})) << "misses the box";
}

// ---- looks --------------------------------------------------------------------------------------

TEST(Looks, EachLookSetsRelativeParametersAndDenseIsTheThesisDefault) {
  Session session;
  session.view.width = 321;  // not a look's business
  applyLook(Look::SeeThrough, session);
  EXPECT_EQ(session.look, Look::SeeThrough);
  EXPECT_EQ(session.view.color, ColorMode::Magnitude);
  EXPECT_GT(session.view.opticalDepth, 0.0f);
  EXPECT_GT(session.view.rangeTail, 0.0f);
  EXPECT_EQ(session.view.magnitudeThreshold, kEmptySpeedFraction);
  EXPECT_EQ(session.view.width, 321);

  applyLook(Look::Streamlines, session);
  EXPECT_GT(session.noise.seedFraction, 0.0f);
  EXPECT_TRUE(session.view.percentileWindow);
  EXPECT_EQ(session.view.lighting, Lighting::Lines);

  applyLook(Look::Sparse, session);
  EXPECT_EQ(session.noise.seedFraction, 0.0f);
  EXPECT_NE(session.lic.sparsity.distribution, SparsityDistribution::None);
  EXPECT_GT(session.lic.sparsity.amount, 0.0f);
  EXPECT_FALSE(session.view.percentileWindow);

  // Back to dense: the thesis' parameters, as a fresh session has them.
  applyLook(Look::Dense, session);
  Session fresh;
  fresh.view.width = 321;
  EXPECT_EQ(session.view, fresh.view);
  EXPECT_EQ(session.lic, fresh.lic);
  EXPECT_EQ(session.noise, fresh.noise);
}

}  // namespace
}  // namespace lic3d
