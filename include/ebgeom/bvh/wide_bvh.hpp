// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `WideBvh<T, K>`: the compact, flattened form of a BVH that every query uses. `flatten<K>`
/// collapses a builder tree (`bvh/build.hpp`) into K-wide nodes laid out depth first; each node
/// stores its K child boxes structure-of-arrays, so one loop bounds all children at once.
/// `refit` recomputes every box after primitives move (same topology).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/bounding_sphere.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/vec.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom::bvh {

/// Reference to a child of a wide node: an inner node, a leaf (a range of primitive slots in leaf
/// order), or nothing. 8 bytes.
struct ChildRef {
  static constexpr std::uint32_t none = ~std::uint32_t(0);
  std::uint32_t index = none; ///< inner: node index; leaf: first primitive slot; empty: `none`
  std::uint32_t count = 0;    ///< leaf: number of primitives (> 0); inner and empty: 0

  static constexpr ChildRef inner(std::uint32_t node) noexcept { return {node, 0}; }
  static constexpr ChildRef leaf(std::uint32_t first, std::uint32_t n) noexcept {
    return {first, n};
  }
  constexpr bool is_leaf() const noexcept { return count != 0; }
  constexpr bool is_inner() const noexcept { return count == 0 && index != none; }
  constexpr bool is_empty() const noexcept { return count == 0 && index == none; }
};

/// K-wide node with bounding volume `BV` per child, stored structure of arrays so one loop bounds
/// all children. Specialised for `Aabb<T>` (the default) and `BoundingSphere<T>`.
template <class T, int K, class BV = Aabb<T>> struct WideNode;

/// K-wide box node: the K child boxes as structure of arrays, then the K child references. An
/// empty slot has an empty box (lo = +inf, hi = -inf), so its distance from any point is +inf and
/// no traversal enters it. Size: 6·K·sizeof(T) + 8·K bytes (K = 4, float: 128 B, two cache lines).
template <class T, int K> struct WideNode<T, K, Aabb<T>> {
  static_assert(K >= 2 && K <= 16, "WideNode<T, K> needs 2 <= K <= 16");
  using bv_type = Aabb<T>;
  T lo_x[K], lo_y[K], lo_z[K], hi_x[K], hi_y[K], hi_z[K];
  ChildRef child[K];

  Aabb<T> child_box(int k) const noexcept {
    return {{lo_x[k], lo_y[k], lo_z[k]}, {hi_x[k], hi_y[k], hi_z[k]}};
  }
  void set_child_box(int k, const Aabb<T>& b) noexcept {
    lo_x[k] = b.lo.x, lo_y[k] = b.lo.y, lo_z[k] = b.lo.z;
    hi_x[k] = b.hi.x, hi_y[k] = b.hi.y, hi_z[k] = b.hi.z;
  }
  Aabb<T> child_bv(int k) const noexcept { return child_box(k); }
  void set_child_bv(int k, const Aabb<T>& b) noexcept { set_child_box(k, b); }
  /// Union of the child boxes.
  Aabb<T> bounds() const noexcept {
    Aabb<T> b;
    for (int k = 0; k < K; ++k)
      if (!child[k].is_empty()) b.extend(child_box(k));
    return b;
  }
};

/// K-wide sphere node: centres and radii structure of arrays. An empty slot has its centre at
/// +inf, so its distance is +inf. Size: 4·K·sizeof(T) + 8·K bytes (K = 4, float: 96 B).
template <class T, int K> struct WideNode<T, K, BoundingSphere<T>> {
  static_assert(K >= 2 && K <= 16, "WideNode<T, K> needs 2 <= K <= 16");
  using bv_type = BoundingSphere<T>;
  T cx[K], cy[K], cz[K], r[K];
  ChildRef child[K];

  BoundingSphere<T> child_bv(int k) const noexcept {
    if (!std::isfinite(cx[k])) return BoundingSphere<T>::empty();
    return {{cx[k], cy[k], cz[k]}, r[k]};
  }
  void set_child_bv(int k, const BoundingSphere<T>& s) noexcept {
    const T c = s.is_empty() ? std::numeric_limits<T>::infinity() : T(0);
    cx[k] = s.is_empty() ? c : s.center.x, cy[k] = s.is_empty() ? c : s.center.y;
    cz[k] = s.is_empty() ? c : s.center.z, r[k] = s.is_empty() ? T(0) : s.radius;
  }
  /// Box of child `k`'s sphere.
  Aabb<T> child_box(int k) const noexcept { return child_bv(k).bounds(); }
  /// Sphere enclosing the child spheres.
  BoundingSphere<T> bounds() const noexcept {
    BoundingSphere<T> b;
    for (int k = 0; k < K; ++k)
      if (!child[k].is_empty()) b = merge(b, child_bv(k));
    return b;
  }
};

/// The box of a bounding volume.
template <class T> Aabb<T> to_box(const Aabb<T>& b) noexcept { return b; }
template <class T> Aabb<T> to_box(const BoundingSphere<T>& s) noexcept { return s.bounds(); }

/// Squared distances from `p` to the K child spheres of `n` (0 inside, +inf for empty slots).
template <class T, int K>
EBGEOM_FORCE_INLINE void child_dist2(const WideNode<T, K, BoundingSphere<T>>& n, const Vec3<T>& p,
                                     T (&d2)[K]) noexcept {
  for (int k = 0; k < K; ++k) {
    const T dx = p.x - n.cx[k], dy = p.y - n.cy[k], dz = p.z - n.cz[k];
    const T d = std::max(std::sqrt(dx * dx + dy * dy + dz * dz) - n.r[k], T(0));
    d2[k] = d * d;
  }
}

/// Squared distances from `p` to the farthest point of each child sphere (+inf for empty slots).
template <class T, int K>
EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<T, K, BoundingSphere<T>>& n,
                                         const Vec3<T>& p, T (&d2)[K]) noexcept {
  for (int k = 0; k < K; ++k) {
    const T dx = p.x - n.cx[k], dy = p.y - n.cy[k], dz = p.z - n.cz[k];
    const T d = std::sqrt(dx * dx + dy * dy + dz * dz) + n.r[k];
    d2[k] = d * d;
  }
}

/// Squared distances from `p` to the K child boxes of `n` (0 inside, +inf for empty slots).
/// Branch-free: compiles to K-wide min/max.
template <class T, int K>
EBGEOM_FORCE_INLINE void child_dist2(const WideNode<T, K>& n, const Vec3<T>& p,
                                     T (&d2)[K]) noexcept {
  for (int k = 0; k < K; ++k) {
    const T dx = std::max(std::max(n.lo_x[k] - p.x, p.x - n.hi_x[k]), T(0));
    const T dy = std::max(std::max(n.lo_y[k] - p.y, p.y - n.hi_y[k]), T(0));
    const T dz = std::max(std::max(n.lo_z[k] - p.z, p.z - n.hi_z[k]), T(0));
    d2[k] = dx * dx + dy * dy + dz * dz;
  }
}

/// Squared distances from `p` to the farthest point of each child box (+inf for empty slots).
template <class T, int K>
EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<T, K>& n, const Vec3<T>& p,
                                         T (&d2)[K]) noexcept {
  for (int k = 0; k < K; ++k) {
    const T dx = std::max(p.x - n.lo_x[k], n.hi_x[k] - p.x);
    const T dy = std::max(p.y - n.lo_y[k], n.hi_y[k] - p.y);
    const T dz = std::max(p.z - n.lo_z[k], n.hi_z[k] - p.z);
    d2[k] = dx * dx + dy * dy + dz * dz;
  }
}

/// The compact BVH. `root` is an inner reference to `nodes[0]`, or a leaf when all primitives fit
/// in one leaf, or empty for zero primitives. `prim[slot]` is the input index of the primitive in
/// leaf slot `slot`. Immutable after construction: concurrent queries are safe.
template <class T, int K, class BV = Aabb<T>> struct WideBvh {
  static_assert(K >= 2 && K <= 16, "WideBvh<T, K> needs 2 <= K <= 16");
  using scalar_type = T;
  static constexpr int arity = K;
  /// Deepest tree `flatten` can make (a builder tree of depth <= max_build_depth + 1 whose nodes
  /// have up to 16 children, regrouped K at a time).
  static constexpr int max_depth = (max_build_depth + 1) * (K >= 16 ? 1 : (K >= 4 ? 2 : 4));
  /// Entries a nearest-first traversal stack can hold at most: (K - 1) per level, plus one.
  static constexpr int stack_capacity = max_depth * (K - 1) + 1;

  using bv_type = BV;
  using node_type = WideNode<T, K, BV>;

  std::vector<node_type> nodes;
  std::vector<std::uint32_t> prim;
  ChildRef root;
  Aabb<T> box;   ///< box of everything
  int depth = 0; ///< node levels (0 when the root is a leaf or empty)

  std::size_t size() const noexcept { return prim.size(); }
  bool empty() const noexcept { return prim.empty(); }
  std::size_t memory_bytes() const noexcept {
    return nodes.size() * sizeof(node_type) + prim.size() * sizeof(std::uint32_t);
  }
};

namespace detail {
template <class T, int K, class BV> struct Flattener {
  /// Builder nodes that become the children of one wide node: at most max(K, 16) (a builder node
  /// has at most 16 children; collapsing stops at K). A fixed array: no allocation per node.
  struct Kids {
    static constexpr int capacity = K > max_build_children ? K : max_build_children;
    std::uint32_t v[capacity];
    int n = 0;
  };

  const BuildTree<T>& tree;
  const std::vector<BV>& bv; // per builder node
  WideBvh<T, K, BV>& out;

  ChildRef ref_of(std::uint32_t b, int level) {
    const BuildNode<T>& n = tree.nodes[b];
    if (n.is_leaf()) return ChildRef::leaf(n.first, n.count);
    Kids kids;
    for (std::uint32_t c = 0; c < n.children; ++c) kids.v[kids.n++] = n.first + c;
    return emit(kids, level);
  }

  /// Emits one wide node for the builder nodes `kids` (collapsing inner children with the largest
  /// boxes while they fit, regrouping when there are more than K). Pre-order: the node's index is
  /// smaller than its descendants'.
  ChildRef emit(Kids kids, int level) {
    while (kids.n < K) {
      int pick = -1;
      T best_area = -std::numeric_limits<T>::infinity();
      for (int i = 0; i < kids.n; ++i) {
        const BuildNode<T>& c = tree.nodes[kids.v[i]];
        if (c.is_leaf() || std::size_t(kids.n) - 1 + c.children > std::size_t(K)) continue;
        const T a = c.box.half_area();
        if (a > best_area) {
          best_area = a;
          pick = i;
        }
      }
      if (pick < 0) break;
      // Replace kids[pick] by its children, in place and in order.
      const BuildNode<T>& c = tree.nodes[kids.v[pick]];
      const int m = int(c.children);
      for (int i = kids.n - 1; i > pick; --i) kids.v[i + m - 1] = kids.v[i];
      for (int j = 0; j < m; ++j) kids.v[pick + j] = c.first + std::uint32_t(j);
      kids.n += m - 1;
    }
    const std::uint32_t index = std::uint32_t(out.nodes.size());
    out.nodes.emplace_back();
    out.depth = std::max(out.depth, level + 1);
    for (int k = 0; k < K; ++k) {
      out.nodes[index].set_child_bv(k, BV());
      out.nodes[index].child[k] = ChildRef{};
    }
    if (kids.n <= K) {
      for (int k = 0; k < kids.n; ++k) {
        const ChildRef r = ref_of(kids.v[k], level + 1);
        auto& w = out.nodes[index]; // `out.nodes` may have grown
        w.child[k] = r;
        w.set_child_bv(k, bv[kids.v[k]]);
      }
      return ChildRef::inner(index);
    }
    // More than K children (a K-ary partition with more parts than K): K groups of consecutive
    // children, each its own node.
    for (int g = 0; g < K; ++g) {
      const int a = kids.n * g / K, b = kids.n * (g + 1) / K;
      if (a == b) continue;
      BV group;
      for (int i = a; i < b; ++i) group = merge(group, bv[kids.v[i]]);
      ChildRef r;
      if (b - a == 1) {
        r = ref_of(kids.v[a], level + 1);
      } else {
        Kids sub;
        for (int i = a; i < b; ++i) sub.v[sub.n++] = kids.v[i];
        r = emit(sub, level + 1);
      }
      auto& w = out.nodes[index];
      w.child[g] = r;
      w.set_child_bv(g, group);
    }
    return ChildRef::inner(index);
  }
};
} // namespace detail

/// Collapses a builder tree into the compact K-wide form with bounding volumes `BV` (EBGeometry's
/// pluggable bounding volumes): `leaf_bv(first, count)` gives the volume of leaf slots
/// [first, first + count); inner volumes are `merge`s of their children's. O(nodes · K).
template <int K, class BV, class T, class LeafBv>
WideBvh<T, K, BV> flatten(const BuildTree<T>& tree, const LeafBv& leaf_bv) {
  WideBvh<T, K, BV> out;
  out.prim = tree.prim;
  if (tree.empty()) return out;
  out.box = tree.nodes[0].box;
  // Builder children always have larger indices than their parent: one reverse pass.
  std::vector<BV> bv(tree.nodes.size());
  for (std::size_t i = tree.nodes.size(); i-- > 0;) {
    const BuildNode<T>& n = tree.nodes[i];
    if (n.is_leaf()) {
      bv[i] = leaf_bv(n.first, n.count);
    } else {
      BV b;
      for (std::uint32_t c = n.first; c < n.first + n.children; ++c) b = merge(b, bv[c]);
      bv[i] = b;
    }
  }
  out.nodes.reserve(tree.nodes.size() / 2 + 1);
  detail::Flattener<T, K, BV> f{tree, bv, out};
  out.root = f.ref_of(0, 0);
  EBGEOM_ASSERT((out.depth <= WideBvh<T, K, BV>::max_depth));
  return out;
}

/// Collapses a builder tree into the compact K-wide form with boxes (the builder's own).
template <int K, class T> WideBvh<T, K> flatten(const BuildTree<T>& tree) {
  WideBvh<T, K> out;
  out.prim = tree.prim;
  if (tree.empty()) return out;
  out.box = tree.nodes[0].box;
  std::vector<Aabb<T>> bv(tree.nodes.size());
  for (std::size_t i = 0; i < bv.size(); ++i) bv[i] = tree.nodes[i].box;
  out.nodes.reserve(tree.nodes.size() / 2 + 1);
  detail::Flattener<T, K, Aabb<T>> f{tree, bv, out};
  out.root = f.ref_of(0, 0);
  EBGEOM_ASSERT((out.depth <= WideBvh<T, K>::max_depth));
  return out;
}

/// Builds and flattens in one call.
template <int K, class T>
WideBvh<T, K> build_wide(Span<const Aabb<T>> boxes, Span<const Vec3<T>> centroids,
                         const BuildOptions& options = {}) {
  return flatten<K>(build(boxes, centroids, options));
}

/// Recomputes every bounding volume of `bvh` after its primitives moved (same primitives, same
/// leaves). `leaf_bv(first, count)` returns the volume of leaf slots [first, first + count).
/// O(nodes · K).
template <class T, int K, class BV, class LeafBv>
void refit(WideBvh<T, K, BV>& bvh, const LeafBv& leaf_bv) {
  // Pre-order layout: every child node has a larger index than its parent.
  for (std::size_t i = bvh.nodes.size(); i-- > 0;) {
    auto& n = bvh.nodes[i];
    for (int k = 0; k < K; ++k) {
      const ChildRef r = n.child[k];
      if (r.is_leaf())
        n.set_child_bv(k, leaf_bv(r.index, r.count));
      else if (r.is_inner())
        n.set_child_bv(k, bvh.nodes[r.index].bounds());
    }
  }
  if (bvh.root.is_leaf())
    bvh.box = to_box(BV(leaf_bv(bvh.root.index, bvh.root.count)));
  else if (bvh.root.is_inner())
    bvh.box = to_box(bvh.nodes[bvh.root.index].bounds());
}

} // namespace ebgeom::bvh

EBGEOM_END_EXACT_FP
