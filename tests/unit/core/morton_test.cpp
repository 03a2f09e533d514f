// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/core/morton.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>

using namespace ebgeom;

namespace {
// Reference: interleave bit by bit (bit i of x goes to bit 3i, of y to 3i + 1, of z to 3i + 2).
std::uint64_t interleave_reference(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  std::uint64_t code = 0;
  for (int i = 0; i < 21; ++i) {
    code |= ((x >> i) & 1u) << (3 * i);
    code |= ((y >> i) & 1u) << (3 * i + 1);
    code |= ((z >> i) & 1u) << (3 * i + 2);
  }
  return code;
}
} // namespace

TEST(Morton, UnitAxesAndTheLargestCode) {
  EXPECT_EQ(morton_encode(0, 0, 0), 0u);
  EXPECT_EQ(morton_encode(1, 0, 0), 1u);
  EXPECT_EQ(morton_encode(0, 1, 0), 2u);
  EXPECT_EQ(morton_encode(0, 0, 1), 4u);
  EXPECT_EQ(morton_encode(0x1fffff, 0x1fffff, 0x1fffff), (std::uint64_t(1) << 63) - 1);
  EXPECT_EQ(morton_spread_21(0x1fffff), 0x1249249249249249ULL);
}

TEST(Morton, EqualsBitByBitInterleavingAndIgnoresHighBits) {
  std::mt19937_64 rng(7);
  for (int i = 0; i < 10000; ++i) {
    const std::uint64_t x = rng() & 0x1fffff, y = rng() & 0x1fffff, z = rng() & 0x1fffff;
    ASSERT_EQ(morton_encode(x, y, z), interleave_reference(x, y, z)) << x << " " << y << " " << z;
    ASSERT_EQ(morton_encode(x | (rng() << 21), y, z), morton_encode(x, y, z));
  }
}
