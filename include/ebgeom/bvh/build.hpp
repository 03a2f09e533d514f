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
/// `build_morton` is the bottom-up alternative: 63-bit Morton codes of the centroids, sorted, and a
/// hierarchy split at the highest differing bit (LBVH).
///
/// Depth is bounded by `max_build_depth` (a node that deep becomes a leaf whatever its size), and
/// a partition that returns no useful split is replaced by an index-median split, so every build
/// terminates and the traversal stack size proven from the depth is always enough.

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>
#include <numeric>
#include <utility>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#endif

namespace ebgeom::bvh {

/// Largest number of children a builder node may have (partitions return at most this many parts).
inline constexpr int max_build_children = 16;
/// Nodes at this depth become leaves whatever their size.
inline constexpr int max_build_depth = 64;

/// One node of the builder tree. Leaf: `children == 0`, primitives `prim[first .. first+count)`.
/// Inner: children are the consecutive nodes `nodes[first .. first+children)`.
template <class T> struct BuildNode {
  Aabb<T> box;
  std::uint32_t first = 0;
  std::uint32_t count = 0;    ///< leaf: number of primitives; inner: 0
  std::uint32_t children = 0; ///< inner: number of children; leaf: 0
  bool is_leaf() const noexcept { return children == 0; }
};

/// The builder tree: index-based, root at `nodes[0]`, and one permutation `prim` (leaf order ->
/// input primitive index). Every primitive appears in exactly one leaf.
template <class T> struct BuildTree {
  std::vector<BuildNode<T>> nodes;
  std::vector<std::uint32_t> prim;
  int depth = 0; ///< number of levels (a single leaf has depth 1); <= max_build_depth + 1

  bool empty() const noexcept { return nodes.empty(); }
  std::size_t leaf_count() const noexcept {
    return std::size_t(std::count_if(nodes.begin(), nodes.end(),
                                     [](const BuildNode<T>& n) { return n.is_leaf(); }));
  }
};

/// What a partition sees of the node it splits.
template <class T> struct PartitionInput {
  Span<const Aabb<T>> boxes;     ///< per input primitive
  Span<const Vec3<T>> centroids; ///< per input primitive
  Aabb<T> box;                   ///< the node's box (union of its primitives' boxes)
  Aabb<T> centroid_box;          ///< box of its primitives' centroids
  int depth = 0;                 ///< the node's depth (root = 0)
};

/// Output of a partition: part i is `idx[ends[i-1] .. ends[i])` (ends[-1] = 0) after the
/// partition reordered `idx`; `count` parts, `ends[count-1]` = the node's size.
struct Parts {
  int count = 0;
  std::array<std::uint32_t, max_build_children> ends{};
};

/// How the ready-made builder splits nodes.
enum class BuildMethod : std::uint8_t {
  sah_binned, ///< binned surface-area heuristic (default; best queries)
  median,     ///< median split on the longest centroid axis
  morton,     ///< bottom-up from Morton codes (fastest build)
};

/// Options of `build`.
struct BuildOptions {
  BuildMethod method = BuildMethod::sah_binned;
  std::uint32_t max_leaf_size = 4; ///< a node with at most this many primitives becomes a leaf
  int bins = 16;                   ///< SAH bins per axis (2..64)
  std::uint32_t block = 1; ///< SAH: fill leaves in whole blocks of this size (see SahPartition)
};

/// Leaf when a node holds at most `max_leaf_size` primitives.
struct LeafSizeStop {
  std::uint32_t max_leaf_size = 4;
  template <class T> bool operator()(const PartitionInput<T>&, std::uint32_t count) const noexcept {
    return count <= max_leaf_size;
  }
};

namespace detail {
/// Sorts `idx` by centroid coordinate `axis`, ties by index (deterministic on any platform).
template <class T>
void sort_by_axis(std::uint32_t* idx, std::uint32_t n, Span<const Vec3<T>> c, int axis) {
  std::sort(idx, idx + n, [&](std::uint32_t a, std::uint32_t b) {
    const T ca = c[a][axis], cb = c[b][axis];
    return ca < cb || (ca == cb && a < b);
  });
}
/// Median split into two halves along the longest centroid axis (always makes progress for n >= 2).
template <class T>
Parts median_split(const PartitionInput<T>& in, std::uint32_t* idx, std::uint32_t n) {
  const int axis = in.centroid_box.longest_axis();
  const std::uint32_t mid = n / 2;
  std::nth_element(idx, idx + mid, idx + n, [&](std::uint32_t a, std::uint32_t b) {
    const T ca = in.centroids[a][axis], cb = in.centroids[b][axis];
    return ca < cb || (ca == cb && a < b);
  });
  Parts p;
  p.count = 2;
  p.ends[0] = mid;
  p.ends[1] = n;
  return p;
}
} // namespace detail

/// Median split on the longest centroid axis: two halves of equal size.
struct MedianPartition {
  template <class T>
  Parts operator()(const PartitionInput<T>& in, std::uint32_t* idx, std::uint32_t n) const {
    return detail::median_split(in, idx, n);
  }
};

/// The seeds' partitioner: sort centroids along the longest axis of their box, cut into `K` chunks
/// of (nearly) equal size. O(n log n) per node.
template <int K> struct ChunkPartition {
  static_assert(K >= 2 && K <= max_build_children, "ChunkPartition<K> needs 2 <= K <= 16");
  template <class T>
  Parts operator()(const PartitionInput<T>& in, std::uint32_t* idx, std::uint32_t n) const {
    detail::sort_by_axis(idx, n, in.centroids, in.centroid_box.longest_axis());
    Parts p;
    const std::uint32_t k = std::min<std::uint32_t>(K, n);
    for (std::uint32_t i = 0; i < k; ++i)
      p.ends[i] = std::uint32_t((std::uint64_t(n) * (i + 1)) / k);
    p.count = int(k);
    return p;
  }
};

/// Binned surface-area heuristic: `bins` bins per axis over the centroid box, all three axes
/// binned in one pass; the split minimising area(L)·|L| + area(R)·|R| wins. Falls back to a median
/// split when all centroids coincide. O(n) per node.
///
/// `block` > 1 makes leaves that fill whole blocks of that many primitives (mesh SDFs process W
/// triangles at once): nodes of at most 4·block primitives are cut, along the longest centroid
/// axis, after a multiple of `block` (the one nearest the middle), so almost every leaf is full,
/// and the cost counts blocks, ceil(|L| / block), rather than primitives.
struct SahPartition {
  int bins = 16;
  std::uint32_t block = 1;
  template <class T>
  Parts operator()(const PartitionInput<T>& in, std::uint32_t* idx, std::uint32_t n) const {
    Parts parts;
    parts.count = 2;
    parts.ends[1] = n;
    if (block > 1 && n <= 4 * block) {
      detail::sort_by_axis(idx, n, in.centroids, in.centroid_box.longest_axis());
      const std::uint32_t k = std::max<std::uint32_t>(1, (n + block) / (2 * block));
      parts.ends[0] = std::min(n - 1, k * block);
      return parts;
    }
    constexpr int max_bins = 64;
    const int nb = std::max(2, std::min(bins, max_bins));
    const Vec3<T> lo = in.centroid_box.lo, ext = in.centroid_box.extent();
    Vec3<T> scale;
    for (int a = 0; a < 3; ++a) scale[a] = ext[a] > T(0) ? T(nb) / ext[a] : T(0);
    Aabb<T> bbox[3][max_bins];
    std::uint32_t bcount[3][max_bins];
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < nb; ++b) bbox[a][b] = Aabb<T>(), bcount[a][b] = 0;
    for (std::uint32_t i = 0; i < n; ++i) {
      const std::uint32_t p = idx[i];
      const Vec3<T> c = in.centroids[p];
      const Aabb<T>& box = in.boxes[p];
      for (int a = 0; a < 3; ++a) {
        const int b = std::min(nb - 1, int((c[a] - lo[a]) * scale[a]));
        bbox[a][b].extend(box);
        ++bcount[a][b];
      }
    }
    T best_cost = std::numeric_limits<T>::infinity();
    int best_axis = -1, best_bin = 0;
    for (int axis = 0; axis < 3; ++axis) {
      if (!(ext[axis] > T(0))) continue;
      T right_cost[max_bins];
      Aabb<T> acc;
      std::uint32_t cnt = 0;
      for (int b = nb - 1; b > 0; --b) {
        acc.extend(bbox[axis][b]);
        cnt += bcount[axis][b];
        right_cost[b] = cnt ? acc.half_area() * T((cnt + block - 1) / block) : T(0);
      }
      acc = Aabb<T>();
      cnt = 0;
      for (int b = 0; b < nb - 1; ++b) {
        acc.extend(bbox[axis][b]);
        cnt += bcount[axis][b];
        if (cnt == 0 || cnt == n) continue;
        const T cost = acc.half_area() * T((cnt + block - 1) / block) + right_cost[b + 1];
        if (cost < best_cost) {
          best_cost = cost;
          best_axis = axis;
          best_bin = b;
        }
      }
    }
    if (best_axis < 0) return detail::median_split(in, idx, n);
    const int ax = best_axis;
    std::uint32_t* mid = std::partition(idx, idx + n, [&](std::uint32_t p) {
      return std::min(nb - 1, int((in.centroids[p][ax] - lo[ax]) * scale[ax])) <= best_bin;
    });
    parts.ends[0] = std::uint32_t(mid - idx);
    return parts;
  }
};

/// Top-down construction with a user partition and stop predicate (see the file comment).
/// `boxes` and `centroids` have one entry per primitive (same size). Parts the partition returns
/// empty are dropped; if fewer than two non-empty parts remain, or the partition returns more than
/// `max_build_children` parts, an index-median split is used instead. O(n log n) for balanced
/// partitions. Deterministic.
template <class T, class Partition, class Stop>
BuildTree<T> build_top_down(Span<const Aabb<T>> boxes, Span<const Vec3<T>> centroids,
                            const Partition& partition, const Stop& stop) {
  EBGEOM_ASSERT(boxes.size() == centroids.size());
  BuildTree<T> tree;
  const std::uint32_t n = std::uint32_t(boxes.size());
  if (n == 0) return tree;
  tree.prim.resize(n);
  std::iota(tree.prim.begin(), tree.prim.end(), 0u);
  tree.nodes.reserve(2 * std::size_t(n));
  tree.nodes.emplace_back();
  struct Task {
    std::uint32_t node, begin, end;
    int depth;
  };
  std::vector<Task> todo{{0, 0, n, 0}};
  while (!todo.empty()) {
    const Task t = todo.back();
    todo.pop_back();
    PartitionInput<T> in{boxes, centroids, Aabb<T>(), Aabb<T>(), t.depth};
    for (std::uint32_t i = t.begin; i < t.end; ++i) {
      in.box.extend(boxes[tree.prim[i]]);
      in.centroid_box.extend(centroids[tree.prim[i]]);
    }
    tree.nodes[t.node].box = in.box;
    tree.depth = std::max(tree.depth, t.depth + 1);
    const std::uint32_t count = t.end - t.begin;
    auto make_leaf = [&] {
      tree.nodes[t.node].first = t.begin;
      tree.nodes[t.node].count = count;
      tree.nodes[t.node].children = 0;
    };
    if (count <= 1 || t.depth >= max_build_depth || stop(in, count)) {
      make_leaf();
      continue;
    }
    std::uint32_t* idx = tree.prim.data() + t.begin;
    Parts parts = partition(in, idx, count);
    // Drop empty parts; fall back to a median split when the partition made no progress.
    std::array<std::uint32_t, max_build_children + 1> bounds{};
    int m = 0;
    bool ok = parts.count >= 2 && parts.count <= max_build_children &&
              parts.ends[std::size_t(parts.count - 1)] == count;
    if (ok) {
      std::uint32_t prev = 0;
      for (int i = 0; i < parts.count && ok; ++i) {
        const std::uint32_t e = parts.ends[std::size_t(i)];
        if (e < prev || e > count)
          ok = false;
        else if (e > prev)
          bounds[std::size_t(++m)] = e;
        prev = e;
      }
      ok = ok && m >= 2;
    }
    if (!ok) {
      parts = detail::median_split(in, idx, count);
      m = 2;
      bounds[1] = parts.ends[0];
      bounds[2] = count;
    }
    const std::uint32_t first_child = std::uint32_t(tree.nodes.size());
    tree.nodes[t.node].first = first_child;
    tree.nodes[t.node].count = 0;
    tree.nodes[t.node].children = std::uint32_t(m);
    tree.nodes.resize(tree.nodes.size() + std::size_t(m));
    // Push in reverse so children are processed (and laid out below them) in order.
    for (int i = m - 1; i >= 0; --i)
      todo.push_back({first_child + std::uint32_t(i), t.begin + bounds[std::size_t(i)],
                      t.begin + bounds[std::size_t(i) + 1], t.depth + 1});
  }
  return tree;
}

namespace detail {
/// Four lanes of T with the few operations the SAH builder needs, each lane's result equal to the
/// scalar one (`min(a, b)` is `b < a ? b : a`, as `std::min`, for non-NaN values). SSE2 on x86-64
/// (the compilers do not vectorise these reliably on their own); plain arrays elsewhere.
template <class T> struct Lanes4 {
  T v[4];
  static Lanes4 load(const T* p) noexcept { return {{p[0], p[1], p[2], p[3]}}; }
  static Lanes4 splat(T x) noexcept { return {{x, x, x, x}}; }
  void store(T* p) const noexcept {
    for (int j = 0; j < 4; ++j) p[j] = v[j];
  }
  friend Lanes4 min(const Lanes4& a, const Lanes4& b) noexcept {
    Lanes4 r;
    for (int j = 0; j < 4; ++j) r.v[j] = b.v[j] < a.v[j] ? b.v[j] : a.v[j];
    return r;
  }
  friend Lanes4 max(const Lanes4& a, const Lanes4& b) noexcept {
    Lanes4 r;
    for (int j = 0; j < 4; ++j) r.v[j] = a.v[j] < b.v[j] ? b.v[j] : a.v[j];
    return r;
  }
  /// min(int((c - lo) * scale), top) per lane, for (c - lo) * scale >= 0.
  static void bin(const T* c, const Lanes4& lo, const Lanes4& scale, T top, int* out) noexcept {
    for (int j = 0; j < 4; ++j) out[j] = int(std::min((c[j] - lo.v[j]) * scale.v[j], top));
  }
};
#if defined(__SSE2__) || defined(_M_X64)
template <> struct Lanes4<float> {
  __m128 v;
  static Lanes4 load(const float* p) noexcept { return {_mm_loadu_ps(p)}; }
  static Lanes4 splat(float x) noexcept { return {_mm_set1_ps(x)}; }
  void store(float* p) const noexcept { _mm_storeu_ps(p, v); }
  friend Lanes4 min(const Lanes4& a, const Lanes4& b) noexcept { return {_mm_min_ps(b.v, a.v)}; }
  friend Lanes4 max(const Lanes4& a, const Lanes4& b) noexcept { return {_mm_max_ps(b.v, a.v)}; }
  static void bin(const float* c, const Lanes4& lo, const Lanes4& scale, float top,
                  int* out) noexcept {
    const __m128 f = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(c), lo.v), scale.v);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out),
                     _mm_cvttps_epi32(_mm_min_ps(f, _mm_set1_ps(top))));
  }
};
template <> struct Lanes4<double> {
  __m128d a, b;
  static Lanes4 load(const double* p) noexcept { return {_mm_loadu_pd(p), _mm_loadu_pd(p + 2)}; }
  static Lanes4 splat(double x) noexcept { return {_mm_set1_pd(x), _mm_set1_pd(x)}; }
  void store(double* p) const noexcept { _mm_storeu_pd(p, a), _mm_storeu_pd(p + 2, b); }
  friend Lanes4 min(const Lanes4& x, const Lanes4& y) noexcept {
    return {_mm_min_pd(y.a, x.a), _mm_min_pd(y.b, x.b)};
  }
  friend Lanes4 max(const Lanes4& x, const Lanes4& y) noexcept {
    return {_mm_max_pd(y.a, x.a), _mm_max_pd(y.b, x.b)};
  }
  static void bin(const double* c, const Lanes4& lo, const Lanes4& scale, double top,
                  int* out) noexcept {
    const __m128d t = _mm_set1_pd(top);
    const __m128d f0 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(c), lo.a), scale.a);
    const __m128d f1 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(c + 2), lo.b), scale.b);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out),
                     _mm_unpacklo_epi64(_mm_cvttpd_epi32(_mm_min_pd(f0, t)),
                                        _mm_cvttpd_epi32(_mm_min_pd(f1, t))));
  }
};
#endif

/// A primitive as the fast SAH builder moves it: box and centroid, each in 4 lanes (lane 3 is
/// zero) so that a box update or a bin index is one 4-wide operation, and the input index.
/// 52 B (float), 104 B (double).
template <class T> struct SahPrim {
  T lo[4];
  T hi[4];
  T c[4];
  std::uint32_t index;
};
/// A bin (or any box) in 4 lanes.
template <class T> struct SahBox {
  Lanes4<T> lo, hi;
  EBGEOM_FORCE_INLINE void reset() noexcept {
    lo = Lanes4<T>::splat(std::numeric_limits<T>::infinity());
    hi = Lanes4<T>::splat(-std::numeric_limits<T>::infinity());
  }
  EBGEOM_FORCE_INLINE void extend(const T* l, const T* h) noexcept {
    lo = min(lo, Lanes4<T>::load(l));
    hi = max(hi, Lanes4<T>::load(h));
  }
  EBGEOM_FORCE_INLINE void extend(const SahBox& b) noexcept {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  Aabb<T> aabb() const noexcept {
    T l[4], h[4];
    lo.store(l);
    hi.store(h);
    return {{l[0], l[1], l[2]}, {h[0], h[1], h[2]}};
  }
};
template <class T> Aabb<T> box_of(const SahPrim<T>* p, std::uint32_t n) noexcept {
  SahBox<T> b;
  b.reset();
  for (std::uint32_t i = 0; i < n; ++i) b.extend(p[i].lo, p[i].hi);
  return b.aabb();
}
template <class T> Aabb<T> centroid_box_of(const SahPrim<T>* p, std::uint32_t n) noexcept {
  SahBox<T> b;
  b.reset();
  for (std::uint32_t i = 0; i < n; ++i) b.extend(p[i].c, p[i].c);
  return b.aabb();
}
} // namespace detail

/// The ready-made binned SAH build, fast: the same tree as
/// `build_top_down(boxes, centroids, SahPartition{bins, block}, LeafSizeStop{max_leaf_size})`
/// (the same nodes in the same order, with the same boxes, and every leaf holding the same
/// primitives; only their order inside a leaf may differ), built about 3x faster. Each primitive's
/// box, centroid and index are copied once into one array that the build partitions in place, so
/// every pass reads memory in order (no gather through an index array); a node's box and centroid
/// box come from its parent's bins and partition pass instead of a pass of their own; a box update
/// is one 4-wide min and max. One allocation for the whole build besides the tree. O(n log n).
template <class T>
BuildTree<T> build_sah(Span<const Aabb<T>> boxes, Span<const Vec3<T>> centroids,
                       const SahPartition& sah, std::uint32_t max_leaf_size) {
  EBGEOM_ASSERT(boxes.size() == centroids.size());
  using detail::Lanes4;
  using detail::SahBox;
  using detail::SahPrim;
  BuildTree<T> tree;
  const std::uint32_t n = std::uint32_t(boxes.size());
  if (n == 0) return tree;
  const std::uint32_t block = sah.block;
  constexpr int max_bins = 64;
  const int nb = std::max(2, std::min(sah.bins, max_bins));

  std::vector<SahPrim<T>> prims(n);
  Aabb<T> root_box, root_cbox;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Aabb<T>& b = boxes[i];
    const Vec3<T>& c = centroids[i];
    prims[i] = {
        {b.lo.x, b.lo.y, b.lo.z, T(0)}, {b.hi.x, b.hi.y, b.hi.z, T(0)}, {c.x, c.y, c.z, T(0)}, i};
    root_box.extend(b);
    root_cbox.extend(c);
  }
  tree.prim.resize(n);
  tree.nodes.reserve(2 * std::size_t(n));
  tree.nodes.emplace_back();
  struct Task {
    std::uint32_t node, begin, end;
    int depth;
    Aabb<T> box, cbox;
  };
  std::vector<Task> todo;
  todo.reserve(2 * max_build_depth + 2);
  todo.push_back({0, 0, n, 0, root_box, root_cbox});
  SahBox<T> bins[3][max_bins];
  std::uint32_t counts[3][max_bins];
  while (!todo.empty()) {
    const Task t = todo.back();
    todo.pop_back();
    tree.nodes[t.node].box = t.box;
    tree.depth = std::max(tree.depth, t.depth + 1);
    const std::uint32_t count = t.end - t.begin;
    SahPrim<T>* p = prims.data() + t.begin;
    if (count <= 1 || t.depth >= max_build_depth || count <= max_leaf_size) {
      tree.nodes[t.node].first = t.begin;
      tree.nodes[t.node].count = count;
      tree.nodes[t.node].children = 0;
      continue;
    }
    std::uint32_t mid = 0;
    Aabb<T> lbox, rbox, lcbox, rcbox;
    bool boxes_known = false;
    auto by_axis = [](int axis) {
      return [axis](const SahPrim<T>& a, const SahPrim<T>& b) {
        return a.c[axis] < b.c[axis] || (a.c[axis] == b.c[axis] && a.index < b.index);
      };
    };
    if (block > 1 && count <= 4 * block) {
      // Small node: whole blocks, cut after a multiple of `block` along the longest axis.
      std::sort(p, p + count, by_axis(t.cbox.longest_axis()));
      const std::uint32_t k = std::max<std::uint32_t>(1, (count + block) / (2 * block));
      mid = std::min(count - 1, k * block);
    } else {
      const Vec3<T> ext = t.cbox.extent();
      const T lo[4] = {t.cbox.lo.x, t.cbox.lo.y, t.cbox.lo.z, T(0)};
      T scale[4] = {T(0), T(0), T(0), T(0)};
      for (int a = 0; a < 3; ++a) scale[a] = ext[a] > T(0) ? T(nb) / ext[a] : T(0);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < nb; ++b) bins[a][b].reset(), counts[a][b] = 0;
      // int(min(f, nb - 1)) == min(int(f), nb - 1) for f >= 0: SahPartition's bin, exactly.
      const Lanes4<T> lo4 = Lanes4<T>::load(lo), scale4 = Lanes4<T>::load(scale);
      const T top = T(nb - 1);
      for (std::uint32_t i = 0; i < count; ++i) {
        const SahPrim<T>& q = p[i];
        int b[4];
        Lanes4<T>::bin(q.c, lo4, scale4, top, b);
        for (int a = 0; a < 3; ++a) {
          bins[a][b[a]].extend(q.lo, q.hi);
          ++counts[a][b[a]];
        }
      }
      // The sweep of SahPartition, operation for operation (same costs, same choice).
      T best_cost = std::numeric_limits<T>::infinity();
      int best_axis = -1, best_bin = 0;
      for (int axis = 0; axis < 3; ++axis) {
        if (!(ext[axis] > T(0))) continue;
        T right_cost[max_bins];
        Aabb<T> acc;
        std::uint32_t cnt = 0;
        for (int b = nb - 1; b > 0; --b) {
          acc.extend(bins[axis][b].aabb());
          cnt += counts[axis][b];
          right_cost[b] = cnt ? acc.half_area() * T((cnt + block - 1) / block) : T(0);
        }
        acc = Aabb<T>();
        cnt = 0;
        for (int b = 0; b < nb - 1; ++b) {
          acc.extend(bins[axis][b].aabb());
          cnt += counts[axis][b];
          if (cnt == 0 || cnt == count) continue;
          const T cost = acc.half_area() * T((cnt + block - 1) / block) + right_cost[b + 1];
          if (cost < best_cost) {
            best_cost = cost;
            best_axis = axis;
            best_bin = b;
          }
        }
      }
      if (best_axis < 0) {
        // All centroids coincide (or no split separates them): median split, as SahPartition.
        mid = count / 2;
        std::nth_element(p, p + mid, p + count, by_axis(t.cbox.longest_axis()));
      } else {
        const int ax = best_axis;
        const T lo_a = lo[ax], scale_a = scale[ax];
        auto left = [&](const SahPrim<T>& q) {
          return std::min(nb - 1, int((q.c[ax] - lo_a) * scale_a)) <= best_bin;
        };
        // Two-cursor partition; each primitive's centroid joins its side's box exactly once.
        SahPrim<T>* first = p;
        SahPrim<T>* last = p + count;
        SahBox<T> lc, rc;
        lc.reset();
        rc.reset();
        for (;;) {
          for (; first != last && left(*first); ++first) lc.extend(first->c, first->c);
          if (first == last) break;
          --last;
          for (; first != last && !left(*last); --last) rc.extend(last->c, last->c);
          rc.extend(first->c, first->c);
          if (first == last) break;
          lc.extend(last->c, last->c);
          std::swap(*first, *last);
          ++first;
        }
        mid = std::uint32_t(first - p);
        lcbox = lc.aabb();
        rcbox = rc.aabb();
        SahBox<T> l, r;
        l.reset();
        r.reset();
        for (int b = 0; b <= best_bin; ++b) l.extend(bins[ax][b]);
        for (int b = best_bin + 1; b < nb; ++b) r.extend(bins[ax][b]);
        lbox = l.aabb();
        rbox = r.aabb();
        boxes_known = true;
      }
    }
    if (!boxes_known) {
      lbox = detail::box_of(p, mid);
      rbox = detail::box_of(p + mid, count - mid);
      lcbox = detail::centroid_box_of(p, mid);
      rcbox = detail::centroid_box_of(p + mid, count - mid);
    }
    const std::uint32_t first_child = std::uint32_t(tree.nodes.size());
    tree.nodes[t.node].first = first_child;
    tree.nodes[t.node].count = 0;
    tree.nodes[t.node].children = 2;
    tree.nodes.resize(tree.nodes.size() + 2);
    todo.push_back({first_child + 1, t.begin + mid, t.end, t.depth + 1, rbox, rcbox});
    todo.push_back({first_child, t.begin, t.begin + mid, t.depth + 1, lbox, lcbox});
  }
  for (std::uint32_t i = 0; i < n; ++i) tree.prim[i] = prims[i].index;
  return tree;
}

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
    return build_sah<T>(boxes, centroids, SahPartition{options.bins, options.block}, leaf);
  }
}

} // namespace ebgeom::bvh
