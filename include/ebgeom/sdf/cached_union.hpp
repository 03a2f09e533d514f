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

#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/union_cache_options.hpp"

namespace ebgeom {

namespace detail {
/// Hint that `p` will be read soon (no effect where the compiler has no prefetch builtin).
EBGEOM_FORCE_INLINE void prefetch(const void* p) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}
} // namespace detail

/// `BvhUnion<S, K>` with an exact candidate cache (see the file comment). Same values as
/// `linear()`, bit for bit. Kind: that of `BvhUnion<S, K>`. Immutable after construction;
/// concurrent queries are safe.
template <class S, int K = 4> class CachedUnion {
  EBGEOM_REQUIRE_SDF(S);

 public:
  using scalar_type = sdf_scalar_t<S>;
  using T = scalar_type;
  using Options = UnionCacheOptions<T>;
  static constexpr SdfKind kind = BvhUnion<S, K>::kind;
  /// The cache needs 1-Lipschitz objects (not `implicit`) that are prunable.
  static constexpr bool cacheable = BvhUnion<S, K>::prunes && S::kind != SdfKind::implicit;

  CachedUnion() = default;

  /// Builds the cache over `u` (see `UnionCacheOptions` for the costs).
  explicit CachedUnion(BvhUnion<S, K> u, const Options& options = {}) : union_(std::move(u)) {
    if constexpr (cacheable) build(options);
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
  T operator()(const Vec3<T>& p) const noexcept { return value(p, locate(p)); }

  /// `out[i] = (*this)(points[i])` for a batch (the member `evaluate()` and the grid samplers
  /// use). Same values; faster when the cache is larger than the CPU caches: it takes 32 points
  /// at a time through each step (top cell, each octree level, list, objects), requesting what
  /// the next step reads for all 32 before reading any, so their memory latencies overlap (a
  /// pipeline across groups, overlapping evaluation with the next group's requests, measured no
  /// faster). Precondition: `out.size() >= points.size()`.
  void eval(Span<const Vec3<T>> points, Span<T> out) const noexcept {
    constexpr std::size_t batch = 32;
    Spot at[batch];
    const S* objs = union_.objects().data();
    for (std::size_t b = 0; b < points.size(); b += batch) {
      const std::size_t n = std::min(batch, points.size() - b);
      for (std::size_t j = 0; j < n; ++j) {
        at[j] = Spot{};
        at[j].w = top_word(points[b + j], at[j].u);
        if (at[j].w) detail::prefetch(at[j].w);
      }
      for (bool again = true; again;) { // one octree level per pass
        again = false;
        for (std::size_t j = 0; j < n; ++j)
          if (at[j].w && (*at[j].w >> 30) == split_tag) {
            at[j].w = child_word(*at[j].w, at[j].u);
            ++at[j].level;
            detail::prefetch(at[j].w);
            again = true;
          }
      }
      for (std::size_t j = 0; j < n; ++j) {
        if (!at[j].w) continue;
        const std::uint32_t t = *at[j].w >> 30;
        if (t == list_tag) { // a list with its gaps may straddle two cache lines
          detail::prefetch(lists_.data() + (*at[j].w & index_mask));
          detail::prefetch(lists_.data() + (*at[j].w & index_mask) + 12);
        } else if (t == single_tag)
          detail::prefetch(objs + *at[j].w);
      }
      for (std::size_t j = 0; j < n; ++j)
        if (at[j].w && (*at[j].w >> 30) == list_tag)
          for_each_candidate(at[j], [&](std::uint32_t slot) { detail::prefetch(objs + slot); });
      for (std::size_t j = 0; j < n; ++j) out[b + j] = value(points[b + j], at[j]);
    }
  }

  /// The linear union (every object), which `operator()` equals.
  T linear(const Vec3<T>& p) const noexcept { return union_.linear(p); }

  /// The cell answering `p` (for tests and diagnostics).
  UnionCacheCell cell(const Vec3<T>& p) const noexcept {
    UnionCacheCell c;
    const Spot at = locate(p);
    c.level = at.level;
    const std::uint32_t* w = at.w;
    if (!w || (*w >> 30) == fallback_tag) return c;
    c.cached = true;
    if ((*w >> 30) == single_tag) {
      c.slots = {w, 1};
      c.evaluated = 1;
    } else {
      const std::uint32_t* list = lists_.data() + (*w & index_mask);
      c.slots = {list + 1, list[0]};
      for_each_candidate(at, [&](std::uint32_t) { ++c.evaluated; });
    }
    return c;
  }

  Aabb<T> bounds() const noexcept { return union_.bounds(); }
  std::size_t size() const noexcept { return union_.size(); }
  const BvhUnion<S, K>& bvh_union() const noexcept { return union_; }
  /// The region the cache covers (empty without a cache).
  Aabb<T> region() const noexcept { return region_; }
  const UnionCacheStats& stats() const noexcept { return stats_; }

 private:
  // A cell's 32-bit word: the top two bits say what it is, the other 30 an index.
  static constexpr std::uint32_t single_tag = 0;   // the one candidate's slot
  static constexpr std::uint32_t list_tag = 1;     // offset of [n, slots, gaps] in lists_
  static constexpr std::uint32_t split_tag = 2;    // first of 8 child words in nodes_, / 8
  static constexpr std::uint32_t fallback_tag = 3; // the BVH answers
  static constexpr std::uint32_t index_mask = (std::uint32_t(1) << 30) - 1;
  static constexpr std::uint32_t word(std::uint32_t tag, std::size_t index) noexcept {
    return (tag << 30) | std::uint32_t(index);
  }

  /// The word of the top cell holding `p` and `p`'s coordinates in it (in [0, 1)), or null
  /// outside the region (or without a cache). The one rounding here is covered by the slack.
  const std::uint32_t* top_word(const Vec3<T>& p, T (&u)[3]) const noexcept {
    if (top_.empty()) return nullptr;
    std::uint32_t i[3];
    for (int a = 0; a < 3; ++a) {
      u[a] = (p[a] - region_.lo[a]) * inv_[a];
      if (!(u[a] >= T(0) && u[a] < T(dims_[a]))) return nullptr;
      i[a] = std::uint32_t(u[a]);
      u[a] -= T(i[a]);
    }
    return &top_[(std::size_t(i[2]) * dims_[1] + i[1]) * dims_[0] + i[0]];
  }
  /// The word of the octant of split cell `w` holding the point at `u`, and the point's
  /// coordinates in it (exact: doubling, and subtracting 1 in [1, 2)).
  const std::uint32_t* child_word(std::uint32_t w, T (&u)[3]) const noexcept {
    std::uint32_t octant = 0;
    for (int a = 0; a < 3; ++a) {
      u[a] += u[a];
      const std::uint32_t b = u[a] >= T(1);
      u[a] -= T(b);
      octant |= b << a;
    }
    return &nodes_[std::size_t(w & index_mask) * 8 + octant];
  }
  /// Where a point is: the word of its leaf cell (null outside the region or without a cache),
  /// its coordinates in that cell (in [0, 1)) and the cell's level.
  struct Spot {
    const std::uint32_t* w = nullptr;
    T u[3] = {};
    int level = 0;
  };
  Spot locate(const Vec3<T>& p) const noexcept {
    Spot at;
    at.w = top_word(p, at.u);
    for (; at.w && (*at.w >> 30) == split_tag; ++at.level) at.w = child_word(*at.w, at.u);
    return at;
  }

  /// Calls `fn(slot)` for the candidates of list cell `at` that can be the minimum at the point
  /// itself, in list (leaf) order. A list stores with each candidate its gap g = S_i(c) - U
  /// above the union at the cell's centre, rounded down to a multiple of the level's `gap_unit_`
  /// (one byte). The union at p is at most U + d and S_i(p) at least S_i(c) - d, with d = |p - c|,
  /// so a candidate with g > 2d (plus the slack) cannot be the minimum at p and is skipped: about
  /// half of them for uniformly random points. What is skipped is strictly larger than the
  /// minimum, so the result and its tie-breaking are those of the whole list.
  template <class Fn> EBGEOM_FORCE_INLINE void for_each_candidate(const Spot& at, Fn&& fn) const {
    const std::uint32_t* list = lists_.data() + (*at.w & index_mask);
    const std::uint32_t n = list[0];
    const auto* gaps = reinterpret_cast<const unsigned char*>(list + 1 + n);
    T d2 = T(0);
    for (int a = 0; a < 3; ++a) {
      const T x = (at.u[a] - T(0.5)) * level_size_[at.level][a];
      d2 += x * x;
    }
    // Kept when gap <= 2d + slack, in gap bytes, rounded towards keeping. (Comparing squares
    // instead, without this square root, measured slower.)
    constexpr T up = T(1) + T(8) * std::numeric_limits<T>::epsilon();
    const T limit = (T(2) * std::sqrt(d2) * up + slack_) * gap_per_unit_[at.level] * up;
    // A byte g is kept when g <= limit, i.e. g <= floor(limit) (limit >= 0): one integer compare
    // per candidate instead of a conversion and a floating-point compare (-10% time per query).
    // A NaN limit (impossible inside the region) would keep every candidate, as before.
    const unsigned cut = !(limit < T(255)) ? 255u : unsigned(limit);
    auto keep = [&](std::uint32_t k) { return gaps[k] <= cut; };
    // Compacted without branches first: a branch per candidate would mispredict half the time.
    constexpr std::uint32_t most = 64;
    if (n > most) {
      for (std::uint32_t k = 0; k < n; ++k)
        if (keep(k)) fn(list[1 + k]);
      return;
    }
    std::uint32_t kept[most];
    std::uint32_t m = 0;
    for (std::uint32_t k = 0; k < n; ++k) {
      kept[m] = list[1 + k];
      m += keep(k);
    }
    for (std::uint32_t k = 0; k < m; ++k) fn(kept[k]);
  }

  /// The union at the point at `at` (no leaf word: the BVH).
  EBGEOM_FORCE_INLINE T value(const Vec3<T>& p, const Spot& at) const noexcept {
    const std::uint32_t* w = at.w;
    if (!w || (*w >> 30) == fallback_tag) return union_(p);
    T best = std::numeric_limits<T>::infinity();
    for (const S& s : union_.unbounded()) best = std::min(best, s(p));
    const S* objs = union_.objects().data();
    if ((*w >> 30) == single_tag) return std::min(best, objs[*w](p));
    for_each_candidate(at, [&](std::uint32_t slot) { best = std::min(best, objs[slot](p)); });
    return best;
  }

  /// A cell of the level being built: integer coordinates at that level, where its word goes
  /// (top_ at level 0, nodes_ below) and which item of the level's `Lists` holds its candidates.
  struct Cell {
    std::uint32_t i[3];
    std::size_t word_at, item;
  };
  /// Candidate lists written in parallel by chunks of `grain` consecutive items: item k's slots
  /// are buf[k / grain][first[k] ...] and their gap bytes gaps[k / grain][first[k] ...], count[k]
  /// long (the same whatever the thread count).
  struct Lists {
    std::size_t grain = 1;
    std::vector<std::vector<std::uint32_t>> buf;
    std::vector<std::vector<unsigned char>> gaps;
    std::vector<std::uint32_t> first, count;
    void reset(std::size_t items, std::size_t g) {
      grain = g;
      buf.assign((items + g - 1) / g, {});
      gaps.assign(buf.size(), {});
      first.assign(items, 0);
      count.assign(items, 0);
    }
    const std::uint32_t* of(std::size_t k) const noexcept {
      return buf[k / grain].data() + first[k];
    }
    const unsigned char* gaps_of(std::size_t k) const noexcept {
      return gaps[k / grain].data() + first[k];
    }
  };
  static constexpr std::size_t cells_per_task = 64;

  static T box_distance2(const Aabb<T>& a, const Aabb<T>& b) noexcept {
    T d2 = T(0);
    for (int k = 0; k < 3; ++k) {
      const T d = std::max(std::max(a.lo[k] - b.hi[k], b.lo[k] - a.hi[k]), T(0));
      d2 += d * d;
    }
    return d2;
  }

  /// Cells of one level: size, half-diagonal (rounded up) and gap bytes per unit length (a kept
  /// candidate's gap is at most 2h plus the slack: 255). Levels below 0 are coarser than the top
  /// grid (the seed grid and its refinements, see `build`).
  struct Geometry {
    Vec3<T> size;
    T h, gap_per_unit;
  };
  Geometry geometry(int level) const noexcept {
    Geometry g;
    for (int a = 0; a < 3; ++a)
      g.size[a] = region_.extent()[a] / T(level >= 0 ? std::uint64_t(dims_[a]) << level
                                                     : std::uint64_t(dims_[a]) >> -level);
    g.h = T(0.5) * norm(g.size) * (T(1) + T(8) * std::numeric_limits<T>::epsilon());
    g.gap_per_unit = T(255) / (T(2) * g.h + slack_);
    return g;
  }
  Aabb<T> cell_box(const std::uint32_t (&i)[3], const Geometry& g) const noexcept {
    Aabb<T> box;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = region_.lo[a] + T(i[a]) * g.size[a];
      box.hi[a] = region_.lo[a] + T(i[a] + 1) * g.size[a];
    }
    return box;
  }
  /// The lists of the 8 children of `parent` (items 8t + o of `out`, in the chunk of item 8t).
  void child_lists(const Cell& parent, const Lists& lists, std::size_t t, const Geometry& g,
                   std::vector<T>& values, Lists& out) const {
    auto& buf = out.buf[8 * t / out.grain];
    auto& gaps = out.gaps[8 * t / out.grain];
    for (std::uint32_t o = 0; o < 8; ++o) {
      std::uint32_t i[3];
      for (int a = 0; a < 3; ++a) i[a] = 2 * parent.i[a] + ((o >> a) & 1);
      const std::size_t item = 8 * t + o;
      out.first[item] = std::uint32_t(buf.size());
      candidates(cell_box(i, g), g, lists.of(parent.item), lists.count[parent.item], values, buf,
                 gaps);
      out.count[item] = std::uint32_t(buf.size() - out.first[item]);
    }
  }

  /// Appends to `out`, in leaf order, the objects that may be the minimum somewhere in `box`
  /// (see the file comment): those of `parent` (m slots, ascending), or of the whole tree when
  /// `parent` is null; and to `gaps` their gap bytes at `level` (see `for_each_candidate`).
  /// `values` is scratch.
  void candidates(const Aabb<T>& box, const Geometry& geo, const std::uint32_t* parent,
                  std::uint32_t m, std::vector<T>& values, std::vector<std::uint32_t>& out,
                  std::vector<unsigned char>& gaps) const {
    const T h = geo.h;
    constexpr T eps = std::numeric_limits<T>::epsilon();
    const auto& objs = union_.objects();
    const Vec3<T> c = box.center();
    T u = std::numeric_limits<T>::infinity();
    if (!parent) {
      u = union_(c);
    } else {
      values.resize(m);
      for (const S& s : union_.unbounded()) u = std::min(u, s(c));
      for (std::uint32_t j = 0; j < m; ++j) u = std::min(u, values[j] = objs[parent[j]](c));
    }
    // Object i may be the minimum in the cell only if S_i(c) <= u + 2h and its box is within
    // max(u + h, 0) of the cell, both with the slack; NaN values are kept.
    const T limit = u + T(2) * h + slack_;
    const T r = std::max(u + h, T(0)) + slack_;
    const T r2 = r * r * (T(1) + T(8) * eps);
    // The gap byte rounds (v - u) down in units of 1/gap_per_unit_; NaN gives 0 (never skipped).
    auto gap = [&](T v) -> unsigned char {
      const T g = (v - u) * geo.gap_per_unit;
      return g > T(0) ? static_cast<unsigned char>(std::min(std::floor(g), T(255))) : 0;
    };
    auto keep = [&](std::uint32_t s, T v) {
      if (!(v > limit) && box_distance2(box, objs[s].bounds()) <= r2) {
        out.push_back(s);
        gaps.push_back(gap(v));
      }
    };
    if (!parent) {
      const std::size_t start = out.size();
      bvh::for_each_leaf_if(
          union_.tree(), [&](const auto& b) { return box_distance2(box, b) <= r2; },
          [&](std::uint32_t first, std::uint32_t count) {
            for (std::uint32_t s = first; s < first + count; ++s) keep(s, objs[s](c));
            return true;
          });
      std::sort(out.begin() + std::ptrdiff_t(start), out.end());
      for (std::size_t k = start; k < out.size(); ++k) gaps[k] = gap(objs[out[k]](c));
    } else {
      for (std::uint32_t j = 0; j < m; ++j) keep(parent[j], values[j]);
    }
  }

  void build(const Options& opt) {
    const auto& objs = union_.objects();
    if (objs.empty() || objs.size() > index_mask) return;
    Aabb<T> region = opt.region;
    if (region.is_empty()) {
      region = union_.tree().box;
      region = region.grown(opt.margin * max_component(region.extent()));
    }
    const Vec3<T> ext = region.extent();
    if (!all_finite(region.lo) || !all_finite(region.hi) || !(min_component(ext) > T(0))) return;
    const std::size_t cap_words = std::min<std::size_t>(opt.max_bytes, std::size_t(1) << 32) / 4;

    // Top grid: near-cubic cells, about top_cells_per_object per object, within the cap. It
    // refines a seed grid of about one cell per object `seed` times by octants, so that only the
    // seed cells search the BVH and the top cells filter their lists (8^seed times fewer
    // searches; the lists are the same or shorter, and as exact).
    const double volume = double(ext.x) * double(ext.y) * double(ext.z);
    const double per_object = std::max(opt.top_cells_per_object, 1.0 / double(objs.size()));
    double side = std::cbrt(volume / (per_object * double(objs.size())));
    int seed = 0;
    while (seed < 4 && per_object >= std::ldexp(1.0, 3 * (seed + 1))) ++seed;
    std::size_t ncells = 0;
    for (;; side *= 1.25) {
      bool single = true;
      for (int a = 0; a < 3; ++a) {
        const double cells = std::round(double(ext[a]) / std::ldexp(side, seed));
        dims_[a] = std::uint32_t(std::clamp(cells, 1.0, std::ldexp(1.0, 20 - seed))) << seed;
        single = single && cells <= 1.0;
      }
      ncells = std::size_t(dims_[0]) * dims_[1] * dims_[2];
      if (ncells + 1 <= cap_words) break;
      if (single) { // max_bytes is very small: refine less
        if (seed == 0) return;
        --seed;
      }
    }
    region_ = region;
    // Cell coordinates at the deepest level must fit in 32 bits.
    int max_depth = std::clamp(opt.max_depth, 0, 16);
    for (int a = 0; a < 3; ++a)
      while (max_depth > 0 && (std::uint64_t(dims_[a]) << max_depth) > (std::uint64_t(1) << 31))
        --max_depth;
    for (int a = 0; a < 3; ++a) inv_[a] = T(dims_[a]) / ext[a];
    T scale = T(0);
    for (const Aabb<T>& b : {region, union_.tree().box})
      for (int a = 0; a < 3; ++a) scale = std::max({scale, std::abs(b.lo[a]), std::abs(b.hi[a])});
    slack_ = T(1024) * std::numeric_limits<T>::epsilon() * scale;
    for (int l = 0; l <= max_depth; ++l) {
      const Geometry g = geometry(l);
      level_size_[l] = g.size;
      gap_per_unit_[l] = g.gap_per_unit;
    }
    top_.assign(ncells, 0);
    lists_.assign(1, 0); // the shared empty list
    stats_.top_cells = ncells;
    for (int a = 0; a < 3; ++a) stats_.dims[a] = dims_[a];

    // The seed cells' candidates from the BVH, then every seed cell refined `seed` times.
    std::vector<Cell> cells, next;
    for (std::uint32_t z = 0; z < dims_[2] >> seed; ++z)
      for (std::uint32_t y = 0; y < dims_[1] >> seed; ++y)
        for (std::uint32_t x = 0; x < dims_[0] >> seed; ++x)
          cells.push_back({{x, y, z}, 0, cells.size()});
    Lists lists, kids;
    lists.reset(cells.size(), cells_per_task);
    const Geometry seed_geometry = geometry(-seed);
    parallel_for(
        0, cells.size(), cells_per_task,
        [&](std::size_t begin, std::size_t end) {
          std::vector<T> values;
          for (std::size_t k = begin; k < end; ++k) {
            auto& buf = lists.buf[k / cells_per_task];
            lists.first[k] = std::uint32_t(buf.size());
            candidates(cell_box(cells[k].i, seed_geometry), seed_geometry, nullptr, 0, values, buf,
                       lists.gaps[k / cells_per_task]);
            lists.count[k] = std::uint32_t(buf.size() - lists.first[k]);
          }
        },
        opt.exec);
    for (int level = -seed + 1; level <= 0; ++level) {
      const Geometry g = geometry(level);
      kids.reset(8 * cells.size(), 8 * cells_per_task);
      parallel_for(
          0, cells.size(), cells_per_task,
          [&](std::size_t begin, std::size_t end) {
            std::vector<T> values;
            for (std::size_t t = begin; t < end; ++t)
              child_lists(cells[t], lists, t, g, values, kids);
          },
          opt.exec);
      next.clear();
      for (std::size_t t = 0; t < cells.size(); ++t)
        for (std::uint32_t o = 0; o < 8; ++o) {
          Cell child{{}, 0, 8 * t + o};
          for (int a = 0; a < 3; ++a) child.i[a] = 2 * cells[t].i[a] + ((o >> a) & 1);
          next.push_back(child);
        }
      std::swap(cells, next);
      std::swap(lists, kids);
    }
    for (Cell& c : cells) c.word_at = (std::size_t(c.i[2]) * dims_[1] + c.i[1]) * dims_[0] + c.i[0];
    for (int level = 0; !cells.empty(); ++level) {
      stats_.depth = level;
      const std::size_t n = cells.size();
      auto count = [&](std::size_t k) { return lists.count[cells[k].item]; };
      // Cells with long lists try a split: the lists of the 8 children of the t-th trying cell
      // (items 8t + o of `kids`) are computed, and the split is wanted when it cuts the mean
      // list enough (min_split_gain). A split cannot cut more than the whole list: cells for
      // which even that is too little do not try.
      std::vector<unsigned char> want(n, 0);
      std::vector<std::uint32_t> tries, try_of(n, 0);
      // The cell's volume over the region's volume per bounded object.
      const double cell_volume = std::ldexp(double(objs.size()) / double(ncells), -3 * level);
      for (std::size_t k = 0; k < n && level < max_depth; ++k)
        if (count(k) > opt.max_candidates && double(count(k)) * cell_volume >= opt.min_split_gain) {
          try_of[k] = std::uint32_t(tries.size());
          tries.push_back(std::uint32_t(k));
        }
      kids.reset(8 * tries.size(), 8 * cells_per_task);
      const Geometry child_geometry = geometry(level + 1);
      parallel_for(
          0, tries.size(), cells_per_task,
          [&](std::size_t begin, std::size_t end) {
            std::vector<T> values;
            for (std::size_t t = begin; t < end; ++t) {
              const std::size_t k = tries[t];
              child_lists(cells[k], lists, t, child_geometry, values, kids);
              std::size_t total = 0;
              for (std::uint32_t o = 0; o < 8; ++o) total += kids.count[8 * t + o];
              want[k] = (double(count(k)) - double(total) / 8) * cell_volume >= opt.min_split_gain;
            }
          },
          opt.exec);
      // What each cell becomes, within the cap. A leaf costs its list (1 + m words and m gap
      // bytes; nothing for one candidate, which the word holds, or for none, which shares
      // lists_[0]); a split costs 8 words and its children's lists instead. Longest lists are
      // split first.
      auto list_words = [](std::uint32_t m) -> std::size_t {
        return m >= 2 ? 1 + m + (m + 3) / 4 : 0;
      };
      std::size_t used = top_.size() + nodes_.size() + lists_.size();
      for (std::size_t k = 0; k < n; ++k) used += list_words(count(k));
      std::vector<std::uint32_t> order(n);
      std::iota(order.begin(), order.end(), 0u);
      std::stable_sort(order.begin(), order.end(),
                       [&](std::uint32_t a, std::uint32_t b) { return count(a) > count(b); });
      std::vector<std::uint32_t> fate(n, list_tag);
      for (std::uint32_t k : order) {
        if (used > cap_words && list_words(count(k)) > 0) { // only at the top level
          used -= list_words(count(k));
          fate[k] = fallback_tag;
          stats_.capped = true;
        } else if (want[k]) {
          std::size_t extra = 8;
          for (std::size_t o = 0; o < 8; ++o) extra += list_words(kids.count[8 * try_of[k] + o]);
          extra -= list_words(count(k));
          if (used + extra <= cap_words) {
            used += extra;
            fate[k] = split_tag;
          } else {
            stats_.capped = true;
          }
        }
      }
      next.clear();
      const double volume_share = std::ldexp(1.0, -3 * level) / double(ncells);
      for (std::size_t k = 0; k < n; ++k) {
        const std::uint32_t m = count(k);
        std::uint32_t w = word(fallback_tag, 0);
        if (fate[k] == split_tag) {
          const std::size_t g = nodes_.size() / 8;
          w = word(split_tag, g);
          nodes_.resize(nodes_.size() + 8, word(fallback_tag, 0));
          for (std::uint32_t o = 0; o < 8; ++o) {
            Cell child{{}, g * 8 + o, 8 * std::size_t(try_of[k]) + o};
            for (int a = 0; a < 3; ++a) child.i[a] = 2 * cells[k].i[a] + ((o >> a) & 1);
            next.push_back(child);
          }
          ++stats_.split_cells;
        } else if (fate[k] == fallback_tag) {
          ++stats_.fallback_cells;
        } else {
          const std::uint32_t* l = lists.of(cells[k].item);
          if (m == 1) {
            w = l[0];
          } else {
            // An empty list (an unbounded object wins everywhere in the cell) is lists_[0].
            w = word(list_tag, m == 0 ? 0 : lists_.size());
            if (m > 0) {
              lists_.push_back(m);
              lists_.insert(lists_.end(), l, l + m);
              const std::size_t at = lists_.size();
              lists_.resize(at + (m + 3) / 4, 0);
              std::memcpy(lists_.data() + at, lists.gaps_of(cells[k].item), m);
            }
          }
          ++stats_.leaf_cells;
          stats_.candidates += m;
          stats_.longest_list = std::max<std::size_t>(stats_.longest_list, m);
          stats_.mean_candidates += volume_share * m;
          stats_.mean_level += volume_share * level;
        }
        (level == 0 ? top_[cells[k].word_at] : nodes_[cells[k].word_at]) = w;
      }
      std::swap(cells, next);
      std::swap(lists, kids);
    }
    stats_.bytes = (top_.size() + nodes_.size() + lists_.size()) * sizeof(std::uint32_t);
    top_.shrink_to_fit();
    nodes_.shrink_to_fit();
    lists_.shrink_to_fit();
  }

  BvhUnion<S, K> union_;
  Aabb<T> region_;
  Vec3<T> inv_{};              // top cells per unit length, per axis
  std::uint32_t dims_[3] = {}; // top grid resolution
  T slack_ = T(0);
  Vec3<T> level_size_[17] = {}; // cell size per octree level
  T gap_per_unit_[17] = {};
  std::vector<std::uint32_t> top_;   // one word per top cell, x fastest
  std::vector<std::uint32_t> nodes_; // 8 words per split cell
  std::vector<std::uint32_t> lists_; // [n, slot_1 .. slot_n] per leaf cell with n >= 2
  UnionCacheStats stats_;
};

} // namespace ebgeom
