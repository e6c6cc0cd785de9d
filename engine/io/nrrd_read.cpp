// SPDX-License-Identifier: BSD-3-Clause
// The NRRD readers: the payload, raw or gzip, attached or in a detached header's data file, read
// in chunks into the volume each reader makes, after the header has been checked (nrrd_header.cpp).

#include <zlib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/text.h"
#include "io/file_util.h"
#include "io/nrrd.h"
#include "io/nrrd_header.h"
#include "io/number_type.h"
#include "io/volume_io.h"

namespace lic3d {
namespace {

using nrrd::Encoding;
using nrrd::Expectation;
using nrrd::Layout;
using nrrd::Opened;

// Moves `reader` past `line skip` lines and, for raw data, `byte skip` bytes.
Result<void> skipToPayload(FileReader& reader, const Layout& layout) {
  for (std::uint64_t line = 0; line < layout.lineSkip; ++line) {
    int c = reader.get();
    while (c >= 0 && c != '\n') c = reader.get();
    if (c < 0)
      return fileError(reader.path(), "line skip: the data ends after " + std::to_string(line) +
                                          " of the " + std::to_string(layout.lineSkip) +
                                          " lines to skip");
  }
  if (layout.encoding != Encoding::Raw || layout.byteSkip == 0) return {};
  const std::uint64_t needed = layout.payloadBytes();
  // -1: the data is the last bytes of the file, whatever precedes it.
  const std::uint64_t skip = layout.byteSkip > 0 ? static_cast<std::uint64_t>(layout.byteSkip)
                             : reader.remaining() >= needed ? reader.remaining() - needed
                                                            : 0;
  if (skip > reader.remaining())
    return fileError(reader.path(), "byte skip: " + std::to_string(skip) + " bytes to skip, only " +
                                        std::to_string(reader.remaining()) + " left in the file");
  if (reader.skip(skip) != skip)
    return fileError(reader.path(), "cannot read: " + reader.failureReason());
  return {};
}

// Refuses a payload that the file cannot hold, before the caller allocates the volume.
Result<void> checkPayloadFits(FileReader& reader, const Layout& layout) {
  const std::uint64_t needed = layout.payloadBytes();
  const std::uint64_t available = reader.remaining();
  if (layout.encoding == Encoding::Raw) {
    if (available < needed)
      return fileError(reader.path(), "data is truncated: the header promises " +
                                          std::to_string(needed) + " bytes, the file holds " +
                                          std::to_string(available) + " where the data starts");
    return {};
  }
  if (available == 0) return fileError(reader.path(), "gzip data is missing: the data is empty");
  // A gzip byte skip counts decompressed bytes, which the stream must hold as well.
  const std::uint64_t inflated =
      needed + static_cast<std::uint64_t>(std::max<std::int64_t>(layout.byteSkip, 0));
  if (inflated < needed || inflated / kMaxDeflateRatio > available)
    return fileError(reader.path(), "gzip data of " + std::to_string(available) +
                                        " bytes cannot inflate to the " + std::to_string(needed) +
                                        " bytes the header promises (truncated?)");
  return {};
}

using ChunkSink = std::function<void(const char* data, std::size_t bytes)>;

// Calls `use` with each value of a chunk in native byte order, as a double.
template <class Use>
void forEachValue(NumberType type, const char* data, std::size_t bytes, Use&& use) {
  const std::size_t size = numberType(type).bytes;
  const std::size_t count = bytes / size;
  std::array<double, 4096> values;
  for (std::size_t done = 0; done < count;) {
    const std::size_t n = std::min(values.size(), count - done);
    convertValues(type, reinterpret_cast<const unsigned char*>(data) + done * size, n,
                  std::endian::native, values.data());
    for (std::size_t i = 0; i < n; ++i) use(values[i]);
    done += n;
  }
}

// Hands the payload to `sink` in native byte order, in chunks of whole values.
Result<void> readRaw(FileReader& reader, const Layout& layout, const ChunkSink& sink) {
  const std::size_t bytesPerValue = numberType(layout.type).bytes;
  std::uint64_t left = layout.payloadBytes();
  std::vector<char> chunk(static_cast<std::size_t>(std::min<std::uint64_t>(kFileChunkBytes, left)));
  while (left > 0) {
    const std::size_t count = static_cast<std::size_t>(std::min<std::uint64_t>(chunk.size(), left));
    if (reader.read(chunk.data(), count) != count)
      return fileError(reader.path(), "data is truncated: " + reader.failureReason());
    toNativeOrder(chunk.data(), count / bytesPerValue, bytesPerValue, layout.order);
    sink(chunk.data(), count);
    left -= count;
  }
  return {};
}

// The gzip counterpart of readRaw. The stream must hold exactly the promised bytes: shorter is
// truncation, longer means the header and data disagree. Bytes after the stream's end are ignored.
Result<void> readGzip(FileReader& reader, const Layout& layout, const ChunkSink& sink) {
  const std::filesystem::path& path = reader.path();
  const std::size_t bytesPerValue = numberType(layout.type).bytes;
  const std::uint64_t total = layout.payloadBytes();
  InflateStream inflater;
  if (!inflater.init()) return runtimeError("zlib: cannot initialise inflate for " + path.string());
  z_stream& zs = inflater.stream();
  // Small files get a small buffer: the data's size bounds what can be read.
  std::vector<unsigned char> input(
      static_cast<std::size_t>(std::clamp<std::uint64_t>(reader.remaining(), 1, kFileChunkBytes)));
  std::vector<char> output(
      static_cast<std::size_t>(std::min<std::uint64_t>(kFileChunkBytes, total)));
  std::uint64_t produced = 0;
  bool ended = false;
  // teem applies a gzip byte skip to the decompressed stream.
  std::uint64_t toSkip = static_cast<std::uint64_t>(std::max<std::int64_t>(layout.byteSkip, 0));

  // Inflates into [out, out + capacity) until it is full or the stream ends.
  const auto inflateInto = [&](char* out, std::size_t capacity) -> Result<std::size_t> {
    zs.next_out = reinterpret_cast<Bytef*>(out);
    zs.avail_out = static_cast<uInt>(capacity);
    while (zs.avail_out > 0 && !ended) {
      if (zs.avail_in == 0) {
        const std::size_t got = reader.read(input.data(), input.size());
        if (got == 0) {
          if (toSkip > 0)
            return fileError(path, "gzip data is truncated within the " +
                                       std::to_string(layout.byteSkip) + " bytes of 'byte skip'");
          const std::uint64_t done = produced + capacity - zs.avail_out;
          if (done >= total)
            return fileError(path, "gzip data is truncated: the stream lacks its end and checksum");
          return fileError(path, "gzip data is truncated after " + std::to_string(done) + " of " +
                                     std::to_string(total) + " bytes (" + reader.failureReason() +
                                     ")");
        }
        zs.next_in = input.data();
        zs.avail_in = static_cast<uInt>(got);
      }
      const int status = inflate(&zs, Z_NO_FLUSH);
      if (status == Z_STREAM_END) {
        ended = true;
      } else if (status == Z_MEM_ERROR) {
        return runtimeError("zlib: out of memory while reading " + path.string());
      } else if (status == Z_DATA_ERROR || status == Z_NEED_DICT || status == Z_STREAM_ERROR ||
                 (status == Z_BUF_ERROR && zs.avail_in > 0)) {
        return fileError(
            path, std::string("gzip data is corrupt: ") + (zs.msg ? zs.msg : "inflate failed"));
      }
    }
    return capacity - zs.avail_out;
  };

  while (toSkip > 0) {
    const std::size_t capacity =
        static_cast<std::size_t>(std::min<std::uint64_t>(output.size(), toSkip));
    LIC3D_TRY_ASSIGN(const std::size_t got, inflateInto(output.data(), capacity));
    if (got < capacity)
      return fileError(path, "gzip data ends within the " + std::to_string(layout.byteSkip) +
                                 " bytes of 'byte skip'");
    toSkip -= got;
  }
  while (produced < total) {
    const std::size_t capacity =
        static_cast<std::size_t>(std::min<std::uint64_t>(output.size(), total - produced));
    LIC3D_TRY_ASSIGN(const std::size_t got, inflateInto(output.data(), capacity));
    if (got < capacity)
      return fileError(path, "gzip data holds only " + std::to_string(produced + got) +
                                 " bytes, the header promises " + std::to_string(total));
    toNativeOrder(output.data(), got / bytesPerValue, bytesPerValue, layout.order);
    sink(output.data(), got);
    produced += got;
  }
  char extra = 0;
  LIC3D_TRY_ASSIGN(const std::size_t more, inflateInto(&extra, 1));
  if (more > 0)
    return fileError(path, "gzip data holds more than the " + std::to_string(total) +
                               " bytes the header promises");
  return {};
}

Result<void> readPayload(FileReader& reader, const Layout& layout, const ChunkSink& sink) {
  return layout.encoding == Encoding::Raw ? readRaw(reader, layout, sink)
                                          : readGzip(reader, layout, sink);
}

// An error about a detached header's data file names both files.
Error inDataFile(const std::filesystem::path& header, Error error) {
  error.message = header.string() + ": data file " + error.message;
  return error;
}

}  // namespace

Result<Opened> nrrd::openPayload(const std::filesystem::path& path, const Expectation& expected) {
  LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(path));
  LIC3D_TRY_ASSIGN(const Layout layout, nrrd::readLayout(reader, expected));
  if (!layout.dataFile.empty()) {
    // A detached header naming itself would read its own text as the data.
    std::error_code same;
    if (std::filesystem::equivalent(path, layout.dataFile, same))
      return fileError(path,
                       "its 'data file' is the header itself: name the file that holds the "
                       "data, or put the data after the header without 'data file'");
    Result<FileReader> data = FileReader::open(layout.dataFile);
    if (!data.ok()) return inDataFile(path, std::move(data).error());
    reader = std::move(data).value();
  }
  Result<void> positioned = skipToPayload(reader, layout);
  if (positioned.ok()) positioned = checkPayloadFits(reader, layout);
  if (!positioned.ok())
    return layout.dataFile.empty() ? std::move(positioned).error()
                                   : inDataFile(path, std::move(positioned).error());
  return Opened{path, std::move(reader), layout};
}

namespace {

Result<void> readPayload(Opened& opened, const ChunkSink& sink) {
  Result<void> read = readPayload(opened.reader, opened.layout, sink);
  if (read.ok() || opened.layout.dataFile.empty()) return read;
  return inDataFile(opened.header, std::move(read).error());
}

// One value per voxel as float (NaN kept, beyond the float range infinite); `unit` gets the
// header's `sample units`.
Result<ScalarVolume> readScalars(const std::filesystem::path& path, const Expectation& expected,
                                 std::string* unit = nullptr) {
  LIC3D_TRY_ASSIGN(Opened opened, nrrd::openPayload(path, expected));
  const Layout& layout = opened.layout;
  ScalarVolume volume;
  volume.dims = layout.dims;
  volume.geometry = layout.geometry;
  const auto voxels = static_cast<std::size_t>(layout.voxels);
  LIC3D_TRY(reserveDecoded(volume.values, voxels, path));
  std::size_t next = 0;
  LIC3D_TRY(readPayload(opened, [&](const char* data, std::size_t bytes) {
    growDecoded(volume.values, next + bytes / numberType(layout.type).bytes);
    forEachValue(layout.type, data, bytes,
                 [&](double value) { volume.values[next++] = vectorComponent(value); });
  }));
  if (unit) *unit = layout.sampleUnits;
  return volume;
}

}  // namespace

Result<VectorField> readVectorFieldNrrd(const std::filesystem::path& path, FieldReadInfo* info) {
  const Expectation expected{4,
                             3,
                             "3 vector components on a 3D grid",
                             "vector components",
                             {NumberType::Float32, NumberType::Float64},
                             "float or double",
                             true};
  LIC3D_TRY_ASSIGN(Opened opened, nrrd::openPayload(path, expected));
  const Layout& layout = opened.layout;
  VectorField field;
  field.dims = layout.dims;
  field.geometry = layout.geometry;
  const auto voxels = static_cast<std::size_t>(layout.voxels);
  LIC3D_TRY(reserveDecoded(field.vectors, voxels, path));

  // 3 components per voxel, or 2 on a 2D grid (z stays 0).
  const glm::length_t components = static_cast<glm::length_t>(layout.components);
  std::size_t voxel = 0;  // of the next value
  glm::length_t component = 0;
  const auto store = [&](double value) {
    field.vectors[voxel][component] = vectorComponent(value);
    if (++component == components) {
      component = 0;
      ++voxel;
    }
  };
  LIC3D_TRY(readPayload(opened, [&](const char* data, std::size_t bytes) {
    const std::size_t valuesEnd =
        voxel * components + component + bytes / numberType(layout.type).bytes;
    growDecoded(field.vectors, (valuesEnd + components - 1) / components);
    forEachValue(layout.type, data, bytes, store);
  }));
  if (info) {
    *info = FieldReadInfo{};
    info->unit = layout.sampleUnits;
  }
  LIC3D_TRY(finishVectorField(path, field, info));
  return field;
}

Result<ScalarVolume> readScalarNrrd(const std::filesystem::path& path) {
  const Expectation expected{3,
                             1,
                             "a 3D grid of scalars",
                             "",
                             {NumberType::Float32, NumberType::Float64},
                             "float or double"};
  return readScalars(path, expected);
}

Result<PointScalars> readPointScalarsNrrd(const std::filesystem::path& path) {
  const Expectation expected{
      3,
      1,
      "a 3D grid of scalars",
      "",
      {NumberType::Int8, NumberType::UInt8, NumberType::Int16, NumberType::UInt16,
       NumberType::Int32, NumberType::UInt32, NumberType::Int64, NumberType::UInt64,
       NumberType::Float32, NumberType::Float64},
      "a signed or unsigned integer type, float or double",
      true};
  std::string unit;
  LIC3D_TRY_ASSIGN(ScalarVolume volume, readScalars(path, expected, &unit));
  PointScalars scalars;
  scalars.dims = volume.dims;
  scalars.geometry = volume.geometry;
  scalars.values = std::move(volume.values);
  // A NRRD file holds one unnamed array: the file names it.
  scalars.name = path.stem().string();
  scalars.unit = std::move(unit);
  return scalars;
}

Result<RgbaVolume> readRgbaNrrd(const std::filesystem::path& path) {
  const Expectation expected{
      4, 4, "4 colour channels on a 3D grid", "RGBA channels", {NumberType::UInt8}, "uchar"};
  LIC3D_TRY_ASSIGN(Opened opened, nrrd::openPayload(path, expected));
  const Layout& layout = opened.layout;
  RgbaVolume volume;
  volume.dims = layout.dims;
  volume.geometry = layout.geometry;
  const auto payload = static_cast<std::size_t>(layout.payloadBytes());
  LIC3D_TRY(reserveDecoded(volume.rgba, payload, path));
  std::size_t offset = 0;
  LIC3D_TRY(readPayload(opened, [&](const char* data, std::size_t bytes) {
    growDecoded(volume.rgba, offset + bytes);
    std::memcpy(volume.rgba.data() + offset, data, bytes);
    offset += bytes;
  }));
  return volume;
}

Result<NoiseVolume> readNoiseNrrd(const std::filesystem::path& path) {
  const Expectation expected{3,
                             1,
                             "a 3D grid of scalars",
                             "",
                             {NumberType::UInt8, NumberType::UInt16, NumberType::Float32},
                             "uchar, ushort or float"};
  LIC3D_TRY_ASSIGN(Opened opened, nrrd::openPayload(path, expected));
  const Layout& layout = opened.layout;
  NoiseVolume noise;
  noise.dims = layout.dims;
  noise.type = layout.type == NumberType::UInt8    ? NoiseType::UInt8
               : layout.type == NumberType::UInt16 ? NoiseType::UInt16
                                                   : NoiseType::Float32;
  const auto payload = static_cast<std::size_t>(layout.payloadBytes());
  LIC3D_TRY(reserveDecoded(noise.bytes, payload, path));
  std::size_t offset = 0;
  LIC3D_TRY(readPayload(opened, [&](const char* data, std::size_t bytes) {
    growDecoded(noise.bytes, offset + bytes);
    std::memcpy(noise.bytes.data() + offset, data, bytes);
    offset += bytes;
  }));
  // Float values are checked and rescaled as every front end's float noise is.
  if (auto r = finishFloatNoise(noise); !r) return fileError(path, r.error().message);
  return noise;
}

}  // namespace lic3d
