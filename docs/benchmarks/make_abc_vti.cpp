// SPDX-License-Identifier: BSD-3-Clause
// The ABC flow on an N^3 grid as two .vti files, <out>_raw.vti (appended raw) and <out>_zlib.vti
// (zlib blocks of 32 KiB), for the read benchmarks of end_to_end.sh:
//   g++ -O2 -static -o make_abc_vti make_abc_vti.cpp -lz && ./make_abc_vti 256 /tmp/abc256
#include <zlib.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>
int main(int argc, char** argv) {
  const int n = std::atoi(argv[1]);
  const std::string out = argv[2];
  const double a = std::sqrt(3.0), b = std::sqrt(2.0), c = 1.0, h = 2 * M_PI / (n - 1);
  std::vector<float> v(size_t(n) * n * n * 3);
  size_t q = 0;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = i * h, y = j * h, z = k * h;
        v[q++] = a * std::sin(z) + c * std::cos(y);
        v[q++] = b * std::sin(x) + a * std::cos(z);
        v[q++] = c * std::sin(y) + b * std::cos(x);
      }
  const size_t bytes = v.size() * 4;
  auto header = [&](const char* comp) {
    char s[2048];
    std::snprintf(s, sizeof s,
                  "<?xml version=\"1.0\"?>\n<VTKFile type=\"ImageData\" version=\"1.0\" "
                  "byte_order=\"LittleEndian\" header_type=\"UInt64\"%s>\n<ImageData "
                  "WholeExtent=\"0 %d 0 %d 0 %d\" Origin=\"0 0 0\" Spacing=\"%.17g %.17g %.17g\">\n"
                  "<Piece Extent=\"0 %d 0 %d 0 %d\">\n<PointData Vectors=\"velocity\">\n<DataArray "
                  "type=\"Float32\" Name=\"velocity\" NumberOfComponents=\"3\" format=\"appended\" "
                  "offset=\"0\"/>\n</PointData>\n</Piece>\n</ImageData>\n<AppendedData "
                  "encoding=\"raw\">\n_",
                  comp, n - 1, n - 1, n - 1, h, h, h, n - 1, n - 1, n - 1);
    return std::string(s);
  };
  const char* tail = "\n</AppendedData>\n</VTKFile>\n";
  {
    FILE* f = std::fopen((out + "_raw.vti").c_str(), "wb");
    const std::string hd = header("");
    std::fwrite(hd.data(), 1, hd.size(), f);
    const std::uint64_t size = bytes;
    std::fwrite(&size, 8, 1, f);
    std::fwrite(v.data(), 1, bytes, f);
    std::fputs(tail, f);
    std::fclose(f);
  }
  const size_t bs = 1 << 15, count = (bytes + bs - 1) / bs;
  std::vector<std::vector<unsigned char>> blocks(count);
  std::vector<std::uint64_t> head{count, bs, bytes - (count - 1) * bs};
  for (size_t i = 0; i < count; ++i) {
    const size_t len = std::min(bs, bytes - i * bs);
    uLongf cap = compressBound(len);
    blocks[i].resize(cap);
    compress2(blocks[i].data(), &cap, reinterpret_cast<const Bytef*>(v.data()) + i * bs, len, 6);
    blocks[i].resize(cap);
    head.push_back(cap);
  }
  FILE* f = std::fopen((out + "_zlib.vti").c_str(), "wb");
  const std::string hd = header(" compressor=\"vtkZLibDataCompressor\"");
  std::fwrite(hd.data(), 1, hd.size(), f);
  std::fwrite(head.data(), 8, head.size(), f);
  for (auto& blk : blocks) std::fwrite(blk.data(), 1, blk.size(), f);
  std::fputs(tail, f);
  std::fclose(f);
}
