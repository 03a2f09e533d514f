// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The triangle-block kernels of geom/tri_block.hpp against the scalar triangle kernel.
#include "ebgeom/geom/tri_block.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "ebgeom/geom/closest_point_triangle.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class TriBlockTest : public ::testing::Test {};
TYPED_TEST_SUITE(TriBlockTest, test::FloatTypes);

namespace {
template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }
} // namespace

TYPED_TEST(TriBlockTest, BlockKernelEqualsTheScalarKernelBitForBit) {
  using T = TypeParam;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rv = [&] { return Vec3<T>{T(u(rng)), T(u(rng)), T(u(rng))}; };
  for (int round = 0; round < 2000; ++round) {
    TriBlock<T, 8> blk;
    Vec3<T> v[8][3];
    for (int l = 0; l < 8; ++l) {
      v[l][0] = rv(), v[l][1] = rv(), v[l][2] = rv();
      if (l == 1) v[l][1] = v[l][0];                                 // repeated vertex
      if (l == 2) v[l][2] = v[l][1] = v[l][0];                       // a point
      if (l == 3) v[l][2] = v[l][0] + (v[l][1] - v[l][0]) * T(0.25); // collinear
      if (l == 4) v[l][2] = v[l][0] + (v[l][1] - v[l][0]) * T(1e-7) + rv() * T(1e-7); // sliver
      blk.set(l, v[l][0], v[l][1], v[l][2]);
    }
    const Vec3<T> p = round % 5 == 0 ? v[round % 8][0] : rv() * T(2);
    T d2[8];
    block_distance2(blk, p, d2);
    for (int l = 0; l < 8; ++l) {
      const auto ref = closest_point_triangle(p, v[l][0], v[l][1], v[l][2]);
      ASSERT_TRUE(same_bits(d2[l], ref.distance2))
          << "lane " << l << ": " << d2[l] << " vs " << ref.distance2;
    }
  }
}

TYPED_TEST(TriBlockTest, BlockMinReportsOnlyBlocksWithinTheBound) {
  using T = TypeParam;
  TriBlock<T, 8> blk;
  for (int l = 0; l < 8; ++l)
    blk.set(l, {T(l), 0, 0}, {T(l) + T(0.5), 0, 0}, {T(l), T(0.5), 0}); // lanes 0 and 1 tie at p
  const Vec3<T> p{T(0.75), T(0), T(1)};
  T d2[8];
  block_distance2(blk, p, d2);
  const T best = std::min(d2[0], d2[1]);
  ASSERT_EQ(d2[0], d2[1]);
  const LaneMin<T, 8> hit = block_min(blk, p, best);
  EXPECT_EQ(hit.min, best);
  EXPECT_EQ(hit.mask, 3u);
  EXPECT_EQ(block_min(blk, p, std::nextafter(best, T(0))).mask, 0u);
}
