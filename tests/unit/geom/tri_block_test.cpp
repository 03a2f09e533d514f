// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The triangle-block kernels of geom/tri_block.hpp against the scalar triangle kernel.
#include "ebgeom/geom/tri_block.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include "ebgeom/core/aabb.hpp"
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

// block_min_pruned: mask 0 exactly when no lane's triangle box (computed independently here, with
// Aabb) lies within the limit; otherwise block_min's answer, bit for bit.
TYPED_TEST(TriBlockTest, BlockMinPrunedSkipsOnlyBlocksWithEveryTriangleBoxBeyondTheLimit) {
  using T = TypeParam;
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> u(-1, 1);
  auto rnd = [&] { return Vec3<T>{T(u(rng)), T(u(rng)), T(u(rng))}; };
  int skipped = 0, kept = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    TriBlock<T, 8> blk;
    T box2 = std::numeric_limits<T>::infinity(); // nearest lane box
    const Vec3<T> shift = rnd() * T(4);
    for (int l = 0; l < 8; ++l) {
      const Vec3<T> a = shift + rnd() * T(0.3), b = shift + rnd() * T(0.3),
                    c = shift + rnd() * T(0.3);
      blk.set(l, a, b, c);
      Aabb<T> box;
      box.extend(a), box.extend(b), box.extend(c);
      box2 = std::min(box2, box.distance2(Vec3<T>{}));
    }
    const Vec3<T> p{};
    T d2[8];
    block_distance2(blk, p, d2);
    const T b2 = *std::min_element(d2, d2 + 8) * T(u(rng) + 1.5); // sometimes below every lane
    const T lim = T(u(rng) + 1.5) * box2;                         // on both sides of box2
    const LaneMin<T, 8> got = block_min_pruned(blk, p, b2, lim);
    if (box2 > lim) {
      EXPECT_EQ(got.mask, 0u);
      EXPECT_EQ(got.min, b2);
      ++skipped;
    } else {
      const LaneMin<T, 8> want = block_min(blk, p, b2);
      EXPECT_EQ(got.mask, want.mask);
      EXPECT_EQ(got.min, want.min);
      ++kept;
    }
  }
  EXPECT_GT(skipped, 100);
  EXPECT_GT(kept, 100);
}
