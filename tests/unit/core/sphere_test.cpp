// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/core/bounding_sphere.hpp"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "test_support.hpp"

using namespace ebgeom;

template <class T> class BoundingSphereTest : public ::testing::Test {};
TYPED_TEST_SUITE(BoundingSphereTest, test::FloatTypes);

namespace {
template <class T> void expect_encloses(const BoundingSphere<T>& s, const std::vector<Vec3<T>>& p) {
  ASSERT_FALSE(s.is_empty());
  for (const auto& q : p) {
    EXPECT_TRUE(s.contains(q)) << q << " outside " << s.center << " r=" << s.radius;
    EXPECT_EQ(s.distance(q), T(0));
  }
}
// Independent lower bound on any enclosing radius: half the largest pairwise distance.
template <class T> T half_diameter(const std::vector<Vec3<T>>& p) {
  double best = 0;
  for (const auto& a : p)
    for (const auto& b : p) best = std::max(best, norm(Vec3<double>::from(a - b)));
  return T(best / 2);
}
} // namespace

TYPED_TEST(BoundingSphereTest, RandomSetsAreEnclosedAndNearMinimal) {
  using T = TypeParam;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Aabb<T> box = Aabb<T>::of({-3, -1, 100}, {5, 2, 104});
    const auto pts = test::random_points(box, 10 + 20 * seed, seed);
    const auto s = BoundingSphere<T>::of_points(pts);
    expect_encloses(s, pts);
    // Ritter's sphere is at most ~20% above the minimum in the worst case; the minimal radius is
    // at least half the diameter and at most the box's half diagonal.
    EXPECT_GE(s.radius, half_diameter(pts) * T(0.999));
    EXPECT_LE(s.radius, T(1.2) * norm(Aabb<T>::of_range(pts).extent()) * T(0.5));
  }
}

TYPED_TEST(BoundingSphereTest, DegenerateSets) {
  using T = TypeParam;
  const std::vector<Vec3<T>> one{{1.5, -2, 7}};
  auto s = BoundingSphere<T>::of_points(one);
  expect_encloses(s, one);
  EXPECT_LE(s.radius, T(1e-4));

  std::vector<Vec3<T>> dup(50, Vec3<T>{0.1f, 0.2f, 0.3f});
  s = BoundingSphere<T>::of_points(dup);
  expect_encloses(s, dup);
  EXPECT_LE(s.radius, T(1e-5));

  std::vector<Vec3<T>> line;
  for (int i = 0; i < 101; ++i) line.push_back(Vec3<T>{1, 2, 3} + Vec3<T>{1, -1, 2} * T(i * 0.37));
  std::shuffle(line.begin(), line.end(), std::mt19937(3));
  s = BoundingSphere<T>::of_points(line);
  expect_encloses(s, line);
  EXPECT_NEAR(s.radius, half_diameter(line), half_diameter(line) * T(1e-4));

  // A regular tetrahedron plus duplicates: Ritter's far pair is an edge, growth must add the rest.
  std::vector<Vec3<T>> tet{{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}, {1, 1, 1}};
  s = BoundingSphere<T>::of_points(tet);
  expect_encloses(s, tet);

  EXPECT_TRUE(BoundingSphere<T>::of_points(std::vector<Vec3<T>>{}).is_empty());
}

TYPED_TEST(BoundingSphereTest, MergeEnclosesBothAndBoxes) {
  using T = TypeParam;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-5, 5), ur(0, 3);
  for (int i = 0; i < 200; ++i) {
    const BoundingSphere<T> a{{T(u(rng)), T(u(rng)), T(u(rng))}, T(ur(rng))};
    const BoundingSphere<T> b{{T(u(rng)), T(u(rng)), T(u(rng))}, T(ur(rng))};
    const auto m = merge(a, b);
    // every point on the surfaces of a and b is inside m
    for (int k = 0; k < 20; ++k) {
      const Vec3<T> d = test::random_unit<T>(rng);
      EXPECT_TRUE(m.contains(a.center + d * a.radius))
          << a.center << a.radius << " " << m.center << m.radius;
      EXPECT_TRUE(m.contains(b.center + d * b.radius))
          << b.center << b.radius << " " << m.center << m.radius;
    }
    const T rmax = std::max(a.radius, b.radius);
    const T bound = std::max(T(0.5) * (norm(b.center - a.center) + a.radius + b.radius), rmax);
    EXPECT_LE(m.radius, bound * T(1.0001));
    EXPECT_GE(m.radius, std::max(a.radius, b.radius));
  }
  EXPECT_EQ(merge(BoundingSphere<T>{}, BoundingSphere<T>{{1, 2, 3}, 1}).radius, T(1));

  const Aabb<T> box = Aabb<T>::of({-1, 2, 3}, {4, 5, 3.5});
  const auto sb = BoundingSphere<T>::of(box);
  for (int c = 0; c < 8; ++c)
    EXPECT_TRUE(sb.contains({(c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                             (c & 4) ? box.hi.z : box.lo.z}));
  // many boxes (and an empty one): every corner of every box is enclosed
  std::vector<Aabb<T>> boxes{box, Aabb<T>{}, Aabb<T>::of({5, 5, 5}, {6, 7, 5.5}),
                             Aabb<T>::of({-3, 0, 0})};
  const auto sbs = BoundingSphere<T>::of_boxes(boxes);
  for (const auto& bx : boxes)
    for (int c = 0; c < 8 && !bx.is_empty(); ++c)
      EXPECT_TRUE(sbs.contains(
          {(c & 1) ? bx.hi.x : bx.lo.x, (c & 2) ? bx.hi.y : bx.lo.y, (c & 4) ? bx.hi.z : bx.lo.z}));
  EXPECT_TRUE(BoundingSphere<T>::of_boxes(std::vector<Aabb<T>>{Aabb<T>{}}).is_empty());
  const auto sm = merge(BoundingSphere<T>{{10, 0, 0}, 1}, box);
  EXPECT_TRUE(sm.contains(box.lo));
  EXPECT_TRUE(sm.contains(box.hi));
  EXPECT_TRUE(sm.contains({11, 0, 0}));
}

TYPED_TEST(BoundingSphereTest, DistanceOverlapAndMeasures) {
  using T = TypeParam;
  const BoundingSphere<T> s{{1, 2, 3}, 2};
  EXPECT_NEAR(s.distance({1, 2, 8}), T(3), test::tol<T>());
  EXPECT_NEAR(s.distance2({1, 2, 8}), T(9), test::tol<T>() * 10);
  EXPECT_EQ(s.distance({1.5, 2, 3}), T(0));
  EXPECT_NEAR(s.volume(), T(4.0 / 3.0 * M_PI * 8), test::tol<T>() * 100);
  EXPECT_NEAR(s.surface_area(), T(4.0 * M_PI * 4), test::tol<T>() * 100);
  EXPECT_EQ(s.centroid(), (Vec3<T>{1, 2, 3}));
  EXPECT_TRUE(s.overlaps(BoundingSphere<T>{{5, 2, 3}, 2})); // touching
  EXPECT_FALSE(s.overlaps(BoundingSphere<T>{{5.1, 2, 3}, 2}));
  // Sphere-box: the box corner region. Distance from center to box {x,y,z >= 2.5} corner is
  // |(1.5, 0.5, -)|... reference by sampling the box densely.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-4, 8);
  for (int i = 0; i < 300; ++i) {
    Vec3<T> lo{T(u(rng)), T(u(rng)), T(u(rng))};
    const Aabb<T> b = Aabb<T>::of(lo, lo + Vec3<T>{1, 0.5, 2});
    bool any = false;
    for (int a = 0; a <= 20 && !any; ++a)
      for (int c = 0; c <= 20 && !any; ++c)
        for (int d = 0; d <= 20 && !any; ++d) {
          const Vec3<T> q = b.lo + mul(b.extent(), Vec3<T>{T(a / 20.0), T(c / 20.0), T(d / 20.0)});
          any = norm(q - s.center) <= s.radius;
        }
    if (any) {
      EXPECT_TRUE(s.overlaps(b));
    }
    if (b.distance(s.center) > s.radius + T(0.2)) {
      EXPECT_FALSE(s.overlaps(b));
    }
  }
  EXPECT_TRUE(BoundingSphere<T>{}.is_empty());
  EXPECT_FALSE(BoundingSphere<T>{}.contains({0, 0, 0}));
  EXPECT_EQ(BoundingSphere<T>{}.volume(), T(0));
  EXPECT_TRUE(s.bounds().contains(Aabb<T>::of({-1, 0, 1}, {3, 4, 5})));
}
