// SPDX-License-Identifier: BSD-3-Clause
// The VTK XML ImageData readers: each array's data, ascii, base64 or raw appended, plain or in
// zlib blocks, checked against the bytes present and decoded into the volume each reader makes.

#include <algorithm>
#include <array>
#include <bit>
#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/parallel.h"
#include "core/text.h"
#include "io/file_util.h"
#include "io/volume_io.h"
#include "io/vti.h"
#include "io/vti_bytes.h"
#include "io/vti_file.h"

namespace lic3d {

// Inflated bytes of VTI zlib blocks decoded per batch (their inflation runs in parallel).
constexpr std::size_t kInflateBatchBytes = std::size_t{32} << 20;
namespace {

using vti::appendedOffset;
using vti::ArrayRef;
using vti::ByteSource;
using vti::checkArray;
using vti::chooseArray;
using vti::describe;
using vti::listArrays;
using vti::openVti;
using vti::VtiFile;

// Values are converted in chunks of this many.
constexpr std::size_t kChunkValues = std::size_t{1} << 16;
// Uncompressed data not in memory (a large file's appended data, base64) is read in chunks of at
// most this many bytes.
constexpr std::size_t kStreamChunkBytes = std::size_t{32} << 20;

// Receives an array's values in chunks: `count` values from value number `first` on. Called
// from several threads at once for disjoint ranges (sinks write into storage sized by the reader's
// grow call).
using ValueSink = std::function<void(std::uint64_t first, const double* values, std::size_t count)>;

// Whole values in memory, from value number `first` on, converted and delivered on the available
// threads in chunks of kChunkValues.
void decodeInParallel(const NumberTypeInfo& type, std::endian order, const unsigned char* data,
                      std::uint64_t count, std::uint64_t first, const ValueSink& sink) {
  const std::size_t chunks = static_cast<std::size_t>((count + kChunkValues - 1) / kChunkValues);
  parallelChunks(chunks, [&](std::size_t begin, std::size_t end) {
    std::vector<double> values(kChunkValues);
    for (std::size_t c = begin; c < end; ++c) {
      const std::uint64_t at = std::uint64_t{c} * kChunkValues;
      const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(kChunkValues, count - at));
      convertValues(type.type, data + at * type.bytes, n, order, values.data());
      sink(first + at, values.data(), n);
    }
  });
}

// Turns bytes, split anywhere, into values: a value cut between two zlib blocks is completed by
// the next one.
class ValueDecoder {
 public:
  ValueDecoder(const NumberTypeInfo& type, std::endian order, const ValueSink& sink)
      : type_(type), order_(order), sink_(sink) {
    values_.reserve(kChunkValues);
  }

  void add(const unsigned char* data, std::size_t bytes) {
    while (carried_ > 0 && bytes > 0) {
      carry_[carried_++] = *data++;
      --bytes;
      if (carried_ == type_.bytes) {
        emit(carry_.data());
        carried_ = 0;
      }
    }
    const std::size_t whole = bytes / type_.bytes;
    for (std::size_t i = 0; i < whole; ++i) emit(data + i * type_.bytes);
    data += whole * type_.bytes;
    bytes -= whole * type_.bytes;
    std::memcpy(carry_.data(), data, bytes);
    carried_ = bytes;
    flush();
  }

 private:
  void emit(const unsigned char* data) {
    std::array<unsigned char, 8> native{};
    std::memcpy(native.data(), data, type_.bytes);
    if (order_ != std::endian::native) std::reverse(native.begin(), native.begin() + type_.bytes);
    values_.push_back(valueOf(native.data(), type_.type));
    if (values_.size() == kChunkValues) flush();
  }
  void flush() {
    if (!values_.empty()) sink_(next_, values_.data(), values_.size());
    next_ += values_.size();
    values_.clear();
  }

  const NumberTypeInfo& type_;
  std::endian order_;
  const ValueSink& sink_;
  std::array<unsigned char, 8> carry_{};
  std::size_t carried_ = 0;
  std::vector<double> values_;
  std::uint64_t next_ = 0;  // the number of the first value in values_
};

// Makes the sink's storage hold the values below the given index (growDecoded).
using GrowSink = std::function<Result<void>(std::uint64_t valuesEnd)>;

// Grows `v` (reserveDecoded, growDecoded) to the items that hold values below an index,
// `valuesPerItem` values an item.
template <class Vector>
GrowSink growInto(Vector& v, std::size_t total, std::uint64_t valuesPerItem,
                  const std::filesystem::path& path) {
  return [&v, total, valuesPerItem, &path](std::uint64_t valuesEnd) -> Result<void> {
    LIC3D_TRY(reserveDecoded(v, total, path));
    growDecoded(v, static_cast<std::size_t>((valuesEnd + valuesPerItem - 1) / valuesPerItem));
    return {};
  };
}

// Reads one array of `tuples` tuples into `sink`. Before values are delivered, `grow` gets the
// index they end below: for uncompressed data once its size has been checked against the bytes
// present, for zlib blocks batch by batch, once each batch has inflated.
class ArrayReader {
 public:
  ArrayReader(const VtiFile& file, const ArrayRef& array, std::uint64_t tuples)
      : file_(file), array_(array), what_(describe(array)), tuples_(tuples) {}

  Result<void> read(const GrowSink& grow, const ValueSink& sink) {
    LIC3D_TRY(checkArray(file_, array_, tuples_));
    values_ = tuples_ * array_.components;
    bytes_ = values_ * array_.type->bytes;
    const std::string format = array_.node.attribute("format").value();
    if (format == "ascii") return readAscii(grow, sink);
    if (format == "binary") {
      ByteSource source = ByteSource::base64(array_.node.child_value());
      return readBinary(source, grow, sink);
    }
    if (format == "appended") {
      if (!file_.hasAppended) return fail("format is appended, but the file has no AppendedData");
      LIC3D_TRY_ASSIGN(const std::uint64_t offset, appendedOffset(file_, array_));
      if (file_.appendedInFile) {
        LIC3D_TRY_ASSIGN(FileReader reader, FileReader::open(file_.path));
        if (reader.skip(file_.appendedAt + offset) != file_.appendedAt + offset)
          return fail("the AppendedData ends before offset " + std::to_string(offset));
        ByteSource source = ByteSource::file(std::move(reader), file_.appendedSize - offset);
        return readBinary(source, grow, sink);
      }
      const std::string_view data = file_.appended.substr(static_cast<std::size_t>(offset));
      ByteSource source = file_.appendedBase64 ? ByteSource::base64(data) : ByteSource::raw(data);
      return readBinary(source, grow, sink);
    }
    return fail("format: expected ascii, binary or appended, found " + quoteForMessage(format));
  }

 private:
  Error fail(const std::string& problem) const { return file_.fail(what_ + ": " + problem); }

  std::string layoutText() const {
    return std::to_string(tuples_) + " tuples of " + std::to_string(array_.components) + " " +
           std::string(array_.type->vtkXmlName);
  }

  Result<void> readAscii(const GrowSink& grow, const ValueSink& sink) {
    const std::string_view text = array_.node.child_value();
    // Each number takes at least one character and a separator.
    if (values_ > text.size() / 2 + 1)
      return fail("expected " + std::to_string(values_) + " numbers (" + layoutText() +
                  "), the text holds at most " + std::to_string(text.size() / 2 + 1));
    LIC3D_TRY(grow(values_));
    const bool isFloat = array_.type->type == NumberType::Float32;
    std::vector<double> chunk;
    chunk.reserve(std::min<std::uint64_t>(values_, kChunkValues));
    std::uint64_t count = 0;
    std::size_t i = 0;
    for (;;) {
      while (i < text.size() && isAsciiSpace(text[i])) ++i;
      if (i == text.size()) break;
      const std::size_t start = i;
      while (i < text.size() && !isAsciiSpace(text[i])) ++i;
      const std::string_view word = text.substr(start, i - start);
      if (count == values_)
        return fail("holds more than the " + std::to_string(values_) + " numbers expected (" +
                    layoutText() + ")");
      // Float32 text parses as float directly, so it reads exactly as VTK wrote it; beyond the
      // float range it is still a number, read as a double.
      double value = 0.0;
      float single = 0.0f;
      bool parsed = isFloat && parseFloat(word, single);
      if (parsed) value = single;
      if (!parsed) parsed = parseDouble(word, value);
      if (!parsed)
        return fail("expected a number, found " + quoteForMessage(word) + " after " +
                    std::to_string(count) + " values");
      chunk.push_back(value);
      ++count;
      if (chunk.size() == kChunkValues) {
        sink(count - chunk.size(), chunk.data(), chunk.size());
        chunk.clear();
      }
    }
    if (count != values_)
      return fail("holds " + std::to_string(count) + " numbers, expected " +
                  std::to_string(values_) + " (" + layoutText() + ")");
    if (!chunk.empty()) sink(count - chunk.size(), chunk.data(), chunk.size());
    return {};
  }

  Result<std::uint64_t> readHeaderNumber(ByteSource& source, std::string_view field) {
    const std::size_t size = file_.header64 ? 8 : 4;
    std::array<unsigned char, 8> bytes{};
    if (source.read(bytes.data(), size) != size)
      return fail(source.invalid()
                      ? "invalid base64 data"
                      : "the data ends inside its header (" + std::string(field) + ")");
    if (file_.order != std::endian::native) std::reverse(bytes.begin(), bytes.begin() + size);
    if (size == 4) {
      std::uint32_t value;
      std::memcpy(&value, bytes.data(), 4);
      return value;
    }
    std::uint64_t value;
    std::memcpy(&value, bytes.data(), 8);
    return value;
  }

  Error truncated(ByteSource& source, std::uint64_t needed) const {
    if (source.invalid()) return fail("invalid base64 data");
    return fail("the data is truncated: " + std::to_string(needed) + " bytes expected, at most " +
                std::to_string(source.maxRemaining()) + " present");
  }

  Result<void> readBinary(ByteSource& source, const GrowSink& grow, const ValueSink& sink) {
    return file_.zlib ? readCompressed(source, grow, sink) : readUncompressed(source, grow, sink);
  }

  // [byte count][bytes]
  Result<void> readUncompressed(ByteSource& source, const GrowSink& grow, const ValueSink& sink) {
    LIC3D_TRY_ASSIGN(const std::uint64_t size, readHeaderNumber(source, "the byte count"));
    if (size != bytes_)
      return fail("the data block holds " + std::to_string(size) + " bytes, expected " +
                  std::to_string(bytes_) + " (" + layoutText() + ")");
    if (size > source.maxRemaining()) return truncated(source, size);
    LIC3D_TRY(grow(values_));
    if (const std::optional<std::string_view> bytes =
            source.take(static_cast<std::size_t>(bytes_))) {
      decodeInParallel(*array_.type, file_.order,
                       reinterpret_cast<const unsigned char*>(bytes->data()), values_, 0, sink);
      return {};
    }
    // From a file or base64: read in chunks of whole values, each decoded on the threads.
    const std::size_t valueBytes = array_.type->bytes;
    std::vector<unsigned char> chunk(static_cast<std::size_t>(
        std::min<std::uint64_t>(bytes_, kStreamChunkBytes / valueBytes * valueBytes)));
    for (std::uint64_t done = 0; done < bytes_;) {
      const auto want =
          static_cast<std::size_t>(std::min<std::uint64_t>(bytes_ - done, chunk.size()));
      if (source.read(chunk.data(), want) != want) return truncated(source, bytes_);
      decodeInParallel(*array_.type, file_.order, chunk.data(), want / valueBytes,
                       done / valueBytes, sink);
      done += want;
    }
    return {};
  }

  // vtkZLibDataCompressor: [block count][block size][last block size][compressed size per block]
  // and the blocks, each a zlib stream of `block size` bytes (the last one `last block size`,
  // 0 meaning a full block).
  Result<void> readCompressed(ByteSource& source, const GrowSink& grow, const ValueSink& sink) {
    LIC3D_TRY_ASSIGN(const std::uint64_t blocks, readHeaderNumber(source, "the block count"));
    LIC3D_TRY_ASSIGN(const std::uint64_t blockSize, readHeaderNumber(source, "the block size"));
    LIC3D_TRY_ASSIGN(const std::uint64_t lastSize, readHeaderNumber(source, "the last block size"));
    const std::uint64_t headerBytes = file_.header64 ? 8 : 4;
    if (blocks == 0 || blockSize == 0 || lastSize > blockSize)
      return fail("the compression header (" + std::to_string(blocks) + " blocks of " +
                  std::to_string(blockSize) + " bytes, the last " + std::to_string(lastSize) +
                  ") is inconsistent");
    if (blocks > source.maxRemaining() / headerBytes)
      return fail("the compression header promises " + std::to_string(blocks) +
                  " blocks, more than the data can hold");
    // The blocks must inflate to exactly the array's size.
    const std::uint64_t lastBlock = lastSize == 0 ? blockSize : lastSize;
    std::uint64_t total = 0;
    if (__builtin_mul_overflow(blocks - 1, blockSize, &total) ||
        __builtin_add_overflow(total, lastBlock, &total) || total != bytes_)
      return fail("the compressed blocks hold " + std::to_string(blocks) + " x " +
                  std::to_string(blockSize) + " bytes (the last " + std::to_string(lastBlock) +
                  "), expected " + std::to_string(bytes_) + " (" + layoutText() + ")");
    std::vector<std::uint64_t> compressedSizes(static_cast<std::size_t>(blocks));
    std::uint64_t compressedTotal = 0;
    for (std::uint64_t& size : compressedSizes) {
      LIC3D_TRY_ASSIGN(size, readHeaderNumber(source, "the compressed block sizes"));
      if (__builtin_add_overflow(compressedTotal, size, &compressedTotal))
        return fail("the compressed block sizes overflow");
    }
    if (compressedTotal > source.maxRemaining()) return truncated(source, compressedTotal);
    for (std::size_t i = 0; i < compressedSizes.size(); ++i) {
      const std::uint64_t inflated = i + 1 == compressedSizes.size() ? lastBlock : blockSize;
      if (inflated > compressedSizes[i] * kMaxDeflateRatio)
        return fail("block " + std::to_string(i) + ": " + std::to_string(compressedSizes[i]) +
                    " compressed bytes cannot inflate to " + std::to_string(inflated));
    }
    ValueDecoder decoder(*array_.type, file_.order, sink);
    // The blocks are independent zlib streams: a batch of them is read, inflated on the
    // available threads, and decoded in order. A batch holds at most kInflateBatchBytes
    // inflated, so memory stays bounded whatever the file.
    const std::size_t block = static_cast<std::size_t>(std::min(blockSize, bytes_));
    const std::size_t batch = std::clamp<std::size_t>(
        kInflateBatchBytes / std::max<std::size_t>(block, 1), 1, 4 * availableThreads());
    std::vector<unsigned char> compressed;
    std::vector<char> inflated(batch * block);
    std::vector<std::size_t> offsets(batch + 1);
    for (std::size_t first = 0; first < compressedSizes.size(); first += batch) {
      const std::size_t count = std::min(batch, compressedSizes.size() - first);
      offsets[0] = 0;
      for (std::size_t b = 0; b < count; ++b)
        offsets[b + 1] = offsets[b] + static_cast<std::size_t>(compressedSizes[first + b]);
      compressed.resize(offsets[count]);
      if (source.read(compressed.data(), offsets[count]) != offsets[count])
        return truncated(source, compressedTotal);
      const auto inflatedSize = [&](std::size_t i) {
        return static_cast<std::size_t>(i + 1 == compressedSizes.size() ? lastBlock : blockSize);
      };
      std::vector<Result<void>> results(count);
      parallelFor(count, 0, [&](std::size_t b) {
        const std::size_t i = first + b;
        results[b] = inflateExactly(
            file_.path, what_ + " block " + std::to_string(i),
            std::string_view(reinterpret_cast<const char*>(compressed.data() + offsets[b]),
                             offsets[b + 1] - offsets[b]),
            std::span<char>(inflated.data() + b * block, inflatedSize(i)));
      });
      for (std::size_t b = 0; b < count; ++b) LIC3D_TRY(std::move(results[b]));
      // Memory for the values this batch completes, now that they exist.
      const std::uint64_t bytesEnd = std::min<std::uint64_t>((first + count) * blockSize, bytes_);
      LIC3D_TRY(grow((bytesEnd + array_.type->bytes - 1) / array_.type->bytes));
      const auto* data = reinterpret_cast<const unsigned char*>(inflated.data());
      if (block % array_.type->bytes == 0) {
        // Every block holds whole values: the batch is one run of values, decoded in parallel.
        const std::size_t bytes = (count - 1) * block + inflatedSize(first + count - 1);
        decodeInParallel(*array_.type, file_.order, data, bytes / array_.type->bytes,
                         std::uint64_t{first} * (block / array_.type->bytes), sink);
      } else {
        for (std::size_t b = 0; b < count; ++b)
          decoder.add(data + b * block, inflatedSize(first + b));
      }
    }
    return {};
  }

  const VtiFile& file_;
  const ArrayRef& array_;
  std::string what_;
  std::uint64_t tuples_;
  std::uint64_t values_ = 0;
  std::uint64_t bytes_ = 0;
};

// The grid of an array: the points, or the cell centres for cell data.
CellCentredGrid gridOf(const VtiFile& file, const ArrayRef& array) {
  if (array.cellData) return cellCentredGrid(file.dims, file.geometry);
  return {file.dims, file.geometry};
}

bool isValidPointMask(const ArrayRef& array) {
  return !array.cellData && array.components == 1 && array.name == kValidPointMaskName;
}

// Sets point-data vectors to zero where PointData's kValidPointMaskName array is 0; how many.
Result<std::size_t> applyValidPointMask(const VtiFile& file, const std::vector<ArrayRef>& arrays,
                                        VectorField& field) {
  const auto mask = std::find_if(arrays.begin(), arrays.end(), isValidPointMask);
  if (mask == arrays.end()) return std::size_t{0};
  std::vector<std::uint8_t> valid;
  LIC3D_TRY(ArrayReader(file, *mask, voxelCount(file.dims))
                .read(growInto(valid, voxelCount(file.dims), 1, file.path),
                      [&](std::uint64_t first, const double* values, std::size_t count) {
                        for (std::size_t i = 0; i < count; ++i)
                          valid[first + i] = values[i] != 0.0 ? 1 : 0;
                      }));
  return maskVectors(valid, field.vectors);
}

// One 1-component array as float, on its grid; NaN is kept.
Result<ScalarVolume> readScalarArray(const VtiFile& file, const ArrayRef& array) {
  const CellCentredGrid grid = gridOf(file, array);
  ScalarVolume volume;
  volume.dims = grid.dims;
  volume.geometry = grid.geometry;
  LIC3D_TRY(ArrayReader(file, array, voxelCount(grid.dims))
                .read(growInto(volume.values, voxelCount(grid.dims), 1, file.path),
                      [&](std::uint64_t first, const double* values, std::size_t count) {
                        for (std::size_t i = 0; i < count; ++i)
                          volume.values[first + i] = vectorComponent(values[i]);
                      }));
  return volume;
}

}  // namespace

Result<VectorField> readVectorFieldVti(const std::filesystem::path& path,
                                       std::string_view arrayName, FieldReadInfo* info) {
  LIC3D_TRY_ASSIGN(VectorField field, readVectorFieldVtiPiece(path, arrayName, info));
  LIC3D_TRY(finishVectorField(path, field, info));
  return field;
}

Result<VectorField> readVectorFieldVtiPiece(const std::filesystem::path& path,
                                            std::string_view arrayName, FieldReadInfo* info) {
  LIC3D_TRY_ASSIGN(const std::unique_ptr<VtiFile> file, openVti(path));
  LIC3D_TRY_ASSIGN(const std::vector<ArrayRef> arrays, listArrays(*file));
  LIC3D_TRY_ASSIGN(const ArrayRef array, chooseArray(*file, arrays, arrayName, 3, "Vectors", 2));
  // Cell data on N cells becomes a field of N voxels at the cell centres (cellCentredGrid).
  const CellCentredGrid grid = gridOf(*file, array);
  // 2D vectors (x, y) belong to a 2D grid: one layer along z.
  const std::uint64_t components = array.components;
  if (components == 2 && grid.dims.z != 1)
    return file->fail(describe(array) + " holds 2D vectors (2 components) on a grid of " +
                      std::to_string(grid.dims.z) + " layers along z; they need a 2D grid");
  VectorField field;
  field.dims = grid.dims;
  field.geometry = grid.geometry;
  LIC3D_TRY(ArrayReader(*file, array, voxelCount(grid.dims))
                .read(growInto(field.vectors, voxelCount(grid.dims), components, path),
                      [&](std::uint64_t first, const double* values, std::size_t count) {
                        auto tuple = static_cast<std::size_t>(first / components);
                        auto component = static_cast<glm::length_t>(first % components);
                        for (std::size_t i = 0; i < count; ++i) {
                          field.vectors[tuple][component] = vectorComponent(values[i]);
                          if (++component == static_cast<glm::length_t>(components)) {
                            component = 0;
                            ++tuple;
                          }
                        }
                      }));
  // The mask is on the points: it says nothing about cell-centred vectors.
  std::size_t masked = 0;
  if (!array.cellData) {
    LIC3D_TRY_ASSIGN(masked, applyValidPointMask(*file, arrays, field));
  }
  if (info) {
    *info = FieldReadInfo{};
    info->arrayName = array.name;
    for (const ArrayRef& each : arrays) {
      if (each.components == 3 || (each.components == 2 && grid.dims.z == 1))
        info->arrayNames.push_back(each.name);
      if (!each.cellData && each.components == 1 && each.type && !isValidPointMask(each))
        info->scalarNames.push_back(each.name);
    }
    info->maskedVectors = masked;
  }
  return field;
}

Result<ScalarVolume> readScalarVti(const std::filesystem::path& path) {
  LIC3D_TRY_ASSIGN(const std::unique_ptr<VtiFile> file, openVti(path));
  LIC3D_TRY_ASSIGN(const std::vector<ArrayRef> arrays, listArrays(*file));
  LIC3D_TRY_ASSIGN(const ArrayRef array, chooseArray(*file, arrays, {}, 1, "Scalars"));
  return readScalarArray(*file, array);
}

Result<PointScalars> readPointScalarsVti(const std::filesystem::path& path, std::string_view name) {
  LIC3D_TRY_ASSIGN(const std::unique_ptr<VtiFile> file, openVti(path));
  LIC3D_TRY_ASSIGN(std::vector<ArrayRef> arrays, listArrays(*file));
  // VTK's mask of valid points is no colour to offer: it is read only when named.
  if (name != kValidPointMaskName) std::erase_if(arrays, isValidPointMask);
  LIC3D_TRY_ASSIGN(const ArrayRef array, chooseArray(*file, arrays, name, 1, "Scalars"));
  LIC3D_TRY_ASSIGN(ScalarVolume volume, readScalarArray(*file, array));
  PointScalars scalars;
  scalars.dims = volume.dims;
  scalars.geometry = volume.geometry;
  scalars.values = std::move(volume.values);
  scalars.name = array.name;
  return scalars;
}

Result<RgbaVolume> readRgbaVti(const std::filesystem::path& path) {
  LIC3D_TRY_ASSIGN(const std::unique_ptr<VtiFile> file, openVti(path));
  LIC3D_TRY_ASSIGN(std::vector<ArrayRef> arrays, listArrays(*file));
  // Only UInt8 arrays are colours; others of 4 components are left out of the choice.
  std::erase_if(arrays, [](const ArrayRef& array) {
    return array.cellData || !array.type || array.type->type != NumberType::UInt8;
  });
  LIC3D_TRY_ASSIGN(const ArrayRef array, chooseArray(*file, arrays, {}, 4, "Scalars"));
  RgbaVolume volume;
  volume.dims = file->dims;
  volume.geometry = file->geometry;
  LIC3D_TRY(ArrayReader(*file, array, voxelCount(file->dims))
                .read(growInto(volume.rgba, 4 * voxelCount(file->dims), 1, path),
                      [&](std::uint64_t first, const double* values, std::size_t count) {
                        for (std::size_t i = 0; i < count; ++i)
                          volume.rgba[first + i] = static_cast<std::uint8_t>(values[i]);
                      }));
  return volume;
}

}  // namespace lic3d
