// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

#include <gtest/gtest.h>

#include "../mesh/mesh_reference.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class BruteForceMeshSdfTest : public ::testing::Test {};
TYPED_TEST_SUITE(BruteForceMeshSdfTest, test::FloatTypes);

namespace {
template <class T> double tolerance(double d) {
  return (sizeof(T) == 4 ? 2e-5 : 1e-12) * (4 + std::abs(d));
}
template <class T> Vec3<double> dbl(const Vec3<T>& p) { return Vec3<double>::from(p); }
} // namespace

TYPED_TEST(BruteForceMeshSdfTest, SatisfiesTheSdfContract) {
  using S = BruteForceMeshSdf<TypeParam>;
  static_assert(is_sdf_v<S>);
  static_assert(S::kind == SdfKind::exact);
  const S sdf = S::build(make_cube<TypeParam>(1).value()).value();
  EXPECT_EQ(sdf.bounds(), Aabb<TypeParam>::of({-1, -1, -1}, {1, 1, 1}));
}

TYPED_TEST(BruteForceMeshSdfTest, CubeEqualsClosedForm) {
  using T = TypeParam;
  const auto sdf = BruteForceMeshSdf<T>::build(make_cube<T>(T(0.75)).value()).value();
  const Vec3<double> h = Vec3<double>::constant(0.75);
  for (const auto& p : test::random_points(Aabb<T>::of({-2, -2, -2}, {2, 2, 2}), 3000)) {
    const double ref = test::box_sdf(dbl(p), Vec3<double>::zero(), h);
    EXPECT_NEAR(double(sdf(p)), ref, tolerance<T>(ref)) << p;
  }
}

TYPED_TEST(BruteForceMeshSdfTest, CubeEdgeVertexAndSurfacePoints) {
  using T = TypeParam;
  const auto sdf = BruteForceMeshSdf<T>::build(make_cube<T>(T(1)).value()).value();
  // Beyond a corner along the diagonal: closest feature is a vertex, distance |p - v|.
  for (T s : {T(0.01), T(0.5), T(3)}) {
    const Vec3<T> p = Vec3<T>::constant(1 + s);
    const auto c = sdf.closest(p);
    EXPECT_TRUE(is_vertex(c.feature)) << to_string(c.feature);
    EXPECT_NEAR(double(c.distance), std::sqrt(3.0) * double(s), tolerance<T>(3 * s));
    // beyond an edge (x = y = 1, z = 0.3)
    const Vec3<T> q{1 + s, 1 + s, T(0.3)};
    const auto e = sdf.closest(q);
    EXPECT_TRUE(is_edge(e.feature)) << to_string(e.feature);
    EXPECT_NEAR(double(e.distance), std::sqrt(2.0) * double(s), tolerance<T>(3 * s));
    EXPECT_NEAR(double(norm(e.point - Vec3<T>{1, 1, T(0.3)})), 0, tolerance<T>(1));
  }
  // Inside, near a corner: the closest faces tie; distance is to the nearest face.
  EXPECT_NEAR(double(sdf({T(0.9), T(0.95), T(0.97)})), -0.03, tolerance<T>(1));
  // Surface points: vertices, edge midpoints, face centres give 0.
  for (const Vec3<T>& p :
       {Vec3<T>{1, 1, 1}, Vec3<T>{1, -1, 0}, Vec3<T>{0, 0, -1}, Vec3<T>{T(0.3), 1, T(-0.2)}})
    EXPECT_NEAR(double(sdf(p)), 0.0, tolerance<T>(1)) << p;
}

TYPED_TEST(BruteForceMeshSdfTest, OctahedronEqualsClosedForm) {
  using T = TypeParam;
  const auto sdf = BruteForceMeshSdf<T>::build(make_octahedron<T>(T(1.3)).value()).value();
  for (const auto& p : test::random_points(Aabb<T>::of({-3, -3, -3}, {3, 3, 3}), 3000, 5)) {
    const double ref = test::octahedron_sdf(dbl(p), 1.3);
    EXPECT_NEAR(double(sdf(p)), ref, tolerance<T>(ref)) << p;
  }
  // Vertex and edge regions explicitly.
  const auto v = sdf.closest({T(2), T(0.1), T(-0.1)});
  EXPECT_TRUE(is_vertex(v.feature));
  EXPECT_NEAR(double(v.distance), test::octahedron_sdf({2, 0.1, -0.1}, 1.3), tolerance<T>(1));
  const auto e = sdf.closest({T(1), T(1), T(0)});
  EXPECT_TRUE(is_edge(e.feature));
  EXPECT_NEAR(double(e.distance), test::octahedron_sdf({1, 1, 0}, 1.3), tolerance<T>(1));
}

TYPED_TEST(BruteForceMeshSdfTest, TetrahedronClosedFormCases) {
  using T = TypeParam;
  const double r = 2.0;
  const auto soup = make_tetrahedron<T>(T(r)).value();
  const auto sdf = BruteForceMeshSdf<T>::build(soup).value();
  // The centre is at the inradius r/3 from every face.
  EXPECT_NEAR(double(sdf({0, 0, 0})), -r / 3, tolerance<T>(1));
  const Vec3<double> v0 = Vec3<double>::constant(r / std::sqrt(3.0));
  const Vec3<double> v1 = Vec3<double>{1, -1, -1} * (r / std::sqrt(3.0));
  for (double s : {1e-3, 0.2, 1.0, 4.0}) {
    // Beyond vertex 0, radially: closest feature vertex, distance s.
    const Vec3<double> pv = v0 + normalized(v0) * s;
    const auto cv = sdf.closest(Vec3<T>::from(pv));
    EXPECT_TRUE(is_vertex(cv.feature));
    EXPECT_NEAR(double(cv.distance), s, tolerance<T>(s));
    // Beyond the midpoint of edge (v0, v1), radially: the edge direction's normal cone.
    const Vec3<double> m = (v0 + v1) * 0.5;
    const auto ce = sdf.closest(Vec3<T>::from(m + normalized(m) * s));
    EXPECT_TRUE(is_edge(ce.feature));
    EXPECT_NEAR(double(ce.distance), s, tolerance<T>(s));
  }
  // Along a face normal through its centroid, both sides.
  const Vec3<double> fc = Vec3<double>{-1, -1, -1} * (r / 3 / std::sqrt(3.0)); // face (1, 3, 2)
  const Vec3<double> n = normalized(fc);
  for (double s : {-0.5, -0.1, 0.0, 0.1, 1.0}) {
    const auto c = sdf.closest(Vec3<T>::from(fc + n * s));
    EXPECT_NEAR(double(c.distance), s, tolerance<T>(s));
  }
  // Random points against the scanning + winding-number oracle.
  for (const auto& p : test::random_points(Aabb<T>::of({-3, -3, -3}, {3, 3, 3}), 2000, 11)) {
    const double ref = test::ref_signed_distance(soup, dbl(p));
    EXPECT_NEAR(double(sdf(p)), ref, tolerance<T>(ref)) << p;
  }
}

TYPED_TEST(BruteForceMeshSdfTest, NonConvexPrismSignAtReflexEdge) {
  using T = TypeParam;
  const auto soup = test::l_prism<T>();
  const auto sdf = BruteForceMeshSdf<T>::build(soup).value();
  // Inside, near the reflex edge x = y = 1: the closest feature is that edge, sign negative.
  for (double s : {0.01, 0.1, 0.3}) {
    const Vec3<T> p{T(1 - s), T(1 - s), T(0.5)};
    const auto c = sdf.closest(p);
    EXPECT_TRUE(is_edge(c.feature)) << to_string(c.feature);
    EXPECT_NEAR(double(c.distance), -std::sqrt(2.0) * s, tolerance<T>(1));
    // and at the reflex vertex (1, 1, 0), from inside below... the corner region
    const Vec3<T> q{T(1 - s), T(1 - s), T(0.5 * s)};
    EXPECT_LT(sdf(q), T(0));
  }
  // Reflex vertex (1,1,1) from inside: point just below the top, in the notch's bisector.
  const auto cv = sdf.closest({T(0.95), T(0.95), T(1.0 - 0.2)});
  EXPECT_LT(cv.distance, T(0));
  for (const auto& p : test::random_points(Aabb<T>::of({-1, -1, -1}, {3, 3, 2}), 2000, 13)) {
    const double ref = test::ref_signed_distance(soup, dbl(p));
    EXPECT_NEAR(double(sdf(p)), ref, tolerance<T>(ref)) << p;
  }
}

TYPED_TEST(BruteForceMeshSdfTest, IcosphereTracksTheSphere) {
  using T = TypeParam;
  const double r = 1.5;
  const auto soup = make_icosphere<T>(3, T(r)).value();
  const auto sdf = BruteForceMeshSdf<T>::build(soup).value();
  // Tessellation error: every vertex is on the sphere, so |mesh SDF - sphere SDF| is at most
  // r - (smallest distance from the centre to a face plane), the largest sagitta.
  double min_plane = r;
  const auto& m = sdf.mesh();
  for (std::size_t t = 0; t < m.triangle_count(); ++t)
    min_plane = std::min(min_plane, std::abs(dot(dbl(m.face_normals[t]), dbl(m.corner(t, 0)))));
  const double err = r - min_plane;
  EXPECT_LT(err, 0.02); // a fine mesh
  for (const auto& p : test::random_points(Aabb<T>::of({-3, -3, -3}, {3, 3, 3}), 400, 17)) {
    const double ref = norm(dbl(p)) - r;
    EXPECT_NEAR(double(sdf(p)), ref, err + tolerance<T>(ref)) << p;
  }
}

TYPED_TEST(BruteForceMeshSdfTest, EmptyMeshIsInfinite) {
  using T = TypeParam;
  const BruteForceMeshSdf<T> sdf{TriangleMesh<T>{}};
  EXPECT_EQ(sdf({0, 0, 0}), std::numeric_limits<T>::infinity());
  EXPECT_EQ(sdf.closest({0, 0, 0}).triangle, MeshClosestPoint<T>::invalid_triangle);
}
