// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Options, statistics and the per-point view of `CachedUnion`'s candidate cache
/// (`sdf/cached_union.hpp`).

#include <cstddef>
#include <cstdint>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/span.hpp"

namespace ebgeom {

/// Options of `CachedUnion`'s candidate cache.
template <class T> struct UnionCacheOptions {
  /// Region the cache covers; queries outside it use the BVH. Empty (the default): the box of the
  /// bounded objects grown on every side by `margin` times its longest side. Must have a positive
  /// extent on every axis, or no cache is built.
  Aabb<T> region = Aabb<T>::empty();
  T margin = T(0.0625);
  /// Cells of the top grid per bounded object (near-cubic cells over the region): 4 bytes each.
  /// The top grid refines a seed grid of about one cell per object (only those search the BVH).
  double top_cells_per_object = 8.0;
  /// A cell with more candidates than this may be split into octants, up to `max_depth` levels
  /// below the top grid and while `max_bytes` allows.
  std::uint32_t max_candidates = 4;
  /// A split is kept only when (the cut in the mean list length over its 8 octants) times (the
  /// cell's volume over the region's volume per bounded object) is at least this: splits go
  /// where they save the most work for uniformly random queries, and stop around points where
  /// many objects are equally near (where no split shortens the lists).
  double min_split_gain = 1.0;
  int max_depth = 8; ///< clamped to [0, 16]
  /// Hard cap on the cache (top grid, split cells and lists; at most 4 GiB). Splits that might
  /// exceed it are not made (longest lists are split first) and, if even the top grid's lists do
  /// not fit, the top cells with the longest lists fall back to the BVH.
  std::size_t max_bytes = std::size_t(256) << 20;
  /// Threads for the build.
  ExecOptions exec{};
};

/// What a `CachedUnion`'s cache holds.
struct UnionCacheStats {
  std::uint32_t dims[3] = {0, 0, 0}; ///< top grid resolution per axis
  std::size_t top_cells = 0;         ///< cells of the top grid
  std::size_t leaf_cells = 0;        ///< cells holding candidates (not split, not falling back)
  std::size_t split_cells = 0;       ///< cells split into octants
  std::size_t fallback_cells = 0;    ///< cells whose queries use the BVH
  std::size_t candidates = 0;        ///< total length of the leaf cells' lists
  std::size_t longest_list = 0;      ///< most candidates in one leaf cell
  int depth = 0;                     ///< deepest level reached below the top grid
  bool capped = false;               ///< `max_bytes` prevented a split or forced a fallback
  std::size_t bytes = 0;             ///< memory of the cache (not counting the BVH and objects)
  /// Mean candidates and octree level over the region's volume (the work of a uniformly random
  /// query in it, fallback cells left out).
  double mean_candidates = 0;
  double mean_level = 0;
};

/// Where a point's query goes: `cached` is false outside the region (or without a cache) and in
/// fallback cells, where the BVH answers; otherwise `slots` are the candidates (leaf-order slots
/// of `bvh_union().objects()`, ascending) and `level` the cell's level below the top grid.
struct UnionCacheCell {
  bool cached = false;
  Span<const std::uint32_t> slots;
  int level = 0;
  std::size_t evaluated = 0; ///< of them, those a query at this very point evaluates (gap test)
};

} // namespace ebgeom
