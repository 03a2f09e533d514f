// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// TriangleMesh stores a link per triangle side instead of three edge pseudonormals; edge_normal()
// must give back, bit for bit, the table make_triangle_mesh stored before (rebuilt here the old
// way, tests/support/edge_normal_reference.hpp), on every kind of edge: two polygons, fan and
// ear-clipping diagonals, boundaries, three or more polygons, duplicate and opposite faces,
// degenerate polygons.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "edge_normal_reference.hpp"
#include "mesh_reference.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {

template <class T> PolygonSoup<T> with_face(PolygonSoup<T> s, std::vector<Index> face) {
  s.add_face(face);
  return s;
}

/// Soups covering every link kind; each with a name for failure messages.
template <class T> std::vector<std::pair<const char*, PolygonSoup<T>>> edge_cases() {
  std::vector<std::pair<const char*, PolygonSoup<T>>> out;
  out.emplace_back("cube (quads: fan diagonals)", make_cube<T>(1).value());
  out.emplace_back("tetrahedron", make_tetrahedron<T>(1).value());
  out.emplace_back("octahedron", make_octahedron<T>(2).value());
  out.emplace_back("icosphere", make_icosphere<T>(2, T(1.5)).value());
  out.emplace_back("torus (trapezoids)", make_torus<T>(2, T(0.7), 24, 12).value());
  out.emplace_back("L prism (hexagons)", test::l_prism<T>());
  {
    // The bottom hexagon starts where the fan leaves the L: ear clipping.
    PolygonSoup<T> s = test::l_prism<T>();
    const Index bottom[6] = {5, 4, 3, 2, 1, 0};
    std::copy(bottom, bottom + 6, s.indices.begin());
    out.emplace_back("L prism (ear-clipped bottom)", s);
  }
  {
    // Octagonal prism: two 8-gons and eight quads.
    PolygonSoup<T> s;
    for (int z = 0; z < 2; ++z)
      for (int i = 0; i < 8; ++i) {
        const double a = 2 * 3.14159265358979323846 * i / 8;
        s.add_vertex({T(std::cos(a)), T(std::sin(a)), T(z)});
      }
    s.add_face({7, 6, 5, 4, 3, 2, 1, 0});
    s.add_face({8, 9, 10, 11, 12, 13, 14, 15});
    for (Index i = 0; i < 8; ++i) {
      const Index j = (i + 1) % 8;
      s.add_face({i, j, Index(j + 8), Index(i + 8)});
    }
    out.emplace_back("octagonal prism", s);
  }
  {
    // Open: the cube without its last face (four boundary edges), and lone polygons.
    PolygonSoup<T> s = make_cube<T>(1).value();
    s.indices.resize(s.offsets[s.face_count() - 1]);
    s.offsets.pop_back();
    out.emplace_back("open cube", s);
  }
  PolygonSoup<T> tri;
  tri.add_vertex({0, 0, 0});
  tri.add_vertex({1, 0, 0});
  tri.add_vertex({0, 1, 0});
  tri.add_vertex({1, 1, T(0.25)});
  out.emplace_back("one triangle", with_face(tri, {0, 1, 2}));
  out.emplace_back("one non-planar quad", with_face(tri, {0, 1, 3, 2}));
  // Non-manifold: three and four triangles on the edge (0, 1).
  PolygonSoup<T> book = tri;
  book.add_vertex({0, -1, 0});
  book.add_vertex({0, 0, 1});
  book.add_vertex({0, T(-0.5), -1});
  book.add_triangle(0, 1, 2);
  book.add_triangle(1, 0, 4);
  book.add_triangle(0, 1, 5);
  out.emplace_back("book of three pages", book);
  out.emplace_back("book of four pages", with_face(book, {1, 0, 6}));
  // Duplicates: a tetrahedron face twice (three sides on its edges), a triangle twice (two sides
  // of equal polygons), a triangle and its reverse (opposite normals: the sum is zero).
  const PolygonSoup<T> tet = make_tetrahedron<T>(1).value();
  out.emplace_back("tetrahedron + duplicate face",
                   with_face(tet, {tet.indices[0], tet.indices[1], tet.indices[2]}));
  out.emplace_back("tetrahedron + reversed face",
                   with_face(tet, {tet.indices[2], tet.indices[1], tet.indices[0]}));
  out.emplace_back("triangle twice", with_face(with_face(tri, {0, 1, 2}), {0, 1, 2}));
  out.emplace_back("triangle and its reverse", with_face(with_face(tri, {0, 1, 2}), {2, 1, 0}));
  out.emplace_back("quad twice", with_face(with_face(tri, {0, 1, 3, 2}), {0, 1, 3, 2}));
  // Degenerate: a zero-area triangle (zero normal) beside a good one, a polygon visiting a vertex
  // twice (two sides of one polygon on the edge {1, 2}), a triangle with a repeated corner.
  PolygonSoup<T> flat = tri;
  const Index far = flat.add_vertex({2, 0, 0}); // on the line through vertices 0 and 1
  flat.add_triangle(0, 2, 1);
  flat.add_triangle(0, 1, far);
  out.emplace_back("zero-area triangle", flat);
  out.emplace_back("polygon visiting a vertex twice", with_face(tri, {0, 1, 2, 1, 3}));
  out.emplace_back("triangle with a repeated corner", with_face(tri, {0, 1, 1}));
  return out;
}

} // namespace

template <class T> class EdgeLinksTest : public ::testing::Test {};
TYPED_TEST_SUITE(EdgeLinksTest, test::FloatTypes);

TYPED_TEST(EdgeLinksTest, EdgeNormalsEqualTheOldTableBitForBit) {
  using T = TypeParam;
  for (const auto& [name, soup] : edge_cases<T>()) {
    SCOPED_TRACE(name);
    EXPECT_GT(test::expect_edge_normals_match(soup), 0u);
  }
}

TYPED_TEST(EdgeLinksTest, EveryLinkKindIsExercised) {
  using T = TypeParam;
  std::size_t neighbours = 0, diagonals = 0, boundaries = 0, overflows = 0;
  for (const auto& [name, soup] : edge_cases<T>()) {
    const TriangleMesh<T> m = make_triangle_mesh(soup).value();
    for (const auto& links : m.edge_links)
      for (Index l : links) {
        EXPECT_TRUE(m.valid_link(l)) << name;
        neighbours += l < m.triangle_count();
        diagonals += l == TriangleMesh<T>::diagonal_link;
        boundaries += l == TriangleMesh<T>::boundary_link;
        overflows += l <= TriangleMesh<T>::overflow_link && l >= m.triangle_count();
      }
  }
  EXPECT_GT(neighbours, 0u);
  EXPECT_GT(diagonals, 0u);
  EXPECT_GT(boundaries, 0u);
  EXPECT_GT(overflows, 0u);

  // The book: one overflow normal (the spine), shared by its three sides; the rest boundaries.
  const auto cases = edge_cases<T>();
  const auto book = std::find_if(cases.begin(), cases.end(), [](const auto& c) {
    return std::strcmp(c.first, "book of three pages") == 0;
  });
  ASSERT_NE(book, cases.end());
  const TriangleMesh<T> m = make_triangle_mesh(book->second).value();
  EXPECT_EQ(m.edge_overflow.size(), 1u);
  EXPECT_TRUE(m.source_faces.empty()); // all triangles: source_face(t) == t
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    EXPECT_EQ(m.source_face(t), t);
    EXPECT_EQ(m.edge_links[t][0], TriangleMesh<T>::overflow_link);
  }
}

TYPED_TEST(EdgeLinksTest, TriangleSignedDistanceEqualsTheKernelWithTheTable) {
  using T = TypeParam;
  // triangle_signed_distance (Embree peer) against signed_distance_triangle fed the old table.
  std::mt19937_64 rng(7);
  for (const auto& [name, soup] : edge_cases<T>()) {
    SCOPED_TRACE(name);
    const TriangleMesh<T> m = make_triangle_mesh(soup).value();
    const auto ref = test::reference_edge_normals(soup);
    const auto pts = test::random_points(m.bounds().grown(T(0.5)), 40, rng());
    for (std::size_t t = 0; t < m.triangle_count(); ++t) {
      const auto& tri = m.triangles[t];
      const Vec3<T> vn[3] = {m.vertex_normals[tri[0]], m.vertex_normals[tri[1]],
                             m.vertex_normals[tri[2]]};
      for (const Vec3<T>& p : pts) {
        const auto got = triangle_signed_distance(m, t, p);
        const auto want =
            signed_distance_triangle(p, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2),
                                     m.face_normals[t], ref.edge_normals[t].data(), vn);
        EXPECT_EQ(std::memcmp(&got.distance, &want.distance, sizeof(T)), 0) << t << " " << p;
        EXPECT_EQ(got.feature, want.feature);
      }
    }
  }
}

TEST(EdgeLinks, EncodingLimits) {
  constexpr std::size_t top = std::size_t(~Index(0)); // 2^32 - 1, taken by diagonal_link
  EXPECT_TRUE(detail::edge_links_fit(0, 0));
  EXPECT_TRUE(detail::edge_links_fit(1000, 1000));
  EXPECT_TRUE(detail::edge_links_fit(top - 1, 0)); // ids up to 2^32 - 3 = overflow_link
  EXPECT_FALSE(detail::edge_links_fit(top, 0));    // id 2^32 - 2 would read as boundary_link
  EXPECT_TRUE(detail::edge_links_fit(top - 11, 10));
  EXPECT_FALSE(detail::edge_links_fit(top - 10, 10));
  EXPECT_FALSE(detail::edge_links_fit(10, top));
  EXPECT_FALSE(detail::edge_links_fit(top * 2, 0));
}

TEST(EdgeLinks, MeshSdfRefusesABadHandMadeLink) {
  TriangleMesh<float> m = make_triangle_mesh(make_tetrahedron<float>(1).value()).value();
  EXPECT_TRUE(MeshSdf<float>::make(m).has_value());
  TriangleMesh<float> bad = m;
  bad.edge_links[2][1] = TriangleMesh<float>::overflow_link; // no overflow normal stored
  EXPECT_EQ(MeshSdf<float>::make(bad).error().code, ErrorCode::bad_index);
  bad = m;
  bad.edge_links[0][0] = Index(m.triangle_count()); // one past the last triangle
  EXPECT_EQ(MeshSdf<float>::make(bad).error().code, ErrorCode::bad_index);
  bad = m;
  bad.edge_links.pop_back();
  EXPECT_EQ(MeshSdf<float>::make(bad).error().code, ErrorCode::size_mismatch);
  bad = m;
  bad.source_faces.assign(2, 0);
  EXPECT_EQ(MeshSdf<float>::make(bad).error().code, ErrorCode::size_mismatch);
}
