// SPDX-License-Identifier: BSD-3-Clause
// Vector fields read piece by piece: each format's header read as its whole-file reader reads it
// (nrrd_header, raw_volume, vti_file), then the voxels of a piece read with pread, run by run.

#include "io/field_stream.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <mutex>
#include <optional>
#include <utility>
#include <vector>

#include "core/parallel.h"
#include "core/text.h"
#include "io/nrrd_header.h"
#include "io/raw_volume.h"
#include "io/volume_io.h"
#include "io/vti_stream.h"

namespace lic3d {
namespace {

// Values that are converted go through a buffer of at most this many bytes.
constexpr std::size_t kPieceChunkBytes = std::size_t{8} << 20;

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "vectors are read as packed floats");

}  // namespace

FieldStream::FieldStream(FileReader file, std::filesystem::path path)
    : file_(std::move(file)), path_(std::move(path)) {}

Result<FieldStream> FieldStream::open(const std::filesystem::path& path,
                                      std::string_view arrayName) {
  const std::string extension = lowerCaseExtension(path);
  if (extension == ".vti") return openVti(path, arrayName);
  const bool single = extension == ".nrrd" || extension == ".nhdr" || extension == ".raw";
  if (!single)
    return readWholeError(path, extension == ".vtk" ? "a VTK legacy file is parsed front to back"
                                : extension == ".pvti"
                                    ? "a .pvti is read as its pieces' files"
                                    : "its format is not one that streams (.raw, "
                                      ".nrrd, .nhdr, .vti)");
  if (!arrayName.empty())
    return fileError(path, "an array name (" + quoteForMessage(arrayName) +
                               ") applies only to .vtk and .vti files; a " +
                               (extension == ".raw" ? "raw" : "NRRD") +
                               " file holds one unnamed array");
  return extension == ".raw" ? openRaw(path) : openNrrd(path);
}

Result<FieldStream> FieldStream::openRaw(const std::filesystem::path& path) {
  LIC3D_TRY_ASSIGN(const RawLayout layout, readRawLayout(path, kMaxStreamedVoxels));
  LIC3D_TRY_ASSIGN(FileReader file, FileReader::open(path));
  FieldStream stream(std::move(file), path);
  stream.dims_ = layout.dims;
  stream.geometry_ = layout.geometry;
  stream.vectors_.type = layout.valueBytes == 8 ? NumberType::Float64 : NumberType::Float32;
  stream.vectors_.valueBytes = layout.valueBytes;
  stream.vectors_.order = layout.order;
  stream.vectors_.planar = layout.planar;
  LIC3D_TRY(checkFileHolds(stream.file_, path, stream.dims_, stream.vectors_, true));
  return stream;
}

Result<FieldStream> FieldStream::openNrrd(const std::filesystem::path& path) {
  const nrrd::Expectation expected{4,
                                   3,
                                   "3 vector components on a 3D grid",
                                   "vector components",
                                   {NumberType::Float32, NumberType::Float64},
                                   "float or double",
                                   true,
                                   kMaxStreamedVoxels};
  LIC3D_TRY_ASSIGN(nrrd::Opened opened, nrrd::openPayload(path, expected));
  const nrrd::Layout& layout = opened.layout;
  if (layout.encoding != nrrd::Encoding::Raw)
    return readWholeError(path,
                          "its data is gzip compressed, which decompresses only from its start");
  const std::uint64_t offset = opened.reader.position();
  FieldStream stream(std::move(opened.reader), path);
  stream.dims_ = layout.dims;
  stream.geometry_ = layout.geometry;
  stream.unit_ = layout.sampleUnits;
  stream.vectors_.offset = offset;
  stream.vectors_.type = layout.type;
  stream.vectors_.valueBytes = numberType(layout.type).bytes;
  stream.vectors_.order = layout.order;
  stream.vectors_.components = layout.components;  // 2 on a 2D grid
  LIC3D_TRY(checkFileHolds(stream.file_, path, stream.dims_, stream.vectors_, false));
  return stream;
}

Result<FieldStream> FieldStream::openVti(const std::filesystem::path& path, std::string_view name) {
  const auto layoutOf = [](const vti::StoredArray& stored) {
    ArrayLayout layout;
    layout.offset = stored.offset;
    layout.type = stored.type;
    layout.valueBytes = numberType(stored.type).bytes;
    layout.order = stored.order;
    layout.components = stored.components;
    return layout;
  };
  LIC3D_TRY_ASSIGN(
      vti::StreamedVti streamed,
      vti::openStreamedVti(
          path, name,
          [&](const FileReader& file, Dims dims, const vti::StoredArray& stored) -> Result<void> {
            return checkFileHolds(file, path, dims, layoutOf(stored), false);
          }));
  FieldStream stream(std::move(streamed.file), path);
  stream.dims_ = streamed.dims;
  stream.geometry_ = streamed.geometry;
  stream.arrayName_ = std::move(streamed.arrayName);
  stream.vectors_ = layoutOf(streamed.vectors);
  if (streamed.mask) {
    stream.mask_ = layoutOf(*streamed.mask);
    stream.hasMask_ = true;
  }
  return stream;
}

std::uint64_t FieldStream::dataBytes() const {
  const std::uint64_t voxels = voxelCount(dims_);
  return voxels * vectors_.components * vectors_.valueBytes +
         (hasMask_ ? voxels * mask_.components * mask_.valueBytes : 0);
}

Result<void> FieldStream::checkFileHolds(const FileReader& file, const std::filesystem::path& path,
                                         Dims dims, const ArrayLayout& array, bool exact) {
  const std::uint64_t values = voxelCount(dims) * array.components;
  const std::uint64_t needed = array.offset + values * array.valueBytes;
  const std::uint64_t size = file.size();
  if (exact ? size == needed : size >= needed) return {};
  std::string problem = "the file holds " + std::to_string(size) + " bytes; the " + gridText(dims) +
                        " grid of " + std::to_string(array.components) + " " +
                        std::to_string(8 * array.valueBytes) + "-bit values per voxel" +
                        (array.offset > 0 ? " from byte " + std::to_string(array.offset) : "") +
                        " needs " + (exact ? "" : "at least ") + std::to_string(needed) +
                        (size < needed ? " (truncated?)" : "");
  Error error = fileError(file.path(), problem);
  if (file.path() != path) error.message = path.string() + ": data file " + error.message;
  return error;
}

template <class Store>
Result<void> FieldStream::readValues(const ArrayLayout& array, std::uint64_t first,
                                     std::size_t count, std::vector<unsigned char>& buffer,
                                     Store&& store) const {
  const std::uint64_t voxels = voxelCount(dims_);
  const std::size_t bytes = array.valueBytes;
  // Interleaved: one span of every component. Planar: one span per component.
  const std::size_t spans = array.planar ? array.components : 1;
  const std::size_t perVoxel = array.planar ? bytes : bytes * array.components;
  const std::size_t chunkVoxels = std::max<std::size_t>(1, kPieceChunkBytes / perVoxel);
  buffer.resize(std::min(count, chunkVoxels) * perVoxel);
  for (std::size_t span = 0; span < spans; ++span) {
    for (std::size_t done = 0; done < count;) {
      const std::size_t n = std::min(chunkVoxels, count - done);
      const std::uint64_t value =
          array.planar ? span * voxels + first + done : (first + done) * array.components;
      LIC3D_TRY(
          file_.readAt(array.offset + value * bytes, buffer.data(), n * perVoxel, "the data"));
      const std::size_t values = n * perVoxel / bytes;
      for (std::size_t i = 0; i < values; ++i) {
        std::array<unsigned char, 8> native{};
        std::memcpy(native.data(), buffer.data() + i * bytes, bytes);
        if (array.order != std::endian::native)
          std::reverse(native.begin(), native.begin() + static_cast<std::ptrdiff_t>(bytes));
        const double decoded = valueOf(native.data(), array.type);
        const std::size_t voxel = array.planar ? done + i : done + i / array.components;
        const std::size_t component = array.planar ? span : i % array.components;
        store(voxel, component, decoded);
      }
      done += n;
    }
  }
  return {};
}

Result<VectorField> FieldStream::readPiece(Dims offset, Dims dims, std::uint64_t* nonFinite) const {
  VectorField field;
  LIC3D_TRY(readPieceInto(offset, dims, field, nonFinite));
  return field;
}

Result<void> FieldStream::readPieceInto(Dims offset, Dims dims, VectorField& field,
                                        std::uint64_t* nonFinite, const RunVisitor& visit) const {
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || offset[a] < 0 || offset[a] > dims_[a] - dims[a])
      return fileError(path_, "the piece of " + gridText(dims) + " voxels at " +
                                  std::to_string(offset.x) + "," + std::to_string(offset.y) + "," +
                                  std::to_string(offset.z) + " does not lie inside the " +
                                  gridText(dims_) + " grid");
  field.dims = dims;
  field.geometry.spacing = geometry_.spacing;
  field.geometry.origin = geometry_.origin + glm::dvec3(offset) * geometry_.spacing;
  field.unit = unit_;
  field.piece.reset();
  const std::size_t voxels = voxelCount(dims);
  if (field.vectors.capacity() < voxels) field.vectors = {};  // no copy of the old vectors
  resizeLarge(field.vectors, voxels);

  // Runs of voxels adjacent in the file: a row, a layer when the piece spans x, the whole piece
  // when it spans x and y.
  const bool wholeRows = dims.x == dims_.x;
  const bool wholeLayers = wholeRows && dims.y == dims_.y;
  const std::size_t run = static_cast<std::size_t>(dims.x) *
                          static_cast<std::size_t>(wholeRows ? dims.y : 1) *
                          static_cast<std::size_t>(wholeLayers ? dims.z : 1);
  const std::size_t rows = wholeRows ? 1 : static_cast<std::size_t>(dims.y);
  const std::size_t runs = rows * static_cast<std::size_t>(wholeLayers ? 1 : dims.z);
  // The threads take tasks of about chunkBytes_ of the file each: a part of a long run, or
  // several short runs.
  const std::size_t fileVoxelBytes = vectors_.components * vectors_.valueBytes +
                                     (hasMask_ ? mask_.components * mask_.valueBytes : 0);
  const std::size_t chunkVoxels = std::max<std::size_t>(1, chunkBytes_ / fileVoxelBytes);
  const std::size_t parts = (run + chunkVoxels - 1) / chunkVoxels;
  const std::size_t partVoxels = (run + parts - 1) / parts;
  const std::size_t runsPerTask = parts > 1 ? 1 : std::max<std::size_t>(1, chunkVoxels / run);
  const std::size_t tasks = parts > 1 ? runs * parts : (runs + runsPerTask - 1) / runsPerTask;
  // Float32 vectors in the host's order are read straight into the field.
  const bool direct = vectors_.type == NumberType::Float32 && vectors_.components == 3 &&
                      !vectors_.planar && vectors_.order == std::endian::native;

  // What a thread keeps between its tasks.
  struct Scratch {
    std::vector<unsigned char> buffer;
    std::vector<std::uint8_t> valid;
    std::uint64_t zeroed = 0;
  };
  // Voxels [begin, begin + count) of run r: read, masked, non-finite vectors zeroed, visited.
  const auto readRun = [&](std::size_t r, std::size_t begin, std::size_t count,
                           Scratch& scratch) -> Result<void> {
    const int j = static_cast<int>(r % rows), k = static_cast<int>(r / rows);
    const std::uint64_t first =
        voxelIndex(dims_, offset.x, offset.y + j, offset.z + k) + std::uint64_t{begin};
    glm::vec3* vectors = field.vectors.data() + voxelIndex(dims, 0, j, k) + begin;
    if (direct) {
      LIC3D_TRY(file_.readAt(vectors_.offset + first * sizeof(glm::vec3), vectors,
                             count * sizeof(glm::vec3), "the data"));
    } else {
      LIC3D_TRY(readValues(vectors_, first, count, scratch.buffer,
                           [&](std::size_t voxel, std::size_t component, double value) {
                             vectors[voxel][static_cast<glm::length_t>(component)] =
                                 vectorComponent(value);
                           }));
    }
    if (hasMask_) {
      scratch.valid.resize(count);
      LIC3D_TRY(readValues(mask_, first, count, scratch.buffer,
                           [&](std::size_t voxel, std::size_t, double value) {
                             scratch.valid[voxel] = value != 0.0 ? 1 : 0;
                           }));
    }
    // A component is NaN or infinite where its exponent bits are all set: one pass that the
    // compiler vectorizes finds whether any is, and only then (or with a mask) each vector is
    // looked at.
    std::uint32_t nonFiniteSeen = 0;
    for (std::size_t i = 0; i < 3 * count; ++i) {
      std::uint32_t bits;
      std::memcpy(&bits, reinterpret_cast<const float*>(vectors) + i, sizeof(bits));
      nonFiniteSeen |= (bits & 0x7f800000u) == 0x7f800000u ? 1u : 0u;
    }
    for (std::size_t i = 0; i < count && (hasMask_ || nonFiniteSeen != 0); ++i) {
      glm::vec3& v = vectors[i];
      if (hasMask_ && scratch.valid[i] == 0) {
        v = glm::vec3(0.0f);
      } else if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
        v = glm::vec3(0.0f);
        ++scratch.zeroed;
      }
    }
    if (visit) visit(vectors, count);
    return {};
  };
  const auto readTask = [&](std::size_t t, Scratch& scratch) -> Result<void> {
    if (parts > 1) {
      const std::size_t begin = (t % parts) * partVoxels;
      return readRun(t / parts, begin, std::min(partVoxels, run - begin), scratch);
    }
    for (std::size_t r = t * runsPerTask; r < std::min(runs, (t + 1) * runsPerTask); ++r)
      LIC3D_TRY(readRun(r, 0, run, scratch));
    return {};
  };

  // Each thread takes the next task until none is left or one failed (the lowest failed task's
  // error is returned).
  const std::size_t threads = std::min<std::size_t>(availableThreads(), tasks);
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;
  std::optional<Error> failure;
  std::size_t failedTask = tasks;
  std::uint64_t zeroed = 0;
  parallelFor(threads, static_cast<unsigned>(threads), [&](std::size_t) {
    Scratch scratch;
    for (std::size_t t = next++; t < tasks && !failed; t = next++)
      if (Result<void> done = readTask(t, scratch); !done) {
        const std::lock_guard lock(mutex);
        if (t < failedTask) {
          failedTask = t;
          failure = done.error();
        }
        failed = true;
      }
    const std::lock_guard lock(mutex);
    zeroed += scratch.zeroed;
  });
  if (failure) return *failure;
  if (nonFinite) *nonFinite = zeroed;
  return {};
}

}  // namespace lic3d
