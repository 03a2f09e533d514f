// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/geom/point_in_polygon.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "test_support.hpp"

using namespace ebgeom;

template <class T> class PointInPolygonTest : public ::testing::Test {};
TYPED_TEST_SUITE(PointInPolygonTest, test::FloatTypes);

namespace {
double segment_distance(const Vec2<double>& p, const Vec2<double>& a, const Vec2<double>& b) {
  const Vec2<double> e = b - a;
  const double t = clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
  return norm(p - (a + e * t));
}
} // namespace

TYPED_TEST(PointInPolygonTest, UnitSquare) {
  using T = TypeParam;
  const std::vector<Vec2<T>> sq = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  auto c = [&](std::size_t i) { return sq[i]; };
  for (InsideTest m :
       {InsideTest::crossing_number, InsideTest::winding_number, InsideTest::subtended_angle}) {
    EXPECT_TRUE(point_in_polygon(Vec2<T>{T(0.5), T(0.5)}, 4, c, m));
    EXPECT_FALSE(point_in_polygon(Vec2<T>{T(1.5), T(0.5)}, 4, c, m));
    EXPECT_FALSE(point_in_polygon(Vec2<T>{T(0.5), T(-0.1)}, 4, c, m));
    EXPECT_FALSE(point_in_polygon(Vec2<T>{T(-3), T(0.5)}, 4, c, m));
  }
  EXPECT_EQ(winding_number(Vec2<T>{T(0.5), T(0.5)}, 4, c), 1);
  EXPECT_NEAR(subtended_angle(Vec2<T>{T(0.5), T(0.5)}, 4, c), T(2 * 3.14159265358979),
              test::tol<T>());
  // clockwise: winding -1, still inside
  const std::vector<Vec2<T>> cw = {{0, 0}, {0, 1}, {1, 1}, {1, 0}};
  EXPECT_EQ(winding_number(Vec2<T>{T(0.5), T(0.5)}, 4, [&](std::size_t i) { return cw[i]; }), -1);
}

TYPED_TEST(PointInPolygonTest, AllThreeAgreeOnRandomStarPolygons) {
  using T = TypeParam;
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(0, 1);
  int inside = 0, outside = 0;
  for (int trial = 0; trial < 60; ++trial) {
    // star-shaped, strongly non-convex polygon with 5..24 corners
    const int k = 5 + trial % 20;
    std::vector<Vec2<T>> poly(k);
    for (int i = 0; i < k; ++i) {
      const double a = 2 * 3.14159265358979 * (i + 0.3 * u(rng)) / k;
      const double r = 0.2 + u(rng);
      poly[i] = {T(r * std::cos(a)), T(r * std::sin(a))};
    }
    auto c = [&](std::size_t i) { return poly[i]; };
    for (int s = 0; s < 200; ++s) {
      const Vec2<T> p{T(2.4 * u(rng) - 1.2), T(2.4 * u(rng) - 1.2)};
      double dmin = 1e300;
      for (int i = 0; i < k; ++i)
        dmin = std::min(
            dmin,
            segment_distance({double(p.x), double(p.y)}, {double(poly[i].x), double(poly[i].y)},
                             {double(poly[(i + 1) % k].x), double(poly[(i + 1) % k].y)}));
      if (dmin < 1e-4) continue; // the boundary is unspecified
      const bool a = point_in_polygon(p, k, c, InsideTest::crossing_number);
      const bool b = point_in_polygon(p, k, c, InsideTest::winding_number);
      const bool d = point_in_polygon(p, k, c, InsideTest::subtended_angle);
      EXPECT_EQ(a, b) << p;
      EXPECT_EQ(a, d) << p;
      // Independent oracle: the polygon is star-shaped about the origin (increasing angles), so
      // p is inside iff the ray from 0 through p leaves the polygon beyond p.
      const Vec2<double> dir{double(p.x), double(p.y)};
      double exit = 0;
      for (int i = 0; i < k; ++i) {
        const Vec2<double> q0{double(poly[i].x), double(poly[i].y)};
        const Vec2<double> q1{double(poly[(i + 1) % k].x), double(poly[(i + 1) % k].y)};
        const double den = cross(dir, q1 - q0);
        if (den == 0) continue;
        const double t = cross(q0, q1 - q0) / den, sp = cross(q0, dir) / den;
        if (t > 0 && sp >= 0 && sp <= 1) exit = std::max(exit, t);
      }
      EXPECT_EQ(a, exit > 1) << p;
      (a ? inside : outside)++;
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_GT(outside, 1000);
}

// An `InsideTest` value outside the enumeration is a precondition violation: it stops the program
// with a message in every build instead of silently running the crossing test.
TEST(PointInPolygonDeathTest, OutOfRangeMethodIsLoud) {
  const std::vector<Vec2<double>> sq = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  auto c = [&](std::size_t i) { return sq[i]; };
  EXPECT_TRUE(is_valid(InsideTest::subtended_angle));
  EXPECT_FALSE(is_valid(static_cast<InsideTest>(3)));
  EXPECT_DEATH((void)point_in_polygon(Vec2<double>{0.5, 0.5}, 4, c, static_cast<InsideTest>(3)),
               "InsideTest value out of range");
}
