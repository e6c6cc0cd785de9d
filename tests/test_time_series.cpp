// SPDX-License-Identifier: BSD-3-Clause
// Unsteady fields on the CPU side (docs/TIME.md): series of files, the steps around a time, the
// reference blend of two steps, the session's time and the memory of two resident steps.
#include <gtest/gtest.h>

#include <cmath>

#include "core/memory_budget.h"
#include "core/session.h"
#include "io/nrrd.h"
#include "lic/analytic_fields.h"
#include "lic/time_series.h"
#include "passes/time_blend_pass.h"
#include "test_support.h"

namespace lic3d {
namespace {

class TimeSeriesTest : public test::TempFolderTest {
 protected:
  void writeStep(const std::string& name, double time, Dims dims = {6, 5, 4}) const {
    ASSERT_TRUE(
        writeVectorFieldNrrd(path(name), makeAnalyticField(AnalyticField::Tornado, dims, time))
            .ok());
  }
};

TEST_F(TimeSeriesTest, NumberedFilesAreStepsInNumberOrder) {
  writeStep("flow_9.nrrd", 9);
  writeStep("flow_10.nrrd", 10);
  writeStep("flow_2.nrrd", 2);
  writeStep("other_1.nrrd", 1);
  const Result<TimeSeries> series = fileSeries((folder() / "flow_%d.nrrd").string());
  ASSERT_TRUE(series.ok()) << series.error().message;
  ASSERT_EQ(series->steps, 3);
  EXPECT_EQ(series->files[0].filename(), "flow_2.nrrd");
  EXPECT_EQ(series->files[2].filename(), "flow_10.nrrd");
  EXPECT_FALSE(series->periodic());
  EXPECT_EQ(series->endTime(), 2.0);
  // A zero-padded pattern wants at least its digits.
  writeStep("run_007.nrrd", 7);
  writeStep("run_008.nrrd", 8);
  writeStep("run_9.nrrd", 9);
  const Result<TimeSeries> padded = fileSeries((folder() / "run_%03d.nrrd").string());
  ASSERT_TRUE(padded.ok());
  EXPECT_EQ(padded->steps, 2);
  // A glob takes its matches in name order.
  const Result<TimeSeries> globbed = fileSeries((folder() / "run_00?.nrrd").string());
  ASSERT_TRUE(globbed.ok());
  EXPECT_EQ(globbed->files[1].filename(), "run_008.nrrd");
  const Result<VectorField> step = globbed->loadStep(1);
  ASSERT_TRUE(step.ok());
  EXPECT_EQ(step->dims, Dims(6, 5, 4));
}

TEST_F(TimeSeriesTest, PatternsThatNameNoSeriesAreRefused) {
  writeStep("one_1.nrrd", 1);
  for (const std::string pattern : {"one_%d.nrrd", "none_%d.nrrd", "x_%d_%d.nrrd", "x_%s.nrrd",
                                    "none_*.nrrd", "missing/%d.nrrd"}) {
    const Result<TimeSeries> series = fileSeries((folder() / pattern).string());
    ASSERT_FALSE(series.ok()) << pattern;
    EXPECT_EQ(series.error().kind, ErrorKind::InvalidInput);
    EXPECT_NE(series.error().message.find(pattern.substr(0, 4)), std::string::npos)
        << series.error().message;
  }
  // One step number written several ways (hardening, class 13): which file is the step?
  for (const char* name : {"dup_1.nrrd", "dup_01.nrrd", "dup_001.nrrd"}) writeStep(name, 1);
  writeStep("dup_2.nrrd", 2);
  const Result<TimeSeries> duplicated = fileSeries((folder() / "dup_%d.nrrd").string());
  ASSERT_FALSE(duplicated.ok());
  EXPECT_EQ(duplicated.error().kind, ErrorKind::InvalidInput);
  EXPECT_NE(duplicated.error().message.find("both give step number 1"), std::string::npos)
      << duplicated.error().message;
  EXPECT_TRUE(isFieldSeriesPattern("a_%04d.vti"));
  EXPECT_TRUE(isFieldSeriesPattern("a_*.vti"));
  EXPECT_FALSE(isFieldSeriesPattern("a_100%%.vti"));
  EXPECT_FALSE(isFieldSeriesPattern("tornado"));
}

TEST(TimeSeries, TheStepsAroundATimeAndTheWeightOfTheSecond) {
  TimeSeries files;
  files.steps = 4;
  EXPECT_EQ(files.bracket(1.25), (TimeBracket{1, 2, 0.25}));
  EXPECT_EQ(files.bracket(0.0), (TimeBracket{0, 1, 0.0}));
  EXPECT_EQ(files.bracket(3.0), (TimeBracket{2, 3, 1.0}));  // the last step
  EXPECT_EQ(files.bracket(7.0), (TimeBracket{2, 3, 1.0}));  // clamped
  EXPECT_EQ(files.bracket(-1.0), (TimeBracket{0, 1, 0.0}));
  const Result<TimeSeries> tornado = analyticSeries(AnalyticField::Tornado, {4, 4, 4}, 8);
  ASSERT_TRUE(tornado.ok());
  const double dt = tornado->period / 8;
  EXPECT_NEAR(tornado->stepTime(3), 3 * dt, 1e-12);
  // A periodic series wraps: after the last step comes the first.
  const TimeBracket wrap = tornado->bracket(7.5 * dt);
  EXPECT_EQ(wrap.first, 7);
  EXPECT_EQ(wrap.second, 0);
  EXPECT_NEAR(wrap.weight, 0.5, 1e-9);
  EXPECT_EQ(tornado->bracket(tornado->period + 2.25 * dt).first, 2);
  EXPECT_EQ(tornado->bracket(-0.5 * dt).first, 7);
  EXPECT_FALSE(analyticSeries(AnalyticField::Abc, {4, 4, 4}, 8).ok());
  EXPECT_FALSE(analyticSeries(AnalyticField::Tornado, {4, 4, 4}, 1).ok());
}

TEST(TimeSeries, TheReferenceBlendIsLinearPerVoxel) {
  const VectorField a = makeAnalyticField(AnalyticField::Tornado, {5, 4, 3}, 0.0);
  const VectorField b = makeAnalyticField(AnalyticField::Tornado, {5, 4, 3}, 200.0);
  const Result<VectorField> mid = interpolateFields(a, b, 0.25);
  ASSERT_TRUE(mid.ok());
  for (std::size_t i = 0; i < a.vectors.size(); ++i)
    EXPECT_NEAR(glm::length(mid->vectors[i] - (0.75f * a.vectors[i] + 0.25f * b.vectors[i])), 0.0f,
                1e-6f);
  EXPECT_EQ(interpolateFields(a, b, 0.0)->vectors, a.vectors);
  EXPECT_EQ(interpolateFields(a, b, 1.0)->vectors, b.vectors);
  const VectorField other = makeAnalyticField(AnalyticField::Tornado, {5, 4, 4}, 0.0);
  EXPECT_EQ(interpolateFields(a, other, 0.5).error().kind, ErrorKind::InvalidInput);
}

TEST(TimeSeries, TwoResidentStepsAndTheNoiseAreInTheMemoryEstimate) {
  MemoryRequest r;
  r.dims = Dims{100, 100, 100};
  r.precision = FieldPrecision::Half;
  const MemoryEstimate steady = estimateMemory(r);
  r.timeSeries = true;
  const MemoryEstimate unsteady = estimateMemory(r);
  // Two RGBA16F steps (8 B each) and the R32F noise (4 B) per voxel besides the field texture.
  EXPECT_EQ(unsteady.deviceBytes, steady.deviceBytes + 1'000'000u * (8 + 8 + 4));
  r.precision = FieldPrecision::Float;
  EXPECT_EQ(estimateMemory(r).deviceBytes, 1'000'000u * (16 + 4 + 16 + 16 + 4));
  // One step at a time goes up: the largest allocation is one step or the texture, not both.
  EXPECT_EQ(estimateMemory(r).largestImage, 1'000'000u * 16);
}

TEST(TimeSeries, TheSessionCarriesTimeAndTheTwoDimensionalMode) {
  Session s;
  s.twoD = true;
  s.time = 0.375;
  s.timeSteps = 48;
  s.plane = {1, 17, 640, 480};
  const Result<Session> back = sessionFromJson(sessionToJson(s), "s.json");
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(*back, s);
  for (const char* bad : {R"({"mode": "4d"})", R"({"plane": {"axis": "w"}})",
                          R"({"time_steps": 1})", R"({"plane": {"width": -3}})"}) {
    const Result<Session> refused = sessionFromJson(bad, "bad.json");
    ASSERT_FALSE(refused.ok()) << bad;
    EXPECT_NE(refused.error().message.find("bad.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace lic3d
