// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// VTK XML ImageData files in every encoding VTK writes, made here for the reader's tests
// (test_vti.cpp): ascii, binary and appended data, raw or base64, zlib blocks, UInt32 or UInt64
// headers, either byte order.

#include <cstddef>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace lic3d::test {

// How the generated file stores its arrays.
struct Encoding {
  std::string format = "ascii";  // ascii, binary, appended
  bool zlib = false;
  bool header64 = false;
  bool appendedBase64 = false;
  bool bigEndian = false;
  // Base64 of a block's header and data as one stream instead of two (both occur in the wild).
  bool jointBase64 = false;
  std::size_t blockSize = 32768;

  std::string label() const {
    return format + (zlib ? "+zlib" : "") + (header64 ? " UInt64" : " UInt32") +
           (format == "appended" ? (appendedBase64 ? " base64" : " raw") : "") +
           (bigEndian ? " big-endian" : "") + (jointBase64 ? " joint" : "") + " blocks of " +
           std::to_string(blockSize);
  }
};

struct Array {
  std::string name;
  std::string type = "Float32";
  int components = 3;
  bool cellData = false;
  std::vector<double> values;
};

struct Image {
  std::string wholeExtent = "0 2 0 1 0 1";
  std::string origin = "1 2 3";
  std::string spacing = "0.5 0.25 2";
  std::string pointAttributes;  // e.g. Vectors="b"
  std::vector<Array> arrays;
};

std::string base64(const std::string& bytes);
std::string zlibCompress(const std::string& data);
// The values of `array` as its type's bytes, in either byte order.
std::string valueBytes(const Array& array, bool bigEndian);
// Header numbers (byte counts, block tables) as UInt32 or UInt64 in the encoding's byte order.
std::string headerNumbers(const std::vector<std::uint64_t>& numbers, const Encoding& encoding);
// The header and the data of one array's block, as VTK lays them out.
std::pair<std::string, std::string> block(const Array& array, const Encoding& encoding);
std::string encodedBlock(const Array& array, const Encoding& encoding, bool asBase64);
std::string asciiValues(const Array& array);
// The whole file.
std::string makeVti(const Image& image, const Encoding& encoding);
// start, start + step, ...: `count` values.
std::vector<double> ramp(std::size_t count, double start, double step);
// A 3x2x2 grid with a vector array "velocity" and a scalar array.
Image testImage(const std::string& type = "Float32");
// Every encoding once, and a few variants (joint base64, small blocks, big-endian raw).
std::vector<Encoding> everyEncoding();

}  // namespace lic3d::test
