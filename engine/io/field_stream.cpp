// SPDX-License-Identifier: BSD-3-Clause
// Vector fields read piece by piece: each format's header read as its whole-file reader reads it
// (nrrd_header, raw_volume, vti_file), then the voxels of a piece read with pread, run by run.

#include "io/field_stream.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
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
  for (int a = 0; a < 3; ++a)
    if (dims[a] < 1 || offset[a] < 0 || offset[a] > dims_[a] - dims[a])
      return fileError(path_, "the piece of " + gridText(dims) + " voxels at " +
                                  std::to_string(offset.x) + "," + std::to_string(offset.y) + "," +
                                  std::to_string(offset.z) + " does not lie inside the " +
                                  gridText(dims_) + " grid");
  VectorField field;
  field.dims = dims;
  field.geometry.spacing = geometry_.spacing;
  field.geometry.origin = geometry_.origin + glm::dvec3(offset) * geometry_.spacing;
  field.unit = unit_;
  resizeLarge(field.vectors, voxelCount(dims));
  std::vector<std::uint8_t> valid(hasMask_ ? voxelCount(dims) : 0);

  // Runs of voxels adjacent in the file: a row, a layer when the piece spans x, the whole piece
  // when it spans x and y.
  const bool wholeRows = dims.x == dims_.x;
  const bool wholeLayers = wholeRows && dims.y == dims_.y;
  const std::size_t run = static_cast<std::size_t>(dims.x) *
                          static_cast<std::size_t>(wholeRows ? dims.y : 1) *
                          static_cast<std::size_t>(wholeLayers ? dims.z : 1);
  const int rows = wholeRows ? 1 : dims.y;
  const int layers = wholeLayers ? 1 : dims.z;
  // Float32 vectors in the host's order are read straight into the field.
  const bool direct = vectors_.type == NumberType::Float32 && vectors_.components == 3 &&
                      !vectors_.planar && vectors_.order == std::endian::native;
  std::vector<unsigned char> buffer;
  for (int k = 0; k < layers; ++k) {
    for (int j = 0; j < rows; ++j) {
      const std::uint64_t first = voxelIndex(dims_, offset.x, offset.y + j, offset.z + k);
      const std::size_t local = voxelIndex(dims, 0, j, k);
      glm::vec3* vectors = field.vectors.data() + local;
      if (direct) {
        LIC3D_TRY(file_.readAt(vectors_.offset + first * sizeof(glm::vec3), vectors,
                               run * sizeof(glm::vec3), "the data"));
      } else {
        LIC3D_TRY(readValues(vectors_, first, run, buffer,
                             [&](std::size_t voxel, std::size_t component, double value) {
                               vectors[voxel][static_cast<glm::length_t>(component)] =
                                   vectorComponent(value);
                             }));
      }
      if (hasMask_) {
        std::uint8_t* flags = valid.data() + local;
        LIC3D_TRY(readValues(mask_, first, run, buffer,
                             [&](std::size_t voxel, std::size_t, double value) {
                               flags[voxel] = value != 0.0 ? 1 : 0;
                             }));
      }
    }
  }

  std::uint64_t zeroed = 0;
  for (std::size_t i = 0; i < field.vectors.size(); ++i) {
    glm::vec3& v = field.vectors[i];
    if (hasMask_ && valid[i] == 0) {
      v = glm::vec3(0.0f);
    } else if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) {
      v = glm::vec3(0.0f);
      ++zeroed;
    }
  }
  if (nonFinite) *nonFinite = zeroed;
  return field;
}

}  // namespace lic3d
