// SPDX-License-Identifier: BSD-3-Clause
// VTK legacy files: each input is a .vtk file, read for its default array and for one named "v"
// (which takes the other array-selection paths: cell data, names listed in errors).

#include "fuzz_support.h"
#include "io/vtk_legacy.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lic3d;
  const std::filesystem::path file = fuzz::writeFile("input.vtk", fuzz::asText(data, size));
  FieldReadInfo info;
  fuzz::check(readVectorFieldVtk(file, {}, &info));
  fuzz::check(readVectorFieldVtk(file, "v"));
  return 0;
}
