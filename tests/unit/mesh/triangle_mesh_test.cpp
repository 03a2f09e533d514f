// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/mesh/triangle_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "ebgeom/mesh/generate.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class TriangleMeshTest : public ::testing::Test {};
TYPED_TEST_SUITE(TriangleMeshTest, test::FloatTypes);

TYPED_TEST(TriangleMeshTest, CubeQuadsAreFannedWithPseudonormals) {
  using T = TypeParam;
  const auto m = make_triangle_mesh(make_cube<T>(1).value()).value();
  ASSERT_EQ(m.triangle_count(), 12u);
  ASSERT_EQ(m.vertex_count(), 8u);
  const T tol = test::tol<T>();
  for (std::size_t t = 0; t < 12; ++t) {
    EXPECT_EQ(m.source_face(t), t / 2);
    const Vec3<T> n = m.face_normals[t];
    EXPECT_NEAR(norm(n), T(1), tol);
    // the face normal is an axis and agrees with the triangle's own winding
    EXPECT_GT(dot(n, cross(m.corner(t, 1) - m.corner(t, 0), m.corner(t, 2) - m.corner(t, 0))), 0);
    EXPECT_NEAR(max_component(abs(n)), T(1), tol);
    for (int k = 0; k < 3; ++k) {
      const Vec3<T> a = m.corner(t, k), b = m.corner(t, (k + 1) % 3);
      const Vec3<T> en = m.edge_normal(t, k);
      EXPECT_NEAR(norm(en), T(1), tol);
      const bool diagonal = norm2(b - a) > T(4.5); // length 2*sqrt(2) vs 2
      if (diagonal) {
        EXPECT_EQ(en, n); // internal diagonal: the polygon normal
      } else {
        // cube edge: normalised sum of two axis normals, e.g. (1, 1, 0)/sqrt(2)
        const Vec3<T> mid = (a + b) * T(0.5);
        EXPECT_NEAR(norm(en - normalized(mid)), T(0), tol);
      }
    }
  }
  for (std::size_t v = 0; v < 8; ++v)
    EXPECT_NEAR(norm(m.vertex_normals[v] - normalized(m.vertices[v])), T(0), tol);
  // quads: source faces stored; a closed manifold: no overflow normals
  EXPECT_EQ(m.source_faces.size(), 12u);
  EXPECT_TRUE(m.edge_overflow.empty());
  EXPECT_EQ(m.memory_bytes(), 8 * 2 * sizeof(Vec3<T>) + 12 * (12 + 4 + 12 + sizeof(Vec3<T>)));
}

TYPED_TEST(TriangleMeshTest, VertexPseudonormalIsAngleWeighted) {
  using T = TypeParam;
  // Vertex 0 of the unit "corner" tetrahedron: three right angles with axis normals -x,-y,-z,
  // and the slanted face does not touch it. Vertex 1 = (1,0,0) has angles pi/2 (z = 0 face),
  // pi/4 (y = 0 face), pi/3 (slanted face).
  PolygonSoup<T> s;
  s.add_vertex({0, 0, 0});
  s.add_vertex({1, 0, 0});
  s.add_vertex({0, 1, 0});
  s.add_vertex({0, 0, 1});
  s.add_triangle(0, 2, 1); // z = 0, normal -z
  s.add_triangle(0, 1, 3); // y = 0, normal -y
  s.add_triangle(0, 3, 2); // x = 0, normal -x
  s.add_triangle(1, 2, 3); // slanted, normal (1,1,1)/sqrt 3
  const auto m = make_triangle_mesh(s).value();
  EXPECT_NEAR(norm(m.vertex_normals[0] - normalized(Vec3<T>{-1, -1, -1})), T(0), test::tol<T>());
  const double pi = 3.14159265358979323846;
  const Vec3<double> expect =
      normalized(Vec3<double>{0, 0, -1} * (pi / 4) + Vec3<double>{0, -1, 0} * (pi / 4) +
                 normalized(Vec3<double>{1, 1, 1}) * (pi / 3));
  // angle at (1,0,0) in the z = 0 face (0,2,1): between (0,0,0) and (0,1,0): pi/4; same in y = 0.
  EXPECT_NEAR(norm(Vec3<double>::from(m.vertex_normals[1]) - expect), 0.0, 1e-5);
}

TYPED_TEST(TriangleMeshTest, BadSoupsAreErrorsNotCrashes) {
  using T = TypeParam;
  auto code = [](const PolygonSoup<T>& s) {
    const auto r = make_triangle_mesh(s);
    return r ? ErrorCode::ok : r.error().code;
  };
  PolygonSoup<T> empty;
  EXPECT_EQ(code(empty), ErrorCode::empty);
  PolygonSoup<T> s = make_tetrahedron<T>(1).value();
  EXPECT_EQ(code(s), ErrorCode::ok);
  PolygonSoup<T> bad = s;
  bad.indices[4] = 99;
  EXPECT_EQ(code(bad), ErrorCode::bad_index);
  bad = s;
  bad.vertices[2].y = std::numeric_limits<T>::quiet_NaN();
  EXPECT_EQ(code(bad), ErrorCode::non_finite);
  bad = s;
  bad.vertices[1].x = std::numeric_limits<T>::infinity();
  EXPECT_EQ(code(bad), ErrorCode::non_finite);
  bad = s;
  bad.add_face({0, 1});
  EXPECT_EQ(code(bad), ErrorCode::degenerate);
  bad = s;
  bad.offsets.back() = 100; // points past the index array
  EXPECT_EQ(code(bad), ErrorCode::size_mismatch);
  bad = s;
  bad.offsets = {};
  EXPECT_EQ(code(bad), ErrorCode::size_mismatch);
  bad = s;
  std::swap(bad.offsets[1], bad.offsets[2]);
  EXPECT_NE(code(bad), ErrorCode::ok);
}

TYPED_TEST(TriangleMeshTest, GeneratedMeshesAreClosedAndOutward) {
  using T = TypeParam;
  // Outward orientation: the divergence theorem gives a positive volume.
  auto volume = [](const TriangleMesh<T>& m) {
    double v = 0;
    for (std::size_t t = 0; t < m.triangle_count(); ++t)
      v += dot(Vec3<double>::from(m.corner(t, 0)),
               cross(Vec3<double>::from(m.corner(t, 1)), Vec3<double>::from(m.corner(t, 2)))) /
           6;
    return v;
  };
  const double pi = 3.14159265358979323846;
  EXPECT_NEAR(volume(make_triangle_mesh(make_cube<T>(1).value()).value()), 8.0, 1e-5);
  EXPECT_NEAR(volume(make_triangle_mesh(make_octahedron<T>(1).value()).value()), 4.0 / 3, 1e-5);
  EXPECT_NEAR(volume(make_triangle_mesh(make_tetrahedron<T>(std::sqrt(T(3))).value()).value()),
              8.0 / 3, 1e-5); // cube of side 2 minus four corners: 8 - 4 * 4/3
  const auto ico = make_triangle_mesh(make_icosphere<T>(4).value()).value();
  EXPECT_EQ(ico.triangle_count(), 20u * 256);
  EXPECT_EQ(ico.vertex_count(), 10u * 256 + 2);
  EXPECT_NEAR(volume(ico), 4 * pi / 3, 0.01);
  const auto torus = make_triangle_mesh(make_torus<T>(2, T(0.5), 128, 64).value()).value();
  EXPECT_NEAR(volume(torus), 2 * pi * pi * 2 * 0.25, 0.02);
  EXPECT_FALSE(make_icosphere<T>(-1).has_value());
  EXPECT_FALSE(make_icosphere<T>(11).has_value());
  EXPECT_FALSE(make_torus<T>(1, 2).has_value());
  EXPECT_FALSE(make_cube<T>(0).has_value());
}
