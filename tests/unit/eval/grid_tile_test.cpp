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

namespace {

// Lanes of the tile kernel `block_min_planes` against the plain block kernel, for blocks of 16
// (float) or 8 (double) consecutive triangles of a torus, supporting planes taken at one random
// point `p0` and queries at others `p`, with the bound `b2` the block's own minimum (the nearest
// lane ties it, the hardest case) and `r` built from `b2` by `make_r`. Counts the queries where the
// kernel's answer differs from `block_min` (a near lane dropped).
template <class T, Isa I, class MakeR> std::size_t plane_mask_misses(MakeR make_r) {
  constexpr int W = default_block_width<T>;
  const TriangleMesh<T> mesh =
      make_triangle_mesh(make_torus<T>(T(0.6), T(0.25), 40, 20).value()).value();
  const auto pts =
      test::random_points(Aabb<T>({T(-1), T(-1), T(-0.5)}, {T(1), T(1), T(0.5)}), 400, 7);
  std::size_t misses = 0, near = 0;
  for (std::size_t first = 0; first + W <= mesh.triangle_count(); first += 37 * W) {
    TriBlock<T, W> tb;
    for (int l = 0; l < W; ++l)
      tb.set(l, mesh.corner(first + l, 0), mesh.corner(first + l, 1), mesh.corner(first + l, 2));
    for (std::size_t k = 0; k + 1 < pts.size(); k += 2) {
      T nx[W], ny[W], nz[W], off[W];
      block_planes<T, W, I>(tb, pts[k], nx, ny, nz, off);
      for (const Vec3<T>& p : {pts[k], pts[k + 1]}) {
        T d2[W];
        block_distance2<T, W, I>(tb, p, d2);
        T b2 = d2[0];
        for (int l = 1; l < W; ++l) b2 = std::min(b2, d2[l]);
        const T lim = bvh::prune_limit(b2);
        const LaneMin<T, W> want = block_min<T, W, I>(tb, p, b2);
        const LaneMin<T, W> got = detail::MeshTileKernels<I>::template block_min_planes<T, W>(
            tb, p, b2, lim, nx, ny, nz, off, make_r(lim));
        ++near;
        if (got.mask != want.mask || std::memcmp(&got.min, &want.min, sizeof(T)) != 0) ++misses;
      }
    }
  }
  EXPECT_GT(near, 1000u);
  return misses;
}

template <class T, Isa I> void check_plane_mask() {
  // The margins of `MeshTileEval::scan_list_inline` (coordinates below 1 here).
  const T eps = std::numeric_limits<T>::epsilon();
  const std::size_t exact = plane_mask_misses<T, I>(
      [&](T lim) { return std::sqrt(lim) * (T(1) + T(256) * eps) + T(1024) * eps * T(0.85); });
  EXPECT_EQ(exact, 0u) << to_string(I);
  // Mutation: a shortcut that trusts the planes slightly too much (no margin, 0.1% tight) must
  // drop near lanes, at least where the planes were taken at the query point itself.
  const std::size_t broken =
      plane_mask_misses<T, I>([&](T lim) { return std::sqrt(lim) * T(0.999); });
  EXPECT_GT(broken, 100u) << to_string(I);
}

} // namespace

// The lane filter of tile evaluation (triangle boxes and supporting planes before the distance
// kernel) never drops the nearest lane, on every instruction set compiled in; a deliberately
// over-tight filter is caught by the same check.
TYPED_TEST(GridTileTest, PlaneLaneFilterKeepsNearestLane) {
  using T = TypeParam;
  check_plane_mask<T, native_isa>();
#if EBGEOM_ISA_DISPATCH
  if (int(detected_isa()) >= int(Isa::avx2)) check_plane_mask<T, Isa::avx2>();
  if (int(detected_isa()) >= int(Isa::avx512)) check_plane_mask<T, Isa::avx512>();
#endif
}
