// SPDX-License-Identifier: BSD-3-Clause
// NRRD files, attached and detached. Each input is read three ways:
//  - as a NRRD file, by every reader; inputs with `data file: data.raw` or `data.gz` are detached
//    headers whose (valid) data files lie beside them;
//  - as the data file of fixed detached headers (raw with line and byte skips, raw at the end of
//    the file, gzip with a decompressed byte skip), which puts the fuzzer on the payload readers.

#include <zlib.h>

#include <cstring>
#include <vector>

#include "fuzz_support.h"
#include "io/nrrd.h"

namespace {

// A 3x2x2x1 float field's payload, and the fixed headers that name the fuzz input as their data.
void prepareSiblings() {
  using lic3d::fuzz::writeFile;
  std::vector<float> values(12);
  for (std::size_t i = 0; i < values.size(); ++i) values[i] = 0.5f + static_cast<float>(i);
  const std::string raw(reinterpret_cast<const char*>(values.data()), 48);
  writeFile("data.raw", raw);
  std::string gzip(128, '\0');
  z_stream zs{};
  if (deflateInit2(&zs, 9, Z_DEFLATED, 15 + 16, 8, Z_DEFAULT_STRATEGY) != Z_OK) std::abort();
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
  zs.avail_in = static_cast<uInt>(raw.size());
  zs.next_out = reinterpret_cast<Bytef*>(gzip.data());
  zs.avail_out = static_cast<uInt>(gzip.size());
  if (deflate(&zs, Z_FINISH) != Z_STREAM_END) std::abort();
  gzip.resize(zs.total_out);
  deflateEnd(&zs);
  writeFile("data.gz", gzip);
  const std::string fields =
      "NRRD0004\ntype: float\ndimension: 4\nsizes: 3 2 2 1\nendian: little\n";
  writeFile("raw.nhdr", fields + "encoding: raw\nline skip: 1\nbyte skip: 2\ndata file: payload\n");
  writeFile("tail.nhdr", fields + "encoding: raw\nbyte skip: -1\ndata file: payload\n");
  writeFile("gzip.nhdr", fields + "encoding: gzip\nbyte skip: 3\ndata file: payload\n");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  prepareSiblings();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace lic3d;
  const std::string_view bytes = fuzz::asText(data, size);
  const std::filesystem::path file = fuzz::writeFile("input.nrrd", bytes);
  FieldReadInfo info;
  fuzz::check(readVectorFieldNrrd(file, &info));
  fuzz::check(readNoiseNrrd(file));
  fuzz::check(readScalarNrrd(file));
  fuzz::check(readRgbaNrrd(file));
  fuzz::writeFile("payload", bytes);
  for (const char* header : {"raw.nhdr", "tail.nhdr", "gzip.nhdr"})
    fuzz::check(readVectorFieldNrrd(fuzz::scratchFolder() / header));
  return 0;
}
