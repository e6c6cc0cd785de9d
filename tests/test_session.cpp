// SPDX-License-Identifier: BSD-3-Clause
// Session files: every parameter survives a JSON round trip, and bad files are refused with the
// file and the key named.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <random>
#include <string>

#include "core/session.h"
#include "io/session_file.h"
#include "test_support.h"

namespace lic3d {
namespace {

class SessionTest : public test::TempFolderTest {};

// A session with every field away from its default, so a key the writer or the reader forgets
// shows up as a difference.
Session unusualSession() {
  Session s;
  s.field = {"data/carotid.vtk", Dims{17, 19, 23}, "velocity"};
  s.noise = {"noise.nrrd", 77, 300};
  s.precision = FieldPrecision::Half;
  LicParams& l = s.lic;
  l.length = 13;
  l.step = 0.375f;
  l.bias = -4;
  l.integrator = Integrator::Rk4;
  l.kernel = Kernel::Gauss;
  l.noiseFilter = NoiseFilter::Nearest;
  l.direction = DirectionMode::Magnitude;
  l.sparsity = {SparsityDistribution::Hammersley, 1234, 2.5f, 0.125f, 9};
  ViewParams& v = s.view;
  v.width = 333;
  v.height = 222;
  v.slicing = Slicing::AxisAligned;
  v.slices = 99;
  v.camera = {12.5f, -30.0f, 2.25f, 45.0f, false, glm::vec3(0.1f, -0.2f, 0.3f)};
  v.background = {0.25f, 0.5f, 0.75f};
  v.alpha = 0.125f;
  v.opacityMode = OpacityMode::Constant;
  v.filter = VolumeFilter::Nearest;
  v.contrast = false;
  v.manualWindow = true;
  v.windowLow = 0.25f;
  v.windowHigh = 0.75f;
  v.gain = 1.5f;
  v.brightness = -0.25f;
  v.color = ColorMode::Magnitude;
  v.colormap = Colormap::Viridis;
  v.autoColorRange = false;
  v.colorLow = 0.5f;
  v.colorHigh = 2.5f;
  v.legend = true;
  v.axes = true;
  v.legendTitle = "|B| [T]";
  v.fontSize = 18.5f;
  v.magnitudeOpacity = 0.5f;
  v.magnitudeThreshold = 0.25f;
  v.clipMin = {0.125f, 0.25f, 0.375f};
  v.clipMax = {0.5f, 0.625f, 0.75f};
  v.roi = RoiShape::Cylinder;
  v.roiCenter = {0.25f, 0.5f, 0.75f};
  v.roiSize = 0.375f;
  v.roiRotation = {10.0f, 20.0f, 30.0f};
  v.roiOutside = true;
  v.fog = true;
  v.fogStart = 0.125f;
  v.fogEnd = 0.875f;
  v.fogColorFromBackground = false;
  v.fogColor = {0.5f, 0.25f, 0.125f};
  v.stereo = StereoMode::SideBySide;
  v.eyeSeparation = 0.0625f;
  v.zeroParallax = 1.5f;
  v.lighting = Lighting::Phong;
  v.light = {0.25f, 0.5f, 0.125f, 8.0f};
  return s;
}

TEST(Session, EveryParameterSurvivesAJsonRoundTrip) {
  const Session original = unusualSession();
  ASSERT_NE(original, Session{}) << "the test session must differ from the defaults";
  Result<Session> back = sessionFromJson(sessionToJson(original), "memory");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_EQ(*back, original) << sessionToJson(*back);

  // Stereo needs a perspective camera, so the orthographic flag gets a session of its own.
  Session ortho = original;
  ortho.view.stereo = StereoMode::None;
  ortho.view.camera.orthographic = true;
  Result<Session> orthoBack = sessionFromJson(sessionToJson(ortho), "memory");
  ASSERT_TRUE(orthoBack) << orthoBack.error().message;
  EXPECT_EQ(*orthoBack, ortho);
}

// `points` colour and opacity points with the longest numbers sessionToJson writes: 17 digits and
// an exponent for x and the opacities, 9 digits and an exponent for the (float) colours.
TransferFunction longestNumbers(std::size_t points, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> tiny(1.0e-300, 9.9e-300);
  std::uniform_real_distribution<float> tinyFloat(1.2e-38f, 9.9e-38f);
  std::vector<double> xs(points);
  for (double& x : xs) x = tiny(random);
  std::sort(xs.begin(), xs.end());
  TransferFunction tf;
  tf.name = "longest";
  for (const double x : xs) {
    tf.colors.push_back({x, {tinyFloat(random), tinyFloat(random), tinyFloat(random)}});
    tf.opacities.push_back({x, tiny(random)});
  }
  return tf;
}

// kMaxSessionBytes follows from what can be saved: it allows 100 bytes of session text for each
// control point a preset file can hold, so sessionToJson must write no point longer than that,
// and keep every number exact (a float's 0.2 as 0.2, not 0.20000000298023224).
TEST(Session, EachControlPointTakesAtMostAHundredBytesAndStaysExact) {
  const std::size_t points = 1000;
  const TransferFunction longest = longestNumbers(points, 7);
  Session colours, opacities;
  colours.view.transfer.name = opacities.view.transfer.name = longest.name;
  colours.view.transfer.colors = longest.colors;
  opacities.view.transfer.opacities = longest.opacities;
  Session none = colours;
  none.view.transfer.colors.clear();
  const std::size_t base = sessionToJson(none).size();
  for (const Session* s : {&colours, &opacities}) {
    const std::string text = sessionToJson(*s);
    EXPECT_LE(text.size() - base, 100 * points) << text.substr(0, 2000);
    Result<Session> back = sessionFromJson(text, "memory");
    ASSERT_TRUE(back) << back.error().message;
    EXPECT_TRUE(*back == *s) << "not exact";
  }
  // The same with ordinary values: the shortest digits of 0.2f read back as 0.2f.
  Session ordinary;
  std::mt19937 random(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (int i = 0; i <= 100; ++i)
    ordinary.view.transfer.colors.push_back(
        {i / 100.0, {unit(random), unit(random), std::round(unit(random) * 10) / 10}});
  ordinary.view.transfer.colors.push_back({1.0, {0.2f, 0.3f, 0.7f}});
  const std::string text = sessionToJson(ordinary);
  EXPECT_NE(text.find("0.2, 0.3, 0.7"), std::string::npos) << text;
  Result<Session> back = sessionFromJson(text, "memory");
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(*back == ordinary);
}

// A session of more than 1 MiB (what was once the limit) reads back: a preset of 20,000 points.
TEST_F(SessionTest, ASessionWithALargeTransferFunctionReadsBack) {
  Session original;
  original.view.transfer = longestNumbers(20000, 5);
  ASSERT_TRUE(writeSession(path("large.json"), original));
  EXPECT_GT(std::filesystem::file_size(path("large.json")), std::size_t{1} << 20);
  Result<Session> back = readSession(path("large.json"));
  ASSERT_TRUE(back) << back.error().message;
  EXPECT_TRUE(*back == original);
}

TEST(Session, MissingKeysKeepTheirDefaults) {
  Result<Session> s = sessionFromJson(R"({"lic": {"length": 7}})", "partial.json");
  ASSERT_TRUE(s) << s.error().message;
  Session expected;
  expected.lic.length = 7;
  EXPECT_EQ(*s, expected);
}

TEST(Session, BadFilesAreRefusedWithTheFileAndKeyNamed) {
  struct Case {
    const char* json;
    const char* mentions;
  };
  for (const Case& c : {Case{R"({"lic": {"lenght": 7}})", "lenght"},
                        Case{R"({"lic": {"length": "long"}})", "length"},
                        Case{R"({"lic": {"kernel": "triangle"}})", "kernel"},
                        Case{R"({"view": {"clip_min": [0, 1]}})", "clip_min"},
                        Case{R"({"lic": {"length": -3}})", "length"},
                        Case{R"([1, 2, 3])", "object"}, Case{R"({"lic": )", "bad.json"}}) {
    Result<Session> s = sessionFromJson(c.json, "bad.json");
    ASSERT_FALSE(s) << c.json;
    EXPECT_EQ(s.error().kind, ErrorKind::InvalidInput) << c.json;
    EXPECT_NE(s.error().message.find("bad.json"), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find(c.mentions), std::string::npos) << s.error().message;
  }
}

// Numbers are read as what they are, or refused: nothing beyond a double aborts the reader,
// no integer wraps or truncates, no key is given twice (issue: hardening, classes 1 and 6).
TEST(Session, NumbersThatDoNotFitAndDuplicateKeysAreRefused) {
  struct Case {
    const char* json;
    const char* mentions;
  };
  for (const Case& c : {Case{R"({"time": 1e400})", "1e400"}, Case{R"({"time": -1e309})", "-1e309"},
                        Case{R"({"view": {"width": 4294967328}})", "view.width"},
                        Case{R"({"field": {"grid": [4294967304, 8, 8]}})", "field.grid"},
                        Case{R"({"lic": {"length": 4294967297}})", "lic.length"},
                        Case{R"({"lic": {"length": 4.7}})", "lic.length"},
                        Case{R"({"lic": {"length": 1e30}})", "got '1e+30'"},
                        Case{R"({"view": {"slices": 4294967296}})", "view.slices"},
                        Case{R"({"lic3d_session": 1.9})", "lic3d_session"},
                        Case{R"({"noise": {"seed": -1}})", "noise.seed"},
                        Case{R"({"noise": {"seed": 18446744073709551616}})", "noise.seed"},
                        Case{R"({"look": "dense", "look": "see-through"})", "look"},
                        Case{R"({"lic": {"length": 7, "length": 8}})", "length"}}) {
    Result<Session> s = sessionFromJson(c.json, "bad.json");
    ASSERT_FALSE(s) << c.json;
    EXPECT_EQ(s.error().kind, ErrorKind::InvalidInput) << c.json;
    EXPECT_NE(s.error().message.find("bad.json"), std::string::npos) << s.error().message;
    EXPECT_NE(s.error().message.find(c.mentions), std::string::npos) << s.error().message;
  }
  // Text that is not UTF-8 (a file name in another encoding) cannot be recorded as JSON: the
  // session is refused, not written later with an exception (found by fuzzing the command line).
  Session latin1;
  latin1.field.field = "wa\xeb.nrrd";
  const Result<void> refused = validate(latin1);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("not UTF-8"), std::string::npos);
  // Whole numbers written as floats are whole numbers; the largest seed is a seed.
  Result<Session> s = sessionFromJson(
      R"({"lic": {"length": 20.0}, "noise": {"seed": 18446744073709551615}})", "good.json");
  ASSERT_TRUE(s) << s.error().message;
  EXPECT_EQ(s->lic.length, 20);
  EXPECT_EQ(s->noise.seed, std::uint64_t{18446744073709551615u});
  // A huge value is quoted in the message, cut short.
  const std::string huge = R"({"lic": {"length": ")" + std::string(900000, 'y') + R"("}})";
  Result<Session> cut = sessionFromJson(huge, "huge.json");
  ASSERT_FALSE(cut);
  EXPECT_LT(cut.error().message.size(), 300u) << cut.error().message.substr(0, 400);
  // Deep nesting is refused before it can exhaust the stack.
  const std::string deep = std::string(10000, '[') + std::string(10000, ']');
  EXPECT_FALSE(sessionFromJson(deep, "deep.json"));
}

TEST_F(SessionTest, FileRoundTripLeavesNoTemporary) {
  const Session original = unusualSession();
  ASSERT_TRUE(writeSession(path("s.json"), original));
  Result<Session> back = readSession(path("s.json"));
  ASSERT_TRUE(back) << back.error().message;
  // The file paths come back naming the same files: stored relative to the session's folder,
  // read back from there (absolute, as the working folder made them).
  Session expected = original;
  for (std::string* file : {&expected.field.field, &expected.noise.file})
    *file = (std::filesystem::current_path() / *file).lexically_normal().string();
  EXPECT_EQ(*back, expected);
  EXPECT_EQ(listFolder(), std::vector<std::string>{"s.json"});

  // A session that would not read back is not written (the app once saved a NaN as null).
  Session bad = original;
  bad.view.camera.azimuth = std::numeric_limits<float>::quiet_NaN();
  Result<void> refused = writeSession(path("bad.json"), bad);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("not saved"), std::string::npos)
      << refused.error().message;
  EXPECT_NE(refused.error().message.find("azimuth"), std::string::npos) << refused.error().message;
  EXPECT_EQ(listFolder(), std::vector<std::string>{"s.json"});

  Result<Session> missing = readSession(path("none.json"));
  ASSERT_FALSE(missing);
  EXPECT_NE(missing.error().message.find("none.json"), std::string::npos);
}

}  // namespace
}  // namespace lic3d
