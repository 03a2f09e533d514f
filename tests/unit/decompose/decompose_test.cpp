// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Brick decomposition: layouts cover the grid, RCB parts tile it exactly (every sample in one
// part), balance follows the weights, the work estimate is conservative, and per-part sampling
// reassembles the serial grid bit for bit.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <numeric>
#include <vector>

#include "ebgeom/eval/decompose.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/sdf/shapes.hpp"

using namespace ebgeom;

namespace {

template <class T> struct Ball {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> c;
  T r;
  T operator()(const Vec3<T>& p) const noexcept { return norm(p - c) - r; }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(c).grown(r); }
};

GridSpec<double> grid(std::size_t nx, std::size_t ny, std::size_t nz) {
  return {Aabb<double>({-1, -1.1, -0.9}, {1.05, 0.97, 1.1}), {{nx, ny, nz}}, Centering::cell};
}

// Every sample of the grid lies in exactly one part.
void expect_tiles(const Decomposition& d) {
  const auto& dims = d.layout.dims;
  std::vector<int> hits(dims[0] * dims[1] * dims[2], 0);
  for (const auto& p : d.parts) {
    if (p.empty()) continue;
    for (std::size_t k = p.range.lo[2]; k < p.range.hi[2]; ++k)
      for (std::size_t j = p.range.lo[1]; j < p.range.hi[1]; ++j)
        for (std::size_t i = p.range.lo[0]; i < p.range.hi[0]; ++i)
          ++hits[i + dims[0] * (j + dims[1] * k)];
  }
  for (std::size_t n = 0; n < hits.size(); ++n) ASSERT_EQ(hits[n], 1) << "sample " << n;
}

} // namespace

TEST(BrickLayout, CoversTheGridWithClippedLastBricks) {
  const BrickLayout l = BrickLayout::of({{20, 8, 17}}, {{8, 8, 8}});
  EXPECT_EQ(l.counts, (std::array<std::size_t, 3>{{3, 1, 3}}));
  EXPECT_EQ(l.size(), 9u);
  std::size_t total = 0;
  for (std::size_t b = 0; b < l.size(); ++b) total += l.brick_range(b).size();
  EXPECT_EQ(total, 20u * 8 * 17);
  const GridRange last = l.brick_range(l.size() - 1);
  EXPECT_EQ(last.lo, (std::array<std::size_t, 3>{{16, 0, 16}}));
  EXPECT_EQ(last.hi, (std::array<std::size_t, 3>{{20, 8, 17}}));
}

TEST(BrickLayout, SideIsATileMultipleAndRespectsTheCap) {
  BrickOptions o;
  o.max_bricks = 64;
  const BrickLayout l = make_brick_layout(grid(256, 256, 256), o);
  EXPECT_EQ(l.brick[0] % grid_tile, 0u);
  EXPECT_LE(l.size(), 64u);
  EXPECT_EQ(l.brick[0], 64u); // 4^3 bricks; 56 would give 5^3 = 125
  EXPECT_EQ(make_brick_layout(grid(5, 5, 5)).brick[0], 8u);
}

TEST(Decompose, UniformPartsTileTheGridAndBalance) {
  for (std::size_t parts : {1u, 2u, 3u, 4u, 5u, 7u, 8u, 16u}) {
    const BrickLayout l = BrickLayout::of({{64, 48, 40}}, {{8, 8, 8}});
    const Decomposition d = decompose(l, parts);
    ASSERT_EQ(d.parts.size(), parts);
    expect_tiles(d);
    for (const auto& p : d.parts) EXPECT_FALSE(p.empty()) << parts << " parts";
    // 240 bricks: uniform RCB is within one brick slab of perfect.
    EXPECT_LT(d.imbalance(), parts == 1 ? 1.0 + 1e-12 : 1.25) << parts << " parts";
  }
}

TEST(Decompose, MorePartsThanBricksLeavesSomeEmpty) {
  const BrickLayout l = BrickLayout::of({{16, 8, 8}}, {{8, 8, 8}});
  const Decomposition d = decompose(l, 4);
  expect_tiles(d);
  std::size_t nonempty = 0;
  for (const auto& p : d.parts) nonempty += !p.empty();
  EXPECT_EQ(nonempty, 2u);
}

TEST(Decompose, WeightsMoveTheCuts) {
  // All the work in the first x slab of bricks: 2 parts should split that slab, not the volume.
  const BrickLayout l = BrickLayout::of({{64, 64, 64}}, {{8, 8, 8}});
  std::vector<double> w(l.size(), 0.0);
  for (std::size_t b = 0; b < l.size(); ++b)
    if (b % l.counts[0] == 0) w[b] = 1.0;
  const Decomposition d = decompose(l, 2, Span<const double>(w));
  expect_tiles(d);
  EXPECT_DOUBLE_EQ(d.parts[0].work, 32.0);
  EXPECT_DOUBLE_EQ(d.parts[1].work, 32.0);
  EXPECT_DOUBLE_EQ(d.imbalance(), 1.0);
  // The cut is not across x (that would leave all the work on one side).
  EXPECT_EQ(d.parts[0].range.hi[0], 64u);
}

TEST(Decompose, IsDeterministic) {
  const BrickLayout l = BrickLayout::of({{100, 37, 61}}, {{16, 16, 16}});
  std::vector<double> w(l.size());
  for (std::size_t b = 0; b < w.size(); ++b) w[b] = double((b * 7919) % 13);
  const Decomposition a = decompose(l, 6, Span<const double>(w));
  const Decomposition b = decompose(l, 6, Span<const double>(w));
  for (std::size_t p = 0; p < 6; ++p) {
    EXPECT_EQ(a.parts[p].range.lo, b.parts[p].range.lo);
    EXPECT_EQ(a.parts[p].range.hi, b.parts[p].range.hi);
  }
  expect_tiles(a);
}

TEST(EstimateBrickWork, DenseCountsSamplesBandIsConservative) {
  const GridSpec<double> spec = grid(48, 40, 56);
  const Ball<double> ball{{0.1, -0.05, 0.02}, 0.6};
  const BrickLayout l = BrickLayout::of(spec.dims, {{8, 8, 8}});
  std::vector<double> dense(l.size()), band(l.size());
  estimate_brick_work(ball, spec, l, 0, Span<double>(dense));
  for (std::size_t b = 0; b < l.size(); ++b) EXPECT_EQ(dense[b], double(l.brick_range(b).size()));
  BrickWorkOptions o;
  o.band = 2 * spec.spacing().x;
  o.far_cost = 0;
  estimate_brick_work(ball, spec, l, 0, Span<double>(band), o);
  std::size_t kept = 0;
  for (std::size_t b = 0; b < l.size(); ++b) {
    const GridRange r = l.brick_range(b);
    bool near = false;
    for (std::size_t k = r.lo[2]; k < r.hi[2]; ++k)
      for (std::size_t j = r.lo[1]; j < r.hi[1]; ++j)
        for (std::size_t i = r.lo[0]; i < r.hi[0]; ++i)
          near = near || std::abs(ball(spec.point(i, j, k))) <= o.band;
    if (near) {
      EXPECT_GT(band[b], 0) << "brick " << b << " meets the band but was estimated far";
    }
    kept += band[b] > 0;
  }
  EXPECT_LT(kept, l.size()); // some bricks are far
  // An offset `first` gives the same values.
  std::vector<double> tail(l.size() - 5);
  estimate_brick_work(ball, spec, l, 5, Span<double>(tail), o);
  for (std::size_t b = 0; b < tail.size(); ++b) EXPECT_EQ(tail[b], band[b + 5]);
}

TEST(Decompose, PartsSampledSeparatelyEqualTheSerialGrid) {
  const GridSpec<double> spec = grid(37, 45, 29);
  const Ball<double> ball{{0.1, -0.05, 0.02}, 0.6};
  for (double band : {0.0, 0.1}) {
    GridOptions g;
    g.band = band;
    std::vector<double> serial(spec.size());
    ASSERT_TRUE(sample_grid(ball, spec, Span<double>(serial), g));
    const BrickLayout l = BrickLayout::of(spec.dims, {{8, 8, 8}});
    std::vector<double> w(l.size());
    BrickWorkOptions o;
    o.band = band;
    estimate_brick_work(ball, spec, l, 0, Span<double>(w), o);
    const Decomposition d = decompose(l, 5, Span<const double>(w));
    std::vector<double> joined(spec.size(), std::nan(""));
    for (const auto& p : d.parts) {
      if (p.empty()) continue;
      std::vector<double> part(p.range.size());
      ASSERT_TRUE(sample_grid_box(ball, spec, p.range, Span<double>(part), g));
      for (std::size_t k = p.range.lo[2]; k < p.range.hi[2]; ++k)
        for (std::size_t j = p.range.lo[1]; j < p.range.hi[1]; ++j)
          for (std::size_t i = p.range.lo[0]; i < p.range.hi[0]; ++i)
            joined[spec.index(i, j, k)] = part[p.range.index(i, j, k)];
    }
    for (std::size_t n = 0; n < serial.size(); ++n)
      ASSERT_EQ(std::memcmp(&serial[n], &joined[n], sizeof(double)), 0)
          << "sample " << n << " band " << band;
  }
}
