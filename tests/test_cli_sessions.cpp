// SPDX-License-Identifier: BSD-3-Clause
// Sessions that travel: the file paths a session names are stored relative to the PNG or session
// file that holds it and read back from there, so results remake themselves from any folder, and
// a slice PNG records its slice; a large session stays small in its PNG.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_test_support.h"
#include "io/nrrd.h"
#include "io/png_writer.h"
#include "io/session_file.h"
#include "lic/analytic_fields.h"
#include "lic/noise.h"
#include "png_read.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;
using test::CliTest;
using test::CommandRun;

// Runs from the root folder, so that nothing resolves from the test's folder by chance.
const std::string kFromRoot = "cd / &&";

class SessionFiles : public CliTest {
 protected:
  void SetUp() override {
    CliTest::SetUp();
    fs::create_directories(path("data"));
    fs::create_directories(path("out"));
    const Dims dims(12, 10, 8);
    ASSERT_TRUE(
        writeVectorFieldNrrd(path("data/field.nrrd"), makeAnalyticField(AnalyticField::Abc, dims))
            .ok());
    ASSERT_TRUE(writeNoiseNrrd(path("data/noise.nrrd"), makeWhiteNoise(dims, 3)).ok());
  }

  std::vector<std::uint8_t> pixels(const std::string& file) const {
    return test::readRgbaPng(path(file)).rgba;
  }
};

TEST_F(SessionFiles, APngRemakesItselfFromAnyFolderAndAfterTheFolderMoves) {
  const std::string view = " --width 40 --height 32 --look streamlines --azimuth 40";
  const CommandRun made = run("render -q --field data/field.nrrd --noise data/noise.nrrd" + view +
                              " --color-by data/noise.nrrd --color magnitude -o out/r.png");
  ASSERT_EQ(made.status, 0) << made.output;
  const Result<Session> stored = test::sessionInPng(path("out/r.png"));
  ASSERT_TRUE(stored.ok()) << stored.error().message;
  EXPECT_EQ(stored->field.field, "../data/field.nrrd");
  EXPECT_EQ(stored->noise.file, "../data/noise.nrrd");
  EXPECT_EQ(stored->view.colorBy, "../data/noise.nrrd");

  // `--session` takes the PNG itself; from the root folder its paths resolve from the PNG's.
  const CommandRun again = run("render -q --session '" + path("out/r.png").string() + "' -o '" +
                                   path("again.png").string() + "'",
                               kFromRoot);
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(pixels("again.png"), pixels("out/r.png"));

  // The inputs and results move together: still the same picture.
  fs::create_directories(path("moved"));
  fs::rename(path("data"), path("moved/data"));
  fs::rename(path("out"), path("moved/out"));
  const CommandRun moved = run("render -q --session '" + path("moved/out/r.png").string() +
                                   "' -o '" + path("moved.png").string() + "'",
                               kFromRoot);
  ASSERT_EQ(moved.status, 0) << moved.output;
  EXPECT_EQ(pixels("moved.png"), pixels("again.png"));
  // The new PNG's session names the inputs from its own folder.
  const Result<Session> moved_session = test::sessionInPng(path("moved.png"));
  ASSERT_TRUE(moved_session.ok());
  EXPECT_EQ(moved_session->field.field, "moved/data/field.nrrd");
}

TEST_F(SessionFiles, SessionFilesStorePathsRelativeToThemselves) {
  Session session;
  session.field.field = path("data/field.nrrd").string();  // absolute, as the app holds it
  session.noise.file = path("data/noise.nrrd").string();
  fs::create_directories(path("sessions"));
  ASSERT_TRUE(writeSession(path("sessions/s.json"), session).ok());
  const std::string text = test::readWhole(path("sessions/s.json"));
  EXPECT_NE(text.find("\"../data/field.nrrd\""), std::string::npos) << text;
  EXPECT_EQ(text.find(folder().string()), std::string::npos) << text;

  const Result<Session> back = readSession(path("sessions/s.json"));
  ASSERT_TRUE(back.ok()) << back.error().message;
  EXPECT_EQ(fs::path(back->field.field), path("sessions/../data/field.nrrd").lexically_normal());
  const CommandRun r = run("compute -q --session '" + path("sessions/s.json").string() +
                               "' -L 4 -o '" + path("s.nrrd").string() + "'",
                           kFromRoot);
  EXPECT_EQ(r.status, 0) << r.output;

  // A session written before paths were stored relative: its paths are from the working
  // folder, which still works from there.
  writeBytes("sessions/old.json",
             "{\"lic3d_session\": 1, \"field\": {\"source\": \"data/field.nrrd\"}}");
  const CommandRun old = run("compute -q --session sessions/old.json -L 4 -o old.nrrd");
  EXPECT_EQ(old.status, 0) << old.output;
  // An analytic field is a name, not a path.
  session.field.field = "tornado";
  ASSERT_TRUE(writeSession(path("sessions/t.json"), session).ok());
  EXPECT_EQ(readSession(path("sessions/t.json"))->field.field, "tornado");
}

TEST_F(SessionFiles, ASlicePngRecordsItsSliceAndRemakesItself) {
  const std::string flags = "compute -q --cpu --field data/field.nrrd --length 6 ";
  ASSERT_EQ(run(flags + "--slice y:3 -o out/y3.png").status, 0);
  ASSERT_EQ(run(flags + "--slice x -o out/xm.png").status, 0);
  const Result<Session> y3 = test::sessionInPng(path("out/y3.png"));
  ASSERT_TRUE(y3.ok());
  EXPECT_EQ(y3->plane.axis, 1);
  EXPECT_EQ(y3->plane.index, 3);
  const Result<Session> middle = test::sessionInPng(path("out/xm.png"));
  ASSERT_TRUE(middle.ok());
  EXPECT_EQ(middle->plane.axis, 0);
  EXPECT_EQ(middle->plane.index, 6) << "the middle of 12, not -1";

  for (const char* name : {"y3", "xm"}) {
    const std::string from = path(std::string("out/") + name + ".png").string();
    const std::string to = path(std::string(name) + "_again.png").string();
    // --cpu as the PNG was made (the device is not part of a session).
    const CommandRun r =
        run("compute -q --cpu --session '" + from + "' -o '" + to + "'", kFromRoot);
    ASSERT_EQ(r.status, 0) << r.output;
    const test::DecodedPng a = test::decodePng(from);
    const test::DecodedPng b = test::decodePng(to);
    ASSERT_TRUE(a.ok && b.ok);
    EXPECT_EQ(a.width, b.width) << name;
    EXPECT_EQ(a.bytes, b.bytes) << name;
  }
  // A flag still overrides the recorded slice; a volume output ignores it.
  ASSERT_EQ(run("compute -q --session out/y3.png --slice z:2 -o z2.png").status, 0);
  EXPECT_EQ(test::sessionInPng(path("z2.png"))->plane.axis, 2);
  ASSERT_EQ(run("compute -q --session out/y3.png -o volume.nrrd").status, 0);
  // A PNG that holds no session is named as such.
  ASSERT_TRUE(
      writePng(path("plain.png"), RgbaImage{2, 2, std::vector<std::uint8_t>(16, 255)}).ok());
  const CommandRun noSession = run("render -q --session plain.png -o n.png");
  EXPECT_EQ(noSession.status, 2) << noSession.output;
  EXPECT_NE(noSession.output.find("plain.png: this PNG holds no lic3d session"), std::string::npos)
      << noSession.output;
}

// The session in a PNG is compressed: a 230 KB preset once made a 940 KB picture of 32x32 pixels
// (and a 13 MB one 64 MB); the session still reads back whole.
TEST_F(CliTest, APngWithALargePresetStaysSmallAndReadsBack) {
  writeBytes("big.json", test::shortNumberPreset(6400));
  const std::string flags = "render -q --grid 8 --length 4 --width 32 --height 32 ";
  ASSERT_EQ(run(flags + "--tf big.json -o big.png").status, 0);
  EXPECT_LT(fs::file_size(path("big.png")), fs::file_size(path("big.json")));
  const CommandRun again = run("render -q --session big.png -o again.png");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_TRUE(test::readRgbaPng(path("again.png")).rgba == test::readRgbaPng(path("big.png")).rgba);
}

// A bad value the session file set is refused naming the file and the session's key, however
// long the value (a 900 KB field name hid the file's name); the same value given as a flag names
// the flag.
TEST_F(CliTest, ABadValueFromASessionNamesTheSessionFile) {
  const std::string session =
      R"({"lic3d_session": 1, "field": {"source": ")" + std::string(900000, 'q') + R"("}})";
  writeBytes("long.json", session);
  const CommandRun fromFile = run("render -q --session long.json -o out.png");
  EXPECT_EQ(fromFile.status, 2) << fromFile.output.substr(0, 500);
  EXPECT_NE(fromFile.output.find("long.json: field.source 'qqq"), std::string::npos)
      << fromFile.output.substr(0, 500);
  EXPECT_NE(fromFile.output.find("is neither an analytic field"), std::string::npos)
      << fromFile.output.substr(0, 500);
  EXPECT_LT(fromFile.output.size(), 2000u);
  const CommandRun fromFlag = run("render -q --session long.json --field qqq -o out.png");
  EXPECT_EQ(fromFlag.status, 2);
  EXPECT_NE(fromFlag.output.find("--field 'qqq' is neither"), std::string::npos) << fromFlag.output;
  EXPECT_FALSE(fs::exists(path("out.png")));
}

}  // namespace
}  // namespace lic3d
