// SPDX-License-Identifier: BSD-3-Clause
// The NRRD writers: lic3d's own volumes as headers that teem, 3D Slicer and ParaView read, with
// little-endian raw data whatever the host's byte order.

#include <algorithm>
#include <cstring>
#include <ostream>
#include <string>
#include <vector>

#include "core/text.h"
#include "io/file_util.h"
#include "io/nrrd.h"
#include "io/nrrd_header.h"
#include "io/number_type.h"
#include "io/volume_io.h"
#include "io/volume_stream.h"

namespace lic3d {
namespace {

static_assert(sizeof(glm::vec3) == 3 * sizeof(float), "vectors are written as packed floats");

// Appends rather than "(" + ...: GCC 12 at -O3 gives a false -Wrestrict on prepending a literal.
std::string formatVector(const glm::dvec3& v) {
  std::string text = "(";
  text += tripleText(v, ",");
  text += ')';
  return text;
}

// Writes `count` values of `bytesPerValue` bytes, stored in native order, as little endian.
bool writeLittleEndian(std::ostream& out, const void* data, std::size_t count,
                       std::size_t bytesPerValue) {
  const char* bytes = static_cast<const char*>(data);
  if (std::endian::native == std::endian::little || bytesPerValue < 2)
    return static_cast<bool>(out.write(bytes, static_cast<std::streamsize>(count * bytesPerValue)));
  std::vector<char> chunk(kFileChunkBytes);
  const std::size_t perChunk = kFileChunkBytes / bytesPerValue;
  for (std::size_t first = 0; first < count && out; first += perChunk) {
    const std::size_t n = std::min(perChunk, count - first);
    std::memcpy(chunk.data(), bytes + first * bytesPerValue, n * bytesPerValue);
    toNativeOrder(chunk.data(), n, bytesPerValue, std::endian::big);
    out.write(chunk.data(), static_cast<std::streamsize>(n * bytesPerValue));
  }
  return static_cast<bool>(out);
}

// The magic line, the comment and the type, as every header here begins.
std::string headerStart(NumberType type) {
  return "NRRD0004\n# written by lic3d\ntype: " + std::string(numberType(type).nrrdNames[0]) + "\n";
}

std::string sizesText(Dims dims) {
  return std::to_string(dims.x) + " " + std::to_string(dims.y) + " " + std::to_string(dims.z);
}

std::string directionsText(const GridGeometry& geometry) {
  return formatVector({geometry.spacing.x, 0.0, 0.0}) + " " +
         formatVector({0.0, geometry.spacing.y, 0.0}) + " " +
         formatVector({0.0, 0.0, geometry.spacing.z});
}

// `labels`, one per axis. VTK's and ParaView's NRRD reader names the array by the first label
// ("ImageFile" without one), so the first axis carries the data's name: the component axis of
// vectors and colours, the x axis of a scalar volume. (That reader also takes "space dimension"
// as the number of axes once it comes, so lic3d writes it after "sizes": before, ParaView read a
// 4-axis RGBA file as one slice.)
std::string labelsText(std::string_view name, bool componentAxis) {
  return "labels: \"" + std::string(name) + "\" " +
         (componentAxis ? "\"x\" \"y\" \"z\"\n" : "\"y\" \"z\"\n");
}

}  // namespace

std::string nrrd::scalarHeader(Dims dims, const GridGeometry& geometry, std::string_view name) {
  return headerStart(NumberType::Float32) + "dimension: 3\nsizes: " + sizesText(dims) +
         "\nspace dimension: 3\nspace directions: " + directionsText(geometry) +
         "\nkinds: domain domain domain\n" + labelsText(name, false) +
         "endian: little\nencoding: raw\nspace origin: " + formatVector(geometry.origin) + "\n\n";
}

Result<void> writeScalarNrrd(const std::filesystem::path& path, const ScalarVolume& volume,
                             std::string_view name) {
  // By every thread at once, straight from the values (io/volume_stream.h).
  return writeScalarVolumeFile(path, ScalarFileFormat::Nrrd, volume, {.name = name});
}

Result<void> writeVectorFieldNrrd(const std::filesystem::path& path, const VectorField& field) {
  LIC3D_TRY(checkVolumeForWriting(path, field.dims, field.vectors.size(), 1, &field.geometry));
  const std::string header =
      headerStart(NumberType::Float32) + "dimension: 4\nsizes: 3 " + sizesText(field.dims) +
      "\nspace dimension: 3\nspace directions: none " + directionsText(field.geometry) +
      "\nkinds: vector domain domain domain\n" + labelsText("vectors", true) +
      "endian: little\nencoding: raw\nspace origin: " + formatVector(field.geometry.origin) +
      "\n\n";
  return writeFileAtomically(path, [&](std::ostream& out) {
    out << header;
    return writeLittleEndian(out, field.vectors.data(), 3 * field.vectors.size(), sizeof(float));
  });
}

Result<void> writeNoiseNrrd(const std::filesystem::path& path, const NoiseVolume& noise) {
  const std::size_t bytesPerValue = lic3d::bytesPerValue(noise.type);
  if (noise.bytes.size() % bytesPerValue != 0)
    return inputError("cannot write '" + path.string() + "': the noise holds " +
                      std::to_string(noise.bytes.size()) + " bytes, not a whole number of values");
  LIC3D_TRY(
      checkVolumeForWriting(path, noise.dims, noise.bytes.size() / bytesPerValue, 1, nullptr));
  const NumberType type = noise.type == NoiseType::UInt8    ? NumberType::UInt8
                          : noise.type == NoiseType::UInt16 ? NumberType::UInt16
                                                            : NumberType::Float32;
  const std::string header = headerStart(type) + "dimension: 3\nsizes: " + sizesText(noise.dims) +
                             "\nkinds: domain domain domain\n" + labelsText("noise", false) +
                             (bytesPerValue > 1 ? "endian: little\n" : "") + "encoding: raw\n\n";
  return writeFileAtomically(path, [&](std::ostream& out) {
    out << header;
    return writeLittleEndian(out, noise.bytes.data(), noise.bytes.size() / bytesPerValue,
                             bytesPerValue);
  });
}

Result<void> writeRgbaNrrd(const std::filesystem::path& path, const RgbaVolume& volume) {
  LIC3D_TRY(checkVolumeForWriting(path, volume.dims, volume.rgba.size(), 4, &volume.geometry));
  const std::string header =
      headerStart(NumberType::UInt8) + "dimension: 4\nsizes: 4 " + sizesText(volume.dims) +
      "\nspace dimension: 3\nspace directions: none " + directionsText(volume.geometry) +
      "\nkinds: RGBA-color domain domain domain\n" + labelsText("RGBA", true) +
      "encoding: raw\nspace origin: " + formatVector(volume.geometry.origin) + "\n\n";
  return writeFileAtomically(path, [&](std::ostream& out) {
    out << header;
    return static_cast<bool>(out.write(reinterpret_cast<const char*>(volume.rgba.data()),
                                       static_cast<std::streamsize>(volume.rgba.size())));
  });
}

}  // namespace lic3d
