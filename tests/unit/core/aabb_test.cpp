// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/core/aabb.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace ebgeom;

template <class T> class AabbTest : public ::testing::Test {};
TYPED_TEST_SUITE(AabbTest, test::FloatTypes);

TYPED_TEST(AabbTest, EmptyExtendAndMeasures) {
  using T = TypeParam;
  Aabb<T> b;
  EXPECT_TRUE(b.is_empty());
  EXPECT_EQ(b.volume(), T(0));
  b.extend({0, 0, 0}).extend({1, 2, 3});
  EXPECT_FALSE(b.is_empty());
  EXPECT_EQ(b.volume(), T(6));
  EXPECT_EQ(b.surface_area(), T(2 * (2 + 6 + 3)));
  EXPECT_EQ(b.center(), (Vec3<T>{0.5, 1, 1.5}));
  EXPECT_EQ(b.longest_axis(), 2);
  EXPECT_EQ(merge(b, Aabb<T>::of({-1, 0, 0})).lo.x, T(-1));
}

TYPED_TEST(AabbTest, DistanceMatchesBruteForceClosestPoint) {
  using T = TypeParam;
  const Aabb<T> b = Aabb<T>::of({-1, -2, -3}, {1, 2, 3});
  for (const auto& p : test::random_points(b.grown(5), 2000)) {
    // independent reference: clamp p into the box
    const Vec3<T> q{clamp(p.x, b.lo.x, b.hi.x), clamp(p.y, b.lo.y, b.hi.y),
                    clamp(p.z, b.lo.z, b.hi.z)};
    EXPECT_NEAR(b.distance(p), norm(p - q), test::tol<T>() * 10);
    EXPECT_EQ(b.contains(p), b.distance2(p) == T(0));
    // farthest corner, by enumerating all eight
    T far2 = 0;
    for (int c = 0; c < 8; ++c) {
      const Vec3<T> k{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y,
                      (c & 4) ? b.hi.z : b.lo.z};
      far2 = std::max(far2, norm2(p - k));
    }
    EXPECT_NEAR(b.max_distance2(p), far2, far2 * test::tol<T>());
  }
}

TYPED_TEST(AabbTest, Overlaps) {
  using T = TypeParam;
  const Aabb<T> a = Aabb<T>::of({0, 0, 0}, {1, 1, 1});
  EXPECT_TRUE(a.overlaps(Aabb<T>::of({1, 1, 1}, {2, 2, 2}))); // touching corner
  EXPECT_FALSE(a.overlaps(Aabb<T>::of({1.01, 0, 0}, {2, 1, 1})));
  EXPECT_TRUE(a.overlaps(Aabb<T>::of({0.2, 0.2, 0.2}, {0.3, 0.3, 0.3})));
  EXPECT_TRUE(a.contains(Aabb<T>::of({0.2, 0.2, 0.2}, {0.3, 0.3, 0.3})));
  EXPECT_FALSE(a.overlaps(Aabb<T>::empty()));
}
