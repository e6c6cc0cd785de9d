// SPDX-License-Identifier: BSD-3-Clause
// Raw float32/float64 vector fields with a JSON sidecar: layouts, byte orders, sidecar names and
// malformed sidecars.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "io/field_io.h"
#include "io/raw_volume.h"
#include "test_support.h"

namespace lic3d {
namespace {

namespace fs = std::filesystem;
using test::bytesOf;
using test::expectInputError;
using test::expectSameField;

class RawVolumeTest : public test::TempFolderTest {};

VectorField makeField(Dims dims) {
  VectorField field;
  field.dims = dims;
  field.geometry = {{0.5, 0.25, 2.0}, {-1.0, 3.0, 0.125}};
  for (std::size_t i = 0; i < voxelCount(dims); ++i) {
    const float t = static_cast<float>(i);
    field.vectors.push_back({std::sin(t), std::cos(0.5f * t) + 2.0f, 0.1f * t - 1.0f});
  }
  return field;
}

template <class T>
std::vector<T> interleaved(const VectorField& field) {
  std::vector<T> values;
  for (const glm::vec3& v : field.vectors) values.insert(values.end(), {T(v.x), T(v.y), T(v.z)});
  return values;
}

template <class T>
std::vector<T> planar(const VectorField& field) {
  std::vector<T> values;
  for (glm::length_t axis = 0; axis < 3; ++axis)
    for (const glm::vec3& v : field.vectors) values.push_back(T(v[axis]));
  return values;
}

const char kGeometry[] = R"("spacing": [0.5, 0.25, 2], "origin": [-1, 3, 0.125])";

TEST_F(RawVolumeTest, ReadsEveryLayoutTypeAndByteOrder) {
  const VectorField field = makeField({4, 3, 2});
  struct Case {
    const char* label;
    std::string sidecar;
    std::string data;
  };
  const Case cases[] = {
      {"defaults", std::string(R"({"dims": [4, 3, 2], )") + kGeometry + "}",
       bytesOf(interleaved<float>(field), std::endian::little)},
      {"interleaved float32 little",
       std::string(
           R"({"dims": [4,3,2], "components": 3, "order": "interleaved", "type": "float32", "endian": "little", )") +
           kGeometry + "}",
       bytesOf(interleaved<float>(field), std::endian::little)},
      {"planar", std::string(R"({"dims": [4,3,2], "order": "planar", )") + kGeometry + "}",
       bytesOf(planar<float>(field), std::endian::little)},
      {"big endian", std::string(R"({"dims": [4,3,2], "endian": "big", )") + kGeometry + "}",
       bytesOf(interleaved<float>(field), std::endian::big)},
      {"float64", std::string(R"({"dims": [4,3,2], "type": "float64", )") + kGeometry + "}",
       bytesOf(interleaved<double>(field), std::endian::little)},
      {"planar float64 big endian",
       std::string(R"({"dims": [4,3,2], "type": "float64", "order": "planar", "endian": "big", )") +
           kGeometry + "}",
       bytesOf(planar<double>(field), std::endian::big)},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.label);
    const fs::path file = writeBytes("field.raw", c.data);
    writeBytes("field.json", c.sidecar);
    FieldReadInfo info;
    const Result<VectorField> read = readVectorField(file, {}, &info);
    ASSERT_TRUE(read.ok()) << read.error().message;
    expectSameField(*read, field);
    EXPECT_EQ(info.nonFiniteVectors, 0u);
  }
}

TEST_F(RawVolumeTest, DefaultGeometryAndTheOtherSidecarName) {
  VectorField field = makeField({2, 2, 2});
  field.geometry = {};
  const fs::path file =
      writeBytes("flow.RAW", bytesOf(interleaved<float>(field), std::endian::little));
  writeBytes("flow.RAW.json", R"({"dims": [2, 2, 2]})");
  const Result<VectorField> read = readVectorField(file);
  ASSERT_TRUE(read.ok()) << read.error().message;
  expectSameField(*read, field);
  EXPECT_EQ(*findRawSidecar(file), path("flow.RAW.json"));
  // Both names at once are ambiguous.
  writeBytes("flow.json", R"({"dims": [2, 2, 2]})");
  expectInputError(readVectorFieldRaw(file), file,
                   "two JSON sidecars describe it, 'flow.json' and 'flow.RAW.json'");
}

TEST_F(RawVolumeTest, NonFiniteVectorsBecomeZeroAndAreCounted) {
  VectorField field = makeField({3, 1, 1});
  std::vector<float> values = interleaved<float>(field);
  values[1] = std::numeric_limits<float>::quiet_NaN();
  values[8] = std::numeric_limits<float>::infinity();
  const fs::path file = writeBytes("nan.raw", bytesOf(values, std::endian::little));
  writeBytes("nan.json", R"({"dims": [3, 1, 1]})");
  FieldReadInfo info;
  const Result<VectorField> read = readVectorFieldRaw(file, &info);
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(info.nonFiniteVectors, 2u);
  EXPECT_EQ(read->vectors[0], glm::vec3(0.0f));
  EXPECT_EQ(read->vectors[1], field.vectors[1]);
  EXPECT_EQ(read->vectors[2], glm::vec3(0.0f));

  const fs::path zero = writeBytes("zero.raw", std::string(36, '\0'));
  writeBytes("zero.json", R"({"dims": [3, 1, 1]})");
  expectInputError(readVectorFieldRaw(zero), zero, "every vector of the field is zero");
}

TEST_F(RawVolumeTest, SizeMismatchAndMissingSidecarAreErrors) {
  const fs::path file = writeBytes("field.raw", std::string(95, '\1'));
  expectInputError(readVectorField(file), file,
                   "no JSON sidecar: expected 'field.json' or 'field.raw.json' beside it");
  writeBytes("field.json", R"({"dims": [2, 2, 2]})");
  expectInputError(readVectorField(file), file,
                   "the file holds 95 bytes; the 2x2x2 grid of 3 float32 components its sidecar "
                   "describes needs 96");
  writeBytes("field.json", R"({"dims": [2, 2, 2], "type": "float64"})");
  expectInputError(readVectorField(file), file, "needs 192");
  expectInputError(readVectorField(file, "velocity"), file, "a raw file holds one unnamed array");
}

TEST_F(RawVolumeTest, MalformedSidecarsAreInputErrorsNamingBothFiles) {
  struct Case {
    const char* label;
    std::string sidecar;
    const char* fragment;
  };
  const Case cases[] = {
      {"empty", "", "not valid JSON"},
      {"not json", "dims = 2 2 2", "not valid JSON"},
      {"array", "[2, 2, 2]", "expected a JSON object"},
      {"missing dims", R"({"spacing": [1, 1, 1]})", "missing \"dims\""},
      {"two dims", R"({"dims": [2, 2]})",
       "dims: expected 3 whole numbers [nx, ny, nz], found '[2,2]'"},
      {"negative dims", R"({"dims": [2, -2, 2]})", "dims: expected 3 whole numbers"},
      {"fractional dims", R"({"dims": [2, 2.5, 2]})", "dims: expected 3 whole numbers"},
      {"text dims", R"({"dims": "2 2 2"})", "dims: expected 3 whole numbers"},
      {"zero dims", R"({"dims": [2, 0, 2]})", "outside [1, 16384]"},
      {"huge dims", R"({"dims": [16384, 16384, 16384]})", "more than the limit"},
      {"enormous dims", R"({"dims": [2, 99999999999999999999999, 2]})", "dims: expected"},
      {"zero spacing", R"({"dims": [2, 2, 2], "spacing": [1, 0, 1]})",
       "spacing: expected 3 positive numbers"},
      {"huge spacing", R"({"dims": [2, 2, 2], "spacing": [1, 1e999, 1]})",
       "number overflow parsing '1e999'"},
      {"text origin", R"({"dims": [2, 2, 2], "origin": ["a", 0, 0]})",
       "origin: expected 3 finite numbers"},
      {"components", R"({"dims": [2, 2, 2], "components": 2})", "components: expected 3"},
      {"order", R"({"dims": [2, 2, 2], "order": "zigzag"})",
       "order: expected \"interleaved\" or \"planar\", found '\"zigzag\"'"},
      {"type", R"({"dims": [2, 2, 2], "type": "float16"})", "type: expected \"float32\" or"},
      {"endian", R"({"dims": [2, 2, 2], "endian": 1})", "endian: expected \"little\" or \"big\""},
      {"unknown key", R"({"dims": [2, 2, 2], "spacings": [1, 1, 1]})", "unknown key 'spacings'"},
      {"deep", std::string(5000, '[') + std::string(5000, ']'), "nested deeper than"},
      {"trailing", R"({"dims": [2, 2, 2]} x)", "not valid JSON"},
      {"key twice", R"({"dims": [2, 2, 2], "dims": [4, 4, 4]})",
       "the key 'dims' appears twice in one object"},
      {"too large", R"({"dims": [2, 2, 2], "pad": ")" + std::string(70000, ' ') + "\"}",
       "too large"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.label);
    const fs::path file = writeBytes("bad field.raw", std::string(96, '\1'));
    writeBytes("bad field.json", c.sidecar);
    expectInputError(readVectorFieldRaw(file),
                     c.label == std::string("too large") ? path("bad field.json") : file,
                     c.fragment);
  }
}

TEST_F(RawVolumeTest, CorruptedSidecarsNeverCrashTheReader) {
  const std::string good =
      R"({"dims": [2, 3, 2], "spacing": [0.5, 1, 2], "origin": [1, 2, 3], "components": 3,)"
      R"( "order": "planar", "type": "float32", "endian": "big"})";
  const fs::path file = writeBytes("mutated.raw", std::string(144, '\x3f'));
  std::mt19937 random(5);
  for (int trial = 0; trial < 500; ++trial) {
    std::string mutated = good;
    const int flips = 1 + static_cast<int>(random() % 4);
    for (int f = 0; f < flips; ++f)
      mutated[random() % mutated.size()] = "0123456789[]{}\",:-.eE \\"[random() % 24];
    if (trial % 5 == 0) mutated.resize(random() % mutated.size());
    writeBytes("mutated.json", mutated);
    const Result<VectorField> read = readVectorFieldRaw(file);
    if (!read.ok()) {
      EXPECT_EQ(read.error().kind, ErrorKind::InvalidInput) << read.error().message;
    } else {
      EXPECT_EQ(read->vectors.size(), voxelCount(read->dims));
    }
  }
}

}  // namespace
}  // namespace lic3d
