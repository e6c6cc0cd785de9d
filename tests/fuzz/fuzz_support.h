// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// What the fuzz targets share: the readers take paths, so each input is written to a private
// scratch folder first; and the one property every reader must keep on any input.

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#include "core/error.h"
#include "core/volume.h"

namespace lic3d::fuzz {

// Made once per process in the temporary folder (TMPDIR: the fuzz test points it into its WORK
// folder, which its next run empties, so a fuzzer that ends without its exit handlers, on a crash
// or a timeout, leaves nothing outside the build folder) and removed at a normal exit. The exit
// handler holds its own copy of the path: the static's destructor, registered after it, runs
// before it (the handler read a destroyed path and removed nothing).
inline const std::filesystem::path& scratchFolder() {
  static const std::filesystem::path folder = [] {
    std::error_code error;
    const std::filesystem::path base = std::filesystem::temp_directory_path(error);
    std::string pattern = (error ? std::filesystem::path("/tmp") : base) / "lic3d-fuzz-XXXXXX";
    if (!::mkdtemp(pattern.data())) std::abort();
    static std::string removed;  // a plain copy for the handler, alive as long as it runs
    removed = pattern;
    std::atexit([] {
      std::error_code ignored;
      std::filesystem::remove_all(removed, ignored);
    });
    return std::filesystem::path(pattern);
  }();
  return folder;
}

inline std::filesystem::path writeFile(const std::string& name, std::string_view bytes) {
  const std::filesystem::path path = scratchFolder() / name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) std::abort();
  return path;
}

inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

// A reader returns a value or an InvalidInput error, never anything else; a value is consistent.
template <class T>
void check(const Result<T>& result) {
  if (!result.ok()) {
    if (result.error().kind != ErrorKind::InvalidInput || result.error().message.empty())
      std::abort();
    return;
  }
  if constexpr (requires { result->vectors; }) {
    if (result->vectors.size() != voxelCount(result->dims)) std::abort();
  }
  if constexpr (requires { result->values; }) {
    if (result->values.size() != voxelCount(result->dims)) std::abort();
  }
}

}  // namespace lic3d::fuzz
