// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// BVH construction: the index-based builder tree `BuildTree<T>` and the builders that make it.
///
/// Builders know nothing about triangles or shapes: they take one box and one centroid per
/// primitive. Top-down construction is driven by two function objects (template parameters, never
/// `std::function` per node): a *stop* predicate that decides whether a node becomes a leaf, and a
/// *partition* that splits a node's primitives into 2..16 parts. Ready ones:
///  - `SahPartition`: binned surface-area heuristic (binary splits; the default);
///  - `MedianPartition`: split at the median centroid along the longest axis (binary);
///  - `ChunkPartition<K>`: EBGeometry's partitioner: sort centroids along the longest
///    axis of their box and cut into K equal chunks (K-ary);
///  - `LeafSizeStop`: leaf when a node holds at most `max_leaf_size` primitives.
/// `build_sah` makes `build_top_down(SahPartition, LeafSizeStop)`'s tree, faster (it is what
/// `build` runs). `build_morton` is the bottom-up alternative: 63-bit Morton codes of the
/// centroids, sorted, and a hierarchy split at the highest differing bit (LBVH).
///
/// The types, partitions and `build_top_down` live in `bvh/build_tree.hpp`, `build_sah` in
/// `bvh/build_sah.hpp`; this header includes both and adds `build_morton` and `build`.
///
/// Depth is bounded by `max_build_depth` (a node that deep becomes a leaf whatever its size), and
/// a partition that returns no useful split is replaced by an index-median split, so every build
/// terminates and the traversal stack size proven from the depth is always enough.

#include <algorithm>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "ebgeom/bvh/build_sah.hpp"
#include "ebgeom/bvh/build_tree.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/error.hpp"
#include "ebgeom/core/morton.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom::bvh {

namespace detail {
/// Index of the highest set bit of `v` (v != 0).
inline int highest_bit(std::uint64_t v) noexcept {
  int b = 0;
  while (v >>= 1) ++b;
  return b;
}
} // namespace detail

/// 63-bit Morton code of `p` quantised to 2^21 cells per axis of `box`.
template <class T> std::uint64_t morton_code(const Vec3<T>& p, const Aabb<T>& box) noexcept {
  const Vec3<T> e = box.extent();
  std::uint64_t q[3];
  for (int a = 0; a < 3; ++a) {
    const T u = e[a] > T(0) ? (p[a] - box.lo[a]) / e[a] : T(0);
    const double c = std::min(std::max(double(u) * 2097152.0, 0.0), 2097151.0);
    q[a] = std::uint64_t(c);
  }
  return morton_encode(q[0], q[1], q[2]);
}

namespace detail {
/// Sorts (key, index) pairs by key, stably: a least-significant-digit radix sort with 16-bit
/// digits (digits equal in every key are skipped), `std::stable_sort` below 4,096 elements.
/// Given pairs in index order, the result is the order of (key, index), as `std::sort` on pairs.
inline void radix_sort_keys(std::vector<std::pair<std::uint64_t, std::uint32_t>>& v) {
  using Item = std::pair<std::uint64_t, std::uint32_t>;
  const std::size_t n = v.size();
  if (n < 4096) {
    std::stable_sort(v.begin(), v.end(),
                     [](const Item& a, const Item& b) { return a.first < b.first; });
    return;
  }
  std::uint64_t all_and = ~0ULL, all_or = 0;
  for (const Item& it : v) all_and &= it.first, all_or |= it.first;
  const std::uint64_t varying = all_and ^ all_or; // bits that differ between some keys
  std::vector<Item> tmp(n);
  std::vector<std::size_t> count(65536);
  for (int shift = 0; shift < 64; shift += 16) {
    if (((varying >> shift) & 0xffff) == 0) continue;
    std::fill(count.begin(), count.end(), 0);
    for (const Item& it : v) ++count[(it.first >> shift) & 0xffff];
    std::size_t sum = 0;
    for (std::size_t& c : count) {
      const std::size_t k = c;
      c = sum;
      sum += k;
    }
    for (const Item& it : v) tmp[count[(it.first >> shift) & 0xffff]++] = it;
    v.swap(tmp);
  }
}
} // namespace detail

/// Bottom-up construction (LBVH): Morton codes of the centroids, sorted (ties by index), then a
/// binary hierarchy split at the highest bit that differs within each range (the middle when all
/// codes are equal); ranges of at most `max_leaf_size` primitives become leaves. The same tree as
/// `build_top_down` with that split, but the codes are radix-sorted and the boxes are computed
/// bottom up (each primitive's box is read once, in Morton order), so it is O(n) after the sort.
template <class T>
BuildTree<T> build_morton(Span<const Aabb<T>> boxes, Span<const Vec3<T>> centroids,
                          std::uint32_t max_leaf_size = 4) {
  EBGEOM_ASSERT(boxes.size() == centroids.size());
  BuildTree<T> tree;
  const std::uint32_t n = std::uint32_t(boxes.size());
  if (n == 0) return tree;
  const std::uint32_t leaf = std::max<std::uint32_t>(1, max_leaf_size);
  Aabb<T> cbox;
  for (const auto& c : centroids) cbox.extend(c);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  for (std::uint32_t i = 0; i < n; ++i) keys[i] = {morton_code(centroids[i], cbox), i};
  detail::radix_sort_keys(keys);
  tree.prim.resize(n);
  for (std::uint32_t i = 0; i < n; ++i) tree.prim[i] = keys[i].second;
  // Where a sorted range of codes splits: after the last code below the highest differing bit.
  auto split = [&](std::uint32_t begin, std::uint32_t end) -> std::uint32_t {
    const std::uint64_t a = keys[begin].first, b = keys[end - 1].first;
    if (a == b) return (end - begin) / 2;
    const int bit = detail::highest_bit(a ^ b);
    const std::uint64_t mask = ~0ULL << bit;
    const std::uint64_t prefix = (a & mask) | (1ULL << bit);
    std::uint32_t lo = begin, hi = end;
    while (lo < hi) {
      const std::uint32_t mid = lo + (hi - lo) / 2;
      if ((keys[mid].first & mask) < prefix)
        lo = mid + 1;
      else
        hi = mid;
    }
    return lo - begin;
  };
  // Topology top down, in build_top_down's node order (children consecutive, after the parent).
  tree.nodes.reserve(2 * std::size_t(n / leaf + 1));
  tree.nodes.emplace_back();
  struct Task {
    std::uint32_t node, begin, end;
    int depth;
  };
  std::vector<Task> todo{{0, 0, n, 0}};
  while (!todo.empty()) {
    const Task t = todo.back();
    todo.pop_back();
    tree.depth = std::max(tree.depth, t.depth + 1);
    const std::uint32_t count = t.end - t.begin;
    BuildNode<T>& node = tree.nodes[t.node];
    if (count <= 1 || t.depth >= max_build_depth || count <= leaf) {
      node.first = t.begin, node.count = count, node.children = 0;
      continue;
    }
    const std::uint32_t mid = split(t.begin, t.end);
    const std::uint32_t first_child = std::uint32_t(tree.nodes.size());
    node.first = first_child, node.count = 0, node.children = 2;
    tree.nodes.resize(tree.nodes.size() + 2);
    todo.push_back({first_child + 1, t.begin + mid, t.end, t.depth + 1});
    todo.push_back({first_child, t.begin, t.begin + mid, t.depth + 1});
  }
  // Boxes bottom up: children come after their parent, so a reverse pass sees them first.
  for (std::size_t i = tree.nodes.size(); i-- > 0;) {
    BuildNode<T>& node = tree.nodes[i];
    Aabb<T> b;
    if (node.is_leaf())
      for (std::uint32_t j = node.first; j < node.first + node.count; ++j)
        b.extend(boxes[tree.prim[j]]);
    else
      for (std::uint32_t c = node.first; c < node.first + node.children; ++c)
        b.extend(tree.nodes[c].box);
    node.box = b;
  }
  return tree;
}

/// `invalid_argument` when `options.method` is not one of the listed `BuildMethod` values (what
/// the checked `make` functions of the BVH-based SDFs return for it), else ok.
inline Error check(const BuildOptions& options) {
  if (!is_valid(options.method))
    return {ErrorCode::invalid_argument, "BVH build: BuildMethod value " +
                                             std::to_string(int(options.method)) +
                                             " is none of sah_binned, median, morton"};
  return {};
}

/// The ready-made builder: `options.method` with `LeafSizeStop{options.max_leaf_size}`.
/// Precondition: `is_valid(options.method)` (`check(options)`); another value aborts with a
/// message in every build, never silently building with another method.
template <class T>
BuildTree<T> build(Span<const Aabb<T>> boxes, Span<const Vec3<T>> centroids,
                   const BuildOptions& options = {}) {
  EBGEOM_PRECONDITION(is_valid(options.method), "bvh::build: BuildMethod value out of range");
  const std::uint32_t leaf = std::max<std::uint32_t>(1, options.max_leaf_size);
  switch (options.method) {
  case BuildMethod::median:
    return build_top_down<T>(boxes, centroids, MedianPartition{}, LeafSizeStop{leaf});
  case BuildMethod::morton:
    return build_morton<T>(boxes, centroids, leaf);
  case BuildMethod::sah_binned:
    break;
  }
  return build_sah<T>(boxes, centroids,
                      SahPartition{options.bins, options.block, options.longest_axis_above}, leaf);
}

} // namespace ebgeom::bvh
