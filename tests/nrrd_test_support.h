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

}  // namespace lic3d::test
