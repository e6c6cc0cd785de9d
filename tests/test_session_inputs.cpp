// SPDX-License-Identifier: BSD-3-Clause
// The engine's one loader of a session's inputs (loading/session_inputs.h), which the CLI, the
// desktop app and the ParaView plugin call: what it makes of each kind of field, and the field
// it brings the renderer to at a time.
#include <gtest/gtest.h>

#include "gpu_test_support.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "loading/session_inputs.h"

namespace lic3d {
namespace {

using test::GpuTest;

Session tornado(int grid) {
  Session s;
  s.field.grid = Dims(grid);
  s.lic.length = 4;
  return s;
}

TEST(SessionInputs, SteadyAndSampledFields) {
  Session s = tornado(12);
  s.time = 3.0;
  Result<SessionInputs> sampled = loadSessionInputs(s);
  ASSERT_TRUE(sampled) << sampled.error().message;
  EXPECT_TRUE(sampled->sampled.has_value()) << "the tornado changes with time: sampled exactly";
  EXPECT_FALSE(sampled->series.has_value());
  EXPECT_EQ(sampled->field.vectors,
            makeAnalyticField(AnalyticField::Tornado, Dims(12), 3.0).vectors);
  EXPECT_EQ(sampled->noise.bytes, makeWhiteNoise(Dims(12), s.noise.seed).bytes);

  s.field.field = "abc";
  Result<SessionInputs> steady = loadSessionInputs(s);
  ASSERT_TRUE(steady);
  EXPECT_FALSE(steady->sampled.has_value());
  EXPECT_FALSE(steady->fromFile);

  // Steps asked of a steady field are an error naming the parameter.
  Result<SessionInputs> refused = loadSessionInputs(s, {.analyticTimeSteps = 8});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().parameter, "time_steps");
}

TEST(SessionInputs, ErrorsNameTheParameter) {
  Session s = tornado(8);
  s.field.array = "velocity";
  EXPECT_EQ(loadSessionInputs(s).error().parameter, "field.array");
  s = tornado(8);
  s.field.field = "no_extension";
  EXPECT_EQ(loadSessionInputs(s).error().parameter, "field.source");
  s = tornado(8);
  s.noise.seedSpots = 5;
  s.noise.file = "noise.nrrd";
  EXPECT_EQ(loadSessionInputs(s).error().parameter, "noise.seed_spots");
}

TEST(SessionInputs, APieceGetsTheWholeGridsNoise) {
  VectorField piece = makeAnalyticField(AnalyticField::Abc, {6, 5, 4});
  piece.piece = FieldPiece{Dims(10), Dims(2, 3, 4), 1.0};
  const Result<NoiseVolume> noise = loadNoise(NoiseSource{}, piece);
  ASSERT_TRUE(noise);
  EXPECT_EQ(noise->bytes, makeWhiteNoisePiece(Dims(10), Dims(2, 3, 4), {6, 5, 4}, 1).bytes);
  NoiseSource spots;
  spots.seedSpots = 3;
  EXPECT_FALSE(loadNoise(spots, piece)) << "a piece cannot take seed noise of its own";
}

// A series of the tornado's steps: the renderer's blend on the GPU at a time between two steps
// matches the host's blend of the same steps.
class SessionInputsGpu : public GpuTest {};

TEST_F(SessionInputsGpu, ASeriesIsBlendedAtTheTimeAsOnTheHost) {
  Session s = tornado(16);
  s.timeSteps = 8;
  s.time = 10.0;
  Result<SessionInputs> inputs = loadSessionInputs(s, {.analyticTimeSteps = s.timeSteps});
  ASSERT_TRUE(inputs) << inputs.error().message;
  ASSERT_TRUE(inputs->series.has_value());
  const TimeBracket b = inputs->series->bracket(s.time);
  EXPECT_EQ(inputs->fieldStep, b.first);
  EXPECT_EQ(inputs->stepsRead, 1);

  Result<LicRenderer> renderer = LicRenderer::create(context());
  ASSERT_TRUE(renderer);
  ASSERT_TRUE(moveToTime(*inputs, s, s.time, *renderer, true));
  EXPECT_EQ(inputs->stepsRead, 2) << "the first step is used as it was read, not read again";
  EXPECT_TRUE(renderer->hasTimeStep(b.first));
  EXPECT_TRUE(renderer->hasTimeStep(b.second));
  EXPECT_TRUE(missingSteps(*renderer, b).empty());
  ASSERT_TRUE(renderer->updateLic(s.lic));
  const Result<ScalarVolume> gpu = renderer->readLicVolume();
  ASSERT_TRUE(gpu);

  Result<VectorField> host = hostFieldAt(*inputs, s, s.time);
  ASSERT_TRUE(host);
  Result<LicRenderer> reference = LicRenderer::create(context());
  ASSERT_TRUE(reference);
  ASSERT_TRUE(reference->setInputs(*host, inputs->noise));
  ASSERT_TRUE(reference->updateLic(s.lic));
  const Result<ScalarVolume> expected = reference->readLicVolume();
  ASSERT_TRUE(expected);
  EXPECT_LT(test::compareVolumes(*gpu, *expected).quantile999, 0.02);
}

}  // namespace
}  // namespace lic3d
