// SPDX-License-Identifier: BSD-3-Clause
#include "io/number_type.h"

#include <algorithm>
#include <cstdint>
#include <cstring>

namespace lic3d {
namespace {

using enum NumberType;
using enum NumberKind;

// VTK legacy sizes: `long` is 8 bytes because VTK writes sizeof(long), and legacy files come from
// LP64 systems; vtkIdType is always written as a 32-bit int.
constexpr NumberTypeInfo kNumberTypes[] = {
    {Int8, 1, Signed, "Int8", {"signed char", "int8", "int8_t"}, {"char"}},
    {UInt8,
     1,
     Unsigned,
     "UInt8",
     {"uchar", "unsigned char", "uint8", "uint8_t"},
     {"unsigned_char"}},
    {Int16,
     2,
     Signed,
     "Int16",
     {"short", "short int", "signed short", "signed short int", "int16", "int16_t"},
     {"short"}},
    {UInt16,
     2,
     Unsigned,
     "UInt16",
     {"ushort", "unsigned short", "unsigned short int", "uint16", "uint16_t"},
     {"unsigned_short"}},
    {Int32, 4, Signed, "Int32", {"int", "signed int", "int32", "int32_t"}, {"int", "vtkidtype"}},
    {UInt32,
     4,
     Unsigned,
     "UInt32",
     {"uint", "unsigned int", "uint32", "uint32_t"},
     {"unsigned_int"}},
    {Int64,
     8,
     Signed,
     "Int64",
     {"longlong", "long long", "long long int", "signed long long", "signed long long int", "int64",
      "int64_t"},
     {"long", "vtktypeint64"}},
    {UInt64,
     8,
     Unsigned,
     "UInt64",
     {"ulonglong", "unsigned long long", "unsigned long long int", "uint64", "uint64_t"},
     {"unsigned_long", "vtktypeuint64"}},
    {Float32, 4, Real, "Float32", {"float"}, {"float"}},
    {Float64, 8, Real, "Float64", {"double"}, {"double"}},
};

static_assert(
    [] {
      for (std::size_t i = 0; i < std::size(kNumberTypes); ++i)
        if (static_cast<std::size_t>(kNumberTypes[i].type) != i) return false;
      return true;
    }(),
    "kNumberTypes lists the types in NumberType's order");

template <class Names>
bool named(const Names& names, std::string_view name) {
  return !name.empty() && std::find(names.begin(), names.end(), name) != names.end();
}

template <class T>
double load(const unsigned char* data) {
  T value;
  std::memcpy(&value, data, sizeof(T));
  return static_cast<double>(value);
}

template <class T>
void convert(const unsigned char* data, std::size_t count, std::endian order, double* out) {
  for (std::size_t i = 0; i < count; ++i) {
    std::array<unsigned char, sizeof(T)> bytes;
    std::memcpy(bytes.data(), data + i * sizeof(T), sizeof(T));
    if (order != std::endian::native) std::reverse(bytes.begin(), bytes.end());
    out[i] = load<T>(bytes.data());
  }
}

}  // namespace

const NumberTypeInfo& numberType(NumberType type) {
  return kNumberTypes[static_cast<std::size_t>(type)];
}

const NumberTypeInfo* findVtkXmlType(std::string_view name) {
  for (const NumberTypeInfo& info : kNumberTypes)
    if (info.vtkXmlName == name) return &info;
  return nullptr;
}

const NumberTypeInfo* findNrrdType(std::string_view spelling) {
  for (const NumberTypeInfo& info : kNumberTypes)
    if (named(info.nrrdNames, spelling)) return &info;
  return nullptr;
}

const NumberTypeInfo* findVtkLegacyType(std::string_view name) {
  for (const NumberTypeInfo& info : kNumberTypes)
    if (named(info.vtkLegacyNames, name)) return &info;
  return nullptr;
}

double valueOf(const unsigned char* data, NumberType type) {
  switch (type) {
    case Int8: return load<std::int8_t>(data);
    case UInt8: return load<std::uint8_t>(data);
    case Int16: return load<std::int16_t>(data);
    case UInt16: return load<std::uint16_t>(data);
    case Int32: return load<std::int32_t>(data);
    case UInt32: return load<std::uint32_t>(data);
    case Int64: return load<std::int64_t>(data);
    case UInt64: return load<std::uint64_t>(data);
    case Float32: return load<float>(data);
    case Float64: return load<double>(data);
  }
  return 0.0;
}

void convertValues(NumberType type, const unsigned char* data, std::size_t count, std::endian order,
                   double* out) {
  switch (type) {
    case Int8: return convert<std::int8_t>(data, count, order, out);
    case UInt8: return convert<std::uint8_t>(data, count, order, out);
    case Int16: return convert<std::int16_t>(data, count, order, out);
    case UInt16: return convert<std::uint16_t>(data, count, order, out);
    case Int32: return convert<std::int32_t>(data, count, order, out);
    case UInt32: return convert<std::uint32_t>(data, count, order, out);
    case Int64: return convert<std::int64_t>(data, count, order, out);
    case UInt64: return convert<std::uint64_t>(data, count, order, out);
    case Float32: return convert<float>(data, count, order, out);
    case Float64: return convert<double>(data, count, order, out);
  }
}

void toNativeOrder(char* data, std::size_t count, std::size_t valueBytes, std::endian order) {
  if (order == std::endian::native || valueBytes < 2) return;
  for (std::size_t i = 0; i < count; ++i)
    std::reverse(data + i * valueBytes, data + (i + 1) * valueBytes);
}

}  // namespace lic3d
