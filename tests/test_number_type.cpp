// SPDX-License-Identifier: BSD-3-Clause
// The one number-type table: every format's names for a type lead to the same size and kind, and
// the one conversion reads each type in either byte order. The text helpers the formats share.

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <string>

#include "core/text.h"
#include "io/number_type.h"

namespace lic3d {
namespace {

TEST(NumberTypeTest, EveryFormatsNamesFindTheSameType) {
  struct Names {
    NumberType type;
    std::size_t bytes;
    const char* vtkXml;
    const char* nrrd;
    const char* vtkLegacy;
  };
  const Names names[] = {
      {NumberType::Int8, 1, "Int8", "signed char", "char"},
      {NumberType::UInt8, 1, "UInt8", "uchar", "unsigned_char"},
      {NumberType::Int16, 2, "Int16", "short", "short"},
      {NumberType::UInt16, 2, "UInt16", "ushort", "unsigned_short"},
      {NumberType::Int32, 4, "Int32", "int", "int"},
      {NumberType::UInt32, 4, "UInt32", "uint", "unsigned_int"},
      {NumberType::Int64, 8, "Int64", "longlong", "long"},
      {NumberType::UInt64, 8, "UInt64", "ulonglong", "unsigned_long"},
      {NumberType::Float32, 4, "Float32", "float", "float"},
      {NumberType::Float64, 8, "Float64", "double", "double"},
  };
  for (const Names& each : names) {
    SCOPED_TRACE(each.vtkXml);
    const NumberTypeInfo& info = numberType(each.type);
    EXPECT_EQ(info.type, each.type);
    EXPECT_EQ(info.bytes, each.bytes);
    EXPECT_EQ(info.vtkXmlName, each.vtkXml);
    EXPECT_EQ(info.nrrdNames[0], each.nrrd);  // what the NRRD writers write
    EXPECT_EQ(findVtkXmlType(each.vtkXml), &info);
    EXPECT_EQ(findNrrdType(each.nrrd), &info);
    EXPECT_EQ(findVtkLegacyType(each.vtkLegacy), &info);
  }
  // Aliases, and names that are none.
  EXPECT_EQ(findNrrdType("unsigned long long int")->type, NumberType::UInt64);
  EXPECT_EQ(findNrrdType("int16_t")->type, NumberType::Int16);
  EXPECT_EQ(findVtkLegacyType("vtkidtype")->type, NumberType::Int32);
  EXPECT_EQ(findVtkLegacyType("vtktypeuint64")->type, NumberType::UInt64);
  EXPECT_EQ(findNrrdType("block"), nullptr);
  EXPECT_EQ(findNrrdType(""), nullptr);
  EXPECT_EQ(findVtkXmlType("float32"), nullptr);  // VTK XML names are compared as written
  EXPECT_EQ(findVtkLegacyType("bit"), nullptr);
}

TEST(NumberTypeTest, ConvertsEachTypeInEitherByteOrder) {
  const std::int16_t int16 = -12345;
  const std::uint64_t uint64 = (std::uint64_t{1} << 53) + 2;
  const double float64 = -0.1;
  std::array<unsigned char, 8> bytes{};
  const std::endian other =
      std::endian::native == std::endian::little ? std::endian::big : std::endian::little;
  const auto check = [&](NumberType type, const void* value, double expected) {
    const std::size_t size = numberType(type).bytes;
    std::memcpy(bytes.data(), value, size);
    EXPECT_EQ(valueOf(bytes.data(), type), expected);
    double out = 0.0;
    convertValues(type, bytes.data(), 1, std::endian::native, &out);
    EXPECT_EQ(out, expected);
    // Swapped into the other byte order, the bytes read back as the same value in that order.
    toNativeOrder(reinterpret_cast<char*>(bytes.data()), 1, size, other);
    convertValues(type, bytes.data(), 1, other, &out);
    EXPECT_EQ(out, expected);
  };
  check(NumberType::Int16, &int16, -12345.0);
  check(NumberType::UInt64, &uint64, static_cast<double>(uint64));
  check(NumberType::Float64, &float64, -0.1);
}

TEST(TextTest, TripleTextWritesEachFormatsSeparator) {
  const glm::dvec3 v(1.0, 0.1, -2.5);
  EXPECT_EQ(tripleText(v, " "), "1 0.1 -2.5");     // VTK XML
  EXPECT_EQ(tripleText(v, ", "), "1, 0.1, -2.5");  // JSON lists
  EXPECT_EQ(tripleText(v, ","), "1,0.1,-2.5");     // NRRD vectors, the CLI's summary
}

TEST(TextTest, ParseIntTakesWholeNumbersOnly) {
  int value = 0;
  EXPECT_TRUE(parseInt("-42", value));
  EXPECT_EQ(value, -42);
  EXPECT_FALSE(parseInt("", value));
  EXPECT_FALSE(parseInt("4x", value));
  EXPECT_FALSE(parseInt("+4", value));
  EXPECT_FALSE(parseInt("99999999999", value));
}

}  // namespace
}  // namespace lic3d
