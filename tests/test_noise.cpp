// SPDX-License-Identifier: BSD-3-Clause
#include <gtest/gtest.h>

#include <cmath>

#include "lic/noise.h"

namespace lic3d {
namespace {

TEST(Noise, SameSeedSameNoiseOnEveryMachine) {
  // Golden values: integer-only hashing makes them the same for every compiler and CPU. A change
  // here changes every picture lic3d has made for a seed.
  EXPECT_EQ(noiseHash(1, 0), 0x8209B480FAED1B10ull);
  EXPECT_EQ(noiseHash(1, 1), 0x2D0F28C7E7E786B2ull);
  EXPECT_EQ(noiseHash(42, 123456), 0xB0BEA3E4735CB1A8ull);
  const NoiseVolume a = makeWhiteNoise({8, 8, 8}, 1);
  EXPECT_EQ(a.bytes[0], 0x82);
  EXPECT_EQ(a.bytes[1], 0x2D);
}

TEST(Noise, DifferentSeedsDiffer) {
  const NoiseVolume a = makeWhiteNoise({16, 16, 16}, 1);
  const NoiseVolume b = makeWhiteNoise({16, 16, 16}, 2);
  std::size_t same = 0;
  for (std::size_t i = 0; i < a.bytes.size(); ++i) same += a.bytes[i] == b.bytes[i];
  EXPECT_LT(same, a.bytes.size() / 64);  // chance alone: 1 in 256
}

TEST(Noise, IsUniformAndUncorrelated) {
  const NoiseVolume n = makeWhiteNoise({64, 64, 64}, 9);
  std::vector<double> histogram(256, 0.0);
  double mean = 0.0, lag1 = 0.0;
  for (std::size_t i = 0; i < n.bytes.size(); ++i) {
    histogram[n.bytes[i]] += 1.0;
    mean += n.value(i);
  }
  mean /= static_cast<double>(n.bytes.size());
  for (std::size_t i = 1; i < n.bytes.size(); ++i)
    lag1 += (n.value(i) - mean) * (n.value(i - 1) - mean);
  lag1 /= static_cast<double>(n.bytes.size() - 1) * (1.0 / 12.0);
  EXPECT_NEAR(mean, 0.5, 0.005);
  EXPECT_NEAR(lag1, 0.0, 0.01);
  // Chi-square with 255 degrees of freedom: mean 255, sd 22.6; 400 is far in the tail.
  const double expected = static_cast<double>(n.bytes.size()) / 256.0;
  double chi2 = 0.0;
  for (double count : histogram) chi2 += (count - expected) * (count - expected) / expected;
  EXPECT_LT(chi2, 400.0);
}

TEST(Noise, ValueScalesIntegerTypesByTheirMaximum) {
  NoiseVolume n;
  n.dims = {2, 1, 1};
  n.type = NoiseType::UInt16;
  const std::uint16_t values[2] = {0, 65535};
  n.bytes.assign(reinterpret_cast<const std::uint8_t*>(values),
                 reinterpret_cast<const std::uint8_t*>(values) + 4);
  EXPECT_EQ(n.value(0), 0.0f);
  EXPECT_EQ(n.value(1), 1.0f);
}

}  // namespace
}  // namespace lic3d
