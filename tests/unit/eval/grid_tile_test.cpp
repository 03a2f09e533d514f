// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Tile evaluation of mesh SDFs (`MeshSdf::eval_lattice`, `GridSearch::tile`, the default):
// bit for bit per-point evaluation, with partial tiles, 1 and 2 threads, sub-boxes, far tiles
// whose candidate lists split, and through `SignedMeshSdf`.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "ebgeom/eval/grid.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {

template <class T> class GridTileTest : public ::testing::Test {};
TYPED_TEST_SUITE(GridTileTest, test::FloatTypes);

template <class S>
std::vector<sdf_scalar_t<S>> pointwise(const S& sdf, const GridSpec<sdf_scalar_t<S>>& g,
                                       const GridRange& r) {
  std::vector<sdf_scalar_t<S>> ref(r.size());
  for (std::size_t k = r.lo[2]; k < r.hi[2]; ++k)
    for (std::size_t j = r.lo[1]; j < r.hi[1]; ++j)
      for (std::size_t i = r.lo[0]; i < r.hi[0]; ++i) ref[r.index(i, j, k)] = sdf(g.point(i, j, k));
  return ref;
}

// Bit patterns equal (sign of zero included); reports the first mismatch.
template <class T> void expect_bits(const std::vector<T>& a, const std::vector<T>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t n = 0; n < a.size(); ++n)
    ASSERT_EQ(std::memcmp(&a[n], &b[n], sizeof(T)), 0)
        << "sample " << n << ": " << a[n] << " vs " << b[n];
}

template <class T> MeshSdf<T> fine_torus() { // 14,400 triangles, 1,800 leaves
  return MeshSdf<T>::build(make_torus<T>(T(0.6), T(0.25), 120, 60).value()).value();
}

} // namespace

TYPED_TEST(GridTileTest, MeshSdfHasLatticeEval) {
  using T = TypeParam;
  static_assert(has_lattice_eval_v<MeshSdf<T>>);
  static_assert(has_lattice_eval_v<SignedMeshSdf<T>>);
  static_assert(!has_lattice_eval_v<Sphere<T>>);
  EXPECT_EQ(GridOptions{}.search, GridSearch::tile);
}

// Direct calls on lattice tiles of several shapes, including far from the mesh (long candidate
// lists that split by octants) and tiles straddling the surface.
TYPED_TEST(GridTileTest, EvalLatticeEqualsPerPoint) {
  using T = TypeParam;
  const MeshSdf<T> sdf = fine_torus<T>();
  const std::array<std::array<std::size_t, 3>, 5> shapes{
      {{{8, 8, 8}}, {{1, 1, 1}}, {{3, 8, 5}}, {{8, 1, 2}}, {{16, 16, 16}}}};
  const std::array<Vec3<T>, 4> origins{{{T(-1), T(-1), T(-0.4)},
                                        {T(0.3), T(-0.2), T(-0.1)},
                                        {T(-4), T(3), T(2.5)},
                                        {T(0.55), T(0.0), T(0.2)}}};
  const std::array<T, 3> steps{{T(0.013), T(0.05), T(0.31)}};
  std::size_t checked = 0;
  for (const auto& d : shapes)
    for (const Vec3<T>& o : origins)
      for (T h : steps) {
        std::vector<Vec3<T>> pts;
        for (std::size_t z = 0; z < d[2]; ++z)
          for (std::size_t y = 0; y < d[1]; ++y)
            for (std::size_t x = 0; x < d[0]; ++x)
              pts.push_back({o.x + T(x) * h, o.y + T(y) * h * T(1.3), o.z + T(z) * h * T(0.7)});
        std::vector<T> got(pts.size()), ref(pts.size());
        sdf.eval_lattice(Span<const Vec3<T>>(pts), d, Span<T>(got));
        for (std::size_t l = 0; l < pts.size(); ++l) ref[l] = sdf(pts[l]);
        expect_bits(got, ref);
        checked += pts.size();
      }
  EXPECT_GT(checked, 0u);
}

// Dense grids whose tiles are partly outside the grid (odd sizes), far and near samples, 1 and 2
// threads, against per-point evaluation and against the other search strategies.
TYPED_TEST(GridTileTest, DenseGridEqualsPerPointAnyThreads) {
  using T = TypeParam;
  const MeshSdf<T> sdf = fine_torus<T>();
  for (const Aabb<T>& box : {Aabb<T>({T(-1.05), T(-0.95), T(-0.6)}, {T(0.98), T(1.02), T(0.63)}),
                             Aabb<T>({T(-6), T(-5), T(-3)}, {T(5), T(6), T(4)})}) {
    const GridSpec<T> g{box, {{37, 29, 19}}, Centering::cell};
    const std::vector<T> ref = pointwise(sdf, g, GridRange::all(g));
    for (int threads : {1, 2}) {
      GridOptions opt;
      opt.exec.threads = threads;
      std::vector<T> out(g.size(), T(-77));
      ASSERT_TRUE(sample_grid(sdf, g, Span<T>(out), opt));
      expect_bits(out, ref);
      opt.search = GridSearch::independent;
      std::vector<T> ind(g.size(), T(-77));
      ASSERT_TRUE(sample_grid(sdf, g, Span<T>(ind), opt));
      expect_bits(ind, ref);
    }
  }
}

TYPED_TEST(GridTileTest, NodeCentredGridEqualsPerPoint) {
  using T = TypeParam;
  const MeshSdf<T> sdf =
      MeshSdf<T>::build(make_icosphere<T>(3, T(0.7)).value()).value(); // 1,280 triangles
  const GridSpec<T> g{
      Aabb<T>({T(-1), T(-1), T(-1)}, {T(1), T(1), T(1)}), {{17, 9, 33}}, Centering::node};
  std::vector<T> out(g.size());
  ASSERT_TRUE(sample_grid(sdf, g, Span<T>(out)));
  expect_bits(out, pointwise(sdf, g, GridRange::all(g)));
}

TYPED_TEST(GridTileTest, SubBoxEqualsPerPoint) {
  using T = TypeParam;
  const MeshSdf<T> sdf = fine_torus<T>();
  const GridSpec<T> g{Aabb<T>({T(-1.2), T(-1.1), T(-0.7)}, {T(1.1), T(1.2), T(0.65)}),
                      {{41, 35, 23}},
                      Centering::cell};
  for (const GridRange& r :
       {GridRange{{{3, 5, 7}}, {{30, 20, 22}}}, GridRange{{{9, 0, 0}}, {{10, 35, 23}}},
        GridRange{{{40, 34, 22}}, {{41, 35, 23}}}}) {
    for (int threads : {1, 2}) {
      GridOptions opt;
      opt.exec.threads = threads;
      std::vector<T> out(r.size(), T(-77));
      ASSERT_TRUE(sample_grid_box(sdf, g, r, Span<T>(out), opt));
      expect_bits(out, pointwise(sdf, g, r));
    }
  }
}

TYPED_TEST(GridTileTest, SignedMeshSdfForwardsPseudonormalMode) {
  using T = TypeParam;
  const PolygonSoup<T> soup = make_torus<T>(T(0.6), T(0.25), 40, 20).value();
  const GridSpec<T> g{
      Aabb<T>({T(-1), T(-1), T(-0.5)}, {T(1), T(1), T(0.5)}), {{21, 19, 11}}, Centering::cell};
  for (SignMode mode : {SignMode::pseudonormal, SignMode::winding}) {
    SignOptions so;
    so.mode = mode;
    const SignedMeshSdf<T> sdf = SignedMeshSdf<T>::build(soup, so).value();
    std::vector<T> out(g.size());
    ASSERT_TRUE(sample_grid(sdf, g, Span<T>(out)));
    expect_bits(out, pointwise(sdf, g, GridRange::all(g)));
  }
}
