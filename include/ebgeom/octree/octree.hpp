// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `Octree<T, P>`: a generic, index-based octree with per-node payload `P`, built depth-first or
/// breadth-first from a user refinement predicate, optionally linking leaves to primitives, and
/// traversed like the BVH (stack based, optionally nearest-first with pruning).

#include <algorithm>
#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <utility>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/error.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"

namespace ebgeom {

/// Payload for octrees that need none.
struct NoPayload {
  friend bool operator==(NoPayload, NoPayload) noexcept { return true; }
};

/// The order in which nodes are created. Both give the same tree (same boxes, payloads and
/// leaves); only the storage order of the node array differs.
enum class OctreeOrder {
  depth_first,  ///< whole sub-trees first; each node's descendants are contiguous in memory
  breadth_first ///< one level at a time; nodes of one depth are contiguous
};

/// Build parameters.
struct OctreeOptions {
  /// Nodes at this depth are never refined (root depth is 0). At most 21.
  int max_depth = 10;
  OctreeOrder order = OctreeOrder::depth_first;
  /// For `build_from_boxes`: a leaf is refined while it holds more primitives than this.
  std::size_t max_leaf_size = 8;
  /// `build` in breadth-first order only: the refinement predicate runs on this many threads
  /// (0 = all cores) for the nodes of one level, which must then be thread-safe (it may only
  /// write its own payload). The tree does not depend on it. Default 1: serial.
  int threads = 1;
};

/// Octant `c` (bit 0: upper x half, bit 1: upper y, bit 2: upper z) of `box`.
template <class T> constexpr Aabb<T> octant(const Aabb<T>& box, int c) noexcept {
  const Vec3<T> m = box.center();
  return {{(c & 1) ? m.x : box.lo.x, (c & 2) ? m.y : box.lo.y, (c & 4) ? m.z : box.lo.z},
          {(c & 1) ? box.hi.x : m.x, (c & 2) ? box.hi.y : m.y, (c & 4) ? box.hi.z : m.z}};
}

/// An octree over a root box. Children of a node tile it exactly (the 8 octants of its centre),
/// stored as 8 consecutive nodes in octant order. Immutable after construction; `const` queries
/// are thread-safe.
///
/// Node size: 24 B box (float) or 48 B (double) + 12 B links + sizeof(P), padded.
template <class T, class P = NoPayload> class Octree {
 public:
  using scalar_type = T;
  using payload_type = P;
  static constexpr std::uint32_t no_child = std::numeric_limits<std::uint32_t>::max();

  struct Node {
    Aabb<T> box;
    std::uint32_t first_child = no_child; ///< index of the first of 8 children, or `no_child`
    std::uint32_t first_primitive = 0;    ///< leaves built from boxes: range in `primitives()`
    std::uint32_t primitive_count = 0;
    std::uint8_t depth = 0;
    P payload{};

    bool is_leaf() const noexcept { return first_child == no_child; }
  };

  Octree() = default;

  /// Builds from `root`. `refine(box, depth, payload) -> bool` is called once per created node:
  /// it may fill the node's payload and returns whether to split the node into 8 children
  /// (ignored at `max_depth`). The predicate must depend only on its arguments for the two orders
  /// to agree. O(number of nodes) calls.
  template <class Refine>
  static Result<Octree> build(const Aabb<T>& root, Refine&& refine, const OctreeOptions& opt = {}) {
    if (auto e = check(root, opt); e.code != ErrorCode::ok) return e;
    Octree tree;
    tree.nodes_.push_back(Node{root});
    auto split = [&](std::uint32_t i) {
      Node& n = tree.nodes_[i];
      return n.depth < opt.max_depth && refine(std::as_const(n.box), int(n.depth), n.payload);
    };
    tree.grow(
        opt.order, split, [](std::uint32_t, std::uint32_t) {}, opt.threads);
    return tree;
  }

  /// Builds an octree over primitives given by their boxes: a leaf is split while it overlaps more
  /// than `max_leaf_size` primitive boxes and is shallower than `max_depth`; each leaf lists every
  /// primitive whose box overlaps it (a primitive may appear in several leaves). The root is the
  /// box of all primitives unless `root` is given (non-empty).
  static Result<Octree> build_from_boxes(Span<const Aabb<T>> boxes, const OctreeOptions& opt = {},
                                         Aabb<T> root = Aabb<T>::empty()) {
    for (std::size_t i = 0; i < boxes.size(); ++i)
      if (!all_finite(boxes[i].lo) || !all_finite(boxes[i].hi) || boxes[i].is_empty())
        return make_error(ErrorCode::non_finite, "octree: primitive ", i,
                          " has an empty or non-finite box");
    if (root.is_empty())
      for (const auto& b : boxes) root.extend(b);
    if (boxes.empty()) root = Aabb<T>::of(Vec3<T>::zero());
    if (auto e = check(root, opt); e.code != ErrorCode::ok) return e;
    if (boxes.size() >= no_child)
      return make_error(ErrorCode::size_mismatch, "octree: too many primitives");

    Octree tree;
    tree.nodes_.push_back(Node{root});
    // Per-node candidate lists, consumed as nodes are processed (a node only needs its parent's).
    std::vector<std::vector<std::uint32_t>> cand(1);
    for (std::uint32_t i = 0; i < boxes.size(); ++i)
      if (boxes[i].overlaps(root)) cand[0].push_back(i);
    auto split = [&](std::uint32_t i) {
      const bool refine =
          tree.nodes_[i].depth < opt.max_depth && cand[i].size() > opt.max_leaf_size;
      if (!refine) {
        Node& n = tree.nodes_[i];
        n.first_primitive = static_cast<std::uint32_t>(tree.primitives_.size());
        n.primitive_count = static_cast<std::uint32_t>(cand[i].size());
        tree.primitives_.insert(tree.primitives_.end(), cand[i].begin(), cand[i].end());
      }
      return refine;
    };
    auto on_children = [&](std::uint32_t parent, std::uint32_t first) {
      cand.resize(tree.nodes_.size());
      for (int c = 0; c < 8; ++c) {
        const Aabb<T>& cb = tree.nodes_[first + c].box;
        for (std::uint32_t k : cand[parent])
          if (boxes[k].overlaps(cb)) cand[first + c].push_back(k);
      }
      std::vector<std::uint32_t>().swap(cand[parent]);
    };
    tree.grow(opt.order, split, on_children);
    return tree;
  }

  Span<const Node> nodes() const noexcept { return {nodes_.data(), nodes_.size()}; }
  const Node& node(std::uint32_t i) const noexcept { return nodes_[i]; }
  const Node& root() const noexcept { return nodes_[0]; }
  std::size_t size() const noexcept { return nodes_.size(); }
  /// Primitive indices referenced by leaves (`first_primitive`, `primitive_count`).
  Span<const std::uint32_t> primitives() const noexcept {
    return {primitives_.data(), primitives_.size()};
  }
  Span<const std::uint32_t> primitives(const Node& leaf) const noexcept {
    return {primitives_.data() + leaf.first_primitive, leaf.primitive_count};
  }
  /// Deepest node depth.
  int depth() const noexcept {
    int d = 0;
    for (const Node& n : nodes_) d = std::max(d, int(n.depth));
    return d;
  }

  /// Index of the leaf containing `p` (the first in octant order on shared faces), or `no_child`
  /// when `p` is outside the root box. O(depth).
  std::uint32_t find_leaf(const Vec3<T>& p) const noexcept {
    if (nodes_.empty() || !nodes_[0].box.contains(p)) return no_child;
    std::uint32_t i = 0;
    while (!nodes_[i].is_leaf()) {
      const Vec3<T> m = nodes_[i].box.center();
      const int c = int(p.x >= m.x) | (int(p.y >= m.y) << 1) | (int(p.z >= m.z) << 2);
      i = nodes_[i].first_child + c;
    }
    return i;
  }

  /// Depth-first traversal: `visit(index, node) -> bool` returns whether to descend into the
  /// node's children (its return value is ignored for leaves). Children in octant order.
  template <class Visit> void traverse(Visit&& visit) const {
    if (nodes_.empty()) return;
    std::vector<std::uint32_t> todo{0};
    while (!todo.empty()) {
      const std::uint32_t i = todo.back();
      todo.pop_back();
      const Node& n = nodes_[i];
      if (visit(i, n) && !n.is_leaf())
        for (int c = 7; c >= 0; --c) todo.push_back(n.first_child + c);
    }
  }

  /// Best-first traversal, as the BVH's ordered search: `priority(node) -> T` is a lower bound
  /// of what the sub-tree can offer (e.g. box distance); nodes are visited in increasing
  /// priority, and a node is skipped when its priority is >= `bound()`. `visit(index, node)` is
  /// called for every visited node (and may lower the value `bound()` returns).
  template <class Priority, class Bound, class Visit>
  void traverse_ordered(Priority&& priority, Bound&& bound, Visit&& visit) const {
    if (nodes_.empty()) return;
    struct Pending {
      T prio;
      std::uint32_t index;
    };
    std::vector<Pending> todo{{priority(nodes_[0]), 0}};
    while (!todo.empty()) {
      const Pending top = todo.back();
      todo.pop_back();
      if (!(top.prio < bound())) continue;
      const Node& n = nodes_[top.index];
      visit(top.index, n);
      if (n.is_leaf()) continue;
      std::array<Pending, 8> kids;
      for (int c = 0; c < 8; ++c)
        kids[c] = {priority(nodes_[n.first_child + c]), n.first_child + c};
      // push far-to-near so the nearest pops first
      std::sort(kids.begin(), kids.end(),
                [](const Pending& a, const Pending& b) { return a.prio > b.prio; });
      for (const Pending& k : kids)
        if (k.prio < bound()) todo.push_back(k);
    }
  }

 private:
  static Error check(const Aabb<T>& root, const OctreeOptions& opt) {
    if (root.is_empty() || !all_finite(root.lo) || !all_finite(root.hi))
      return make_error(ErrorCode::invalid_argument,
                        "octree: the root box must be finite and non-empty");
    if (opt.max_depth < 0 || opt.max_depth > 21)
      return make_error(ErrorCode::invalid_argument, "octree: max_depth ", opt.max_depth,
                        " is outside [0, 21]");
    return {};
  }

  // Creates the 8 children of node `i` at the end of the node array; returns the first index.
  std::uint32_t add_children(std::uint32_t i) {
    const auto first = static_cast<std::uint32_t>(nodes_.size());
    nodes_[i].first_child = first;
    const Aabb<T> box = nodes_[i].box;
    const auto depth = static_cast<std::uint8_t>(nodes_[i].depth + 1);
    for (int c = 0; c < 8; ++c) {
      Node child;
      child.box = octant(box, c);
      child.depth = depth;
      nodes_.push_back(child);
    }
    return first;
  }

  // Grows the tree from the root. `split(i)` decides node i (after its payload is set);
  // `on_children(parent, first)` runs right after children are created. `threads != 1`
  // (breadth-first only) decides the nodes of a level concurrently, then creates their children
  // serially in node order, so the tree is the same.
  template <class Split, class OnChildren = void (*)(std::uint32_t, std::uint32_t)>
  void grow(
      OctreeOrder order, Split& split, OnChildren on_children = [](std::uint32_t, std::uint32_t) {},
      int threads = 1) {
    if (order == OctreeOrder::breadth_first) {
      // Level by level: every node of depth d is decided before any of depth d + 1 is created.
      std::size_t level_begin = 0, level_end = 1;
      std::vector<std::uint8_t> decide;
      while (level_begin < level_end) {
        if (threads != 1) {
          decide.assign(level_end - level_begin, 0);
          ExecOptions ex;
          ex.threads = threads;
          ex.serial_threshold = 64;
          // No node is added while the level is decided, so references into nodes_ stay valid.
          parallel_for(
              level_begin, level_end, 16,
              [&](std::size_t b, std::size_t e) {
                for (std::size_t i = b; i < e; ++i)
                  decide[i - level_begin] = split(static_cast<std::uint32_t>(i)) ? 1 : 0;
              },
              ex);
          for (std::size_t i = level_begin; i < level_end; ++i) {
            const auto idx = static_cast<std::uint32_t>(i);
            if (decide[i - level_begin]) on_children(idx, add_children(idx));
          }
          level_begin = level_end;
          level_end = nodes_.size();
          continue;
        }
        for (std::size_t i = level_begin; i < level_end; ++i) {
          const auto idx = static_cast<std::uint32_t>(i);
          if (split(idx)) on_children(idx, add_children(idx));
        }
        level_begin = level_end;
        level_end = nodes_.size();
      }
      return;
    }
    // Depth-first: a node's whole sub-tree is built before its next sibling is decided.
    // Explicit stack of nodes whose split decision is pending.
    std::vector<std::uint32_t> todo{0};
    while (!todo.empty()) {
      const std::uint32_t i = todo.back();
      todo.pop_back();
      if (!split(i)) continue;
      const std::uint32_t first = add_children(i);
      on_children(i, first);
      for (int c = 7; c >= 0; --c) todo.push_back(first + c);
    }
  }

  std::vector<Node> nodes_;
  std::vector<std::uint32_t> primitives_;
};

} // namespace ebgeom
