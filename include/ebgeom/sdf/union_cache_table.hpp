// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// The frozen candidate cache of `CachedUnion` (`sdf/cached_union.hpp`): a grid of top cells over
/// a region, cells split into octants, and per leaf cell a word (one candidate, a list of
/// candidates with their gap bytes, a split, or "ask the BVH"); `locate` finds a point's cell and
/// `for_each_candidate` walks the candidates that can be the minimum at that point. Built by
/// `sdf/union_cache_build.hpp`; see `sdf/cached_union.hpp` for why the lists are exact.

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/union_cache_options.hpp"

namespace ebgeom::detail {

/// A union's candidate cache over scalar type `T` (plain data filled by `UnionCacheBuilder`;
/// empty `top`: no cache). Immutable once built; queries are thread-safe.
template <class T> struct UnionCacheTable {
  // A cell's 32-bit word: the top two bits say what it is, the other 30 an index.
  static constexpr std::uint32_t single_tag = 0;   // the one candidate's slot
  static constexpr std::uint32_t list_tag = 1;     // offset of [n, slots, gaps] in lists
  static constexpr std::uint32_t split_tag = 2;    // first of 8 child words in nodes, / 8
  static constexpr std::uint32_t fallback_tag = 3; // the BVH answers
  static constexpr std::uint32_t index_mask = (std::uint32_t(1) << 30) - 1;
  static constexpr std::uint32_t word(std::uint32_t tag, std::size_t index) noexcept {
    return (tag << 30) | std::uint32_t(index);
  }

  /// The word of the top cell holding `p` and `p`'s coordinates in it (in [0, 1)), or null
  /// outside the region (or without a cache). The one rounding here is covered by the slack.
  const std::uint32_t* top_word(const Vec3<T>& p, T (&u)[3]) const noexcept {
    if (top.empty()) return nullptr;
    std::uint32_t i[3];
    for (int a = 0; a < 3; ++a) {
      u[a] = (p[a] - region.lo[a]) * inv[a];
      if (!(u[a] >= T(0) && u[a] < T(dims[a]))) return nullptr;
      i[a] = std::uint32_t(u[a]);
      u[a] -= T(i[a]);
    }
    return &top[(std::size_t(i[2]) * dims[1] + i[1]) * dims[0] + i[0]];
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
    return &nodes[std::size_t(w & index_mask) * 8 + octant];
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
    const std::uint32_t* list = lists.data() + (*at.w & index_mask);
    const std::uint32_t n = list[0];
    const auto* gaps = reinterpret_cast<const unsigned char*>(list + 1 + n);
    T d2 = T(0);
    for (int a = 0; a < 3; ++a) {
      const T x = (at.u[a] - T(0.5)) * level_size[at.level][a];
      d2 += x * x;
    }
    // Kept when gap <= 2d + slack, in gap bytes, rounded towards keeping. (Comparing squares
    // instead, without this square root, measured slower.)
    constexpr T up = T(1) + T(8) * std::numeric_limits<T>::epsilon();
    const T limit = (T(2) * std::sqrt(d2) * up + slack) * gap_per_unit[at.level] * up;
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

  Aabb<T> region;
  Vec3<T> inv{};              // top cells per unit length, per axis
  std::uint32_t dims[3] = {}; // top grid resolution
  T slack = T(0);
  Vec3<T> level_size[17] = {}; // cell size per octree level
  T gap_per_unit[17] = {};
  std::vector<std::uint32_t> top;   // one word per top cell, x fastest
  std::vector<std::uint32_t> nodes; // 8 words per split cell
  std::vector<std::uint32_t> lists; // [n, slot_1 .. slot_n] per leaf cell with n >= 2
  UnionCacheStats stats;
};

} // namespace ebgeom::detail
