// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Builds `CachedUnion`'s candidate cache (`detail::UnionCacheTable`, sdf/union_cache_table.hpp)
/// over a `BvhUnion`: seed cells searched in the BVH, refined to the top grid by octants, then
/// cells with long lists split where that pays, within the memory cap (see the costs in
/// sdf/cached_union.hpp). Parallel; the result does not depend on the thread count.

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
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/union_cache_options.hpp"
#include "ebgeom/sdf/union_cache_table.hpp"

namespace ebgeom::detail {

/// Fills a `UnionCacheTable` for the objects of `union_` (`build`).
template <class S, int K> class UnionCacheBuilder {
 public:
  using T = sdf_scalar_t<S>;
  using Table = UnionCacheTable<T>;

  UnionCacheBuilder(const BvhUnion<S, K>& u, Table& c) noexcept : union_(u), c_(c) {}

  /// Builds the cache with `opt` (leaves the table empty when no cache can be built: no
  /// objects, more than 2^30, or a region without positive extent).
  void build(const UnionCacheOptions<T>& opt);

 private:
  /// A cell of the level being built: integer coordinates at that level, where its word goes
  /// (c_.top at level 0, c_.nodes below) and which item of the level's `Lists` holds its
  /// candidates.
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
      g.size[a] = c_.region.extent()[a] / T(level >= 0 ? std::uint64_t(c_.dims[a]) << level
                                                       : std::uint64_t(c_.dims[a]) >> -level);
    g.h = T(0.5) * norm(g.size) * (T(1) + T(8) * std::numeric_limits<T>::epsilon());
    g.gap_per_unit = T(255) / (T(2) * g.h + c_.slack);
    return g;
  }
  Aabb<T> cell_box(const std::uint32_t (&i)[3], const Geometry& g) const noexcept {
    Aabb<T> box;
    for (int a = 0; a < 3; ++a) {
      box.lo[a] = c_.region.lo[a] + T(i[a]) * g.size[a];
      box.hi[a] = c_.region.lo[a] + T(i[a] + 1) * g.size[a];
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
    const T limit = u + T(2) * h + c_.slack;
    const T r = std::max(u + h, T(0)) + c_.slack;
    const T r2 = r * r * (T(1) + T(8) * eps);
    // The gap byte rounds (v - u) down in units of 1/c_.gap_per_unit; NaN gives 0 (never skipped).
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

  const BvhUnion<S, K>& union_;
  Table& c_;
};

template <class S, int K> void UnionCacheBuilder<S, K>::build(const UnionCacheOptions<T>& opt) {
  const auto& objs = union_.objects();
  if (objs.empty() || objs.size() > Table::index_mask) return;
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
      c_.dims[a] = std::uint32_t(std::clamp(cells, 1.0, std::ldexp(1.0, 20 - seed))) << seed;
      single = single && cells <= 1.0;
    }
    ncells = std::size_t(c_.dims[0]) * c_.dims[1] * c_.dims[2];
    if (ncells + 1 <= cap_words) break;
    if (single) { // max_bytes is very small: refine less
      if (seed == 0) return;
      --seed;
    }
  }
  c_.region = region;
  // Cell coordinates at the deepest level must fit in 32 bits.
  int max_depth = std::clamp(opt.max_depth, 0, 16);
  for (int a = 0; a < 3; ++a)
    while (max_depth > 0 && (std::uint64_t(c_.dims[a]) << max_depth) > (std::uint64_t(1) << 31))
      --max_depth;
  for (int a = 0; a < 3; ++a) c_.inv[a] = T(c_.dims[a]) / ext[a];
  T scale = T(0);
  for (const Aabb<T>& b : {region, union_.tree().box})
    for (int a = 0; a < 3; ++a) scale = std::max({scale, std::abs(b.lo[a]), std::abs(b.hi[a])});
  c_.slack = T(1024) * std::numeric_limits<T>::epsilon() * scale;
  for (int l = 0; l <= max_depth; ++l) {
    const Geometry g = geometry(l);
    c_.level_size[l] = g.size;
    c_.gap_per_unit[l] = g.gap_per_unit;
  }
  c_.top.assign(ncells, 0);
  c_.lists.assign(1, 0); // the shared empty list
  c_.stats.top_cells = ncells;
  for (int a = 0; a < 3; ++a) c_.stats.dims[a] = c_.dims[a];

  // The seed cells' candidates from the BVH, then every seed cell refined `seed` times.
  std::vector<Cell> cells, next;
  for (std::uint32_t z = 0; z < c_.dims[2] >> seed; ++z)
    for (std::uint32_t y = 0; y < c_.dims[1] >> seed; ++y)
      for (std::uint32_t x = 0; x < c_.dims[0] >> seed; ++x)
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
  for (Cell& c : cells)
    c.word_at = (std::size_t(c.i[2]) * c_.dims[1] + c.i[1]) * c_.dims[0] + c.i[0];
  for (int level = 0; !cells.empty(); ++level) {
    c_.stats.depth = level;
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
    // c_.lists[0]); a split costs 8 words and its children's lists instead. Longest lists are
    // split first.
    auto list_words = [](std::uint32_t m) -> std::size_t {
      return m >= 2 ? 1 + m + (m + 3) / 4 : 0;
    };
    std::size_t used = c_.top.size() + c_.nodes.size() + c_.lists.size();
    for (std::size_t k = 0; k < n; ++k) used += list_words(count(k));
    std::vector<std::uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    std::stable_sort(order.begin(), order.end(),
                     [&](std::uint32_t a, std::uint32_t b) { return count(a) > count(b); });
    std::vector<std::uint32_t> fate(n, Table::list_tag);
    for (std::uint32_t k : order) {
      if (used > cap_words && list_words(count(k)) > 0) { // only at the top level
        used -= list_words(count(k));
        fate[k] = Table::fallback_tag;
        c_.stats.capped = true;
      } else if (want[k]) {
        std::size_t extra = 8;
        for (std::size_t o = 0; o < 8; ++o) extra += list_words(kids.count[8 * try_of[k] + o]);
        extra -= list_words(count(k));
        if (used + extra <= cap_words) {
          used += extra;
          fate[k] = Table::split_tag;
        } else {
          c_.stats.capped = true;
        }
      }
    }
    next.clear();
    const double volume_share = std::ldexp(1.0, -3 * level) / double(ncells);
    for (std::size_t k = 0; k < n; ++k) {
      const std::uint32_t m = count(k);
      std::uint32_t w = Table::word(Table::fallback_tag, 0);
      if (fate[k] == Table::split_tag) {
        const std::size_t g = c_.nodes.size() / 8;
        w = Table::word(Table::split_tag, g);
        c_.nodes.resize(c_.nodes.size() + 8, Table::word(Table::fallback_tag, 0));
        for (std::uint32_t o = 0; o < 8; ++o) {
          Cell child{{}, g * 8 + o, 8 * std::size_t(try_of[k]) + o};
          for (int a = 0; a < 3; ++a) child.i[a] = 2 * cells[k].i[a] + ((o >> a) & 1);
          next.push_back(child);
        }
        ++c_.stats.split_cells;
      } else if (fate[k] == Table::fallback_tag) {
        ++c_.stats.fallback_cells;
      } else {
        const std::uint32_t* l = lists.of(cells[k].item);
        if (m == 1) {
          w = l[0];
        } else {
          // An empty list (an unbounded object wins everywhere in the cell) is c_.lists[0].
          w = Table::word(Table::list_tag, m == 0 ? 0 : c_.lists.size());
          if (m > 0) {
            c_.lists.push_back(m);
            c_.lists.insert(c_.lists.end(), l, l + m);
            const std::size_t at = c_.lists.size();
            c_.lists.resize(at + (m + 3) / 4, 0);
            std::memcpy(c_.lists.data() + at, lists.gaps_of(cells[k].item), m);
          }
        }
        ++c_.stats.leaf_cells;
        c_.stats.candidates += m;
        c_.stats.longest_list = std::max<std::size_t>(c_.stats.longest_list, m);
        c_.stats.mean_candidates += volume_share * m;
        c_.stats.mean_level += volume_share * level;
      }
      (level == 0 ? c_.top[cells[k].word_at] : c_.nodes[cells[k].word_at]) = w;
    }
    std::swap(cells, next);
    std::swap(lists, kids);
  }
  c_.stats.bytes = (c_.top.size() + c_.nodes.size() + c_.lists.size()) * sizeof(std::uint32_t);
  c_.top.shrink_to_fit();
  c_.nodes.shrink_to_fit();
  c_.lists.shrink_to_fit();
}

} // namespace ebgeom::detail
