// SPDX-License-Identifier: BSD-3-Clause
// The VTK XML ImageData writers: one point-data array appended raw, which ParaView reads without
// decoding, after a plain-text header in which only the caller's array name needs escaping.

#include <bit>
#include <ostream>
#include <string>

#include "core/text.h"
#include "io/file_util.h"
#include "io/number_type.h"
#include "io/volume_io.h"
#include "io/volume_stream.h"
#include "io/vti.h"
#include "io/vti_header.h"

namespace lic3d {
namespace {

// XML attribute text: names come from the caller and may hold any character.
Result<std::string> escapeXml(const std::filesystem::path& path, std::string_view text) {
  if (text.empty())
    return inputError("cannot write '" + path.string() + "': the array name is empty");
  std::string escaped;
  for (const char c : text) {
    const unsigned char byte = static_cast<unsigned char>(c);
    if (byte < 0x20 || byte == 0x7f)
      return inputError("cannot write '" + path.string() + "': the array name " +
                        quoteForMessage(text) + " holds a control character");
    switch (c) {
      case '&': escaped += "&amp;"; break;
      case '<': escaped += "&lt;"; break;
      case '>': escaped += "&gt;"; break;
      case '"': escaped += "&quot;"; break;
      case '\'': escaped += "&apos;"; break;
      default: escaped += c;
    }
  }
  return escaped;
}

// One point-data array, appended raw after a UInt64 byte count, in the host's byte order.
Result<void> writeVti(const std::filesystem::path& path, Dims dims, const GridGeometry& geometry,
                      NumberType type, int components, std::string_view arrayName, const void* data,
                      std::size_t bytes) {
  LIC3D_TRY_ASSIGN(const std::string header,
                   vti::appendedHeader(path, dims, geometry, type, components, arrayName));
  const std::uint64_t size = bytes;
  return writeFileAtomically(path, [&](std::ostream& out) {
    out << header;
    out.write(reinterpret_cast<const char*>(&size), sizeof size);
    out.write(static_cast<const char*>(data), static_cast<std::streamsize>(bytes));
    out << vti::kAppendedEnd;
    return static_cast<bool>(out);
  });
}

}  // namespace

Result<std::string> vti::appendedHeader(const std::filesystem::path& path, Dims dims,
                                        const GridGeometry& geometry, NumberType type,
                                        int components, std::string_view arrayName) {
  LIC3D_TRY_ASSIGN(const std::string name, escapeXml(path, arrayName));
  const std::string extent = "0 " + std::to_string(dims.x - 1) + " 0 " +
                             std::to_string(dims.y - 1) + " 0 " + std::to_string(dims.z - 1);
  const char* order = std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";
  return std::string("<?xml version=\"1.0\"?>\n<!-- written by lic3d -->\n") +
         "<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"" + order +
         "\" header_type=\"UInt64\">\n  <ImageData WholeExtent=\"" + extent + "\" Origin=\"" +
         tripleText(geometry.origin, " ") + "\" Spacing=\"" + tripleText(geometry.spacing, " ") +
         "\" Direction=\"1 0 0 0 1 0 0 0 1\">\n    <Piece Extent=\"" + extent +
         "\">\n      <PointData Scalars=\"" + name + "\">\n        <DataArray type=\"" +
         std::string(numberType(type).vtkXmlName) + "\" Name=\"" + name +
         "\" NumberOfComponents=\"" + std::to_string(components) +
         "\" format=\"appended\" offset=\"0\"/>\n      </PointData>\n      <CellData>\n"
         "      </CellData>\n    </Piece>\n  </ImageData>\n  <AppendedData encoding=\"raw\">\n   _";
}

Result<void> writeScalarVti(const std::filesystem::path& path, const ScalarVolume& volume,
                            std::string_view arrayName) {
  // By every thread at once, straight from the values (io/volume_stream.h).
  return writeScalarVolumeFile(path, ScalarFileFormat::Vti, volume, {.name = arrayName});
}

Result<void> writeRgbaVti(const std::filesystem::path& path, const RgbaVolume& volume) {
  LIC3D_TRY(checkVolumeForWriting(path, volume.dims, volume.rgba.size(), 4, &volume.geometry));
  return writeVti(path, volume.dims, volume.geometry, NumberType::UInt8, 4, "rgba",
                  volume.rgba.data(), volume.rgba.size());
}

}  // namespace lic3d
