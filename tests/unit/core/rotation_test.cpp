// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/core/rotation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "test_support.hpp"

using namespace ebgeom;

template <class T> class RotationTest : public ::testing::Test {};
TYPED_TEST_SUITE(RotationTest, test::FloatTypes);

namespace {
template <class T> void expect_near(const Vec3<T>& a, const Vec3<T>& b, T tol) {
  EXPECT_NEAR(a.x, b.x, tol) << a << " vs " << b;
  EXPECT_NEAR(a.y, b.y, tol) << a << " vs " << b;
  EXPECT_NEAR(a.z, b.z, tol) << a << " vs " << b;
}
} // namespace

TYPED_TEST(RotationTest, CoordinateAxesRightHandedAndExactQuarterTurns) {
  using T = TypeParam;
  // 90 degrees about z takes x to y, about x takes y to z, about y takes z to x: exactly.
  EXPECT_EQ(Mat3<T>::coordinate_axis(Axis::z, 90) * Vec3<T>::unit(0), Vec3<T>::unit(1));
  EXPECT_EQ(Mat3<T>::coordinate_axis(Axis::x, 90) * Vec3<T>::unit(1), Vec3<T>::unit(2));
  EXPECT_EQ(Mat3<T>::coordinate_axis(Axis::y, 90) * Vec3<T>::unit(2), Vec3<T>::unit(0));
  EXPECT_EQ(Mat3<T>::coordinate_axis(Axis::z, -90) * Vec3<T>::unit(1), Vec3<T>::unit(0));
  EXPECT_EQ(Mat3<T>::coordinate_axis(Axis::z, 450) * Vec3<T>::unit(0), Vec3<T>::unit(1));
  EXPECT_EQ(Mat3<T>::coordinate_axis(Axis::x, 180) * Vec3<T>::unit(1), -Vec3<T>::unit(1));
  // an Axis forced out of range is never a silent identity: every entry is NaN
  for (const int bad : {-1, 3, 7, 90})
    for (int i = 0; i < 9; ++i) {
      EXPECT_TRUE(std::isnan(Mat3<T>::coordinate_axis(static_cast<Axis>(bad), 30).m[i]));
      EXPECT_TRUE(std::isnan(Mat3<T>::coordinate_axis(static_cast<Axis>(bad), 0).m[i]));
    }
  EXPECT_TRUE(std::isnan(Quaternion<T>::coordinate_axis(static_cast<Axis>(3), 30).w));
  // 30 degrees about z: (cos 30, sin 30, 0), written from the definition
  expect_near(Mat3<T>::coordinate_axis(Axis::z, 30) * Vec3<T>::unit(0),
              Vec3<T>{T(std::sqrt(3.0) / 2), T(0.5), 0}, test::tol<T>());
  expect_near(Quaternion<T>::coordinate_axis(Axis::z, 30).rotate(Vec3<T>::unit(0)),
              Vec3<T>{T(std::sqrt(3.0) / 2), T(0.5), 0}, test::tol<T>());
  expect_near(Quaternion<T>::coordinate_axis(Axis::y, 90).rotate(Vec3<T>::unit(2)),
              Vec3<T>::unit(0), test::tol<T>());
  EXPECT_EQ(Quaternion<T>::coordinate_axis(Axis::y, 180).rotate(Vec3<T>::unit(2)),
            -Vec3<T>::unit(2));
}

TYPED_TEST(RotationTest, MatrixAndQuaternionAgreeAndAreOrthonormal) {
  using T = TypeParam;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> ang(-7, 7);
  for (int i = 0; i < 200; ++i) {
    const Vec3<T> axis = test::random_unit<T>(rng) * T(3); // not unit on purpose
    const T a = T(ang(rng));
    const Mat3<T> m = Mat3<T>::axis_angle(axis, a);
    const Quaternion<T> q = Quaternion<T>::axis_angle(axis, a);
    const Vec3<T> v = test::random_unit<T>(rng) * T(2.5);
    expect_near(m * v, q.rotate(v), test::tol<T>() * 10);
    expect_near(q.to_mat3() * v, m * v, test::tol<T>() * 10);
    // R R^T = I, det = 1, axis fixed, angle preserved: cos a = (tr R - 1) / 2
    const Mat3<T> id = m * m.transposed();
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(id(r, c), T(r == c), test::tol<T>() * 10);
    EXPECT_NEAR(m.determinant(), T(1), test::tol<T>() * 10);
    expect_near(m * axis, axis, test::tol<T>() * 30);
    EXPECT_NEAR((m(0, 0) + m(1, 1) + m(2, 2) - 1) / 2, T(std::cos(double(a))), test::tol<T>() * 10);
    // degrees variant
    expect_near(Mat3<T>::axis_degrees(axis, a * T(180 / M_PI)) * v, m * v, test::tol<T>() * 100);
    expect_near(Quaternion<T>::axis_degrees(axis, a * T(180 / M_PI)).rotate(v), m * v,
                test::tol<T>() * 100);
  }
}

TYPED_TEST(RotationTest, CompositionOrder) {
  using T = TypeParam;
  std::mt19937_64 rng(9);
  for (int i = 0; i < 100; ++i) {
    const auto qa = Quaternion<T>::axis_angle(test::random_unit<T>(rng), T(0.3 + i * 0.05));
    const auto qb = Quaternion<T>::axis_angle(test::random_unit<T>(rng), T(-1.1 + i * 0.03));
    const Vec3<T> v = test::random_unit<T>(rng);
    expect_near((qa * qb).rotate(v), qa.rotate(qb.rotate(v)), test::tol<T>() * 10);
    expect_near((qa.to_mat3() * qb.to_mat3()) * v, qa.rotate(qb.rotate(v)), test::tol<T>() * 10);
    expect_near(qa.conjugate().rotate(qa.rotate(v)), v, test::tol<T>() * 10);
    expect_near(qa.to_mat3().transposed() * (qa.to_mat3() * v), v, test::tol<T>() * 10);
  }
  const Quaternion<T> big{2, 0, 0, 2};
  EXPECT_NEAR(big.normalized().norm2(), T(1), test::tol<T>());
  // zero or non-finite axes and a zero quaternion describe no rotation: NaN, not the identity
  EXPECT_TRUE(std::isnan(Quaternion<T>{0, 0, 0, 0}.normalized().w));
  EXPECT_TRUE(std::isnan(Quaternion<T>::axis_angle(Vec3<T>::zero(), 1).x));
  EXPECT_TRUE(std::isnan(Quaternion<T>::axis_degrees(Vec3<T>::zero(), 90).w));
  const T inf = std::numeric_limits<T>::infinity();
  for (const Vec3<T>& bad :
       {Vec3<T>::zero(), Vec3<T>{inf, 0, 0}, Vec3<T>{std::numeric_limits<T>::quiet_NaN(), 1, 0}}) {
    const Mat3<T> a = Mat3<T>::axis_angle(bad, 1), d = Mat3<T>::axis_degrees(bad, 90);
    for (int i = 0; i < 9; ++i) {
      EXPECT_TRUE(std::isnan(a.m[i])) << bad;
      EXPECT_TRUE(std::isnan(d.m[i])) << bad;
    }
  }
  EXPECT_EQ(Mat3<T>::from_cols(Vec3<T>{1, 2, 3}, Vec3<T>{4, 5, 6}, Vec3<T>{7, 8, 9}),
            Mat3<T>::from_rows(Vec3<T>{1, 4, 7}, Vec3<T>{2, 5, 8}, Vec3<T>{3, 6, 9}));
}

TEST(Axis, CheckedConversionsAndNames) {
  static_assert(index(Axis::x) == 0 && index(Axis::y) == 1 && index(Axis::z) == 2);
  static_assert(!std::is_convertible_v<int, Axis>, "a number must not convert to an Axis");
  static_assert(is_valid(Axis::z) && !is_valid(static_cast<Axis>(3)));
  EXPECT_EQ(name(Axis::y), 'y');
  EXPECT_EQ(name(static_cast<Axis>(-1)), '?');
  for (int i = 0; i < 3; ++i) EXPECT_EQ(index(axis_from_index(i).value()), i);
  for (const int bad : {-1, 3, 90}) {
    const auto r = axis_from_index(bad);
    ASSERT_FALSE(r.has_value());
    EXPECT_EQ(r.error().code, ErrorCode::invalid_argument);
    EXPECT_NE(r.error().message.find(std::to_string(bad)), std::string::npos) << r.error().message;
  }
  EXPECT_EQ(axis_from_name("Z").value(), Axis::z);
  EXPECT_EQ(axis_from_name("x").value(), Axis::x);
  EXPECT_FALSE(axis_from_name("w").has_value());
  EXPECT_FALSE(axis_from_name("").has_value());
  EXPECT_FALSE(axis_from_name("xy").has_value());
}
