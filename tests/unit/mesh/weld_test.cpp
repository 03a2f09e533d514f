// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/mesh/weld.hpp"

#include <gtest/gtest.h>

#include <random>

#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class WeldTest : public ::testing::Test {};
TYPED_TEST_SUITE(WeldTest, test::FloatTypes);

namespace {
/// Un-welds a mesh like an STL file: every face gets its own copies of its corners.
template <class T> PolygonSoup<T> explode(const PolygonSoup<T>& s) {
  PolygonSoup<T> out;
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    std::vector<Index> c;
    for (Index i : s.face(f)) c.push_back(out.add_vertex(s.vertices[i]));
    out.add_face(c);
  }
  return out;
}
} // namespace

TYPED_TEST(WeldTest, ExactWeldRestoresAnExplodedMesh) {
  using T = TypeParam;
  const auto ico = make_icosphere<T>(2).value();
  const auto soup = explode(ico);
  EXPECT_FALSE(validate(soup).sdf_well_defined);
  const auto w = weld(soup).value();
  EXPECT_EQ(w.soup.vertex_count(), ico.vertex_count());
  EXPECT_EQ(w.soup.face_count(), ico.face_count());
  EXPECT_EQ(w.merged_vertices, soup.vertex_count() - ico.vertex_count());
  EXPECT_EQ(w.unused_vertices, 0u);
  EXPECT_EQ(w.dropped_faces, 0u);
  EXPECT_TRUE(validate(w.soup).sdf_well_defined) << validate(w.soup).verdict;
  // every face keeps its geometry
  for (std::size_t f = 0; f < soup.face_count(); ++f)
    for (std::size_t i = 0; i < 3; ++i)
      EXPECT_EQ(w.soup.vertices[w.soup.face(f)[i]], soup.vertices[soup.face(f)[i]]);
  for (std::size_t v = 0; v < soup.vertex_count(); ++v)
    EXPECT_EQ(w.soup.vertices[w.vertex_map[v]], soup.vertices[v]);
}

TYPED_TEST(WeldTest, ToleranceWeldMergesJitteredCopiesOnly) {
  using T = TypeParam;
  const auto cube = make_cube<T>(1).value();
  auto soup = explode(cube);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1e-4, 1e-4);
  for (auto& v : soup.vertices) v += Vec3<T>{T(u(rng)), T(u(rng)), T(u(rng))};
  // exact weld merges nothing
  EXPECT_EQ(weld(soup).value().soup.vertex_count(), soup.vertex_count());
  WeldOptions opt;
  opt.tolerance = 1e-3;
  const auto w = weld(soup, opt).value();
  EXPECT_EQ(w.soup.vertex_count(), 8u);
  EXPECT_EQ(w.soup.face_count(), 6u);
  EXPECT_TRUE(validate(w.soup).sdf_well_defined) << validate(w.soup).verdict;
  // a tolerance larger than the cube collapses it: every face drops
  opt.tolerance = 10;
  const auto all = weld(soup, opt).value();
  EXPECT_EQ(all.soup.vertex_count(), 1u);
  EXPECT_EQ(all.dropped_faces, 6u);
  EXPECT_EQ(all.soup.face_count(), 0u);
}

TYPED_TEST(WeldTest, UnusedVerticesAreDroppedAndBadInputRejected) {
  using T = TypeParam;
  auto tet = make_tetrahedron<T>(1).value();
  PolygonSoup<T> s;
  s.add_vertex({9, 9, 9}); // unused
  for (const auto& v : tet.vertices) s.add_vertex(v);
  s.add_vertex({8, 8, 8}); // unused
  for (std::size_t f = 0; f < tet.face_count(); ++f) {
    std::vector<Index> c;
    for (Index i : tet.face(f)) c.push_back(i + 1);
    s.add_face(c);
  }
  const auto w = weld(s).value();
  EXPECT_EQ(w.unused_vertices, 2u);
  EXPECT_EQ(w.soup, tet);
  EXPECT_EQ(w.vertex_map[0], ~Index(0));

  auto bad = s;
  bad.indices[0] = 77;
  EXPECT_EQ(weld(bad).error().code, ErrorCode::bad_index);
  bad = s;
  bad.vertices[0].x = std::numeric_limits<T>::quiet_NaN();
  EXPECT_EQ(weld(bad).error().code, ErrorCode::non_finite);
  WeldOptions opt;
  opt.tolerance = -1;
  EXPECT_EQ(weld(s, opt).error().code, ErrorCode::invalid_argument);
}
