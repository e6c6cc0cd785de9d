// SPDX-License-Identifier: BSD-3-Clause
#include "vti_test_files.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <algorithm>
#include <bit>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace lic3d::test {

std::string base64(const std::string& bytes) {
  constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t bits = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (i + 1 < bytes.size())
      bits |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (i + 2 < bytes.size()) bits |= static_cast<unsigned char>(bytes[i + 2]);
    text += kAlphabet[bits >> 18 & 63];
    text += kAlphabet[bits >> 12 & 63];
    text += i + 1 < bytes.size() ? kAlphabet[bits >> 6 & 63] : '=';
    text += i + 2 < bytes.size() ? kAlphabet[bits & 63] : '=';
  }
  return text;
}

std::string zlibCompress(const std::string& data) {
  uLongf size = compressBound(static_cast<uLong>(data.size()));
  std::string out(size, '\0');
  EXPECT_EQ(
      compress2(reinterpret_cast<Bytef*>(out.data()), &size,
                reinterpret_cast<const Bytef*>(data.data()), static_cast<uLong>(data.size()), 6),
      Z_OK);
  out.resize(size);
  return out;
}

std::string valueBytes(const Array& array, bool bigEndian) {
  std::string bytes;
  const auto append = [&](const auto value) {
    char raw[sizeof value];
    std::memcpy(raw, &value, sizeof value);
    if (bigEndian == (std::endian::native == std::endian::little))
      std::reverse(raw, raw + sizeof value);
    bytes.append(raw, sizeof value);
  };
  for (const double v : array.values) {
    if (array.type == "Float32") append(static_cast<float>(v));
    if (array.type == "Float64") append(v);
    if (array.type == "UInt8") append(static_cast<std::uint8_t>(v));
    if (array.type == "Int16") append(static_cast<std::int16_t>(v));
    if (array.type == "UInt64") append(static_cast<std::uint64_t>(v));
  }
  return bytes;
}

std::string headerNumbers(const std::vector<std::uint64_t>& numbers, const Encoding& encoding) {
  Array header;
  header.type = encoding.header64 ? "UInt64" : "UInt32";
  std::string bytes;
  for (const std::uint64_t n : numbers) {
    if (encoding.header64) {
      header.values = {static_cast<double>(n)};
      bytes += valueBytes(header, encoding.bigEndian);
    } else {
      std::uint32_t small = static_cast<std::uint32_t>(n);
      char raw[4];
      std::memcpy(raw, &small, 4);
      if (encoding.bigEndian == (std::endian::native == std::endian::little))
        std::reverse(raw, raw + 4);
      bytes.append(raw, 4);
    }
  }
  return bytes;
}

// The header and the data of one array's block, as VTK lays them out.
std::pair<std::string, std::string> block(const Array& array, const Encoding& encoding) {
  const std::string data = valueBytes(array, encoding.bigEndian);
  if (!encoding.zlib) return {headerNumbers({data.size()}, encoding), data};
  std::vector<std::uint64_t> header;
  std::string compressed;
  const std::size_t blocks = (data.size() + encoding.blockSize - 1) / encoding.blockSize;
  header.push_back(blocks);
  header.push_back(encoding.blockSize);
  header.push_back(data.size() % encoding.blockSize);
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::string piece = zlibCompress(data.substr(b * encoding.blockSize, encoding.blockSize));
    header.push_back(piece.size());
    compressed += piece;
  }
  return {headerNumbers(header, encoding), compressed};
}

std::string encodedBlock(const Array& array, const Encoding& encoding, bool asBase64) {
  const auto [header, data] = block(array, encoding);
  if (!asBase64) return header + data;
  return encoding.jointBase64 ? base64(header + data) : base64(header) + base64(data);
}

std::string asciiValues(const Array& array) {
  std::string text;
  for (std::size_t i = 0; i < array.values.size(); ++i) {
    char number[40];
    std::snprintf(number, sizeof number, array.type == "Float32" ? "%.9g" : "%.17g",
                  array.values[i]);
    text += number;
    text += i % 6 == 5 ? "\n" : " ";
  }
  return text;
}

std::string makeVti(const Image& image, const Encoding& encoding) {
  std::string appended;
  const auto arrayXml = [&](const Array& array) {
    std::string xml = "        <DataArray type=\"" + array.type + "\" Name=\"" + array.name +
                      "\" NumberOfComponents=\"" + std::to_string(array.components) +
                      "\" format=\"" + encoding.format + "\"";
    if (encoding.format == "ascii")
      return xml + ">\n" + asciiValues(array) + "        </DataArray>\n";
    if (encoding.format == "binary")
      return xml + ">\n          " + encodedBlock(array, encoding, true) +
             "\n        </DataArray>\n";
    xml += " offset=\"" + std::to_string(appended.size()) + "\"/>\n";
    appended += encodedBlock(array, encoding, encoding.appendedBase64);
    return xml;
  };
  std::string pointXml;
  std::string cellXml;
  for (const Array& array : image.arrays) (array.cellData ? cellXml : pointXml) += arrayXml(array);
  std::string file =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" byte_order=\"";
  file += encoding.bigEndian ? "BigEndian" : "LittleEndian";
  file += std::string("\" header_type=\"") + (encoding.header64 ? "UInt64" : "UInt32") + "\"";
  if (encoding.zlib) file += " compressor=\"vtkZLibDataCompressor\"";
  file += ">\n  <ImageData WholeExtent=\"" + image.wholeExtent + "\" Origin=\"" + image.origin +
          "\" Spacing=\"" + image.spacing + "\">\n    <Piece Extent=\"" + image.wholeExtent +
          "\">\n      <PointData " + image.pointAttributes + ">\n" + pointXml +
          "      </PointData>\n      <CellData>\n" + cellXml +
          "      </CellData>\n    </Piece>\n"
          "  </ImageData>\n";
  if (encoding.format == "appended")
    file += std::string("  <AppendedData encoding=\"") +
            (encoding.appendedBase64 ? "base64" : "raw") + "\">\n   _" + appended +
            "\n  </AppendedData>\n";
  return file + "</VTKFile>\n";
}

std::vector<double> ramp(std::size_t count, double start, double step) {
  std::vector<double> values(count);
  for (std::size_t i = 0; i < count; ++i) values[i] = start + step * static_cast<double>(i);
  return values;
}

// A 3x2x2 grid with a vector array "velocity" and a scalar array.
Image testImage(const std::string& type) {
  Image image;
  image.arrays.push_back({"density", "Float64", 1, false, ramp(12, 0, 1)});
  image.arrays.push_back({"velocity", type, 3, false, ramp(36, -3.25, 0.5)});
  return image;
}

std::vector<Encoding> everyEncoding() {
  std::vector<Encoding> encodings;
  Encoding ascii;
  encodings.push_back(ascii);
  for (const char* format : {"binary", "appended"})
    for (const bool zlib : {false, true})
      for (const bool header64 : {false, true})
        for (const bool appendedBase64 : {false, true}) {
          if (std::string(format) == "binary" && appendedBase64) continue;
          Encoding e;
          e.format = format;
          e.zlib = zlib;
          e.header64 = header64;
          e.appendedBase64 = appendedBase64;
          encodings.push_back(e);
        }
  // Big-endian files, blocks that split values, and base64 of header and data as one stream.
  Encoding big;
  big.format = "binary";
  big.zlib = true;
  big.bigEndian = true;
  big.header64 = true;
  big.blockSize = 10;
  encodings.push_back(big);
  Encoding small;
  small.format = "appended";
  small.zlib = true;
  small.blockSize = 7;
  encodings.push_back(small);
  Encoding joint;
  joint.format = "binary";
  joint.jointBase64 = true;
  encodings.push_back(joint);
  joint.zlib = true;
  joint.blockSize = 16;
  encodings.push_back(joint);
  Encoding bigRaw;
  bigRaw.format = "appended";
  bigRaw.bigEndian = true;
  encodings.push_back(bigRaw);
  return encodings;
}

}  // namespace lic3d::test
