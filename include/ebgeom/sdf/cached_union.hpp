// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `CachedUnion<S, K>`: a `BvhUnion` plus an exact *candidate cache*, for unions queried many
/// times in a known region. The region is covered by a grid of cells, split into octants where
/// that pays; each leaf cell stores the few objects that can be the minimum anywhere in it. A
/// query finds its cell in O(1) (plus one step per octree level) and takes the minimum over that
/// list, in the same order as `linear()`, so the result equals `linear()` bit for bit.
///
/// Why a list can be trusted. Let C be a cell with centre c and half-diagonal h, and U = min_j
/// S_j(c) the union at its centre. For 1-Lipschitz objects (every exact or bound SDF) the union is
/// at most U + h anywhere in C, while object i is at least S_i(c) - h there and, when it is
/// prunable (`prunable_in_union`), at least dist(C, box_i) outside its box. So i can be the
/// minimum somewhere in C only if S_i(c) <= U + 2h and dist(C, box_i) <= max(U + h, 0). A query
/// at p, at distance d from c, narrows this to S_i(c) <= U + 2d, using the gap S_i(c) - U stored
/// (rounded down, one byte) with each candidate: about half the list for random points. Every
/// test carries an absolute slack of 1024 ulps of the region's coordinates, which covers the
/// rounding of every evaluation and of locating a point's cell, so no object that rounds to the
/// minimum is ever left out: ties, signed zeros included, are resolved as in `linear()`.
///
/// Costs. Memory: 4 bytes per top cell, 32 bytes per split cell and 4 + 5n bytes (rounded up to
/// 4) per list of n >= 2 candidates (a single candidate is stored in the cell itself);
/// `UnionCacheOptions::max_bytes` caps the total. Build: one BVH union query and one box-range
/// search per seed cell (about one per object), then one evaluation of each parent candidate
/// per finer cell (top cells and the octants tried); parallel (`parallel_for`), and the result
/// does not depend on the thread count. Queries outside the region, or in cells the memory cap
/// left without a list, use the BVH. Objects with unbounded boxes are evaluated by every query.
/// The cache is built only when `cacheable` (prunable and not `implicit`); otherwise every query
/// uses the BVH.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/simd.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/union_cache_build.hpp"
#include "ebgeom/sdf/union_cache_options.hpp"
#include "ebgeom/sdf/union_cache_table.hpp"

namespace ebgeom {

/// `BvhUnion<S, K>` with an exact candidate cache (see the file comment). Same values as
/// `linear()`, bit for bit. Kind: that of `BvhUnion<S, K>`. Immutable after construction;
/// concurrent queries are safe.
template <class S, int K = 4> class CachedUnion {
  EBGEOM_REQUIRE_SDF(S);

 public:
  using scalar_type = sdf_scalar_t<S>;
  using T = scalar_type;
  using Options = UnionCacheOptions<T>;
  using Table = detail::UnionCacheTable<T>;
  static constexpr SdfKind kind = BvhUnion<S, K>::kind;
  /// The cache needs 1-Lipschitz objects (not `implicit`) that are prunable.
  static constexpr bool cacheable = BvhUnion<S, K>::prunes && S::kind != SdfKind::implicit;

  CachedUnion() = default;

  /// Builds the cache over `u` (see `UnionCacheOptions` for the costs).
  explicit CachedUnion(BvhUnion<S, K> u, const Options& options = {}) : union_(std::move(u)) {
    if constexpr (cacheable) detail::UnionCacheBuilder<S, K>(union_, cache_).build(options);
  }
  explicit CachedUnion(std::vector<S> objects, const Options& options = {})
      : CachedUnion(BvhUnion<S, K>(std::move(objects)), options) {}

  /// Checked construction: NaN bounds are refused as by `BvhUnion::make`.
  static Result<CachedUnion> make(std::vector<S> objects, const Options& options = {}) {
    auto u = BvhUnion<S, K>::make(std::move(objects));
    if (!u) return std::move(u).error();
    return CachedUnion(std::move(u).value(), options);
  }

  /// min_i S_i(p), equal to `linear(p)` bit for bit; +inf for an empty union. O(candidates) in
  /// the region, the BVH's O(log N) outside. Thread-safe.
  T operator()(const Vec3<T>& p) const noexcept { return value(p, cache_.locate(p)); }

  /// `out[i] = (*this)(points[i])` for a batch (the member `evaluate()` and the grid samplers
  /// use). Same values; faster when the cache is larger than the CPU caches: it takes 32 points
  /// at a time through each step (top cell, each octree level, list, objects), requesting what
  /// the next step reads for all 32 before reading any, so their memory latencies overlap (a
  /// pipeline across groups, overlapping evaluation with the next group's requests, measured no
  /// faster). Precondition: `out.size() >= points.size()`.
  void eval(Span<const Vec3<T>> points, Span<T> out) const noexcept {
    constexpr std::size_t batch = 32;
    typename Table::Spot at[batch];
    const S* objs = union_.objects().data();
    for (std::size_t b = 0; b < points.size(); b += batch) {
      const std::size_t n = std::min(batch, points.size() - b);
      for (std::size_t j = 0; j < n; ++j) {
        at[j] = typename Table::Spot{};
        at[j].w = cache_.top_word(points[b + j], at[j].u);
        if (at[j].w) detail::prefetch(at[j].w);
      }
      for (bool again = true; again;) { // one octree level per pass
        again = false;
        for (std::size_t j = 0; j < n; ++j)
          if (at[j].w && (*at[j].w >> 30) == Table::split_tag) {
            at[j].w = cache_.child_word(*at[j].w, at[j].u);
            ++at[j].level;
            detail::prefetch(at[j].w);
            again = true;
          }
      }
      for (std::size_t j = 0; j < n; ++j) {
        if (!at[j].w) continue;
        const std::uint32_t t = *at[j].w >> 30;
        if (t == Table::list_tag) { // a list with its gaps may straddle two cache lines
          detail::prefetch(cache_.lists.data() + (*at[j].w & Table::index_mask));
          detail::prefetch(cache_.lists.data() + (*at[j].w & Table::index_mask) + 12);
        } else if (t == Table::single_tag)
          detail::prefetch(objs + *at[j].w);
      }
      for (std::size_t j = 0; j < n; ++j)
        if (at[j].w && (*at[j].w >> 30) == Table::list_tag)
          cache_.for_each_candidate(at[j],
                                    [&](std::uint32_t slot) { detail::prefetch(objs + slot); });
      for (std::size_t j = 0; j < n; ++j) out[b + j] = value(points[b + j], at[j]);
    }
  }

  /// The linear union (every object), which `operator()` equals.
  T linear(const Vec3<T>& p) const noexcept { return union_.linear(p); }

  /// The cell answering `p` (for tests and diagnostics).
  UnionCacheCell cell(const Vec3<T>& p) const noexcept {
    UnionCacheCell c;
    const typename Table::Spot at = cache_.locate(p);
    c.level = at.level;
    const std::uint32_t* w = at.w;
    if (!w || (*w >> 30) == Table::fallback_tag) return c;
    c.cached = true;
    if ((*w >> 30) == Table::single_tag) {
      c.slots = {w, 1};
      c.evaluated = 1;
    } else {
      const std::uint32_t* list = cache_.lists.data() + (*w & Table::index_mask);
      c.slots = {list + 1, list[0]};
      cache_.for_each_candidate(at, [&](std::uint32_t) { ++c.evaluated; });
    }
    return c;
  }

  Aabb<T> bounds() const noexcept { return union_.bounds(); }
  std::size_t size() const noexcept { return union_.size(); }
  const BvhUnion<S, K>& bvh_union() const noexcept { return union_; }
  /// The region the cache covers (empty without a cache).
  Aabb<T> region() const noexcept { return cache_.region; }
  const UnionCacheStats& stats() const noexcept { return cache_.stats; }

 private:
  /// The union at the point at `at` (no leaf word: the BVH).
  EBGEOM_FORCE_INLINE T value(const Vec3<T>& p, const typename Table::Spot& at) const noexcept {
    const std::uint32_t* w = at.w;
    if (!w || (*w >> 30) == Table::fallback_tag) return union_(p);
    T best = std::numeric_limits<T>::infinity();
    for (const S& s : union_.unbounded()) best = std::min(best, s(p));
    const S* objs = union_.objects().data();
    if ((*w >> 30) == Table::single_tag) return std::min(best, objs[*w](p));
    cache_.for_each_candidate(at,
                              [&](std::uint32_t slot) { best = std::min(best, objs[slot](p)); });
    return best;
  }

  BvhUnion<S, K> union_;
  detail::UnionCacheTable<T> cache_;
};

} // namespace ebgeom
