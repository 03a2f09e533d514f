// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/core/vec.hpp"

#include <gtest/gtest.h>

#include "test_support.hpp"

using namespace ebgeom;

template <class T> class VecTest : public ::testing::Test {};
TYPED_TEST_SUITE(VecTest, test::FloatTypes);

TYPED_TEST(VecTest, ArithmeticAndProducts) {
  using T = TypeParam;
  const Vec3<T> a{1, 2, 3}, b{-4, 5, 0.5};
  EXPECT_EQ(a + b, (Vec3<T>{-3, 7, 3.5}));
  EXPECT_EQ(a - b, (Vec3<T>{5, -3, 2.5}));
  EXPECT_EQ(a * T(2), (Vec3<T>{2, 4, 6}));
  EXPECT_EQ(T(2) * a, a * T(2));
  EXPECT_EQ(dot(a, b), T(-4 + 10 + 1.5));
  const Vec3<T> c = cross(a, b);
  EXPECT_NEAR(dot(c, a), T(0), test::tol<T>() * 10);
  EXPECT_NEAR(dot(c, b), T(0), test::tol<T>() * 10);
  EXPECT_EQ(cross(Vec3<T>::unit(0), Vec3<T>::unit(1)), Vec3<T>::unit(2));
  EXPECT_NEAR(norm(Vec3<T>{3, 4, 12}), T(13), test::tol<T>());
  EXPECT_EQ(normalized(Vec3<T>::zero()), Vec3<T>::zero());
  EXPECT_EQ(min(a, b), (Vec3<T>{-4, 2, 0.5}));
  EXPECT_EQ(max(a, b), (Vec3<T>{1, 5, 3}));
  EXPECT_EQ(arg_max(Vec3<T>{1, 5, 3}), 1);
  EXPECT_EQ(arg_max(Vec3<T>{7, 7, 7}), 0);
  EXPECT_EQ(arg_min(Vec3<T>{1, 5, -3}), 2);
  EXPECT_EQ(abs(b), (Vec3<T>{4, 5, 0.5}));
  EXPECT_TRUE(all_finite(a));
  EXPECT_FALSE(all_finite(Vec3<T>{0, std::numeric_limits<T>::quiet_NaN(), 0}));
  const Vec2<T> u{3, 4}, v{1, 0};
  EXPECT_EQ(norm(u), T(5));
  EXPECT_EQ(cross(v, u), T(4));
}
