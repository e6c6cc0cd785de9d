// SPDX-License-Identifier: BSD-3-Clause
// Raw vector fields with a JSON sidecar. An input is the sidecar's text, a NUL byte, then the
// raw file's bytes (all sidecar when there is no NUL).

#include <algorithm>

#include "fuzz_support.h"
#include "io/raw_volume.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lic3d;
  const std::string_view bytes = fuzz::asText(data, size);
  const std::size_t split = std::min(bytes.find('\0'), bytes.size());
  fuzz::writeFile("field.json", bytes.substr(0, split));
  const std::filesystem::path raw =
      fuzz::writeFile("field.raw", bytes.substr(std::min(split + 1, bytes.size())));
  FieldReadInfo info;
  fuzz::check(readVectorFieldRaw(raw, &info));
  return 0;
}
