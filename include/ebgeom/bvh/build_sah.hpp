// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `build_sah`: the binned SAH build of `build_top_down(SahPartition, LeafSizeStop)`, node for
/// node, with about 2.3x fewer instructions (what `bvh::build` runs for `BuildMethod::sah_binned`).

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#include "ebgeom/bvh/build_tree.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#endif

namespace ebgeom::bvh {

namespace detail {
/// Four lanes of T with the few operations the SAH builder needs, each lane's result equal to the
/// scalar one (`min(a, b)` is `b < a ? b : a`, as `std::min`, for non-NaN values). SSE2 on x86-64
/// (the compilers do not vectorise these reliably on their own); plain arrays elsewhere.
template <class T> struct Lanes4 {
  T v[4];
  /// Lanes 0-2 from p[0..2]; lane 3 is 0 here (the SSE versions read p[3], see `SahPrim`).
  static Lanes4 load(const T* p) noexcept { return {{p[0], p[1], p[2], T(0)}}; }
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
  /// Bin of lane j in a flat array of 4 runs of `sah_max_bins`: min(int((c - lo) * scale), top)
  /// + j * sah_max_bins, for (c - lo) * scale >= 0 (lanes 0-2; out[3] is not used).
  static void bin(const T* c, const Lanes4& lo, const Lanes4& scale, T top,
                  std::uint32_t* out) noexcept {
    out[3] = 0;
    for (int j = 0; j < 3; ++j)
      out[j] = std::uint32_t(std::min((c[j] - lo.v[j]) * scale.v[j], top)) + j * sah_max_bins;
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
                  std::uint32_t* out) noexcept {
    const __m128 f = _mm_mul_ps(_mm_sub_ps(_mm_loadu_ps(c), lo.v), scale.v);
    const __m128i b = _mm_cvttps_epi32(_mm_min_ps(f, _mm_set1_ps(top)));
    _mm_storeu_si128(
        reinterpret_cast<__m128i*>(out),
        _mm_add_epi32(b, _mm_setr_epi32(0, sah_max_bins, 2 * sah_max_bins, 3 * sah_max_bins)));
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
                  std::uint32_t* out) noexcept {
    const __m128d t = _mm_set1_pd(top);
    const __m128d f0 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(c), lo.a), scale.a);
    const __m128d f1 = _mm_mul_pd(_mm_sub_pd(_mm_loadu_pd(c + 2), lo.b), scale.b);
    const __m128i b = _mm_unpacklo_epi64(_mm_cvttpd_epi32(_mm_min_pd(f0, t)),
                                         _mm_cvttpd_epi32(_mm_min_pd(f1, t)));
    _mm_storeu_si128(
        reinterpret_cast<__m128i*>(out),
        _mm_add_epi32(b, _mm_setr_epi32(0, sah_max_bins, 2 * sah_max_bins, 3 * sah_max_bins)));
  }
};
#endif

/// A primitive as the fast SAH builder moves it: centroid, box corners and input index, packed
/// into 40 B (float) / 80 B (double), so the top levels of a big build stream less memory. A box
/// update or a bin index is one 4-wide operation on a triple read as 4 lanes: lane 3 then holds
/// the next field (lo.x after c, hi.x after lo, the index bits after hi), which no result uses
/// (boxes and bins take lanes 0-2; min/max/compare on any bits is harmless).
template <class T> struct SahPrim {
  T v[9]; ///< c.xyz, lo.xyz, hi.xyz
  std::uint32_t index;
  const T* c() const noexcept { return v; }
  const T* lo() const noexcept { return v + 3; }
  const T* hi() const noexcept { return v + 6; }
};
static_assert(sizeof(SahPrim<float>) == 40 && sizeof(SahPrim<double>) == 80);
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
/// Order-preserving map of a finite T to an unsigned integer (and back): a < b implies
/// key(a) < key(b), and consecutive keys are consecutive values.
template <class T> struct OrderedKey {
  using U = std::conditional_t<sizeof(T) == 4, std::uint32_t, std::uint64_t>;
  static constexpr U sign = U(1) << (8 * sizeof(T) - 1);
  static U of(T x) noexcept {
    U u;
    std::memcpy(&u, &x, sizeof u);
    return (u & sign) ? ~u : (u | sign);
  }
  static T value(U k) noexcept {
    const U u = (k & sign) ? (k & ~sign) : ~k;
    T x;
    std::memcpy(&x, &u, sizeof x);
    return x;
  }
};
/// The smallest tau in [lo, hi] with bin(tau) > best, where bin(c) = int(min((c - lo) · scale,
/// top)) is SahPartition's bin index (bin(lo) = 0 <= best < top = bin(hi)). The bin is monotone in
/// c, so "bin(c) <= best" is exactly "c < tau". Bisection over the values' order, from a bracket
/// around the estimate lo + (best + 1) / scale (the whole range if that fails): at most
/// 8·sizeof(T) steps, usually 4.
template <class T> T bin_threshold(T lo, T hi, T scale, T top, int best) noexcept {
  using K = OrderedKey<T>;
  using U = typename K::U;
  auto above = [&](U k) { return int(std::min((K::value(k) - lo) * scale, top)) > best; };
  U a = K::of(lo), b = K::of(hi); // above(a) is false, above(b) is true
  const T est = lo + T(best + 1) / scale;
  if (est > lo && est < hi) {
    const U e = K::of(est), ea = e - std::min<U>(8, e - a), eb = e + std::min<U>(8, b - e);
    if (!above(ea) && above(eb)) a = ea, b = eb;
  }
  while (b - a > 1) {
    const U m = a + (b - a) / 2;
    (above(m) ? b : a) = m;
  }
  return K::value(b);
}
/// Puts the `mid` smallest of p[0..count) by (c[axis], input index) first and returns the boxes
/// and centroid boxes of both halves. The order is total, so this selects the same halves as
/// SahPartition's sort.
template <class T>
void select_halves(SahPrim<T>* p, std::uint32_t count, std::uint32_t mid, int axis,
                   Aabb<T> (&box)[2], Aabb<T> (&cbox)[2]) {
  std::nth_element(p, p + mid, p + count, [axis](const SahPrim<T>& a, const SahPrim<T>& b) {
    return a.v[axis] < b.v[axis] || (a.v[axis] == b.v[axis] && a.index < b.index);
  });
  for (int h = 0; h < 2; ++h) {
    SahBox<T> bb, cb;
    bb.reset();
    cb.reset();
    for (std::uint32_t i = h ? mid : 0, e = h ? count : mid; i < e; ++i) {
      bb.extend(p[i].lo(), p[i].hi());
      cb.extend(p[i].c(), p[i].c());
    }
    box[h] = bb.aabb();
    cbox[h] = cb.aabb();
  }
}
} // namespace detail

/// The ready-made binned SAH build, fast: the same tree as
/// `build_top_down(boxes, centroids, sah, LeafSizeStop{max_leaf_size})` (the same nodes in the
/// same order, with the same boxes, and every leaf holding the same primitives; only their order
/// inside a leaf may differ), with about 2.3x fewer instructions. Each primitive's box, centroid
/// and index are copied once into one array that the build partitions in place, so every pass
/// reads memory in order (no gather through an index array); a node's box and centroid box come
/// from its parent's bins and partition pass instead of a pass of their own; a box update is one
/// 4-wide min and max, into one of two sets of bins (even and odd primitives); the partition
/// compares coordinates with one threshold; small nodes select instead of sorting. One allocation
/// for the whole build besides the tree. O(n log n). Single-threaded; deterministic.
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
  constexpr int max_bins = detail::sah_max_bins;
  const int nb = std::max(2, std::min(sah.bins, max_bins));

  std::vector<SahPrim<T>> prims(n);
  Aabb<T> root_box, root_cbox;
  for (std::uint32_t i = 0; i < n; ++i) {
    const Aabb<T>& b = boxes[i];
    const Vec3<T>& c = centroids[i];
    SahPrim<T>& q = prims[i]; // value-initialised: the double record's padding is zero
    const T v[9] = {c.x, c.y, c.z, b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z};
    std::copy(v, v + 9, q.v);
    q.index = i;
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
  // Two sets of bins, for even and odd primitives: consecutive primitives are often neighbours
  // and fall in the same bins, and alternating sets halves the chain of dependent updates.
  SahBox<T> bins[2][4][max_bins]; // per set: one run of bins per axis (the 4th is never used)
  std::uint32_t counts[2][4][max_bins];
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
    Aabb<T> cbox[2], cent[2]; // the children's boxes and centroid boxes
    if (block > 1 && count <= 4 * block) {
      // Small node: whole blocks, cut after a multiple of `block` along the longest axis. The
      // order is total, so selecting the first `mid` gives the halves SahPartition's sort gives.
      mid = detail::block_cut(count, block);
      detail::select_halves(p, count, mid, t.cbox.longest_axis(), cbox, cent);
    } else {
      const Vec3<T> ext = t.cbox.extent();
      const T lo[4] = {t.cbox.lo.x, t.cbox.lo.y, t.cbox.lo.z, T(0)};
      T scale[4] = {T(0), T(0), T(0), T(0)};
      for (int a = 0; a < 3; ++a) scale[a] = detail::bin_scale(nb, ext[a]);
      for (int a = 0; a < 3; ++a)
        for (int b = 0; b < nb; ++b) {
          bins[0][a][b].reset(), bins[1][a][b].reset();
          counts[0][a][b] = counts[1][a][b] = 0;
        }
      // int(min(f, nb - 1)) == min(int(f), nb - 1) for f >= 0: SahPartition's bin, exactly.
      const Lanes4<T> lo4 = Lanes4<T>::load(lo), scale4 = Lanes4<T>::load(scale);
      const T top = T(nb - 1);
      const int la = t.cbox.longest_axis();
      const bool one_axis = count > sah.longest_axis_above;
      const int a0 = one_axis ? la : 0, a1 = one_axis ? la + 1 : 3; // binned and swept axes
      auto bin3 = [&](const SahPrim<T>& q, SahBox<T>(&set)[4][max_bins],
                      std::uint32_t(&cnt)[4][max_bins]) {
        std::uint32_t b[4]; // flat indices into set and cnt
        Lanes4<T>::bin(q.c(), lo4, scale4, top, b);
        for (int a = 0; a < 3; ++a) {
          (&set[0][0])[b[a]].extend(q.lo(), q.hi());
          ++(&cnt[0][0])[b[a]];
        }
      };
      const T lo_l = lo[la], scale_l = scale[la];
      auto bin1 = [&](const SahPrim<T>& q, SahBox<T>(&set)[4][max_bins],
                      std::uint32_t(&cnt)[4][max_bins]) {
        const int b = int(std::min((q.v[la] - lo_l) * scale_l, top));
        set[la][b].extend(q.lo(), q.hi());
        ++cnt[la][b];
      };
      std::uint32_t i = 0;
      if (one_axis) {
        for (; i + 1 < count; i += 2) {
          bin1(p[i], bins[0], counts[0]);
          bin1(p[i + 1], bins[1], counts[1]);
        }
        if (i < count) bin1(p[i], bins[0], counts[0]);
      } else {
        for (; i + 1 < count; i += 2) {
          bin3(p[i], bins[0], counts[0]);
          bin3(p[i + 1], bins[1], counts[1]);
        }
        if (i < count) bin3(p[i], bins[0], counts[0]);
      }
      for (int a = a0; a < a1; ++a)
        for (int b = 0; b < nb; ++b) {
          bins[0][a][b].extend(bins[1][a][b]);
          counts[0][a][b] += counts[1][a][b];
        }
      // SahPartition's sweep (same costs, same choice).
      const detail::SahSplit split = detail::sah_sweep<T>(
          ext, a0, a1, nb, count, block, [&](int a, int b) { return bins[0][a][b].aabb(); },
          [&](int a, int b) { return counts[0][a][b]; });
      const int best_bin = split.bin;
      if (split.axis < 0) {
        // All centroids coincide (or no split separates them): median split, as SahPartition.
        mid = count / 2;
        detail::select_halves(p, count, mid, t.cbox.longest_axis(), cbox, cent);
      } else {
        const int ax = split.axis;
        const T tau = detail::bin_threshold(t.cbox.lo[ax], t.cbox.hi[ax], scale[ax], top, best_bin);
        auto left = [&](const SahPrim<T>& q) { return q.v[ax] < tau; };
        // Two-cursor partition; each primitive's centroid joins its side's box exactly once.
        SahPrim<T>* first = p;
        SahPrim<T>* last = p + count;
        SahBox<T> lc, rc;
        lc.reset();
        rc.reset();
        for (;;) {
          for (; first != last && left(*first); ++first) lc.extend(first->c(), first->c());
          if (first == last) break;
          --last;
          for (; first != last && !left(*last); --last) rc.extend(last->c(), last->c());
          rc.extend(first->c(), first->c());
          if (first == last) break;
          lc.extend(last->c(), last->c());
          std::swap(*first, *last);
          ++first;
        }
        mid = std::uint32_t(first - p);
        cent[0] = lc.aabb();
        cent[1] = rc.aabb();
        SahBox<T> l, r;
        l.reset();
        r.reset();
        for (int b = 0; b <= best_bin; ++b) l.extend(bins[0][ax][b]);
        for (int b = best_bin + 1; b < nb; ++b) r.extend(bins[0][ax][b]);
        cbox[0] = l.aabb();
        cbox[1] = r.aabb();
      }
    }
    const std::uint32_t first_child = std::uint32_t(tree.nodes.size());
    tree.nodes[t.node].first = first_child;
    tree.nodes[t.node].count = 0;
    tree.nodes[t.node].children = 2;
    tree.nodes.resize(tree.nodes.size() + 2);
    todo.push_back({first_child + 1, t.begin + mid, t.end, t.depth + 1, cbox[1], cent[1]});
    todo.push_back({first_child, t.begin, t.begin + mid, t.depth + 1, cbox[0], cent[0]});
  }
  for (std::uint32_t i = 0; i < n; ++i) tree.prim[i] = prims[i].index;
  return tree;
}

} // namespace ebgeom::bvh
