// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// EBGeometry's union example: M^3 spheres of radius r on a lattice in [-1, 1]^3, their
// standard union (every sphere per query) against the accelerated unions. Prints the times per
// query and the speedups, and checks that every union gives the same value bit for bit (exit 1
// otherwise).
//
// Two standard unions are timed: EBGeometry's design (a vector of shared_ptr to a polymorphic SDF
// base, one virtual call per sphere per query: EBGeometry's `Union<T>`), which EBGeometry's 7,580x
// figure is measured against, and ebgeom's own inlined linear loop over a vector of value-type
// spheres (no virtual call), a faster baseline. Two accelerated ones: `BvhUnion` (a nearest search
// per query) and `CachedUnion` (a BvhUnion plus a grid of candidate lists over [-1, 1]^3), the
// latter both one point at a time and through its batch `eval` (which prefetches).
//
// Every union is timed on the same `samples` random points (EBGeometry's protocol; repetitions
// reuse them, so a fast union's working set stays in the CPU caches after the first; the
// accelerated unions, whose runs are short, are repeated 20 times as often), and the accelerated
// ones also on `fresh` other random points, so many that their cells, lists and spheres come
// from memory: the cost of scattered queries. A linear union's cost does not depend on the points
// (it reads every sphere), so its time from the first set is the reference for both.
//
// Usage: ebgeom_example_fast_union [M=40] [samples=1000] [repetitions=5] [fresh=200000]
//                                  [top_cells_per_object=8] [min_split_gain=1]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/cached_union.hpp"
#include "ebgeom/sdf/shapes.hpp"

namespace {
using T = double;
using ebgeom::Aabb;
using ebgeom::Vec3;

using Ball = ebgeom::Sphere<T>; // exact

/// EBGeometry's SDF interface: a polymorphic base held through shared_ptr.
struct SignedDistanceFunction {
  virtual ~SignedDistanceFunction() = default;
  virtual T signedDistance(const Vec3<T>& p) const noexcept = 0;
};
struct SphereSdf final : SignedDistanceFunction {
  explicit SphereSdf(const Ball& b) : ball(b) {}
  T signedDistance(const Vec3<T>& p) const noexcept override { return ball(p); }
  Ball ball;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <class Fn> double seconds(Fn&& fn) {
  const auto t0 = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

std::vector<Vec3<T>> random_points(std::size_t n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<T> u(-1, 1);
  std::vector<Vec3<T>> pts(n);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  return pts;
}

/// Median over `reps` runs of `fn(points, out)`, per point.
template <class Fn>
double per_query(int reps, const std::vector<Vec3<T>>& pts, std::vector<T>& out, Fn&& fn) {
  out.resize(pts.size());
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) t.push_back(seconds([&] { fn(pts, out); }));
  return median(t) / double(pts.size());
}

std::size_t mismatches(const std::vector<T>& a, const std::vector<T>& b) {
  std::size_t n = 0;
  for (std::size_t i = 0; i < a.size(); ++i) n += std::memcmp(&a[i], &b[i], sizeof(T)) != 0;
  return n;
}
} // namespace

int main(int argc, char** argv) {
  const int M = argc > 1 ? std::atoi(argv[1]) : 40;
  const int samples = argc > 2 ? std::atoi(argv[2]) : 1000;
  const int reps = argc > 3 ? std::atoi(argv[3]) : 5;
  const int fresh = argc > 4 ? std::atoi(argv[4]) : 200000;
  ebgeom::UnionCacheOptions<T> opt; // the defaults, but for the region (below)
  if (argc > 5) opt.top_cells_per_object = std::atof(argv[5]);
  if (argc > 6) opt.min_split_gain = std::atof(argv[6]);
  constexpr T radius = 0.02;
  const T delta = (2.0 - 2 * M * radius) / (M + 1);
  if (M < 1 || samples < 1 || reps < 1 || fresh < 0 || delta < 0) {
    std::fprintf(stderr,
                 "usage: %s [M >= 1, 2 M r <= 2] [samples >= 1] [repetitions >= 1] [fresh >= 0]\n",
                 argv[0]);
    return 2;
  }
  std::vector<Ball> spheres;
  for (int i = 1; i <= M; ++i)
    for (int j = 1; j <= M; ++j)
      for (int k = 1; k <= M; ++k)
        spheres.push_back(
            {{-1. + i * (delta + 2 * radius) - radius, -1. + j * (delta + 2 * radius) - radius,
              -1. + k * (delta + 2 * radius) - radius},
             radius});
  std::printf("%zu spheres of radius %g, delta = %g\n", spheres.size(), radius, delta);

  // EBGeometry's standard union: shared_ptr<SDF> objects, one virtual call per sphere.
  std::vector<std::shared_ptr<const SignedDistanceFunction>> poly;
  for (const Ball& b : spheres) poly.push_back(std::make_shared<const SphereSdf>(b));
  auto ebgeometry_union = [&](const std::vector<Vec3<T>>& pts, std::vector<T>& out) {
    for (std::size_t i = 0; i < pts.size(); ++i) {
      T d = std::numeric_limits<T>::infinity();
      for (const auto& s : poly) d = std::min(d, s->signedDistance(pts[i]));
      out[i] = d;
    }
  };
  // ebgeom's linear union: value types, inlined.
  const std::vector<Ball> linear = spheres;
  auto linear_union = [&](const std::vector<Vec3<T>>& pts, std::vector<T>& out) {
    for (std::size_t i = 0; i < pts.size(); ++i) {
      T d = std::numeric_limits<T>::infinity();
      for (const Ball& b : linear) d = std::min(d, b(pts[i]));
      out[i] = d;
    }
  };

  ebgeom::BvhUnion<Ball> bvh;
  const double bvh_build = seconds([&] { bvh = ebgeom::BvhUnion<Ball>(spheres); });
  // The cache covers the query domain [-1, 1]^3 (the default region, the spheres' box grown by
  // 1/16 of its side, would cover it too). Built from a copy of the BVH union.
  opt.region = Aabb<T>::of({-1, -1, -1}, {1, 1, 1});
  ebgeom::CachedUnion<Ball> cached;
  const double cache_build = seconds([&] { cached = ebgeom::CachedUnion<Ball>(bvh, opt); });
  const ebgeom::UnionCacheStats& st = cached.stats();
  std::printf("BVH build: %.1f ms\n", bvh_build * 1e3);
  std::printf("cache build: %.1f ms; %.1f MiB: %u x %u x %u top cells, %zu split, %zu leaves, "
              "depth %d, %zu fallback%s;\n  per uniform query: %.2f candidates (at most %zu), "
              "%.2f octree levels\n",
              cache_build * 1e3, double(st.bytes) / (1 << 20), st.dims[0], st.dims[1], st.dims[2],
              st.split_cells, st.leaf_cells, st.depth, st.fallback_cells,
              st.capped ? " (capped by max_bytes)" : "", st.mean_candidates, st.longest_list,
              st.mean_level);

  auto bvh_union = [&](const std::vector<Vec3<T>>& pts, std::vector<T>& out) {
    for (std::size_t i = 0; i < pts.size(); ++i) out[i] = bvh(pts[i]);
  };
  auto cached_one = [&](const std::vector<Vec3<T>>& pts, std::vector<T>& out) {
    for (std::size_t i = 0; i < pts.size(); ++i) out[i] = cached(pts[i]);
  };
  auto cached_batch = [&](const std::vector<Vec3<T>>& pts, std::vector<T>& out) {
    cached.eval(pts, out);
  };

  const auto pts = random_points(std::size_t(samples), 2024);
  std::vector<T> v_ebgeometry, v_linear, v_bvh, v_one, v_batch;
  const double t_virtual = per_query(reps, pts, v_ebgeometry, ebgeometry_union);
  const double t_linear = per_query(reps, pts, v_linear, linear_union);
  const double t_bvh = per_query(20 * reps, pts, v_bvh, bvh_union);
  const double t_one = per_query(20 * reps, pts, v_one, cached_one);
  const double t_batch = per_query(20 * reps, pts, v_batch, cached_batch);
  std::size_t bad = mismatches(v_ebgeometry, v_linear) + mismatches(v_ebgeometry, v_bvh) +
                    mismatches(v_ebgeometry, v_one) + mismatches(v_ebgeometry, v_batch);
  std::size_t checked = pts.size();

  std::printf(
      "per query (ms), medians of %d runs (%d on the same points for the accelerated "
      "unions),\nand the speedups vs the EBGeometry-style union and vs the inlined linear union:\n",
      reps, 20 * reps);
  std::printf("  EBGeometry-style union (virtual call per sphere): %.6f\n", t_virtual * 1e3);
  std::printf("  inlined linear union:                        %.6f\n", t_linear * 1e3);
  auto row = [&](const char* name, double t) {
    std::printf("  %-44s %.6f  %8.0fx  %8.0fx\n", name, t * 1e3, t_virtual / t, t_linear / t);
  };
  std::printf(" on the same %d points:\n", samples);
  row("BVH union", t_bvh);
  row("cached union, one point at a time", t_one);
  row("cached union, batch eval", t_batch);
  if (fresh > 0) {
    const auto many = random_points(std::size_t(fresh), 7);
    std::vector<T> w_bvh, w_one, w_batch, w_linear(many.size() / 200);
    const double f_bvh = per_query(reps, many, w_bvh, bvh_union);
    const double f_one = per_query(reps, many, w_one, cached_one);
    const double f_batch = per_query(reps, many, w_batch, cached_batch);
    bad += mismatches(w_bvh, w_one) + mismatches(w_bvh, w_batch);
    checked += many.size();
    // Every 200th point against the linear union too (all of them would take minutes).
    for (std::size_t i = 0; i < w_linear.size(); ++i) {
      T d = std::numeric_limits<T>::infinity();
      for (const Ball& b : linear) d = std::min(d, b(many[200 * i]));
      bad += std::memcmp(&d, &w_bvh[200 * i], sizeof(T)) != 0;
    }
    std::size_t listed = 0, evaluated = 0;
    for (const auto& p : many) {
      const ebgeom::UnionCacheCell c = cached.cell(p);
      listed += c.slots.size();
      evaluated += c.evaluated;
    }
    std::printf(" on %d fresh points (from memory; %.2f candidates listed, %.2f evaluated per "
                "query):\n",
                fresh, double(listed) / double(fresh), double(evaluated) / double(fresh));
    row("BVH union", f_bvh);
    row("cached union, one point at a time", f_one);
    row("cached union, batch eval", f_batch);
  }
  if (bad)
    std::printf("MISMATCH: %zu values differ\n", bad);
  else
    std::printf("identical values, bit for bit, at all %zu points\n", checked);
  return bad ? 1 : 0;
}
