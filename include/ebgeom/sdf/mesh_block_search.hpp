// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// The nearest-triangle search of `MeshSdf` (`sdf/mesh_sdf.hpp`): a branch-and-bound search of a
/// `WideBvh` whose leaves are runs of `TriBlock`s (a leaf is (first block, triangle count)), each
/// block scanned with `block_min`. Shared by the per-point queries and tile evaluation
/// (`sdf/mesh_tile_eval.hpp`).

#include <cstddef>
#include <cstdint>

#include "ebgeom/bvh/node_obbs.hpp"
#include "ebgeom/bvh/simd_nodes.hpp" // <immintrin.h> where the target has SSE2 / AVX
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"
#include "ebgeom/core/simd.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/tri_block.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom::detail {

/// A view of a blocked BVH: the tree, its blocks, the triangle id of each block lane (a slot), the
/// absolute pruning slack and the oriented boxes of each node's children (`bvh::NodeObbs`, one per
/// node, or null). Holds pointers only; the owner (`MeshSdf`) keeps the arrays alive.
template <class T, int K, int W> struct BlockSearch {
  const bvh::WideBvh<T, K>* bvh;
  const TriBlock<T, W>* blocks;
  const std::uint32_t* tri;
  T slack;
  const bvh::NodeObbs<T, K>* obbs = nullptr;

  /// Nearest triangle slot (block lane) by squared distance; `best2` is the initial bound. `I`: the
  /// instruction set of the kernels (`core/isa.hpp`); `MeshSearchKernels<I>` compiles it for I.
  /// Without the farthest-box shrink of `bvh::nearest`: the queries start from a seed triangle's
  /// distance, which that shrink seldom lowers, and its extra box pass at each node on the way to
  /// the first leaf made float queries 1-6% slower (docs/dev/performance-log.md).
  /// A child is entered only when its oriented box, too, is near enough (`bvh::NodeObbs`): on the
  /// meshes of docs/performance.md that scans 1.6-3.8x fewer blocks and expands 1.2-1.9x fewer
  /// nodes.
  template <Isa I = native_isa>
  void nearest_slot(const Vec3<T>& p, T& best2, std::uint32_t& best) const noexcept {
    const auto leaf = [&](std::uint32_t first_block, std::uint32_t count, T& b2) noexcept {
      scan_blocks<I>(first_block, count, p, b2, best);
    };
    const auto pre = [this](bvh::ChildRef c) noexcept { prefetch(c); };
    if (obbs)
      bvh::nearest<false, I>(
          *bvh, p, best2, leaf, slack, pre,
          [&](std::uint32_t node, T(&d2)[K]) noexcept { bvh::raise_dist2<I>(obbs[node], p, d2); });
    else
      bvh::nearest<false, I>(*bvh, p, best2, leaf, slack, pre);
  }

  /// Starts loading what visiting child `c` reads: an inner node's boxes and its children's
  /// oriented boxes, or a leaf's first block (all its cache lines: the box test reads every
  /// coordinate). A block and a node are each read from memory at once instead of line after line,
  /// and blocks and nodes still on the stack arrive while others are scanned.
  EBGEOM_FORCE_INLINE void prefetch(bvh::ChildRef c) const noexcept {
    if (c.is_leaf()) {
      const char* b = reinterpret_cast<const char*>(blocks + c.index);
      for (std::size_t o = 0; o < sizeof(TriBlock<T, W>); o += 64) detail::prefetch(b + o);
    } else {
      const char* n = reinterpret_cast<const char*>(bvh->nodes.data() + c.index);
      for (std::size_t o = 0; o < sizeof(bvh->nodes[0]); o += 64) detail::prefetch(n + o);
      if (obbs) {
        const char* b = reinterpret_cast<const char*>(obbs + c.index);
        for (std::size_t o = 0; o < sizeof(obbs[0]); o += 64) detail::prefetch(b + o);
      }
    }
  }

  /// Scans blocks [first, first + ceil(count / W)) at `p`, lowering `b2`/`best` (ties: lowest
  /// triangle index, as the brute force).
  template <Isa I = native_isa>
  EBGEOM_FORCE_INLINE void scan_blocks(std::uint32_t first_block, std::uint32_t count,
                                       const Vec3<T>& p, T& b2,
                                       std::uint32_t& best) const noexcept {
    const std::uint32_t nb = (count + std::uint32_t(W) - 1) / std::uint32_t(W);
    for (std::uint32_t i = 0; i < nb; ++i) {
      const LaneMin<T, W> lm =
          block_min_pruned<T, W, I>(blocks[first_block + i], p, b2, bvh::prune_limit(b2, slack));
      // No lane can win, or only tie with no best yet (as the brute force, which keeps the first
      // triangle strictly below the initial bound).
      if (lm.mask == 0 || !(lm.min < b2 || best != bvh::ChildRef::none)) continue;
      // Lanes of a leaf hold ascending triangle ids (`pack_blocks`): the lowest minimal lane has
      // the lowest id among this block's ties.
      const std::uint32_t slot =
          (first_block + i) * std::uint32_t(W) + std::uint32_t(detail::lowest_bit(lm.mask));
      if (lm.min < b2 || tri[slot] < tri[best]) {
        b2 = lm.min;
        best = slot;
        detail::prefetch(tri + slot); // read by the caller's finish if it stays the best
      }
    }
  }
};

/// The nearest-slot search compiled for instruction set I: the traversal, box tests and block
/// scans all in one function with I's target attribute (`flatten` inlines the traversal into it),
/// calling the block kernel `TriBlockKernels<I>::block_min` once per block.
#define EBGEOM_MESH_SEARCH_KERNELS(I, TARGET)                                                      \
  template <class T, int K, int W>                                                                 \
  TARGET EBGEOM_FLATTEN static void nearest_slot(const BlockSearch<T, K, W>& s, const Vec3<T>& p,  \
                                                 T& best2, std::uint32_t& best) noexcept {         \
    s.template nearest_slot<I>(p, best2, best);                                                    \
  }

template <Isa I> struct MeshSearchKernels { EBGEOM_MESH_SEARCH_KERNELS(I, ) };
#if EBGEOM_ISA_DISPATCH
template <> struct MeshSearchKernels<Isa::avx2> {
  EBGEOM_MESH_SEARCH_KERNELS(Isa::avx2, EBGEOM_TARGET_AVX2)
};
template <> struct MeshSearchKernels<Isa::avx512> {
  EBGEOM_MESH_SEARCH_KERNELS(Isa::avx512, EBGEOM_TARGET_AVX512)
};
#endif
#undef EBGEOM_MESH_SEARCH_KERNELS

} // namespace ebgeom::detail

EBGEOM_END_EXACT_FP
