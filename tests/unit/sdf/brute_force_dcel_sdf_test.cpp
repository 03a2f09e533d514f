// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/brute_force_dcel_sdf.hpp"

#include <gtest/gtest.h>

#include "../mesh/mesh_reference.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class BruteForceDcelSdfTest : public ::testing::Test {};
TYPED_TEST_SUITE(BruteForceDcelSdfTest, test::FloatTypes);

namespace {
template <class T> double tolerance(double d) {
  return (sizeof(T) == 4 ? 2e-5 : 1e-12) * (4 + std::abs(d));
}
template <class T> Vec3<double> dbl(const Vec3<T>& p) { return Vec3<double>::from(p); }
constexpr InsideTest all_tests[] = {InsideTest::crossing_number, InsideTest::winding_number,
                                    InsideTest::subtended_angle};
} // namespace

TYPED_TEST(BruteForceDcelSdfTest, SatisfiesTheSdfContract) {
  using T = TypeParam;
  using S = BruteForceDcelSdf<T>;
  static_assert(is_sdf_v<S>);
  static_assert(S::kind == SdfKind::exact);
  // and at run time: the contract's members give the cube's box and distances
  const S sdf = S::build(make_cube<T>(1).value()).value();
  EXPECT_EQ(sdf.bounds(), Aabb<T>::of({-1, -1, -1}, {1, 1, 1}));
  EXPECT_EQ(sdf(Vec3<T>::zero()), T(-1));
  EXPECT_EQ(sdf(Vec3<T>{3, 0, 0}), T(2));
}

TYPED_TEST(BruteForceDcelSdfTest, CubeOfQuadsEqualsClosedFormWithEveryInsideTest) {
  using T = TypeParam;
  const auto soup = make_cube<T>(T(0.75)).value();
  for (InsideTest it : all_tests) {
    const auto sdf = BruteForceDcelSdf<T>::build(soup, it).value();
    for (const auto& p : test::random_points(Aabb<T>::of({-2, -2, -2}, {2, 2, 2}), 1500)) {
      const double ref = test::box_sdf(dbl(p), Vec3<double>::zero(), Vec3<double>::constant(0.75));
      EXPECT_NEAR(double(sdf(p)), ref, tolerance<T>(ref)) << p;
    }
  }
}

TYPED_TEST(BruteForceDcelSdfTest, FeaturesAndIndices) {
  using T = TypeParam;
  const auto soup = make_cube<T>(1).value();
  const auto sdf = BruteForceDcelSdf<T>::build(soup).value();
  const auto& m = sdf.mesh();
  // vertex case: beyond corner (1,1,1) = vertex 7
  const auto v = sdf.closest({2, 2, 2});
  EXPECT_EQ(v.feature, DcelFeature::vertex);
  EXPECT_EQ(v.index, 7u);
  EXPECT_NEAR(double(v.distance), std::sqrt(3.0), tolerance<T>(1));
  // edge case: beyond edge x = y = 1
  const auto e = sdf.closest({2, 2, T(0.25)});
  EXPECT_EQ(e.feature, DcelFeature::edge);
  const Index a = m.half_edge(e.index).origin, b = m.target(e.index);
  EXPECT_EQ(std::min(a, b), 3u); // (hi, hi, lo)
  EXPECT_EQ(std::max(a, b), 7u); // (hi, hi, hi)
  EXPECT_NEAR(double(e.distance), std::sqrt(2.0), tolerance<T>(1));
  EXPECT_NEAR(double(norm(e.point - Vec3<T>{1, 1, T(0.25)})), 0, tolerance<T>(1));
  // face case, both sides
  const auto f = sdf.closest({T(0.2), T(-0.1), T(3)});
  EXPECT_EQ(f.feature, DcelFeature::face);
  EXPECT_EQ(f.index, 5u); // +z
  EXPECT_NEAR(double(f.distance), 2.0, tolerance<T>(2));
  EXPECT_NEAR(double(sdf({T(0.2), T(-0.1), T(0.7)})), -0.3, tolerance<T>(1));
  // surface points
  EXPECT_NEAR(double(sdf({1, T(0.3), T(0.3)})), 0.0, tolerance<T>(1));
  EXPECT_NEAR(double(sdf({1, 1, 1})), 0.0, tolerance<T>(1));
}

TYPED_TEST(BruteForceDcelSdfTest, NonConvexPolygonsMatchOracleWithEveryInsideTest) {
  using T = TypeParam;
  const auto soup = test::l_prism<T>();
  for (InsideTest it : all_tests) {
    const auto sdf = BruteForceDcelSdf<T>::build(soup, it).value();
    // above the notch: the projection falls outside the L-shaped top face; the closest points
    // are on the top edges of the notch walls, e.g. (1, 1.5, 1)
    const auto c = sdf.closest({T(1.5), T(1.5), T(1.5)});
    EXPECT_EQ(c.feature, DcelFeature::edge);
    EXPECT_NEAR(double(c.distance), std::sqrt(0.5), tolerance<T>(1));
    // beyond the convex corner (0, 0, 0): vertex 0
    const auto v = sdf.closest({T(-1), T(-1), T(-1)});
    EXPECT_EQ(v.feature, DcelFeature::vertex);
    EXPECT_EQ(v.index, 0u);
    EXPECT_NEAR(double(v.distance), std::sqrt(3.0), tolerance<T>(1));
    // inside, near the reflex edge x = y = 1: edge feature, negative (concave pseudonormal)
    const auto e = sdf.closest({T(0.9), T(0.9), T(0.5)});
    EXPECT_EQ(e.feature, DcelFeature::edge);
    EXPECT_NEAR(double(e.distance), -std::sqrt(0.02), tolerance<T>(1));
    for (const auto& p : test::random_points(Aabb<T>::of({-1, -1, -1}, {3, 3, 2}), 1500, 31)) {
      const double ref = test::ref_signed_distance(soup, dbl(p));
      EXPECT_NEAR(double(sdf(p)), ref, tolerance<T>(ref)) << p;
    }
  }
}

TYPED_TEST(BruteForceDcelSdfTest, OctahedronAndTetrahedronEqualClosedForms) {
  using T = TypeParam;
  const auto oct = BruteForceDcelSdf<T>::build(make_octahedron<T>(1).value()).value();
  const auto tet_soup = make_tetrahedron<T>(1).value();
  const auto tet = BruteForceDcelSdf<T>::build(tet_soup).value();
  for (const auto& p : test::random_points(Aabb<T>::of({-2, -2, -2}, {2, 2, 2}), 1500, 41)) {
    const double r1 = test::octahedron_sdf(dbl(p), 1);
    EXPECT_NEAR(double(oct(p)), r1, tolerance<T>(r1)) << p;
    const double r2 = test::ref_signed_distance(tet_soup, dbl(p));
    EXPECT_NEAR(double(tet(p)), r2, tolerance<T>(r2)) << p;
  }
  EXPECT_NEAR(double(tet({0, 0, 0})), -1.0 / 3, tolerance<T>(1));
}

TYPED_TEST(BruteForceDcelSdfTest, DcelAndTriangleMeshAgree) {
  using T = TypeParam;
  const std::vector<PolygonSoup<T>> soups = {make_icosphere<T>(2, T(1.2)).value(),
                                             make_torus<T>(T(1.5), T(0.5), 24, 12).value(),
                                             test::l_prism<T>(), make_cube<T>(1).value()};
  for (const auto& soup : soups) {
    const auto dcel = BruteForceDcelSdf<T>::build(soup).value();
    const auto tri = BruteForceMeshSdf<T>::build(soup).value();
    for (const auto& p : test::random_points(soup.bounds().grown(1), 500, 43)) {
      const T a = dcel(p), b = tri(p);
      EXPECT_NEAR(double(a), double(b), tolerance<T>(a)) << p;
    }
    // surface points: vertices
    for (const auto& v : soup.vertices) EXPECT_NEAR(double(dcel(v)), 0.0, tolerance<T>(1));
  }
}

TYPED_TEST(BruteForceDcelSdfTest, TorusTracksTheAnalyticTorus) {
  using T = TypeParam;
  const double R = 2, r = 0.5;
  const int nu = 96, nv = 48;
  const auto sdf = BruteForceDcelSdf<T>::build(make_torus<T>(T(R), T(r), nu, nv).value()).value();
  // Every vertex is on the torus; chord sagittas bound the deviation of the polygons from it.
  const double pi = 3.14159265358979323846;
  const double err = (R + r) * (1 - std::cos(pi / nu)) + r * (1 - std::cos(pi / nv)) + 1e-3;
  for (const auto& p : test::random_points(Aabb<T>::of({-3, -3, -1}, {3, 3, 1}), 300, 47)) {
    const Vec3<double> q = dbl(p);
    const double ref = std::hypot(std::hypot(q.x, q.y) - R, q.z) - r;
    EXPECT_NEAR(double(sdf(p)), ref, err + tolerance<T>(ref)) << p;
  }
}

TYPED_TEST(BruteForceDcelSdfTest, NonStarPolygonIsEarClippedInTheTriangleMesh) {
  using T = TypeParam;
  // The L prism with its bottom face starting at (0, 2): the fan from there leaves the L, so the
  // triangle mesh must ear-clip it to agree with the DCEL (which tests the polygon directly).
  auto soup = test::l_prism<T>();
  const auto reference = soup;
  const std::vector<Index> bottom = {5, 4, 3, 2, 1, 0};
  std::copy(bottom.begin(), bottom.end(), soup.indices.begin());
  const auto tri = BruteForceMeshSdf<T>::build(soup).value();
  const auto& m = tri.mesh();
  double bottom_area = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    const Vec3<T> c = cross(m.corner(t, 1) - m.corner(t, 0), m.corner(t, 2) - m.corner(t, 0));
    EXPECT_GE(dot(c, m.face_normals[t]), T(0)); // every triangle keeps the polygon's orientation
    if (m.source_face(t) == 0) bottom_area += double(norm(c)) / 2;
  }
  EXPECT_NEAR(bottom_area, 3.0, 1e-5);
  const auto dcel = BruteForceDcelSdf<T>::build(soup).value();
  for (const auto& p : test::random_points(Aabb<T>::of({-1, -1, -1}, {3, 3, 2}), 1500, 53)) {
    const double ref = test::ref_signed_distance(reference, dbl(p));
    EXPECT_NEAR(double(tri(p)), ref, tolerance<T>(ref)) << p;
    EXPECT_NEAR(double(dcel(p)), ref, tolerance<T>(ref)) << p;
  }
}
