// SPDX-License-Identifier: BSD-3-Clause
#pragma once
// Shared by the NRRD tests (test_nrrd.cpp, test_nrrd_read.cpp): one fixture, so gtest sees one
// NrrdTest suite, and the fields and checks that both files build their cases from.

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "core/volume.h"
#include "test_support.h"

namespace lic3d::test {

class NrrdTest : public TempFolderTest {};

// Values as bytes in the given byte order.
template <class T>
std::string bytesOf(const std::vector<T>& values, std::endian order) {
  std::string bytes(values.size() * sizeof(T), '\0');
  std::memcpy(bytes.data(), values.data(), bytes.size());
  if (order != std::endian::native)
    for (std::size_t i = 0; i < values.size(); ++i)
      std::reverse(bytes.begin() + static_cast<std::ptrdiff_t>(i * sizeof(T)),
                   bytes.begin() + static_cast<std::ptrdiff_t>((i + 1) * sizeof(T)));
  return bytes;
}

inline VectorField makeField(Dims dims, GridGeometry geometry) {
  VectorField field;
  field.dims = dims;
  field.geometry = geometry;
  field.vectors.resize(voxelCount(dims));
  for (std::size_t i = 0; i < field.vectors.size(); ++i) {
    const float t = static_cast<float>(i);
    field.vectors[i] = {std::sin(0.7f * t) * 3.0f, std::cos(0.3f * t) - 0.25f, 1.0f / (1.0f + t)};
  }
  return field;
}

template <class T>
void expectInputError(const Result<T>& result, const std::filesystem::path& file,
                      const std::string& fragment) {
  ASSERT_FALSE(result.ok()) << "expected an error containing '" << fragment << "'";
  const std::string& message = result.error().message;
  EXPECT_EQ(result.error().kind, ErrorKind::InvalidInput) << message;
  EXPECT_NE(message.find(file.filename().string()), std::string::npos) << message;
  EXPECT_NE(message.find(fragment), std::string::npos)
      << "'" << fragment << "' not in: " << message;
}

inline void expectSameField(const VectorField& actual, const VectorField& expected) {
  EXPECT_EQ(actual.dims, expected.dims);
  EXPECT_EQ(actual.geometry, expected.geometry);
  ASSERT_EQ(actual.vectors.size(), expected.vectors.size());
  for (std::size_t i = 0; i < expected.vectors.size(); ++i)
    ASSERT_EQ(actual.vectors[i], expected.vectors[i]) << "voxel " << i;
}

}  // namespace lic3d::test
