// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/mesh/half_edge_mesh.hpp"

#include <gtest/gtest.h>

#include <set>

#include "ebgeom/mesh/generate.hpp"
#include "mesh_reference.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class HalfEdgeMeshTest : public ::testing::Test {};
TYPED_TEST_SUITE(HalfEdgeMeshTest, test::FloatTypes);

namespace {
template <class T> void expect_consistent_links(const HalfEdgeMesh<T>& m) {
  for (Index h = 0; h < m.half_edge_count(); ++h) {
    const HalfEdge& e = m.half_edge(h);
    EXPECT_EQ(m.half_edge(e.next).prev, h);
    EXPECT_EQ(m.half_edge(e.prev).next, h);
    EXPECT_EQ(m.half_edge(e.next).face, e.face);
    if (e.pair != invalid_index) {
      EXPECT_EQ(m.half_edge(e.pair).pair, h);
      EXPECT_EQ(m.half_edge(e.pair).origin, m.target(h));
      EXPECT_NE(m.half_edge(e.pair).face, e.face);
    }
  }
}
} // namespace

TYPED_TEST(HalfEdgeMeshTest, CubeTopologyAndFaceData) {
  using T = TypeParam;
  const auto soup = make_cube<T>(1).value();
  const auto m = make_half_edge_mesh(soup).value();
  EXPECT_EQ(m.vertex_count(), 8u);
  EXPECT_EQ(m.face_count(), 6u);
  EXPECT_EQ(m.half_edge_count(), 24u);
  EXPECT_TRUE(m.is_closed_manifold());
  expect_consistent_links(m);
  for (Index f = 0; f < 6; ++f) {
    const auto& face = m.face(f);
    EXPECT_EQ(face.size, 4u);
    EXPECT_NEAR(face.area, T(4), test::tol<T>());
    EXPECT_NEAR(max_component(abs(face.normal)), T(1), test::tol<T>());
    // centroid is the face centre, along the normal at distance 1
    EXPECT_NEAR(norm(face.centroid - face.normal), T(0), test::tol<T>());
    std::vector<Index> vs;
    m.for_each_vertex(f, [&](Index v) { vs.push_back(v); });
    EXPECT_EQ(vs, (std::vector<Index>(soup.face(f).begin(), soup.face(f).end())));
  }
  for (Index v = 0; v < 8; ++v) {
    std::set<Index> faces;
    int n = 0;
    m.for_each_outgoing(v, [&](Index h) {
      EXPECT_EQ(m.half_edge(h).origin, v);
      faces.insert(m.half_edge(h).face);
      ++n;
    });
    EXPECT_EQ(n, 3);
    EXPECT_EQ(faces.size(), 3u);
    EXPECT_NEAR(norm(m.vertex_normal(v) - normalized(m.position(v))), T(0), test::tol<T>());
  }
  for (Index h = 0; h < 24; ++h) {
    const Vec3<T> mid = (m.position(m.half_edge(h).origin) + m.position(m.target(h))) * T(0.5);
    EXPECT_NEAR(norm(m.edge_normal(h) - normalized(mid)), T(0), test::tol<T>());
  }
}

TYPED_TEST(HalfEdgeMeshTest, OpenBoxHasBoundaryAndFullVertexFans) {
  using T = TypeParam;
  auto soup = make_cube<T>(1).value();
  PolygonSoup<T> open;
  open.vertices = soup.vertices;
  for (std::size_t f = 0; f + 1 < soup.face_count(); ++f) open.add_face(soup.face(f)); // drop +z
  const auto m = make_half_edge_mesh(open).value();
  EXPECT_FALSE(m.is_closed_manifold());
  EXPECT_EQ(m.boundary_half_edges().size(), 4u);
  expect_consistent_links(m);
  for (Index v = 0; v < 8; ++v) {
    int corners = 0;
    for (Index i : open.indices) corners += i == v;
    int n = 0;
    m.for_each_outgoing(v, [&](Index) { ++n; });
    EXPECT_EQ(n, corners) << "vertex " << v;
  }
}

TYPED_TEST(HalfEdgeMeshTest, NonManifoldAndFlippedInputBuildsAndIsReported) {
  using T = TypeParam;
  // Three triangles on one edge (0, 1): a "book" with three pages.
  PolygonSoup<T> book;
  book.add_vertex({0, 0, 0});
  book.add_vertex({0, 0, 1});
  book.add_vertex({1, 0, 0});
  book.add_vertex({0, 1, 0});
  book.add_vertex({-1, -1, 0});
  book.add_triangle(0, 1, 2);
  book.add_triangle(1, 0, 3);
  book.add_triangle(0, 1, 4);
  const auto m = make_half_edge_mesh(book).value();
  EXPECT_EQ(m.non_manifold_half_edges().size(), 3u);
  expect_consistent_links(m);
  for (Index v = 0; v < m.vertex_count(); ++v) m.for_each_outgoing(v, [](Index) {});

  auto tet = make_tetrahedron<T>(1).value();
  std::swap(tet.indices[1], tet.indices[2]); // flip face 0
  const auto f = make_half_edge_mesh(tet).value();
  EXPECT_EQ(f.inconsistent_half_edges().size(), 6u); // its 3 edges, two sides each
  EXPECT_FALSE(f.is_closed_manifold());
  for (Index v = 0; v < f.vertex_count(); ++v) f.for_each_outgoing(v, [](Index) {});
}

TYPED_TEST(HalfEdgeMeshTest, BadSoupIsAnError) {
  using T = TypeParam;
  auto tet = make_tetrahedron<T>(1).value();
  tet.indices[0] = 4;
  const auto r = make_half_edge_mesh(tet);
  ASSERT_FALSE(r.has_value());
  EXPECT_EQ(r.error().code, ErrorCode::bad_index);
  EXPECT_EQ(make_half_edge_mesh(PolygonSoup<T>{}).error().code, ErrorCode::empty);
}

TYPED_TEST(HalfEdgeMeshTest, NonConvexFaceData) {
  using T = TypeParam;
  const auto m = make_half_edge_mesh(test::l_prism<T>()).value();
  EXPECT_TRUE(m.is_closed_manifold());
  EXPECT_EQ(m.face(0).size, 6u);
  EXPECT_NEAR(m.face(0).area, T(3), test::tol<T>());
  // centroid of the L (three unit squares): ((0.5+1.5+0.5)/3, (0.5+0.5+1.5)/3)
  EXPECT_NEAR(norm(m.face(1).centroid - Vec3<T>{T(2.5 / 3), T(2.5 / 3), 1}), T(0),
              test::tol<T>() * 10);
  EXPECT_NEAR(norm(m.face(0).normal - Vec3<T>{0, 0, -1}), T(0), test::tol<T>());
}
