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
///  - `ChunkPartition<K>`: the EBGeometry seeds' partitioner: sort centroids along the longest
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
#include <utility>
#include <vector>

#include "ebgeom/bvh/build_sah.hpp"
#include "ebgeom/bvh/build_tree.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom::bvh {

namespace detail {
/// Spreads the low 21 bits of `v` to every third bit.
inline std::uint64_t spread_bits_21(std::uint64_t v) noexcept {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffULL;
  v = (v | v << 16) & 0x1f0000ff0000ffULL;
  v = (v | v << 8) & 0x100f00f00f00f00fULL;
  v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
  v = (v | v << 2) & 0x1249249249249249ULL;
  return v;
}
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
  return detail::spread_bits_21(q[0]) | detail::spread_bits_21(q[1]) << 1 |
         detail::spread_bits_21(q[2]) << 2;
}

/// Bottom-up construction (LBVH): Morton codes of the centroids, sorted (ties by index), then a
/// binary hierarchy split at the highest bit that differs within each range (the middle when all
/// codes are equal); ranges of at most `max_leaf_size` primitives become leaves. O(n log n).
template <class T>
BuildTree<T> build_morton(Span<const Aabb<T>> boxes, Span<const Vec3<T>> centroids,
                          std::uint32_t max_leaf_size = 4) {
  EBGEOM_ASSERT(boxes.size() == centroids.size());
  const std::uint32_t n = std::uint32_t(boxes.size());
  Aabb<T> cbox;
  for (const auto& c : centroids) cbox.extend(c);
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys(n);
  for (std::uint32_t i = 0; i < n; ++i) keys[i] = {morton_code(centroids[i], cbox), i};
  std::sort(keys.begin(), keys.end());
  // Split by code: a "partition" that finds the highest differing bit in a sorted range. The
  // primitives are already in Morton order, so the partition only reports where to cut.
  struct MortonSplit {
    const std::vector<std::uint64_t>* codes;
    Parts operator()(const PartitionInput<T>&, std::uint32_t* idx, std::uint32_t cnt) const {
      const std::uint64_t a = (*codes)[idx[0]], b = (*codes)[idx[cnt - 1]];
      Parts p;
      p.count = 2;
      p.ends[1] = cnt;
      if (a == b) {
        p.ends[0] = cnt / 2;
        return p;
      }
      const int bit = detail::highest_bit(a ^ b);
      const std::uint64_t mask = ~0ULL << bit;
      const std::uint64_t prefix = (a & mask) | (1ULL << bit);
      // First element whose code has the higher prefix (codes are sorted within the range).
      std::uint32_t lo = 0, hi = cnt;
      while (lo < hi) {
        const std::uint32_t mid = (lo + hi) / 2;
        if (((*codes)[idx[mid]] & mask) < prefix)
          lo = mid + 1;
        else
          hi = mid;
      }
      p.ends[0] = lo;
      return p;
    }
  };
  // Start from Morton order: build_top_down begins with the identity permutation, so feed it the
  // sorted order through permuted views and map the result back.
  std::vector<Aabb<T>> sboxes(n);
  std::vector<Vec3<T>> scent(n);
  std::vector<std::uint64_t> scodes(n);
  for (std::uint32_t i = 0; i < n; ++i) {
    sboxes[i] = boxes[keys[i].second];
    scent[i] = centroids[keys[i].second];
    scodes[i] = keys[i].first;
  }
  BuildTree<T> tree = build_top_down<T>(Span<const Aabb<T>>(sboxes), Span<const Vec3<T>>(scent),
                                        MortonSplit{&scodes}, LeafSizeStop{max_leaf_size});
  for (auto& p : tree.prim) p = keys[p].second;
  return tree;
}

/// The ready-made builder: `options.method` with `LeafSizeStop{options.max_leaf_size}`.
template <class T>
BuildTree<T> build(Span<const Aabb<T>> boxes, Span<const Vec3<T>> centroids,
                   const BuildOptions& options = {}) {
  const std::uint32_t leaf = std::max<std::uint32_t>(1, options.max_leaf_size);
  switch (options.method) {
  case BuildMethod::median:
    return build_top_down<T>(boxes, centroids, MedianPartition{}, LeafSizeStop{leaf});
  case BuildMethod::morton:
    return build_morton<T>(boxes, centroids, leaf);
  case BuildMethod::sah_binned:
  default:
    return build_sah<T>(boxes, centroids,
                        SahPartition{options.bins, options.block, options.longest_axis_above},
                        leaf);
  }
}

} // namespace ebgeom::bvh
