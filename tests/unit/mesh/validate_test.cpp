// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/mesh/validate.hpp"

#include <gtest/gtest.h>

#include <limits>

#include "ebgeom/mesh/generate.hpp"
#include "mesh_reference.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class ValidateTest : public ::testing::Test {};
TYPED_TEST_SUITE(ValidateTest, test::FloatTypes);

namespace {
// Count of problems that make the SDF ill-defined, to check the clean cases are fully clean.
template <class T> std::size_t problems(const ValidationReport<T>& r) {
  return r.bad_index_faces.count + r.short_faces.count + r.non_finite_vertices.count +
         r.boundary_edges.count + r.non_manifold_edges.count + r.non_manifold_vertices.count +
         r.inconsistent_edges.count + r.degenerate_faces.count + r.duplicate_faces.count +
         r.isolated_vertices.count;
}
} // namespace

TYPED_TEST(ValidateTest, CleanMeshes) {
  using T = TypeParam;
  const double pi = 3.14159265358979323846;
  struct Case {
    PolygonSoup<T> soup;
    double area, volume, tol;
    std::size_t edges;
  };
  const double a = std::sqrt(8.0 / 3.0) * 1; // edge of the tetrahedron of radius 1
  const Case cases[] = {
      {make_cube<T>(1).value(), 24, 8, 1e-5, 12},
      {make_tetrahedron<T>(1).value(), std::sqrt(3.0) * a * a, a * a * a / (6 * std::sqrt(2.0)),
       1e-5, 6},
      {make_octahedron<T>(1).value(), 4 * std::sqrt(3.0), 4.0 / 3, 1e-5, 12},
      {make_icosphere<T>(4).value(), 4 * pi, 4 * pi / 3, 0.02, 30 * 256},
      {make_torus<T>(2, T(0.5), 128, 64).value(), 4 * pi * pi * 2 * 0.5, 2 * pi * pi * 2 * 0.25,
       0.02, 128 * 64 * 2},
      {test::l_prism<T>(), 2 * 3 + 8, 3, 1e-5, 18},
  };
  for (const Case& c : cases) {
    const auto r = validate(c.soup);
    EXPECT_TRUE(r.sdf_well_defined) << r.verdict;
    EXPECT_EQ(problems(r), 0u) << r.verdict;
    EXPECT_EQ(r.holes, 0u);
    EXPECT_TRUE(r.closed() && r.manifold() && r.consistently_oriented());
    EXPECT_EQ(r.edge_count, c.edges);
    EXPECT_NEAR(r.area, c.area, c.tol * c.area);
    EXPECT_NEAR(r.signed_volume, c.volume, c.tol * c.volume);
    EXPECT_EQ(r.vertex_count, c.soup.vertex_count());
    EXPECT_EQ(r.face_count, c.soup.face_count());
    EXPECT_EQ(r.bounds, c.soup.bounds());
    EXPECT_EQ(r.verdict.rfind("signed distance well defined", 0), 0u) << r.verdict;
    // Euler characteristic V - E + F: 2 for spheres, 0 for the torus.
    const long chi = long(r.vertex_count) - long(r.edge_count) + long(r.face_count);
    EXPECT_TRUE(chi == 2 || chi == 0);
  }
}

TYPED_TEST(ValidateTest, HolesAreCountedAsBoundaryLoops) {
  using T = TypeParam;
  const auto ico = make_icosphere<T>(2).value();
  PolygonSoup<T> s;
  s.vertices = ico.vertices;
  // remove two faces far apart (two holes) and two adjacent faces (one hole of 4 edges)
  const std::size_t nf = ico.face_count();
  for (std::size_t f = 0; f < nf; ++f)
    if (f != 0 && f != nf - 1) s.add_face(ico.face(f));
  auto r = validate(s);
  EXPECT_FALSE(r.sdf_well_defined);
  EXPECT_EQ(r.boundary_edges.count, 6u);
  EXPECT_EQ(r.holes, 2u);
  EXPECT_NE(r.verdict.find("6 boundary edges (2 holes)"), std::string::npos) << r.verdict;
  // one face removed: 3 edges, 1 hole
  PolygonSoup<T> one;
  one.vertices = ico.vertices;
  for (std::size_t f = 1; f < nf; ++f) one.add_face(ico.face(f));
  r = validate(one);
  EXPECT_EQ(r.boundary_edges.count, 3u);
  EXPECT_EQ(r.holes, 1u);
  EXPECT_NE(r.verdict.find("(1 hole)"), std::string::npos) << r.verdict;
}

TYPED_TEST(ValidateTest, FlippedFaceAndInwardOrientation) {
  using T = TypeParam;
  auto tet = make_tetrahedron<T>(1).value();
  auto flipped = tet;
  std::swap(flipped.indices[1], flipped.indices[2]); // flip face 0
  auto r = validate(flipped);
  EXPECT_FALSE(r.sdf_well_defined);
  EXPECT_EQ(r.inconsistent_edges.count, 3u);
  EXPECT_TRUE(r.closed());
  EXPECT_NE(r.verdict.find("inconsistently oriented"), std::string::npos) << r.verdict;
  // All faces flipped: consistent, but inward.
  auto inward = tet;
  flip_faces(inward);
  r = validate(inward);
  EXPECT_FALSE(r.sdf_well_defined);
  EXPECT_LT(r.signed_volume, 0);
  EXPECT_TRUE(r.consistently_oriented());
  EXPECT_NE(r.verdict.find("inward"), std::string::npos) << r.verdict;
  EXPECT_TRUE(orient_outward(inward));
  EXPECT_EQ(inward, tet);
  EXPECT_TRUE(validate(inward).sdf_well_defined);
  EXPECT_FALSE(orient_outward(inward));
}

TYPED_TEST(ValidateTest, DuplicateFaceAndNonManifoldEdge) {
  using T = TypeParam;
  auto tet = make_tetrahedron<T>(1).value();
  auto dup = tet;
  dup.add_face({0, 1, 2});
  auto r = validate(dup);
  EXPECT_EQ(r.duplicate_faces.count, 1u);
  EXPECT_EQ(r.duplicate_faces.items, std::vector<Index>{4});
  EXPECT_EQ(r.non_manifold_edges.count, 3u); // its edges now have three faces
  EXPECT_FALSE(r.sdf_well_defined);
  // Two cubes sharing one edge: 2 non-manifold... no: the edge has 4 faces; its two end vertices
  // have two fans each.
  auto a = make_box<T>({0, 0, 0}, {1, 1, 1}).value();
  const auto b = make_box<T>({1, 1, 0}, {2, 2, 1}).value();
  // weld b's vertices onto a's where they coincide: (1,1,0) and (1,1,1)
  PolygonSoup<T> two = a;
  std::vector<Index> map;
  for (const auto& v : b.vertices) {
    Index id = Index(two.vertices.size());
    for (Index i = 0; i < a.vertices.size(); ++i)
      if (a.vertices[i] == v) id = i;
    if (id == two.vertices.size()) two.add_vertex(v);
    map.push_back(id);
  }
  for (std::size_t f = 0; f < b.face_count(); ++f) {
    std::vector<Index> c;
    for (Index i : b.face(f)) c.push_back(map[i]);
    two.add_face(c);
  }
  r = validate(two);
  EXPECT_EQ(r.non_manifold_edges.count, 1u);
  EXPECT_EQ(r.non_manifold_vertices.count, 2u);
  EXPECT_EQ(r.boundary_edges.count, 0u);
  EXPECT_FALSE(r.sdf_well_defined);
  // Two tetrahedra touching at one vertex: manifold edges, one non-manifold vertex.
  auto t2 = make_tetrahedron<T>(1).value();
  PolygonSoup<T> bow = tet;
  const Index base = Index(bow.vertices.size());
  for (const auto& v : t2.vertices)
    bow.add_vertex(Vec3<T>{T(2) * tet.vertices[0].x - v.x, v.y, v.z});
  for (std::size_t f = 0; f < t2.face_count(); ++f) {
    std::vector<Index> c;
    for (Index i : t2.face(f)) c.push_back(i == 0 ? 0 : base + i);
    std::reverse(c.begin(), c.end()); // mirrored: keep outward
    bow.add_face(c);
  }
  r = validate(bow);
  EXPECT_EQ(r.non_manifold_edges.count, 0u);
  EXPECT_EQ(r.non_manifold_vertices.count, 1u);
  EXPECT_EQ(r.non_manifold_vertices.items, std::vector<Index>{0});
  EXPECT_EQ(r.isolated_vertices.count, 1u); // the unused copy of vertex 0
  EXPECT_FALSE(r.sdf_well_defined);
  EXPECT_NE(r.verdict.find("1 non-manifold vertices"), std::string::npos) << r.verdict;
}

TYPED_TEST(ValidateTest, ZeroAreaNaNBadIndexShortFaceMalformedOffsets) {
  using T = TypeParam;
  auto tet = make_tetrahedron<T>(1).value();
  auto s = tet;
  s.add_vertex({5, 5, 5});
  s.add_face({0, 1, 4}); // not closed anymore, and isolated no longer
  s.vertices[4] = (s.vertices[0] + s.vertices[1]) * T(0.5); // collinear: zero area
  auto r = validate(s);
  EXPECT_EQ(r.degenerate_faces.count, 1u);
  EXPECT_EQ(r.degenerate_faces.items, std::vector<Index>{4});
  EXPECT_FALSE(r.sdf_well_defined);

  s = tet;
  s.vertices[3].z = std::numeric_limits<T>::quiet_NaN();
  r = validate(s);
  EXPECT_EQ(r.non_finite_vertices.items, std::vector<Index>{3});
  EXPECT_FALSE(r.sdf_well_defined);
  EXPECT_NE(r.verdict.find("NaN"), std::string::npos);
  EXPECT_EQ(r.bounds, Aabb<T>::of(tet.vertices[0], tet.vertices[1], tet.vertices[2]));

  s = tet;
  s.indices[5] = 1000000;
  s.add_face({0, 1});
  r = validate(s);
  EXPECT_EQ(r.bad_index_faces.items, std::vector<Index>{1});
  EXPECT_EQ(r.short_faces.items, std::vector<Index>{4});
  EXPECT_FALSE(r.sdf_well_defined);
  EXPECT_GT(r.boundary_edges.count, 0u); // the remaining faces leave a hole

  s = tet;
  s.offsets = {0, 3, 100, 6};
  r = validate(s);
  EXPECT_FALSE(r.offsets_ok);
  EXPECT_FALSE(r.sdf_well_defined);
  flip_faces(s); // must not touch out-of-range memory
  s.offsets = {};
  r = validate(s);
  EXPECT_FALSE(r.offsets_ok);
  EXPECT_EQ(r.face_count, 0u);

  PolygonSoup<T> empty;
  r = validate(empty);
  EXPECT_FALSE(r.sdf_well_defined);
  EXPECT_NE(r.verdict.find("no faces"), std::string::npos);
}

TYPED_TEST(ValidateTest, ListsAreCappedButCountsComplete) {
  using T = TypeParam;
  auto ico = make_icosphere<T>(3).value();
  PolygonSoup<T> half;
  half.vertices = ico.vertices;
  for (std::size_t f = 0; f < ico.face_count(); f += 2) half.add_face(ico.face(f));
  ValidateOptions opt;
  opt.max_listed = 5;
  const auto r = validate(half, opt);
  EXPECT_GT(r.boundary_edges.count, 5u);
  EXPECT_EQ(r.boundary_edges.items.size(), 5u);
}
