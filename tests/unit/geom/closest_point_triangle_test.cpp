// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/geom/closest_point_triangle.hpp"

#include <gtest/gtest.h>

#include <random>

#include "test_support.hpp"

using namespace ebgeom;

namespace {

/// Independent reference in double: project onto the plane, solve for barycentric coordinates by
/// Cramer's rule; inside -> the projection, otherwise the nearest of the three clamped segments.
struct Ref {
  Vec3<double> point;
  double d2;
  bool inside;
};

Vec3<double> ref_segment(const Vec3<double>& p, const Vec3<double>& a, const Vec3<double>& b) {
  const Vec3<double> e = b - a;
  const double ee = dot(e, e);
  if (ee == 0) return a;
  return a + e * clamp(dot(p - a, e) / ee, 0.0, 1.0);
}

Ref reference(const Vec3<double>& p, const Vec3<double>& a, const Vec3<double>& b,
              const Vec3<double>& c) {
  const Vec3<double> e0 = b - a, e1 = c - a, r = p - a;
  const double a00 = dot(e0, e0), a01 = dot(e0, e1), a11 = dot(e1, e1);
  const double b0 = dot(r, e0), b1 = dot(r, e1);
  const double det = a00 * a11 - a01 * a01;
  if (det > 1e-14 * a00 * a11) {
    const double s = (a11 * b0 - a01 * b1) / det, t = (a00 * b1 - a01 * b0) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) {
      const Vec3<double> q = a + e0 * s + e1 * t;
      return {q, norm2(p - q), true};
    }
  }
  Ref best{a, 1e300, false};
  for (const auto& q : {ref_segment(p, a, b), ref_segment(p, b, c), ref_segment(p, c, a)})
    if (norm2(p - q) < best.d2) best = {q, norm2(p - q), false};
  return best;
}

} // namespace

template <class T> class ClosestPointTriangleTest : public ::testing::Test {};
TYPED_TEST_SUITE(ClosestPointTriangleTest, test::FloatTypes);

TYPED_TEST(ClosestPointTriangleTest, FeaturesOfTheUnitRightTriangle) {
  using T = TypeParam;
  const Vec3<T> a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  struct Case {
    Vec3<T> p;
    TriangleFeature f;
    Vec3<T> q;
  };
  const Case cases[] = {
      {{T(0.2), T(0.2), T(1)}, TriangleFeature::face, {T(0.2), T(0.2), 0}},
      {{T(0.2), T(0.2), T(-2)}, TriangleFeature::face, {T(0.2), T(0.2), 0}},
      {{T(0.5), T(-1), T(0.5)}, TriangleFeature::edge0, {T(0.5), 0, 0}},
      {{T(1), T(1), T(0)}, TriangleFeature::edge1, {T(0.5), T(0.5), 0}},
      {{T(-1), T(0.25), T(3)}, TriangleFeature::edge2, {0, T(0.25), 0}},
      {{T(-1), T(-1), T(1)}, TriangleFeature::vertex0, {0, 0, 0}},
      {{T(2), T(-0.1), T(0)}, TriangleFeature::vertex1, {1, 0, 0}},
      {{T(-0.1), T(2), T(-1)}, TriangleFeature::vertex2, {0, 1, 0}},
  };
  for (const Case& k : cases) {
    const auto r = closest_point_triangle(k.p, a, b, c);
    EXPECT_EQ(r.feature, k.f) << k.p << " got " << to_string(r.feature);
    EXPECT_NEAR(norm(r.point - k.q), 0, test::tol<T>()) << k.p;
    EXPECT_NEAR(r.distance2, norm2(k.p - k.q), test::tol<T>()) << k.p;
  }
}

TYPED_TEST(ClosestPointTriangleTest, MatchesBarycentricReferenceOnRandomTriangles) {
  using T = TypeParam;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int faces = 0, edges = 0, vertices = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const Vec3<T> a{T(u(rng)), T(u(rng)), T(u(rng))}, b{T(u(rng)), T(u(rng)), T(u(rng))},
        c{T(u(rng)), T(u(rng)), T(u(rng))};
    for (const auto& p : test::random_points(Aabb<T>::of({-2, -2, -2}, {2, 2, 2}), 30, trial)) {
      const auto r = closest_point_triangle(p, a, b, c);
      const Ref ref = reference(Vec3<double>::from(p), Vec3<double>::from(a), Vec3<double>::from(b),
                                Vec3<double>::from(c));
      const double scale = 1 + ref.d2;
      EXPECT_NEAR(double(r.distance2), ref.d2, 50 * double(test::tol<T>()) * scale);
      EXPECT_NEAR(norm(Vec3<double>::from(r.point) - ref.point), 0, sizeof(T) == 4 ? 2e-3 : 1e-8);
      // the reported point really is on the reported feature
      const Vec3<T> v[3] = {a, b, c};
      if (is_vertex(r.feature)) {
        EXPECT_EQ(r.point, v[vertex_index(r.feature)]);
        ++vertices;
      } else if (is_edge(r.feature)) {
        const int k = edge_index(r.feature);
        const Vec3<double> q = ref_segment(Vec3<double>::from(r.point), Vec3<double>::from(v[k]),
                                           Vec3<double>::from(v[(k + 1) % 3]));
        EXPECT_NEAR(norm(q - Vec3<double>::from(r.point)), 0, sizeof(T) == 4 ? 1e-5 : 1e-12);
        ++edges;
      } else {
        EXPECT_TRUE(ref.inside || ref.d2 < 1e-6);
        ++faces;
      }
    }
  }
  // every region was exercised
  EXPECT_GT(faces, 100);
  EXPECT_GT(edges, 100);
  EXPECT_GT(vertices, 100);
}

TYPED_TEST(ClosestPointTriangleTest, AgreesWithDenseSampling) {
  using T = TypeParam;
  const Vec3<T> a{T(0.1), T(-0.3), T(0.2)}, b{T(1.2), T(0.1), T(-0.4)}, c{T(-0.2), T(0.9), T(0.5)};
  const int n = 200;
  const double h = norm(Vec3<double>::from(b - a)) + norm(Vec3<double>::from(c - a));
  for (const auto& p : test::random_points(Aabb<T>::of({-2, -2, -2}, {2, 2, 2}), 40, 3)) {
    double best = 1e300;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; i + j <= n; ++j) {
        const double s = double(i) / n, t = double(j) / n;
        const Vec3<double> q =
            Vec3<double>::from(a) + Vec3<double>::from(b - a) * s + Vec3<double>::from(c - a) * t;
        best = std::min(best, norm(Vec3<double>::from(p) - q));
      }
    const double d = std::sqrt(double(closest_point_triangle(p, a, b, c).distance2));
    EXPECT_LE(d, best + 1e-5);         // never farther than any sample
    EXPECT_GE(d, best - h / n - 1e-5); // samples are at most h/n from every surface point
  }
}

TYPED_TEST(ClosestPointTriangleTest, DegenerateTrianglesAreFinite) {
  using T = TypeParam;
  const Vec3<T> a{0, 0, 0}, b{1, 0, 0}, c{2, 0, 0}; // collinear
  for (const auto& p : test::random_points(Aabb<T>::of({-2, -2, -2}, {3, 2, 2}), 200, 9)) {
    const auto r = closest_point_triangle(p, a, b, c);
    ASSERT_TRUE(all_finite(r.point));
    const Vec3<double> q =
        ref_segment(Vec3<double>::from(p), Vec3<double>::from(a), Vec3<double>::from(c));
    EXPECT_NEAR(double(r.distance2), norm2(Vec3<double>::from(p) - q), 10 * test::tol<T>());
    EXPECT_NE(r.feature, TriangleFeature::face);
    // repeated vertex and a single point
    const auto r2 = closest_point_triangle(p, a, a, b);
    EXPECT_NEAR(
        double(r2.distance2),
        norm2(Vec3<double>::from(p) -
              ref_segment(Vec3<double>::from(p), Vec3<double>::from(a), Vec3<double>::from(b))),
        10 * test::tol<T>());
    const auto r3 = closest_point_triangle(p, b, b, b);
    EXPECT_EQ(r3.point, b);
    EXPECT_TRUE(is_vertex(r3.feature));
  }
}

TYPED_TEST(ClosestPointTriangleTest, SignFollowsTheFeatureNormal) {
  using T = TypeParam;
  const Vec3<T> a{0, 0, 0}, b{1, 0, 0}, c{0, 1, 0};
  const Vec3<T> fn{0, 0, 1};
  // Deliberately different normals per feature, so the test sees which one was used.
  const Vec3<T> en[3] = {{0, -1, 0}, {1, 1, 0}, {-1, 0, 0}};
  const Vec3<T> vn[3] = {{0, 0, -1}, {0, 0, -1}, {0, 0, 1}};
  auto sd = [&](const Vec3<T>& p) { return signed_distance_triangle(p, a, b, c, fn, en, vn); };
  EXPECT_NEAR(sd({T(0.2), T(0.2), T(2)}).distance, T(2), test::tol<T>());
  EXPECT_NEAR(sd({T(0.2), T(0.2), T(-2)}).distance, T(-2), test::tol<T>());
  EXPECT_NEAR(sd({T(0.5), T(-1), T(0)}).distance, T(1), test::tol<T>()); // along en[0]
  EXPECT_NEAR(sd({T(-1), T(0.5), T(0)}).distance, T(1), test::tol<T>()); // along en[2]
  // vertex0 with normal -z: a point above it (outside the face region) is "inside"
  const auto v0 = sd({T(-1), T(-1), T(1)});
  EXPECT_EQ(v0.feature, TriangleFeature::vertex0);
  EXPECT_NEAR(v0.distance, -std::sqrt(T(3)), test::tol<T>()); // magnitude is |p - v|
  const auto v2 = sd({T(-0.1), T(2), T(-1)});
  EXPECT_EQ(v2.feature, TriangleFeature::vertex2);
  EXPECT_LT(v2.distance, T(0));
  // on the surface: zero
  EXPECT_EQ(sd({T(0.25), T(0.25), T(0)}).distance, T(0));
}
