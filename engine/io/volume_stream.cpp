// SPDX-License-Identifier: BSD-3-Clause
// Scalar volumes written block by block: each run of voxels adjacent in the file written with
// pwrite into a temporary file sized up front, renamed into place once every voxel is there.

#include "io/volume_stream.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cstring>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/text.h"
#include "io/file_util.h"
#include "io/nrrd_header.h"
#include "io/number_type.h"
#include "io/raw_volume.h"

namespace lic3d {
namespace {

// Values converted to little endian on a big-endian host go through a buffer of this many.
constexpr std::size_t kChunkValues = std::size_t{1} << 20;

Error cannotWrite(ErrorKind kind, const std::filesystem::path& path, const std::string& reason) {
  return {kind, "cannot write '" + path.string() + "': " + reason};
}

// Appends rather than "[" + ...: GCC 12 at -O3 gives a false -Wrestrict on prepending a literal.
std::string jsonList(const glm::dvec3& v) {
  std::string text = "[";
  text += tripleText(v, ", ");
  text += ']';
  return text;
}

// What raw_volume.h describes, for one float32 component per voxel, with the data file's size
// ("bytes"): a sidecar left beside data of another size is told by it.
std::string rawSidecar(Dims dims, const GridGeometry& geometry) {
  return "{\"dims\": [" + std::to_string(dims.x) + ", " + std::to_string(dims.y) + ", " +
         std::to_string(dims.z) + "], \"spacing\": " + jsonList(geometry.spacing) +
         ", \"origin\": " + jsonList(geometry.origin) +
         ", \"components\": 1, \"type\": \"float32\", \"endian\": \"little\", \"bytes\": " +
         std::to_string(std::uint64_t{voxelCount(dims)} * sizeof(float)) + "}\n";
}

// All of `bytes` at `offset`; errno's text when it cannot.
std::string writeAllAt(int fd, const void* data, std::size_t bytes, std::uint64_t offset) {
  const char* from = static_cast<const char*>(data);
  for (std::size_t done = 0; done < bytes;) {
    const ssize_t written =
        ::pwrite(fd, from + done, std::min<std::size_t>(bytes - done, std::size_t{1} << 30),
                 static_cast<off_t>(offset + done));
    if (written < 0 && errno == EINTR) continue;
    if (written < 0) return std::strerror(errno);
    done += static_cast<std::size_t>(written);
  }
  return {};
}

}  // namespace

struct ScalarVolumeStream::State {
  TemporaryOutput output;
  Dims dims{0};
  GridGeometry geometry;
  std::uint64_t dataOffset = 0;  // the NRRD header's bytes
  bool raw = false;
  std::atomic<std::uint64_t> written{0};  // voxels
  bool finished = false;
};

ScalarVolumeStream::ScalarVolumeStream(std::unique_ptr<State> state) : state_(std::move(state)) {}
ScalarVolumeStream::ScalarVolumeStream(ScalarVolumeStream&& other) noexcept = default;
ScalarVolumeStream& ScalarVolumeStream::operator=(ScalarVolumeStream&& other) noexcept = default;
ScalarVolumeStream::~ScalarVolumeStream() = default;

const std::filesystem::path& ScalarVolumeStream::path() const { return state_->output.path(); }
Dims ScalarVolumeStream::dims() const { return state_->dims; }

Result<ScalarVolumeStream> ScalarVolumeStream::create(const std::filesystem::path& path, Dims dims,
                                                      const GridGeometry& geometry,
                                                      std::string_view name) {
  const std::string extension = lowerCaseExtension(path);
  if (extension != ".nrrd" && extension != ".raw")
    return cannotWrite(ErrorKind::InvalidInput, path,
                       "a volume is written piece by piece only as .nrrd or .raw, not " +
                           (extension.empty() ? std::string("a file without extension")
                                              : quoteForMessage(extension)));
  LIC3D_TRY(checkVolumeForWriting(path, dims, voxelCount(dims), 1, &geometry));
  const std::string problem =
      gridLimitProblem(static_cast<std::uint64_t>(dims.x), static_cast<std::uint64_t>(dims.y),
                       static_cast<std::uint64_t>(dims.z), kMaxStreamedVoxels);
  if (!problem.empty()) return cannotWrite(ErrorKind::InvalidInput, path, problem);
  const bool raw = extension == ".raw";
  if (raw) LIC3D_TRY(checkRawSidecarReplaceable(path));
  const std::string header = raw ? std::string() : nrrd::scalarHeader(dims, geometry, name);

  LIC3D_TRY_ASSIGN(TemporaryOutput output, TemporaryOutput::create(path));
  const std::uint64_t size = header.size() + std::uint64_t{voxelCount(dims)} * sizeof(float);
  if (::ftruncate(output.fd(), static_cast<off_t>(size)) != 0)
    return cannotWrite(ErrorKind::Runtime, path, std::strerror(errno));
  if (const std::string failure = writeAllAt(output.fd(), header.data(), header.size(), 0);
      !failure.empty())
    return cannotWrite(ErrorKind::Runtime, path, failure);
  auto state =
      std::unique_ptr<State>(new State{std::move(output), dims, geometry, header.size(), raw});
  return ScalarVolumeStream(std::move(state));
}

Result<void> ScalarVolumeStream::write(Dims offset, Dims dims, const float* values) {
  State& state = *state_;
  const std::filesystem::path& path = state.output.path();
  if (state.finished)
    return cannotWrite(ErrorKind::Runtime, path, "a block came after the file was finished");
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || offset[a] < 0 || offset[a] > state.dims[a] - dims[a])
      return cannotWrite(ErrorKind::InvalidInput, path,
                         "the block of " + gridText(dims) + " voxels at " +
                             std::to_string(offset.x) + "," + std::to_string(offset.y) + "," +
                             std::to_string(offset.z) + " does not lie inside the " +
                             gridText(state.dims) + " grid");
  // Runs adjacent in the file: a row, a layer when the block spans x, the whole block when it
  // spans x and y. The block's own values are adjacent the same way.
  const bool wholeRows = dims.x == state.dims.x;
  const bool wholeLayers = wholeRows && dims.y == state.dims.y;
  const std::size_t run = static_cast<std::size_t>(dims.x) *
                          static_cast<std::size_t>(wholeRows ? dims.y : 1) *
                          static_cast<std::size_t>(wholeLayers ? dims.z : 1);
  const int rows = wholeRows ? 1 : dims.y;
  const int layers = wholeLayers ? 1 : dims.z;
  std::vector<float> swapped;
  for (int k = 0; k < layers; ++k) {
    for (int j = 0; j < rows; ++j) {
      const std::uint64_t at =
          state.dataOffset +
          std::uint64_t{voxelIndex(state.dims, offset.x, offset.y + j, offset.z + k)} *
              sizeof(float);
      const float* from = values + voxelIndex(dims, 0, j, k);
      std::string failure;
      if constexpr (std::endian::native == std::endian::little) {
        failure = writeAllAt(state.output.fd(), from, run * sizeof(float), at);
      } else {
        for (std::size_t done = 0; done < run && failure.empty(); done += kChunkValues) {
          const std::size_t n = std::min(kChunkValues, run - done);
          swapped.assign(from + done, from + done + n);
          toNativeOrder(reinterpret_cast<char*>(swapped.data()), n, sizeof(float),
                        std::endian::little);
          failure = writeAllAt(state.output.fd(), swapped.data(), n * sizeof(float),
                               at + done * sizeof(float));
        }
      }
      if (!failure.empty()) return cannotWrite(ErrorKind::Runtime, path, failure);
    }
  }
  state.written += voxelCount(dims);
  return {};
}

Result<void> ScalarVolumeStream::finish() {
  State& state = *state_;
  const std::filesystem::path& path = state.output.path();
  if (state.finished) return cannotWrite(ErrorKind::Runtime, path, "it was already finished");
  const std::uint64_t total = voxelCount(state.dims);
  const std::uint64_t written = state.written.load();
  if (written != total)
    return cannotWrite(ErrorKind::Runtime, path,
                       "blocks of " + std::to_string(written) + " voxels were written for its " +
                           std::to_string(total) + " (" +
                           (written < total ? "a block is missing" : "blocks overlap") + ")");
  state.finished = true;
  if (!state.raw) return state.output.commit();
  // The pair commits as one: both complete on disk under temporary names before either is
  // renamed, then the data, then the sidecar, two renames apart. A run cut short before the
  // renames leaves the old pair; between them, new data beside the old sidecar, whose "bytes"
  // tells a change of grid (a reader that checks it refuses the pair).
  const std::filesystem::path sidecarPath = rawSidecarPath(path);
  LIC3D_TRY_ASSIGN(TemporaryOutput sidecar, TemporaryOutput::create(sidecarPath));
  const std::string text = rawSidecar(state.dims, state.geometry);
  if (const std::string failure = writeAllAt(sidecar.fd(), text.data(), text.size(), 0);
      !failure.empty())
    return cannotWrite(ErrorKind::Runtime, sidecarPath, failure);
  LIC3D_TRY(state.output.commit());
  return sidecar.commit();
}

std::filesystem::path rawSidecarPath(const std::filesystem::path& rawPath) {
  std::filesystem::path sidecar = rawPath;
  sidecar.replace_extension(".json");
  return sidecar;
}

Result<void> checkRawSidecarReplaceable(const std::filesystem::path& rawPath) {
  const std::filesystem::path sidecar = rawSidecarPath(rawPath);
  LIC3D_TRY(checkNotAnInput(sidecar));
  std::error_code error;
  if (!std::filesystem::exists(std::filesystem::symlink_status(sidecar, error))) return {};
  const auto refuse = [&](const std::string& why) {
    return fileError(sidecar, why + ", and writing " + rawPath.string() +
                                  " would replace it with its sidecar: move it or choose "
                                  "another output name");
  };
  Result<std::string> text = readFile(sidecar, 64 * 1024, false);
  if (!text) return refuse("cannot be read as a sidecar (" + text.error().message + ")");
  nlohmann::json json = nlohmann::json::parse(*text, nullptr, false);
  bool own = json.is_object() && json.contains("dims");
  if (own)
    for (const auto& item : json.items())
      if (!isRawSidecarKey(item.key())) own = false;
  if (!own) return refuse("exists and is not the JSON sidecar of a raw volume");
  return {};
}

}  // namespace lic3d
