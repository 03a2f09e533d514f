// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Experimental, for bench/ only (no stability promise; not in any umbrella header): variants of
/// `bvh::nearest` (`bvh/traverse.hpp`) that EBGeometry lists, kept to measure what the production
/// search gains over them. Same results as `nearest` (tested); slower.
/// - `nearest_unordered`: children pushed in storage order, no nearest-first ordering;
/// - `nearest_recursive`: recursion, nearest child first, children sorted with `std::sort`.

#include <algorithm>

#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom::bvh::experimental {

/// `nearest` without ordering: children are pushed in storage order (for comparison in bench/).
template <class T, int K, class BV, class LeafFn>
void nearest_unordered(const WideBvh<T, K, BV>& bvh, const Vec3<T>& p, T& best2,
                       LeafFn&& leaf) noexcept {
  if (bvh.root.is_empty()) return;
  FixedStack<Pending<T>, WideBvh<T, K, BV>::stack_capacity> todo;
  todo.push({bvh.root, bvh.box.distance2(p)});
  while (!todo.empty()) {
    const Pending<T> top = todo.pop();
    if (!(top.dist2 < prune_limit(best2))) continue;
    if (top.ref.is_leaf()) {
      leaf(top.ref.index, top.ref.count, best2);
      continue;
    }
    const auto& n = bvh.nodes[top.ref.index];
    T d2[K];
    child_dist2(n, p, d2);
    const T lim = prune_limit(best2);
    for (int k = 0; k < K; ++k)
      if (d2[k] < lim) todo.push({n.child[k], d2[k]});
  }
}

template <class T, int K, class BV, class LeafFn>
void nearest_recursive_at(const WideBvh<T, K, BV>& bvh, const ChildRef ref, const Vec3<T>& p,
                          T& best2, LeafFn& leaf) noexcept {
  if (ref.is_leaf()) {
    leaf(ref.index, ref.count, best2);
    return;
  }
  const auto& n = bvh.nodes[ref.index];
  T d2[K];
  child_dist2(n, p, d2);
  int order[K];
  for (int k = 0; k < K; ++k) order[k] = k;
  std::sort(order, order + K, [&](int a, int b) { return d2[a] < d2[b]; });
  for (int j = 0; j < K; ++j)
    if (d2[order[j]] < prune_limit(best2))
      nearest_recursive_at(bvh, n.child[order[j]], p, best2, leaf);
}

/// `nearest` by recursion, nearest child first (EBGeometry's recursive variant; for bench/).
template <class T, int K, class BV, class LeafFn>
void nearest_recursive(const WideBvh<T, K, BV>& bvh, const Vec3<T>& p, T& best2,
                       LeafFn&& leaf) noexcept {
  if (bvh.root.is_empty() || !(bvh.box.distance2(p) < prune_limit(best2))) return;
  nearest_recursive_at(bvh, bvh.root, p, best2, leaf);
}

} // namespace ebgeom::bvh::experimental
