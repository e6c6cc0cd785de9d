// SPDX-License-Identifier: BSD-3-Clause
// Scalar volumes written block by block: each run of voxels adjacent in the file written with
// pwrite into a temporary file sized up front, renamed into place once every voxel is there; and
// whole volumes written so, by every thread at once.

#include "io/volume_stream.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cerrno>
#include <cstring>
#include <limits>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "core/text.h"
#include "io/file_util.h"
#include "io/nrrd_header.h"
#include "io/number_type.h"
#include "io/raw_volume.h"
#include "io/vti_header.h"

namespace lic3d {
namespace {

// Values converted to the file's byte order go through a buffer of this many.
constexpr std::size_t kSwapValues = std::size_t{1} << 16;

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
  std::uint64_t dataOffset = 0;  // the header's bytes
  bool raw = false;
  std::endian order = std::endian::little;  // the values' in the file
  std::atomic<std::uint64_t> written{0};    // voxels
  std::atomic<bool> finished{false};
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
  const std::optional<ScalarFileFormat> format =
      extension == ".nrrd"  ? std::optional(ScalarFileFormat::Nrrd)
      : extension == ".vti" ? std::optional(ScalarFileFormat::Vti)
      : extension == ".raw" ? std::optional(ScalarFileFormat::Raw)
                            : std::nullopt;
  if (!format)
    return cannotWrite(ErrorKind::InvalidInput, path,
                       "a volume is written piece by piece only as .nrrd, .vti or .raw, not " +
                           (extension.empty() ? std::string("a file without extension")
                                              : quoteForMessage(extension)));
  return create(path, *format, dims, geometry, name);
}

Result<ScalarVolumeStream> ScalarVolumeStream::create(const std::filesystem::path& path,
                                                      ScalarFileFormat format, Dims dims,
                                                      const GridGeometry& geometry,
                                                      std::string_view name) {
  LIC3D_TRY(checkVolumeForWriting(path, dims, voxelCount(dims), 1, &geometry));
  const std::string problem =
      gridLimitProblem(static_cast<std::uint64_t>(dims.x), static_cast<std::uint64_t>(dims.y),
                       static_cast<std::uint64_t>(dims.z), kMaxStreamedVoxels);
  if (!problem.empty()) return cannotWrite(ErrorKind::InvalidInput, path, problem);
  const std::uint64_t dataBytes = std::uint64_t{voxelCount(dims)} * sizeof(float);
  std::string header;
  std::string_view end;
  std::endian order = std::endian::little;
  switch (format) {
    case ScalarFileFormat::Nrrd: header = nrrd::scalarHeader(dims, geometry, name); break;
    case ScalarFileFormat::Raw: LIC3D_TRY(checkRawSidecarReplaceable(path)); break;
    case ScalarFileFormat::Vti: {
      LIC3D_TRY_ASSIGN(header,
                       vti::appendedHeader(path, dims, geometry, NumberType::Float32, 1, name));
      header.append(reinterpret_cast<const char*>(&dataBytes), sizeof dataBytes);
      end = vti::kAppendedEnd;
      order = std::endian::native;
      break;
    }
  }

  LIC3D_TRY_ASSIGN(TemporaryOutput output, TemporaryOutput::create(path));
  const std::uint64_t size = header.size() + dataBytes + end.size();
  if (::ftruncate(output.fd(), static_cast<off_t>(size)) != 0)
    return cannotWrite(ErrorKind::Runtime, path, std::strerror(errno));
  std::string failure = writeAllAt(output.fd(), header.data(), header.size(), 0);
  if (failure.empty())
    failure = writeAllAt(output.fd(), end.data(), end.size(), header.size() + dataBytes);
  if (!failure.empty()) return cannotWrite(ErrorKind::Runtime, path, failure);
  auto state = std::unique_ptr<State>(new State{std::move(output), dims, geometry, header.size(),
                                                format == ScalarFileFormat::Raw, order});
  return ScalarVolumeStream(std::move(state));
}

Result<void> ScalarVolumeStream::writeRun(std::uint64_t first, const float* values,
                                          std::size_t count) {
  State& state = *state_;
  const std::filesystem::path& path = state.output.path();
  if (state.finished)
    return cannotWrite(ErrorKind::Runtime, path, "voxels came after the file was finished");
  const std::uint64_t total = voxelCount(state.dims);
  if (first > total || count > total - first)
    return cannotWrite(ErrorKind::InvalidInput, path,
                       "the run of " + std::to_string(count) + " voxels from voxel " +
                           std::to_string(first) + " does not lie inside the " +
                           gridText(state.dims) + " grid of " + std::to_string(total) + " voxels");
  const std::uint64_t at = state.dataOffset + first * sizeof(float);
  std::string failure;
  if (state.order == std::endian::native) {
    failure = writeAllAt(state.output.fd(), values, count * sizeof(float), at);
  } else {
    std::vector<float> swapped;
    for (std::size_t done = 0; done < count && failure.empty(); done += kSwapValues) {
      const std::size_t n = std::min(kSwapValues, count - done);
      swapped.assign(values + done, values + done + n);
      toNativeOrder(reinterpret_cast<char*>(swapped.data()), n, sizeof(float), state.order);
      failure = writeAllAt(state.output.fd(), swapped.data(), n * sizeof(float),
                           at + done * sizeof(float));
    }
  }
  if (!failure.empty()) return cannotWrite(ErrorKind::Runtime, path, failure);
  state.written += count;
  return {};
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
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < rows; ++j)
      LIC3D_TRY(writeRun(voxelIndex(state.dims, offset.x, offset.y + j, offset.z + k),
                         values + voxelIndex(dims, 0, j, k), run));
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

Result<void> writeScalarVolumeFile(const std::filesystem::path& path, ScalarFileFormat format,
                                   const ScalarVolume& volume, const ScalarFileOptions& options) {
  LIC3D_TRY(checkVolumeForWriting(path, volume.dims, volume.values.size(), 1, &volume.geometry));
  const bool marking = options.hidden == HiddenVoxels::AsNaN && !volume.drawn.empty();
  if (marking && volume.drawn.size() != volume.values.size())
    return cannotWrite(ErrorKind::InvalidInput, path,
                       "its mask has " + std::to_string(volume.drawn.size()) + " flags for its " +
                           std::to_string(volume.values.size()) + " voxels");
  LIC3D_TRY_ASSIGN(
      ScalarVolumeStream stream,
      ScalarVolumeStream::create(path, format, volume.dims, volume.geometry, options.name));
  const std::size_t total = volume.values.size();
  const std::size_t run = std::max<std::size_t>(options.runBytes / sizeof(float), 1);
  const std::size_t runs = (total + run - 1) / run;
  const unsigned threads = static_cast<unsigned>(std::min<std::size_t>(availableThreads(), runs));
  std::atomic<std::size_t> next{0};
  std::mutex failureMutex;
  std::optional<Error> failure;
  // A worker a thread, each taking the next run until none is left or a write failed.
  parallelFor(threads, threads, [&](std::size_t) {
    std::vector<float> buffer;  // a run with hidden voxels, NaN where they are
    for (std::size_t r = next++; r < runs; r = next++) {
      const std::size_t first = r * run;
      const std::size_t count = std::min(run, total - first);
      const float* values = volume.values.data() + first;
      if (marking && std::memchr(volume.drawn.data() + first, 0, count) != nullptr) {
        buffer.resize(count);
        for (std::size_t i = 0; i < count; ++i)
          buffer[i] =
              volume.drawn[first + i] != 0 ? values[i] : std::numeric_limits<float>::quiet_NaN();
        values = buffer.data();
      }
      Result<void> written = stream.writeRun(first, values, count);
      if (!written) {
        const std::lock_guard lock(failureMutex);
        if (!failure) failure = written.error();
        next = runs;
        return;
      }
    }
  });
  if (failure) return *failure;
  return stream.finish();
}

}  // namespace lic3d
