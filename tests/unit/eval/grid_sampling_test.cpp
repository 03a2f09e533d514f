// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Dense, narrow-band, sub-box and sparse grid sampling against per-point evaluation,
// on mesh SDFs (with a bounded query) and analytic SDFs (exact and bound kinds).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "test_support.hpp"

using namespace ebgeom;

namespace {

template <class T> MeshSdf<T> torus_sdf() {
  return MeshSdf<T>::build(make_torus<T>(T(0.6), T(0.25), 40, 20).value()).value();
}
template <class T> MeshSdf<T> icosphere_sdf() {
  return MeshSdf<T>::build(make_icosphere<T>(3, T(0.7)).value()).value();
}

template <class T> GridSpec<T> odd_grid(std::size_t nx, std::size_t ny, std::size_t nz) {
  return {Aabb<T>({T(-1.05), T(-0.95), T(-0.6)}, {T(0.98), T(1.02), T(0.63)}),
          {{nx, ny, nz}},
          Centering::cell};
}

template <class S>
std::vector<sdf_scalar_t<S>> pointwise(const S& sdf, const GridSpec<sdf_scalar_t<S>>& g) {
  std::vector<sdf_scalar_t<S>> ref(g.size());
  for (std::size_t k = 0; k < g.nz(); ++k)
    for (std::size_t j = 0; j < g.ny(); ++j)
      for (std::size_t i = 0; i < g.nx(); ++i) ref[g.index(i, j, k)] = sdf(g.point(i, j, k));
  return ref;
}

template <class S>
std::vector<sdf_scalar_t<S>> sampled(const S& sdf, const GridSpec<sdf_scalar_t<S>>& g,
                                     const GridOptions& opt) {
  std::vector<sdf_scalar_t<S>> out(g.size(), sdf_scalar_t<S>(-77));
  EXPECT_TRUE(sample_grid(sdf, g, Span<sdf_scalar_t<S>>(out), opt));
  return out;
}

// Bitwise equality (NaN-free data): reports the first mismatch.
template <class T> void expect_bitwise(const std::vector<T>& a, const std::vector<T>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t n = 0; n < a.size(); ++n) {
    ASSERT_EQ(a[n], b[n]) << "sample " << n;
    ASSERT_EQ(std::signbit(a[n]), std::signbit(b[n])) << "sample " << n;
  }
}

// Banded values against the dense reference: exact inside the band, ±band with the sign outside.
template <class T>
void expect_clamped(const std::vector<T>& band, const std::vector<T>& dense, T b) {
  ASSERT_EQ(band.size(), dense.size());
  std::size_t inside = 0;
  for (std::size_t n = 0; n < dense.size(); ++n) {
    const T expect = std::abs(dense[n]) <= b ? dense[n] : std::copysign(b, dense[n]);
    ASSERT_EQ(band[n], expect) << "sample " << n << " dense " << dense[n];
    inside += std::abs(dense[n]) <= b;
  }
  EXPECT_GT(inside, 0u);
  EXPECT_LT(inside, dense.size());
}

// Lower-bound fill: exact inside the band; outside, band <= |v| <= |S| (up to rounding), same
// sign.
template <class T>
void expect_lower_bound(const std::vector<T>& lb, const std::vector<T>& dense, T b) {
  for (std::size_t n = 0; n < dense.size(); ++n) {
    if (std::abs(dense[n]) <= b) {
      ASSERT_EQ(lb[n], dense[n]) << n;
      continue;
    }
    ASSERT_EQ(std::signbit(lb[n]), std::signbit(dense[n])) << n;
    ASSERT_GE(std::abs(lb[n]), b) << n;
    ASSERT_LE(std::abs(lb[n]), std::abs(dense[n]) * (1 + 1e-4) + 1e-6) << n;
  }
}

template <class T> auto csg_scene() {
  // A union of exact shapes is a bound (1-Lipschitz, |S| <= distance).
  return unite(Sphere<T>{{T(0.3), T(0.1), T(0)}, T(0.35)},
               Box<T>{{T(0.2), T(0.3), T(0.25)}, {T(-0.4), T(0), T(0.05)}});
}

} // namespace

template <class T> class GridSamplingTest : public ::testing::Test {};
TYPED_TEST_SUITE(GridSamplingTest, test::FloatTypes);

TYPED_TEST(GridSamplingTest, MeshSdfHasBoundedQuery) {
  using T = TypeParam;
  static_assert(has_bounded_query_v<MeshSdf<T>>);
  static_assert(!has_bounded_query_v<Sphere<T>>);
  const auto sdf = torus_sdf<T>();
  const auto pts = test::random_points(Aabb<T>({T(-1), T(-1), T(-1)}, {T(1), T(1), T(1)}), 500);
  for (const auto& p : pts) {
    const T s = sdf(p);
    for (T m : {T(0.01), T(0.1), T(0.3), T(2)}) {
      const T v = sdf.bounded(p, m);
      if (std::abs(s) <= m)
        ASSERT_EQ(v, s);
      else
        ASSERT_GT(std::abs(v), m);
    }
    ASSERT_EQ(sdf.bounded(p, std::abs(s)), s); // the bound itself is admitted
  }
}

TYPED_TEST(GridSamplingTest, DenseMeshEqualsPointwiseBitwise) {
  using T = TypeParam;
  for (int shape = 0; shape < 2; ++shape) {
    const auto sdf = shape == 0 ? torus_sdf<T>() : icosphere_sdf<T>();
    const auto g = odd_grid<T>(37, 29, 21);
    const auto ref = pointwise(sdf, g);
    for (GridSearch search : {GridSearch::tile, GridSearch::independent})
      for (int threads : {1, 2}) {
        GridOptions opt;
        opt.exec.threads = threads;
        opt.search = search;
        expect_bitwise(sampled(sdf, g, opt), ref);
      }
  }
}

TYPED_TEST(GridSamplingTest, DenseAnalyticEqualsPointwiseBitwise) {
  using T = TypeParam;
  const auto g = odd_grid<T>(23, 18, 17);
  const Torus<T> torus{Vec3<T>::zero(), T(0.5), T(0.2)};
  const auto scene = csg_scene<T>();
  for (int threads : {1, 2}) {
    GridOptions opt;
    opt.exec.threads = threads;
    expect_bitwise(sampled(torus, g, opt), pointwise(torus, g));
    expect_bitwise(sampled(scene, g, opt), pointwise(scene, g));
  }
}

TYPED_TEST(GridSamplingTest, NarrowBandMeshIsClampedDense) {
  using T = TypeParam;
  const auto sdf = torus_sdf<T>();
  const auto g = odd_grid<T>(61, 58, 35); // several octree levels, partial tiles
  const auto dense = pointwise(sdf, g);
  const T h = g.spacing().x;
  // 3 cells (propagated signs), 1.2 cells, and half a cell (below the spacing: no propagation).
  for (T cells : {T(3), T(1.2), T(0.5)}) {
    std::vector<T> first;
    for (int threads : {1, 2}) {
      GridOptions opt;
      opt.exec.threads = threads;
      opt.band = double(cells * h);
      const auto band = sampled(sdf, g, opt);
      expect_clamped(band, dense, T(opt.band));
      if (threads == 1)
        first = band;
      else
        expect_bitwise(band, first);
      opt.outside = BandFill::lower_bound;
      expect_lower_bound(sampled(sdf, g, opt), dense, T(opt.band));
    }
  }
}

TYPED_TEST(GridSamplingTest, NarrowBandAnalyticIsClampedDense) {
  using T = TypeParam;
  const auto g = odd_grid<T>(45, 40, 33);
  const Torus<T> torus{Vec3<T>::zero(), T(0.5), T(0.2)};
  const auto scene = csg_scene<T>();
  GridOptions opt;
  opt.band = 0.07;
  for (int threads : {1, 2}) {
    opt.exec.threads = threads;
    opt.outside = BandFill::clamp;
    expect_clamped(sampled(torus, g, opt), pointwise(torus, g), T(opt.band));
    expect_clamped(sampled(scene, g, opt), pointwise(scene, g), T(opt.band));
    opt.outside = BandFill::lower_bound;
    expect_lower_bound(sampled(torus, g, opt), pointwise(torus, g), T(opt.band));
    expect_lower_bound(sampled(scene, g, opt), pointwise(scene, g), T(opt.band));
  }
}

TYPED_TEST(GridSamplingTest, SubBoxEqualsSliceOfFullGrid) {
  using T = TypeParam;
  const auto sdf = torus_sdf<T>();
  const auto g = odd_grid<T>(53, 41, 30);
  for (double band : {0.0, 0.08}) {
    for (BandFill fill : {BandFill::clamp, BandFill::lower_bound}) {
      GridOptions opt;
      opt.band = band;
      opt.outside = fill;
      opt.exec.threads = 2;
      const auto full = sampled(sdf, g, opt);
      for (GridRange r :
           {GridRange{{{0, 0, 0}}, {{53, 41, 30}}}, GridRange{{{3, 9, 7}}, {{30, 41, 19}}},
            GridRange{{{17, 0, 29}}, {{18, 40, 30}}}, GridRange{{{40, 13, 2}}, {{53, 20, 25}}}}) {
        std::vector<T> part(r.size(), T(-77));
        ASSERT_TRUE(sample_grid_box(sdf, g, r, Span<T>(part), opt));
        for (std::size_t k = r.lo[2]; k < r.hi[2]; ++k)
          for (std::size_t j = r.lo[1]; j < r.hi[1]; ++j)
            for (std::size_t i = r.lo[0]; i < r.hi[0]; ++i)
              ASSERT_EQ(part[r.index(i, j, k)], full[g.index(i, j, k)])
                  << i << " " << j << " " << k;
      }
    }
  }
  std::vector<T> out(10);
  EXPECT_EQ(
      sample_grid_box(sdf, g, GridRange{{{0, 0, 0}}, {{54, 1, 1}}}, Span<T>(out)).error().code,
      ErrorCode::invalid_argument);
  EXPECT_EQ(sample_grid_box(sdf, g, GridRange{{{2, 0, 0}}, {{2, 1, 1}}}, Span<T>(out)).error().code,
            ErrorCode::invalid_argument);
  EXPECT_EQ(sample_grid_box(sdf, g, GridRange{{{0, 0, 0}}, {{2, 1, 1}}}, Span<T>(out)).error().code,
            ErrorCode::invalid_argument); // wrong output size
}

TYPED_TEST(GridSamplingTest, SparseEqualsDenseBand) {
  using T = TypeParam;
  const auto sdf = torus_sdf<T>();
  const Torus<T> analytic{Vec3<T>::zero(), T(0.5), T(0.2)};
  const auto g = odd_grid<T>(61, 50, 37);
  for (int threads : {1, 2}) {
    GridOptions opt;
    opt.band = 3 * double(g.spacing().x);
    opt.exec.threads = threads;
    auto check = [&](const auto& s) {
      const auto dense = sampled(s, g, opt);
      const auto sp = sample_grid_sparse(s, g, opt).value();
      EXPECT_GT(sp.kept_tile_count(), 0u);
      EXPECT_LT(sp.kept_tile_count(), sp.tile_code.size()); // something was skipped
      EXPECT_EQ(sp.values.size(), sp.kept_tile_count() * 512);
      std::size_t in_kept = 0;
      for (std::size_t k = 0; k < g.nz(); ++k)
        for (std::size_t j = 0; j < g.ny(); ++j)
          for (std::size_t i = 0; i < g.nx(); ++i) {
            ASSERT_EQ(sp.value(i, j, k), dense[g.index(i, j, k)]) << i << " " << j << " " << k;
            in_kept += sp.code(i, j, k) >= 0;
          }
      // Every sample inside the band lies in a kept tile.
      const auto ref = pointwise(s, g);
      for (std::size_t k = 0; k < g.nz(); ++k)
        for (std::size_t j = 0; j < g.ny(); ++j)
          for (std::size_t i = 0; i < g.nx(); ++i)
            if (std::abs(ref[g.index(i, j, k)]) <= T(opt.band)) {
              ASSERT_GE(sp.code(i, j, k), 0);
            }
      EXPECT_GT(in_kept, 0u);
      EXPECT_GT(sp.memory_bytes(), sp.values.size() * sizeof(T));
    };
    check(sdf);
    check(analytic);
  }
  GridOptions opt;
  EXPECT_EQ(sample_grid_sparse(sdf, g, opt).error().code, ErrorCode::invalid_argument); // band 0
}

TYPED_TEST(GridSamplingTest, SparseTilesAreInMortonOrderAndCoverBand) {
  using T = TypeParam;
  const auto sdf = icosphere_sdf<T>();
  const auto g = GridSpec<T>::cells(Aabb<T>({T(-1), T(-1), T(-1)}, {T(1), T(1), T(1)}), 128);
  GridOptions opt;
  opt.band = 0.03;
  const auto sp = sample_grid_sparse(sdf, g, opt).value();
  for (std::size_t b = 1; b < sp.kept_tiles.size(); ++b) {
    const auto& p = sp.kept_tiles[b - 1];
    const auto& q = sp.kept_tiles[b];
    ASSERT_LT(detail::morton3(p[0], p[1], p[2]), detail::morton3(q[0], q[1], q[2]));
  }
  // The centre of the sphere is inside, a corner outside.
  EXPECT_EQ(sp.value(64, 64, 64), -T(0.03));
  EXPECT_EQ(sp.value(0, 0, 0), T(0.03));
  // Work follows the surface: far fewer kept tiles than tiles.
  EXPECT_LT(sp.kept_tile_count() * 2, sp.tile_code.size());
}
