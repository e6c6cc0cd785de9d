// SPDX-License-Identifier: BSD-3-Clause
// The adversarial case list: inputs as an attacker or a careless script gives them, each class
// of docs/RELIABILITY.md with its cases, generated here (no committed binaries). Every case must
// end with its exit status and a message naming the flag or file, leave every file it found as it
// was (inputs untouched) and add nothing: no output, no temporary file.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "cli_test_support.h"
#include "core/session.h"
#include "io/nrrd.h"
#include "io/png_writer.h"
#include "lic/analytic_fields.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;

using test::CliTest;
using test::CommandRun;

struct Case {
  std::string name;
  std::string args;        // of lic3d, run in the test's folder
  int status;              // the exit status it must give
  std::string mentions;    // what its message must contain
  std::string makes = "";  // the one file it may add or replace (a case that succeeds)
};

std::string randomBytes(std::size_t count, unsigned seed) {
  std::mt19937 random(seed);
  std::string bytes(count, '\0');
  for (char& c : bytes) c = static_cast<char>(random());
  return bytes;
}

// A NRRD header for a 3-vector float field of 2x2x2 voxels with `extra` lines, and its data.
std::string smallNrrd(const std::string& extra) {
  std::string data(8 * 3 * 4, '\0');
  for (std::size_t i = 0; i < data.size(); i += 4) data[i + 3] = 0x3f;  // 0.5f little-endian
  return "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 2\nendian: little\nencoding: raw\n" +
         extra + "\n" + data;
}

class AdversarialTest : public CliTest {
 protected:
  // Every regular file of the folder and its content.
  std::map<std::string, std::string> snapshot() const {
    std::map<std::string, std::string> files;
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(folder()))
      if (e.is_regular_file())
        files[fs::relative(e.path(), folder()).string()] = test::readWhole(e.path());
    return files;
  }

  void makeInputs() {
    ASSERT_TRUE(writeVectorFieldNrrd(path("base.nrrd"),
                                     makeAnalyticField(AnalyticField::Tornado, Dims(8))));
    fs::create_directories(path("sub"));
    writeBytes("time_1e400.json", R"({"time": 1e400})");
    writeBytes("time_neg.json", R"({"time": -1e309})");
    writeBytes("width_wraps.json", R"({"view": {"width": 4294967328}})");
    writeBytes("grid_wraps.json", R"({"field": {"grid": [4294967304, 8, 8]}})");
    writeBytes("length_wraps.json", R"({"lic": {"length": 4294967297}})");
    writeBytes("length_frac.json", R"({"lic": {"length": 4.7}})");
    writeBytes("length_huge.json", R"({"lic": {"length": 1e30}})");
    writeBytes("slices_wrap.json", R"({"view": {"slices": 4294967296}})");
    writeBytes("version.json", R"({"lic3d_session": 1.9})");
    writeBytes("seed.json", R"({"noise": {"seed": -1}})");
    writeBytes("twice.json", R"({"lic": {"length": 7, "length": 8}})");
    writeBytes("deep.json", std::string(100000, '[') + std::string(100000, ']'));
    writeBytes("empty.json", "");
    // 800 KB of deflate that may claim 768 MB, and stops after 800 KB.
    writeBytes("bomb.nrrd",
               "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 400 400 400\nendian: little\n"
               "encoding: gzip\n\n" +
                   test::deflateBytes(randomBytes(800'000, 1), 15 + 16));
    writeBytes("self.nhdr",
               "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 2\nendian: little\n"
               "encoding: raw\ndata file: self.nhdr\n#" +
                   std::string(200, ' ') + "\n");
    writeBytes("spacing_huge.nrrd", smallNrrd("spacings: NaN 1e308 1e308 1e308\n"));
    writeBytes("spacing_aniso.nrrd", smallNrrd("spacings: NaN 1e-30 1e30 1\n"));
    writeBytes("direction_huge.nrrd",
               smallNrrd("space dimension: 3\nspace directions: none (1e200,0,0) (0,1,0) "
                         "(0,0,1)\n"));
    writeBytes("sizes_overflow.nrrd",
               "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 4294967296 4294967296 "
               "4294967296\nendian: little\nencoding: raw\n\n");
    const std::string whole = smallNrrd("");
    writeBytes("truncated.nrrd", whole.substr(0, whole.size() - 10));
    // A PNG whose session chunk (zTXt) inflates to 1 MiB more than a session may hold.
    ASSERT_TRUE(writePng(path("plain.png"), RgbaImage{1, 1, {0, 0, 0, 255}}));
    writeBytes("session_bomb.png",
               test::withPngChunk(test::readWhole(path("plain.png")), "zTXt",
                                  std::string("lic3d-session\0\0", 15) +
                                      test::deflateZeros(kMaxSessionBytes + (1 << 20))));
    fs::remove(path("plain.png"));
    writeBytes("garbage.vti", randomBytes(4096, 2));
    writeBytes("nested.vti", "<?xml version=\"1.0\"?>" + std::string(100000, '<') + "a");
    writeBytes("empty.vtk", "");
    // .pvti files whose whole extent wraps int, claims far more than its pieces, or has a gap:
    // refused before any piece is read (none of the pieces exists).
    const auto pvti = [&](const std::string& name, const std::string& extent,
                          const std::string& pieces) {
      writeBytes(name, "<VTKFile type=\"PImageData\"><PImageData WholeExtent=\"" + extent + "\">" +
                           pieces + "</PImageData></VTKFile>");
    };
    const std::string twoPoints = "<Piece Extent=\"0 1 0 0 0 0\" Source=\"none.vti\"/>";
    pvti("wraps.pvti", "0 4294967311 0 0 0 0", twoPoints);
    pvti("claims.pvti", "0 99999999999 0 0 0 0", twoPoints);
    pvti("claims_within.pvti", "0 1023 0 1023 0 63", twoPoints);
    pvti("gap.pvti", "0 3 0 0 0 0",
         twoPoints + "<Piece Extent=\"3 3 0 0 0 0\" Source=\"none.vti\"/>");
    // A raw field whose sidecar gives a key twice.
    writeBytes("key_twice.raw", std::string(8 * 3 * 4, '\0'));
    writeBytes("key_twice.json", R"({"dims": [2, 2, 2], "dims": [1, 1, 8]})");
    for (const char* step : {"dup_1.vti", "dup_01.vti", "dup_001.vti"})
      fs::copy_file(path("base.nrrd"), path(step));  // the names are refused before reading
    // FIFOs, which a reader that opens them blocking waits on forever.
    for (const char* fifo : {"fifo.json", "fifo.png", "frame_1.png"})
      ASSERT_EQ(::mkfifo(path(fifo).c_str(), 0600), 0) << fifo;
    writeBytes("run.json", R"({"lic": {"length": 5}})");
    writeBytes("keep.json", "notes of the user\n");
    writeBytes("forged.png", std::string("\x89PNG\r\n\x1a\n", 8) +
                                 std::string("\0\0\0\0IEND\xae\x42\x60\x82", 12));
  }
};

TEST_F(AdversarialTest, EveryCaseEndsWithItsStatusAndChangesNothing) {
  makeInputs();
  const std::string render = "render --grid 8 --width 32 --height 32 -q ";
  const std::string field = "render -q --width 32 --height 32 -o o.png --field ";
  std::vector<Case> cases = {
      // Class 1: numbers beyond a double in sessions.
      {"session 1e400", "render --session time_1e400.json -o o.png", 2, "time_1e400.json"},
      {"session -1e309", "compute --session time_neg.json -o o.nrrd", 2, "time_neg.json"},
      // Class 2: an output that is an input.
      {"-o is the field", "compute --field base.nrrd -o base.nrrd", 2, "base.nrrd"},
      {"-o spelt another way", "compute --field base.nrrd -o sub/../base.nrrd", 2, "base.nrrd"},
      {"rgba volume over the field", field + "base.nrrd --rgba-volume base.nrrd", 2, "base.nrrd"},
      // Class 3: compressed data that promises more than it holds.
      {"gzip bomb", field + "bomb.nrrd", 2, "gzip data holds only"},
      {"PNG session bomb", "render --session session_bomb.png -o o.png", 2,
       "session_bomb.png: no text chunk lic3d-session could be read"},
      // Class 5: NaN, infinite and huge flag values.
      {"azimuth nan", render + "--azimuth nan", 2, "--azimuth"},
      {"azimuth inf", render + "--azimuth inf", 2, "--azimuth"},
      {"azimuth 1e300", render + "--azimuth 1e300", 2, "--azimuth"},
      {"elevation nan", render + "--elevation nan", 2, "--elevation"},
      {"fov nan", render + "--fov nan", 2, "--fov"},
      {"gain nan", render + "--gain nan", 2, "--gain"},
      {"brightness nan", render + "--brightness nan", 2, "--brightness"},
      {"roi-center nan", render + "--roi-center nan,0.5,0.5", 2, "--roi-center"},
      {"roi-rotate inf", render + "--roi-rotate inf,0,0", 2, "--roi-rotate"},
      {"time nan", render + "--time nan", 2, "--time"},
      {"distance nan", render + "--distance nan", 2, "--distance"},
      {"eye-separation nan", render + "--eye-separation nan", 2, "--eye-separation"},
      {"zero-parallax nan", render + "--zero-parallax nan", 2, "--zero-parallax"},
      {"magnitude-opacity nan", render + "--magnitude-opacity nan", 2, "--magnitude-opacity"},
      {"color-range inf", render + "--color-range 0,inf", 2, "--color-range"},
      {"background nan", render + "--background 2,2,nan", 2, "--background"},
      {"width huge", render + "--width 1e9", 2, "--width"},
      {"step zero", render + "--step 0", 2, "--step"},
      {"empty number", render + "--length ''", 2, "--length"},
      {"empty angle", render + "--azimuth ''", 2, "--azimuth"},
      // Class 5: a value of the wrong kind is named with the flag's own range, not CLI11's words.
      {"length abc", render + "--length abc", 2,
       "--length: expected a whole number in [0, 4096], got 'abc'"},
      {"length 1.5", render + "--length 1.5", 2,
       "--length: expected a whole number in [0, 4096], got '1.5'"},
      {"length 1e999", render + "--length 1e999", 2, "--length: must be in [0, 4096], got '1e999'"},
      {"threads -1", "--threads -1 " + render, 2, "--threads: must be in [0, 4096], got '-1'"},
      {"turntable abc", render + "--turntable abc", 2,
       "--turntable: expected a whole number in [1, 1e+06], got 'abc'"},
      {"fps 1e999", render + "--turntable 2 --fps 1e999", 2,
       "--fps: must be in [0.1, 1000], got '1e999'"},
      {"step abc", render + "--step abc", 2, "--step: expected a number in [0.001, 8], got 'abc'"},
      {"unknown flag", render + "--no-such-flag 1", 2, "--no-such-flag"},
      {"devices empty", render + "--devices ''", 2, "--devices: needs 'all'"},
      {"kernel foo", render + "--kernel foo", 2,
       "--kernel: must be one of box, hann, gauss; got 'foo'"},
      {"clip plane zero", render + "-o o.png --clip-plane 0.5,0.5,0.5,0,0,0", 2,
       "the normal given is (0, 0, 0)"},
      {"resolution 1e-300x", field + "base.nrrd --resolution 1e-300x", 2,
       "each axis must be in [2, "},
      // Class 6: integers that would wrap or truncate.
      {"seed -1", render + "--seed -1", 2, "--seed"},
      {"sparsity-seed -5", render + "--sparsity-seed -5", 2, "--sparsity-seed"},
      {"session width wraps", "render --session width_wraps.json -o o.png", 2, "view.width"},
      {"session grid wraps", "render --session grid_wraps.json -o o.png", 2, "field.grid"},
      {"session length wraps", "render --session length_wraps.json -o o.png", 2, "lic.length"},
      {"session length 4.7", "render --session length_frac.json -o o.png", 2, "lic.length"},
      {"session length 1e30", "render --session length_huge.json -o o.png", 2,
       "lic.length must be a whole number in [0, 4096], got '1e+30'"},
      {"seed beyond 64 bits", render + "--seed 99999999999999999999999", 2,
       "from 0 to 18446744073709551615, got 99999999999999999999999"},
      {"budget 0", render + "--memory-budget 0", 2, "from 1 byte to 18446744073709551615 bytes"},
      {"budget -0", render + "--memory-budget -0", 2, "got '-0'"},
      {"budget -1", render + "--memory-budget -1", 2, "got '-1'"},
      {"budget 2^64", render + "--memory-budget 18446744073709551616", 2,
       "got '18446744073709551616'"},
      {"budget -16MiB", render + "--memory-budget -16MiB", 2, "got '-16MiB'"},
      {"budget 1KiB", "compute --grid 8 -q --memory-budget 1KiB -o o.nrrd", 3,
       "the memory budget given is 1.0 KiB (1024 bytes)"},
      {"budget 1KiB to draw", render + "--memory-budget 1KiB -o o.png", 3,
       "within --memory-budget 1024 bytes"},
      {"session slices wrap", "render --session slices_wrap.json -o o.png", 2, "view.slices"},
      {"session version 1.9", "render --session version.json -o o.png", 2, "lic3d_session"},
      {"session seed -1", "render --session seed.json -o o.png", 2, "noise.seed"},
      {"session key twice", "render --session twice.json -o o.png", 2, "length"},
      {"session nested deeply", "render --session deep.json -o o.png", 2, "deep.json"},
      {"session empty", "render --session empty.json -o o.png", 2, "empty.json"},
      {"session missing", "render --session missing.json -o o.png", 2, "missing.json"},
      // Class 9: the longest name a file may have.
      {"250-character name", render + "-o " + std::string(246, 'n') + ".png", 0, "",
       std::string(246, 'n') + ".png"},
      // Class 10: an output that cannot be written stops the run before any output.
      {"unwritable rgba volume", render + "-o out.png --rgba-volume /proc/self/v.vti", 2,
       "/proc/self"},
      {"missing folder", render + "-o no/such/folder/out.png", 2, "no/such/folder"},
      // Class 11 to 14: files that cannot be drawn, or whose message misled.
      {"data file is itself", field + "self.nhdr", 2, "the header itself"},
      {"spacing 1e308", field + "spacing_huge.nrrd", 2, "spacing_huge.nrrd"},
      {"spacing 1e-30 and 1e30", field + "spacing_aniso.nrrd", 2, "spacing_aniso.nrrd"},
      {"direction 1e200", field + "direction_huge.nrrd", 2, "1e+200"},
      {"sizes overflow", field + "sizes_overflow.nrrd", 2, "sizes_overflow.nrrd"},
      {"truncated data", field + "truncated.nrrd", 2, "truncated"},
      {"garbage VTI", field + "garbage.vti", 2, "garbage.vti"},
      {"XML nested deeply", field + "nested.vti", 2, "nested.vti"},
      {"empty VTK", field + "empty.vtk", 2, "empty.vtk"},
      {"pvti extent wraps int", field + "wraps.pvti", 2, "WholeExtent '0 4294967311 0 0 0 0'"},
      {"pvti extent 1e11", field + "claims.pvti", 2, "WholeExtent '0 99999999999 0 0 0 0'"},
      {"pvti pieces fill little", field + "claims_within.pvti", 2, "without data"},
      {"pvti pieces leave a gap", field + "gap.pvti", 2, "without data"},
      {"raw sidecar key twice", field + "key_twice.raw", 2, "the key 'dims' appears twice"},
      {"a folder as field", field + "sub", 2, "sub"},
      {"/dev/zero as field", field + "/dev/zero", 2, "/dev/zero"},
      {"one step three ways", field + "dup_%d.vti", 2, "dup_"},
      {"name not UTF-8", field + "\"$(printf 'wa\\353.nrrd')\"", 2, "not UTF-8"},
      {"100 KB field name", field + std::string(100'000, 'f') + ".nrrd", 2, "fff"},
      // Class 16: files that are not regular files hang no run.
      {"FIFO as JSON session", "render --session fifo.json -o o.png", 2,
       "fifo.json: not a regular file"},
      {"FIFO as PNG session", "render --session fifo.png -o o.png", 2,
       "fifo.png: not a regular file"},
      {"FIFO as --skip-existing output", render + "--skip-existing -o fifo.png", 2,
       "fifo.png: not a regular file"},
      {"FIFO as a turntable frame", render + "--skip-existing --turntable 2 -o frame_%d.png", 2,
       "frame_1.png: not a regular file"},
      // Class 17: a sidecar or a session that an output would replace.
      {"raw sidecar over the session", "compute --session run.json --grid 8 -q -o run.raw", 2,
       "run.json: is an input"},
      {"raw sidecar over another JSON", "compute --grid 8 -q -o keep.raw", 2,
       "keep.json: exists and is not the JSON sidecar"},
      // Class 18: --skip-existing keeps only a PNG that decodes.
      {"forged PNG redone", render + "--skip-existing -o forged.png", 0, "", "forged.png"},
  };
  int handled = 0;
  for (const Case& c : cases) {
    std::map<std::string, std::string> before = snapshot();
    // A hang (a FIFO opened blocking) fails its case instead of the suite.
    const CommandRun r = run(c.args, "timeout -k 5 30");
    EXPECT_EQ(r.status, c.status) << c.name << ": " << r.output.substr(0, 500);
    EXPECT_NE(r.output.find(c.mentions), std::string::npos)
        << c.name << ": " << r.output.substr(0, 500);
    EXPECT_LT(r.output.size(), 2000u) << c.name << ": the message should be short";
    std::map<std::string, std::string> after = snapshot();
    if (!c.makes.empty()) {
      EXPECT_EQ(after.count(c.makes), 1u) << c.name;
      EXPECT_NE(after[c.makes], before[c.makes]) << c.name << ": not made again";
      after.erase(c.makes);
      before.erase(c.makes);
      fs::remove(path(c.makes));
    }
    EXPECT_TRUE(after == before) << c.name << ": the folder changed";
    handled += r.status == c.status && after == before ? 1 : 0;
  }
  std::printf("adversarial cases: %d of %zu handled\n", handled, cases.size());
  EXPECT_EQ(handled, static_cast<int>(cases.size()));
}

// Class 19: outputs larger than the free space of their file system (a 1 MiB tmpfs mounted in a
// user namespace) are refused before any work: status 3 with both numbers, no LIC progress (the
// progress lines are on without -q), nothing left on the small file system. Outputs that share
// it are summed.
TEST_F(AdversarialTest, OutputsLargerThanTheirFileSystemAreRefusedBeforeTheLic) {
  fs::create_directories(path("small"));
  const std::string mount = "mount -t tmpfs -o size=1m tmpfs small";
  const CommandRun probe = shell("unshare -rm sh -c '" + mount + "' 2>&1");
  if (probe.status != 0)
    GTEST_SKIP() << "cannot mount a tmpfs in a user namespace: " << probe.output;
  // lic3d on the small file system, then what is left on it (nothing, after a refusal).
  const std::string onSmall = "unshare -rm sh -c '" + mount +
                              " && \"$0\" \"$@\"; s=$?; echo \"left:[$(ls -A small)]\"; exit $s'";
  struct SpaceCase {
    std::string name;
    std::string args;
    std::string mentions;
  };
  const std::vector<SpaceCase> cases = {
      {"volume", "compute --grid 128 -o small/v.nrrd",
       "small/v.nrrd: the output takes 8454144 bytes, but its file system has 1048576 bytes free"},
      {"raw volume and sidecar", "compute --grid 128 -o small/v.raw", "small/v.raw: the output"},
      {"slice PNG", "compute --grid 768,768,4 --slice z -o small/s.png",
       "small/s.png: the output takes at most"},
      {"picture", "render --grid 16 --width 2048 --height 2048 -o small/p.png",
       "small/p.png: the output takes at most"},
      // Each frame fits, the twelve do not.
      {"frames summed",
       "render --grid 16 --width 480 --height 480 --turntable 12 -o small/f_%d.png",
       "small/f_0.png and 11 other output(s) on its file system: they take at most"},
      {"picture and RGBA volume",
       "render --grid 62 --width 480 --height 480 -o small/p.png --rgba-volume small/v.vti",
       "small/p.png and 1 other output(s) on its file system"},
      {"2D picture", "render2d --field tornado --grid 1000 -o small/p.png",
       "small/p.png: the output takes at most"},
  };
  for (const SpaceCase& c : cases) {
    const CommandRun r = run(c.args, onSmall);
    EXPECT_EQ(r.status, 3) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find(c.mentions), std::string::npos) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find("bytes free"), std::string::npos) << c.name << ": " << r.output;
    EXPECT_EQ(r.output.find("lic3d: LIC"), std::string::npos) << c.name << ": " << r.output;
    EXPECT_NE(r.output.find("left:[]"), std::string::npos) << c.name << ": " << r.output;
  }
  // What fits is written.
  const CommandRun fits =
      run("render -q --grid 16 --width 64 --height 64 -o small/ok.png", onSmall);
  EXPECT_EQ(fits.status, 0) << fits.output;
  EXPECT_NE(fits.output.find("left:[ok.png]"), std::string::npos) << fits.output;
}

}  // namespace
}  // namespace lic3d
