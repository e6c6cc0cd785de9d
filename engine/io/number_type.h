// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// The number types that volume files hold, each with its size, its kind and the names every
// format gives it (NRRD, VTK XML, VTK legacy): one table, so that no reader or writer can disagree
// with another about a type's size or spelling, and one conversion of stored values to double.

#include <array>
#include <bit>
#include <cstddef>
#include <string_view>

namespace lic3d {

enum class NumberType {
  Int8,
  UInt8,
  Int16,
  UInt16,
  Int32,
  UInt32,
  Int64,
  UInt64,
  Float32,
  Float64
};

enum class NumberKind { Signed, Unsigned, Real };

struct NumberTypeInfo {
  NumberType type;
  std::size_t bytes;
  NumberKind kind;
  // A DataArray's `type` in VTK XML files ("Float32"), compared as written.
  std::string_view vtkXmlName;
  // Every spelling NRRD allows, lower case with single spaces; the first is the one lic3d writes.
  std::array<std::string_view, 7> nrrdNames;
  // The names in VTK legacy files, lower case as VTK compares them.
  std::array<std::string_view, 2> vtkLegacyNames;
};

const NumberTypeInfo& numberType(NumberType type);

// The type a file names, or null for a name that is none of these.
const NumberTypeInfo* findVtkXmlType(std::string_view name);
const NumberTypeInfo* findNrrdType(std::string_view spelling);
const NumberTypeInfo* findVtkLegacyType(std::string_view name);

// One value of `type` at `data`, in the host's byte order, as a double.
double valueOf(const unsigned char* data, NumberType type);
// `count` values of `type` at `data`, in byte order `order`, as doubles into `out`.
void convertValues(NumberType type, const unsigned char* data, std::size_t count, std::endian order,
                   double* out);

// Reverses the bytes of each of the `count` values of `valueBytes` bytes at `data` when `order`
// is not the host's byte order.
void toNativeOrder(char* data, std::size_t count, std::size_t valueBytes, std::endian order);

}  // namespace lic3d
