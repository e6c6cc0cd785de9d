// SPDX-License-Identifier: BSD-3-Clause
// Fields larger than the device or the host, from the command line: --devices, a field file read
// and its LIC written brick by brick, and render drawing a reduced copy of a LIC too large to
// draw (docs/SCALE.md).
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "cli_test_support.h"
#include "io/nrrd.h"
#include "lic/analytic_fields.h"

namespace lic3d {
namespace {

using test::CliTest;
using test::CommandRun;

bool has(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST_F(CliTest, DevicesAllOnOneDeviceIsTheDeviceAlone) {
  const CommandRun alone = run("compute --grid 40,32,24 -o alone.nrrd");
  const CommandRun all = run("compute --grid 40,32,24 --devices all -o all.nrrd");
  ASSERT_EQ(alone.status, 0) << alone.output;
  ASSERT_EQ(all.status, 0) << all.output;
  EXPECT_EQ(test::readWhole(path("alone.nrrd")), test::readWhole(path("all.nrrd")));
  // Each device's share: here the one device, all the voxels.
  EXPECT_TRUE(has(all.output, "\"devices\":[{\"device\":")) << all.output;
  EXPECT_TRUE(has(all.output, "\"voxels\":30720")) << all.output;
  for (const char* refused :
       {"compute --grid 8 --devices 0,0 -o x.nrrd", "compute --grid 8 --devices 9 -o x.nrrd",
        "compute --grid 8 --devices 0, -o x.nrrd",
        "--device 0 compute --grid 8 --devices all -o x.nrrd",
        "compute --grid 8 --cpu --devices all -o x.nrrd", "render --grid 8 --cpu --devices all"}) {
    const CommandRun r = run(refused);
    EXPECT_EQ(r.status, 2) << refused << "\n" << r.output;
    EXPECT_TRUE(has(r.output, "--device")) << refused << "\n" << r.output;
  }
  EXPECT_TRUE(has(run("compute --grid 8 --devices 0,0 -o x.nrrd").output, "named twice"));
  EXPECT_FALSE(std::filesystem::exists(path("x.nrrd")));
}

// A raw field file (float32, interleaved) with its sidecar.
void writeRawField(const std::filesystem::path& raw, const VectorField& field) {
  std::ofstream(raw, std::ios::binary)
      .write(reinterpret_cast<const char*>(field.vectors.data()),
             static_cast<std::streamsize>(field.vectors.size() * sizeof(glm::vec3)));
  std::ofstream(std::filesystem::path(raw).replace_extension(".json"))
      << "{\"dims\": [" << field.dims.x << ", " << field.dims.y << ", " << field.dims.z
      << "], \"spacing\": [0.5, 0.25, 0.5], \"origin\": [1, 2, 3]}";
}

double meanDifference(const ScalarVolume& a, const ScalarVolume& b) {
  double sum = 0.0;
  for (std::size_t i = 0; i < a.values.size(); ++i)
    sum += std::abs(static_cast<double>(a.values[i]) - b.values[i]);
  return sum / static_cast<double>(a.values.size());
}

TEST_F(CliTest, AFieldFileLargerThanTheBudgetIsReadAndWrittenByBricks) {
  writeRawField(path("abc.raw"), makeAnalyticField(AnalyticField::Abc, {36, 30, 24}));
  const std::string field = "compute --field abc.raw --length 10 ";
  const CommandRun whole = run(field + "-o whole.nrrd");
  ASSERT_EQ(whole.status, 0) << whole.output;
  EXPECT_FALSE(has(whole.output, "read_by_bricks")) << whole.output;
  const CommandRun bricked = run(field + "--memory-budget 300kB -o bricked.nrrd");
  ASSERT_EQ(bricked.status, 0) << bricked.output;
  EXPECT_TRUE(has(bricked.output, "\"read_by_bricks\":true")) << bricked.output;
  EXPECT_FALSE(has(bricked.output, "\"bricks\":1,")) << bricked.output;
  const Result<ScalarVolume> a = readScalarNrrd(path("whole.nrrd"));
  const Result<ScalarVolume> b = readScalarNrrd(path("bricked.nrrd"));
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->dims, b->dims);
  EXPECT_EQ(a->geometry, b->geometry);
  EXPECT_LE(meanDifference(*a, *b), 1e-3);
  // The same bricks into a raw file: the NRRD's payload, with a sidecar.
  const CommandRun raw = run(field + "--memory-budget 300kB -o bricked.raw");
  ASSERT_EQ(raw.status, 0) << raw.output;
  const std::string nrrd = test::readWhole(path("bricked.nrrd"));
  const std::string bytes = test::readWhole(path("bricked.raw"));
  ASSERT_EQ(bytes.size(), 36u * 30 * 24 * 4);
  EXPECT_EQ(nrrd.substr(nrrd.size() - bytes.size()), bytes);
  EXPECT_TRUE(has(test::readWhole(path("bricked.json")), "\"components\": 1"));
}

// Whether `parts` appear in `text` in this order, each on a line of its own after the one before.
::testing::AssertionResult inOrder(const std::string& text, const std::vector<std::string>& parts) {
  std::size_t at = 0;
  for (const std::string& part : parts) {
    const std::size_t found = text.find(part, at);
    if (found == std::string::npos)
      return ::testing::AssertionFailure()
             << "'" << part << "' not found after offset " << at << " of:\n"
             << text;
    at = text.find('\n', found);
  }
  return ::testing::AssertionSuccess();
}

// A bricked run names its stages as they start, from the plan on: the first line comes before
// the first brick's field and LIC, and the reduced copy and its picture say so too (a 700^3
// render on lavapipe printed nothing for its first minutes, and nothing after "done").
TEST_F(CliTest, ABrickedRunShowsProgressFromItsFirstStage) {
  const CommandRun r =
      run("render --field tornado --grid 96 --width 64 --height 64 --memory-budget 16MB -o r.png",
          "", test::Streams::StderrOnly);
  ASSERT_EQ(r.status, 0) << r.output;
  const std::string first = r.output.substr(0, r.output.find('\n'));
  EXPECT_EQ(first.rfind("lic3d: LIC 96x96x96 on llvmpipe", 0), 0u) << r.output;
  EXPECT_TRUE(has(first, " 0%: 8 bricks of 48x48x48 and")) << r.output;
  EXPECT_TRUE(
      inOrder(r.output,
              {"0%: brick 1 of 8: field and noise on the device", "0%: brick 1 of 8: LIC",
               "brick 2 of 8: field and noise", "brick 8 of 8: LIC",
               "lic3d: LIC 96x96x96 on llvmpipe", "lic3d: the field on 48x48x48, every 2nd voxel",
               "0%: the LIC volume to the device", "0%: the picture", "done in", "lic3d: wrote"}));
  EXPECT_TRUE(has(r.output, "lic3d: drawing 48x48x48 on llvmpipe")) << r.output;
  // compute in bricks, its field read brick by brick: the same stages.
  writeRawField(path("abc.raw"), makeAnalyticField(AnalyticField::Abc, {36, 30, 24}));
  const CommandRun c = run("compute --field abc.raw --length 10 --memory-budget 300kB -o c.nrrd",
                           "", test::Streams::StderrOnly);
  ASSERT_EQ(c.status, 0) << c.output;
  EXPECT_TRUE(inOrder(c.output, {"lic3d: reading abc.raw", "bricks of", "0%: brick 1 of ", ": LIC",
                                 "done in", "lic3d: wrote"}));
  EXPECT_TRUE(has(c.output, ": field and noise upload")) << c.output;
}

TEST_F(CliTest, ALicTooLargeToDrawIsDrawnFromAReducedCopy) {
  const std::string field = "render --field tornado --grid 96 --width 256 --height 256 ";
  const CommandRun full = run(field + "-o full.png");
  ASSERT_EQ(full.status, 0) << full.output;
  EXPECT_FALSE(has(full.output, "\"reduced\"")) << full.output;
  const CommandRun reduced = run(field + "--memory-budget 16MB -o reduced.png");
  ASSERT_EQ(reduced.status, 0) << reduced.output;
  EXPECT_TRUE(has(reduced.output, "\"reduced\":{\"factor\":2,\"grid\":[48,48,48]}"))
      << reduced.output;
  EXPECT_TRUE(has(reduced.output, "every 2nd voxel")) << reduced.output;
  const test::DecodedPng png = test::decodePng(path("reduced.png"));
  ASSERT_TRUE(png.ok);
  ASSERT_TRUE(png.text.count("lic3d-reduced"));
  EXPECT_TRUE(has(png.text.at("lic3d-reduced"), "LIC 96x96x96 made in"))
      << png.text.at("lic3d-reduced");
  // The same look as the whole volume's picture: as many pixels lit, as bright. (A stale
  // contrast window drew 24 % lit at a mean of 56 against 33 % at 39.)
  const test::DecodedPng whole = test::decodePng(path("full.png"));
  ASSERT_TRUE(whole.ok);
  ASSERT_EQ(whole.bytes.size(), png.bytes.size());
  ASSERT_EQ(png.bitDepth, 8);
  const std::size_t channels = png.colorType == 6 ? 4 : 3;
  const auto litAndMean = [&](const test::DecodedPng& picture) {
    std::size_t lit = 0;
    double sum = 0.0;
    for (std::size_t p = 0; p + 2 < picture.bytes.size(); p += channels) {
      const double grey = (picture.bytes[p] + picture.bytes[p + 1] + picture.bytes[p + 2]) / 3.0;
      if (grey > 8.0) {
        ++lit;
        sum += grey;
      }
    }
    const double pixels = static_cast<double>(picture.bytes.size() / channels);
    return std::pair(static_cast<double>(lit) / pixels, lit ? sum / static_cast<double>(lit) : 0.0);
  };
  const auto [wholeLit, wholeMean] = litAndMean(whole);
  const auto [reducedLit, reducedMean] = litAndMean(png);
  EXPECT_GT(wholeLit, 0.1);
  EXPECT_NEAR(reducedLit, wholeLit, 0.03);
  EXPECT_NEAR(reducedMean, wholeMean, 0.1 * wholeMean);
  // Its session makes it again, reduced again.
  const CommandRun again = run("render --session reduced.png --memory-budget 16MB -o again.png");
  ASSERT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(test::decodePng(path("again.png")).bytes, png.bytes);
  // What the LIC changes frame by frame cannot come from one reduced copy.
  const CommandRun bias = run(field + "--memory-budget 16MB --animate-bias 2 -o 'b_%d.png'");
  EXPECT_EQ(bias.status, 3) << bias.output;
}

// `bench --read-field` reads the whole file by each piece shape and packs one brick's inputs: every
// row a rate over the file's bytes.
TEST_F(CliTest, BenchReadFieldGivesTheRatesOfAStreamedFile) {
  const Dims dims{20, 12, 10};
  writeRawField(path("abc.raw"), makeAnalyticField(AnalyticField::Abc, dims));
  const CommandRun r = run("bench --read-field abc.raw --repeats 5 --warmup 1 --json r.json");
  ASSERT_EQ(r.status, 0) << r.output;
  const nlohmann::json report = nlohmann::json::parse(test::readWhole(path("r.json")));
  EXPECT_EQ(report["grid"], "20x12x10");
  EXPECT_EQ(report["file_bytes"], voxelCount(dims) * 12);
  std::vector<std::string> rows;
  for (const nlohmann::json& row : report["rows"]) {
    rows.push_back(row["what"].get<std::string>());
    EXPECT_GT(row.value("gb_per_s", 0.0), 0.0) << row.dump();
  }
  EXPECT_EQ(rows, (std::vector<std::string>{"scan (largest |u|)", "read by z-slabs",
                                            "read by bricks", "read by z-slabs, memory reused",
                                            "noise (GB of vectors)", "packing (GB of vectors)"}));
  EXPECT_TRUE(has(r.output, "read by z-slabs")) << r.output;
  // A file that must be read whole has no piece-read rate.
  std::ofstream(path("f.vtk")) << "# vtk DataFile Version 3.0\n";
  const CommandRun whole = run("bench --read-field f.vtk");
  EXPECT_NE(whole.status, 0) << whole.output;
  EXPECT_TRUE(has(whole.output, "f.vtk")) << whole.output;
}

}  // namespace
}  // namespace lic3d
