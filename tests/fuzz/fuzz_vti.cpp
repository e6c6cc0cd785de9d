// SPDX-License-Identifier: BSD-3-Clause
// VTK XML ImageData files: each input is a .vti file, read as a vector field (default and named
// array), a scalar volume and an RGBA volume.

#include "fuzz_support.h"
#include "io/vti.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lic3d;
  const std::filesystem::path file = fuzz::writeFile("input.vti", fuzz::asText(data, size));
  FieldReadInfo info;
  fuzz::check(readVectorFieldVti(file, {}, &info));
  fuzz::check(readVectorFieldVti(file, "v"));
  fuzz::check(readScalarVti(file));
  fuzz::check(readRgbaVti(file));
  return 0;
}
