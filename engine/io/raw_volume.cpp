// SPDX-License-Identifier: BSD-3-Clause
#include "io/raw_volume.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <system_error>
#include <vector>

#include "core/parallel.h"
#include "core/strict_json.h"
#include "core/text.h"
#include "io/file_util.h"
#include "io/number_type.h"

namespace lic3d {
namespace {

constexpr std::uint64_t kMaxSidecarBytes = 64 * 1024;
// The sidecar is a flat object of short arrays; deeper nesting is refused while parsing.
constexpr int kMaxSidecarDepth = 4;
constexpr std::string_view kKnownKeys[] = {"dims",  "spacing", "origin", "components",
                                           "order", "type",    "endian", "bytes"};

using Json = nlohmann::json;

bool fileExists(const std::filesystem::path& path) {
  std::error_code error;
  return std::filesystem::exists(path, error);
}

class SidecarReader {
 public:
  SidecarReader(const std::filesystem::path& rawPath, const std::filesystem::path& sidecarPath,
                std::uint64_t maxVoxels)
      : rawPath_(rawPath), sidecarName_(sidecarPath.filename().string()), maxVoxels_(maxVoxels) {}

  Error fail(const std::string& problem) const {
    return fileError(rawPath_, "sidecar " + quoteForMessage(sidecarName_) + ": " + problem);
  }

  Result<RawLayout> interpret(const Json& json) const {
    if (!json.is_object()) return fail("expected a JSON object {\"dims\": [nx, ny, nz], ...}");
    for (const auto& [key, value] : json.items()) {
      if (std::find(std::begin(kKnownKeys), std::end(kKnownKeys), key) == std::end(kKnownKeys))
        return fail("unknown key " + quoteForMessage(key) +
                    " (known: dims, spacing, origin, components, order, type, endian, bytes)");
    }
    RawLayout sidecar;
    if (!json.contains("dims")) return fail("missing \"dims\": [nx, ny, nz]");
    const Json& dims = json["dims"];
    std::array<std::uint64_t, 3> sizes{};
    bool good = dims.is_array() && dims.size() == 3;
    for (std::size_t axis = 0; good && axis < 3; ++axis) {
      good = dims[axis].is_number_unsigned();
      if (good) sizes[axis] = dims[axis].get<std::uint64_t>();
    }
    if (!good) return fail("dims: expected 3 whole numbers [nx, ny, nz], found " + shown(dims));
    if (const std::string problem = gridLimitProblem(sizes[0], sizes[1], sizes[2], maxVoxels_);
        !problem.empty())
      return fail("dims: " + problem);
    sidecar.dims =
        Dims(static_cast<int>(sizes[0]), static_cast<int>(sizes[1]), static_cast<int>(sizes[2]));
    LIC3D_TRY_ASSIGN(sidecar.geometry.spacing, triple(json, "spacing", 1.0, true));
    LIC3D_TRY_ASSIGN(sidecar.geometry.origin, triple(json, "origin", 0.0, false));
    if (json.contains("components")) {
      const Json& components = json["components"];
      if (!components.is_number_unsigned() || components.get<std::uint64_t>() != 3)
        return fail("components: expected 3 (a vector field), found " + shown(components));
    }
    LIC3D_TRY_ASSIGN(const std::string order,
                     word(json, "order", "interleaved", {"interleaved", "planar"}));
    sidecar.planar = order == "planar";
    LIC3D_TRY_ASSIGN(const std::string type, word(json, "type", "float32", {"float32", "float64"}));
    sidecar.valueBytes = type == "float64" ? 8 : 4;
    LIC3D_TRY_ASSIGN(const std::string endian, word(json, "endian", "little", {"little", "big"}));
    sidecar.order = endian == "big" ? std::endian::big : std::endian::little;
    if (json.contains("bytes")) {
      const Json& bytes = json["bytes"];
      const std::uint64_t needed = voxelCount(sidecar.dims) * 3 * sidecar.valueBytes;
      if (!bytes.is_number_unsigned() || bytes.get<std::uint64_t>() != needed)
        return fail("bytes: expected " + std::to_string(needed) + " for its grid, found " +
                    shown(bytes));
      // The data file's size is checked against the grid by every reader: a file replaced
      // without its sidecar (an interrupted write of the pair) differs.
    }
    return sidecar;
  }

 private:
  static std::string shown(const Json& value) { return quoteForMessage(value.dump()); }

  Result<glm::dvec3> triple(const Json& json, const char* key, double fallback,
                            bool positive) const {
    if (!json.contains(key)) return glm::dvec3(fallback);
    const Json& value = json[key];
    glm::dvec3 result{0.0};
    bool good = value.is_array() && value.size() == 3;
    for (glm::length_t axis = 0; good && axis < 3; ++axis) {
      good = value[static_cast<std::size_t>(axis)].is_number();
      if (good) result[axis] = value[static_cast<std::size_t>(axis)].get<double>();
      good = good && std::isfinite(result[axis]) && (!positive || result[axis] > 0.0);
    }
    if (!good)
      return fail(std::string(key) + ": expected 3 " + (positive ? "positive" : "finite") +
                  " numbers, found " + shown(value));
    return result;
  }

  Result<std::string> word(const Json& json, const char* key, const char* fallback,
                           std::initializer_list<std::string_view> allowed) const {
    if (!json.contains(key)) return std::string(fallback);
    const Json& value = json[key];
    std::string expected;
    for (const std::string_view each : allowed)
      expected += (expected.empty() ? "\"" : " or \"") + std::string(each) + "\"";
    if (value.is_string()) {
      const std::string text = value.get<std::string>();
      if (std::find(allowed.begin(), allowed.end(), text) != allowed.end()) return text;
    }
    return fail(std::string(key) + ": expected " + expected + ", found " + shown(value));
  }

  const std::filesystem::path& rawPath_;
  std::string sidecarName_;
  std::uint64_t maxVoxels_;
};

Result<RawLayout> readSidecar(const std::filesystem::path& rawPath,
                              const std::filesystem::path& sidecarPath, std::uint64_t maxVoxels) {
  const SidecarReader reader(rawPath, sidecarPath, maxVoxels);
  LIC3D_TRY_ASSIGN(const std::string text, readFile(sidecarPath, kMaxSidecarBytes));
  // A key given twice is refused as in sessions (strict_json.h): "last wins" would read a grid
  // the file's author may not have meant.
  Result<Json> json = parseJsonStrictly<Json>(text, "", kMaxSidecarDepth);
  if (!json)
    return reader.fail(json.error().message.substr(2));  // without parseJsonStrictly's ": "
  return reader.interpret(*json);
}

}  // namespace

bool isRawSidecarKey(std::string_view key) {
  return std::find(std::begin(kKnownKeys), std::end(kKnownKeys), key) != std::end(kKnownKeys);
}

Result<std::filesystem::path> findRawSidecar(const std::filesystem::path& rawPath) {
  std::filesystem::path byStem = rawPath;
  byStem.replace_extension(".json");
  std::filesystem::path byName = rawPath;
  byName += ".json";
  const bool stemExists = fileExists(byStem);
  const bool nameExists = fileExists(byName);
  if (stemExists && nameExists)
    return fileError(rawPath, "two JSON sidecars describe it, " +
                                  quoteForMessage(byStem.filename().string()) + " and " +
                                  quoteForMessage(byName.filename().string()) + "; remove one");
  if (stemExists) return byStem;
  if (nameExists) return byName;
  return fileError(rawPath, "no JSON sidecar: expected " +
                                quoteForMessage(byStem.filename().string()) + " or " +
                                quoteForMessage(byName.filename().string()) +
                                " beside it (with dims, spacing, origin, order, type, endian)");
}

Result<RawLayout> readRawLayout(const std::filesystem::path& rawPath, std::uint64_t maxVoxels) {
  LIC3D_TRY_ASSIGN(const std::filesystem::path sidecarPath, findRawSidecar(rawPath));
  return readSidecar(rawPath, sidecarPath, maxVoxels);
}

Result<VectorField> readVectorFieldRaw(const std::filesystem::path& path, FieldReadInfo* info) {
  LIC3D_TRY_ASSIGN(const RawLayout sidecar, readRawLayout(path, kMaxVoxels));
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  const std::uint64_t voxels = voxelCount(sidecar.dims);
  const std::uint64_t expected = voxels * 3 * sidecar.valueBytes;
  if (reader.size() != expected)
    return fileError(
        path, "the file holds " + std::to_string(reader.size()) + " bytes; the " +
                  std::to_string(sidecar.dims.x) + "x" + std::to_string(sidecar.dims.y) + "x" +
                  std::to_string(sidecar.dims.z) + " grid of 3 " +
                  (sidecar.valueBytes == 8 ? "float64" : "float32") +
                  " components its sidecar describes needs " + std::to_string(expected));

  VectorField field;
  field.dims = sidecar.dims;
  field.geometry = sidecar.geometry;
  resizeLarge(field.vectors, static_cast<std::size_t>(voxels));
  std::vector<char> chunk(
      static_cast<std::size_t>(std::min<std::uint64_t>(kFileChunkBytes, expected)));
  std::uint64_t next = 0;  // the index of the next value in the file
  const NumberType type = sidecar.valueBytes == 8 ? NumberType::Float64 : NumberType::Float32;
  for (std::uint64_t left = expected; left > 0;) {
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), left));
    if (reader.read(chunk.data(), count) != count)
      return fileError(path, "cannot read: " + reader.failureReason());
    const std::size_t values = count / sidecar.valueBytes;
    toNativeOrder(chunk.data(), values, sidecar.valueBytes, sidecar.order);
    for (std::size_t i = 0; i < values; ++i, ++next) {
      const double value = valueOf(
          reinterpret_cast<const unsigned char*>(chunk.data()) + i * sidecar.valueBytes, type);
      // Interleaved: x y z of voxel 0, then voxel 1. Planar: x of every voxel, then y, then z.
      const std::uint64_t voxel = sidecar.planar ? next % voxels : next / 3;
      const std::uint64_t axis = sidecar.planar ? next / voxels : next % 3;
      field.vectors[static_cast<std::size_t>(voxel)][static_cast<glm::length_t>(axis)] =
          vectorComponent(value);
    }
    left -= count;
  }
  if (info) *info = FieldReadInfo{};
  LIC3D_TRY(finishVectorField(path, field, info));
  return field;
}

}  // namespace lic3d
