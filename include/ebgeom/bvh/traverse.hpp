// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Queries over a `WideBvh`: one generic branch-and-bound nearest search shared by mesh SDFs,
/// BVH unions, closest points and nearest neighbours, plus generic visitors for other queries.
///
/// - `nearest` : pruned, ordered (closest child first), stack based. The leaf callback
///   `leaf(first, count, best2)` scans leaf slots [first, first + count) and may lower `best2`;
///   subtrees whose box is at squared distance >= best2 are skipped. With `Shrink = true` the bound
///   also shrinks to each child box's *farthest* distance before any leaf is reached (valid when
///   every primitive lies inside its box and distances are measured to the primitive itself).
///   A caller-supplied initial `best2` gives narrow-band queries.
/// - `for_each_leaf_if` : visits every leaf whose path of boxes satisfies a predicate;
///   `for_each_overlapping` (boxes overlapping a region) and `for_each_within` (boxes within a
///   radius of a point) are built on it.
/// - `k_nearest` : the k primitives nearest to a point, for any primitive distance.
/// All functions are allocation-free except `k_nearest`'s result, and thread-safe on a const BVH.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "ebgeom/bvh/simd_nodes.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"
#include "ebgeom/core/vec.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom::bvh {

/// A subtree waiting to be visited, with the squared distance of its box.
template <class T> struct Pending {
  ChildRef ref;
  T dist2;
};

/// Fixed-capacity stack on the call stack (no allocation). The capacity is proven by the builder.
/// The storage is left uninitialised (a union with an empty constructor): only pushed entries are
/// ever read, and constructing N entries per query would cost more than the query.
template <class E, int N> class FixedStack {
  static_assert(std::is_trivially_copyable_v<E> && std::is_trivially_destructible_v<E>,
                "FixedStack holds trivially copyable entries");

 public:
  FixedStack() noexcept {}
  void push(const E& e) noexcept {
    EBGEOM_ASSERT(size_ < N);
    store_.data[size_++] = e;
  }
  E pop() noexcept { return store_.data[--size_]; }
  bool empty() const noexcept { return size_ == 0; }
  int size() const noexcept { return size_; }

 private:
  union Storage {
    Storage() noexcept {}
    E data[N];
  } store_;
  int size_ = 0;
};

/// Slack applied to a farthest-distance bound so that rounding in a primitive's own distance can
/// never leave the true nearest primitive above the bound.
/// Also adds the smallest normal number so a bound of exactly 0 (a point primitive at the query)
/// still admits that primitive.
template <class T> constexpr T shrink_bound(T far2) noexcept {
  return far2 * (T(1) + T(64) * std::numeric_limits<T>::epsilon()) + std::numeric_limits<T>::min();
}

/// A subtree is skipped only when its box is farther than the best distance by more than a few
/// ulps: a primitive's computed distance can come out slightly *below* the computed distance of
/// its own box (rounding in a projection), and skipping on the exact comparison would then miss
/// the minimum that a brute-force scan over the same kernel finds.
/// `abs_slack` (>= 0) widens it by an absolute amount: the rounding of a primitive's squared
/// distance near its surface is absolute (about eps · size²), not relative, and callers that need
/// exact ties (mesh SDFs) pass a bound on it. A box at distance 0 is always visited.
template <class T> constexpr T prune_limit(T best2, T abs_slack = T(0)) noexcept {
  return best2 * (T(1) + T(64) * std::numeric_limits<T>::epsilon()) + abs_slack +
         std::numeric_limits<T>::min();
}

namespace detail {
/// The low bits of a child key that hold the child (`order_children`): enough for K children.
template <int K>
inline constexpr std::uint32_t child_bits = K <= 2   ? 1u
                                            : K <= 4 ? 2u
                                            : K <= 8 ? 3u
                                                     : 4u;
template <int K> inline constexpr std::uint32_t child_mask = (1u << child_bits<K>)-1u;

/// Key of child `k` at squared distance `d2` (>= 0): the bits of d2's float rounding without the
/// sign (so -0 keys as +0), whose lowest `child_bits<K>` bits are replaced by k. Such keys order as
/// unsigned integers as the distances do, except that distances within a few float ulps of each
/// other may swap (the order only guides the search; ties at equal keys keep the child order).
/// Below 2^31, so every included key is below `excluded_key`.
template <int K, class T> inline std::uint32_t child_key(T d2, int k) noexcept {
  const float f = float(d2);
  std::uint32_t u;
  std::memcpy(&u, &f, sizeof u);
  return (u & 0x7fffffffu & ~child_mask<K>) | std::uint32_t(k);
}

/// The key of a child that `order_children` leaves out: above every included key.
inline constexpr std::uint32_t excluded_key = 0xffffffffu;

#if EBGEOM_ISA_DISPATCH || defined(__AVX2__)
/// One layer of compare-exchanges on four unsigned keys: each lane meets `partner` (its pair's
/// other key); the lanes set in `HiWords` (a 16-bit blend mask) keep the larger key, the others
/// the smaller. One cycle each for the min, max and blend.
template <int HiWords>
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE __m128i compare_exchange4(__m128i x,
                                                                 __m128i partner) noexcept {
  return _mm_blend_epi16(_mm_min_epu32(x, partner), _mm_max_epu32(x, partner), HiWords);
}

/// Sorts four 32-bit keys in one register (`order_children` for K = 4) by the optimal 4-input
/// network (0,1)(2,3) (0,2)(1,3) (1,2), each layer one shuffle, a min, a max and a blend (about
/// 9 cycles in all, a third of the same network on 64-bit keys). Identical keys and order to the
/// scalar network (all keys are distinct).
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE __m128i sort4_keys(__m128i v) noexcept {
  v = compare_exchange4<0xcc>(v, _mm_shuffle_epi32(v, 0xb1));    // (0,1) (2,3): [1 0 3 2]
  v = compare_exchange4<0xf0>(v, _mm_shuffle_epi32(v, 0x4e));    // (0,2) (1,3): [2 3 0 1]
  return compare_exchange4<0x30>(v, _mm_shuffle_epi32(v, 0xd8)); // (1,2): [0 2 1 3]
}

/// Sorts the four children's keys (`child_key<4>` of the distances `f` where `in`, else
/// `excluded_key`) into `key`.
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE void order_keys4(__m128 f, __m128i in,
                                                        std::uint32_t (&key)[4]) noexcept {
  const __m128i bits = _mm_or_si128(_mm_and_si128(_mm_castps_si128(f), _mm_set1_epi32(0x7ffffffc)),
                                    _mm_setr_epi32(0, 1, 2, 3));
  const __m128i k = _mm_blendv_epi8(_mm_set1_epi32(-1), bits, in);
  _mm_storeu_si128(reinterpret_cast<__m128i*>(key), sort4_keys(k));
}

// Not forced inline: they inline into the dispatched AVX2 / AVX-512 kernels (or into every
// caller when the translation unit targets AVX2).
EBGEOM_TARGET_AVX2 inline int order_children4(const double (&d2)[4], double lim,
                                              std::uint32_t (&key)[4]) noexcept {
  const __m256d d = _mm256_loadu_pd(d2);
  const __m256d in = _mm256_cmp_pd(d, _mm256_set1_pd(lim), _CMP_LT_OQ);
  // The all-ones lanes of `in` (a quiet NaN) convert to all-ones floats, and zeros to zeros.
  order_keys4(_mm256_cvtpd_ps(d), _mm_castps_si128(_mm256_cvtpd_ps(in)), key);
  return _mm_popcnt_u32(unsigned(_mm256_movemask_pd(in)));
}

EBGEOM_TARGET_AVX2 inline int order_children4(const float (&d2)[4], float lim,
                                              std::uint32_t (&key)[4]) noexcept {
  const __m128 d = _mm_loadu_ps(d2);
  const __m128 in = _mm_cmplt_ps(d, _mm_set1_ps(lim));
  order_keys4(d, _mm_castps_si128(in), key);
  return _mm_popcnt_u32(unsigned(_mm_movemask_ps(in)));
}

/// One layer of compare-exchanges on eight unsigned keys: each lane meets lane `partner[lane]`;
/// the lanes set in `Hi` (an 8-bit blend mask) keep the larger key, the others the smaller.
template <int Hi>
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE __m256i compare_exchange8(__m256i x,
                                                                 __m256i partner) noexcept {
  const __m256i q = _mm256_permutevar8x32_epi32(x, partner);
  return _mm256_blend_epi32(_mm256_min_epu32(x, q), _mm256_max_epu32(x, q), Hi);
}

/// Sorts eight 32-bit keys in one register (`order_children` for K = 8 floats) by the optimal
/// 8-input network of depth 6 (19 compare-exchanges): (0,2)(1,3)(4,6)(5,7) (0,4)(1,5)(2,6)(3,7)
/// (0,1)(2,3)(4,5)(6,7) (2,4)(3,5) (1,4)(3,6) (1,2)(3,4)(5,6), each layer one lane permutation,
/// a min, a max and a blend. The keys are distinct, so the order is that of any correct sort.
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE __m256i sort8_keys(__m256i v) noexcept {
  v = compare_exchange8<0xcc>(v, _mm256_setr_epi32(2, 3, 0, 1, 6, 7, 4, 5));
  v = compare_exchange8<0xf0>(v, _mm256_setr_epi32(4, 5, 6, 7, 0, 1, 2, 3));
  v = compare_exchange8<0xaa>(v, _mm256_setr_epi32(1, 0, 3, 2, 5, 4, 7, 6));
  v = compare_exchange8<0x30>(v, _mm256_setr_epi32(0, 1, 4, 5, 2, 3, 6, 7));
  v = compare_exchange8<0x50>(v, _mm256_setr_epi32(0, 4, 2, 6, 1, 5, 3, 7));
  return compare_exchange8<0x54>(v, _mm256_setr_epi32(0, 2, 1, 4, 3, 6, 5, 7));
}

/// Sorts the eight children's keys (`child_key<8>` of the float distances `d` where `in`, else
/// `excluded_key`) into `key`; returns how many are in.
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE int order_keys8(__m256 d, __m256 in,
                                                       std::uint32_t (&key)[8]) noexcept {
  const __m256i bits =
      _mm256_or_si256(_mm256_and_si256(_mm256_castps_si256(d), _mm256_set1_epi32(0x7ffffff8)),
                      _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  const __m256i k = _mm256_blendv_epi8(_mm256_set1_epi32(-1), bits, _mm256_castps_si256(in));
  _mm256_storeu_si256(reinterpret_cast<__m256i*>(key), sort8_keys(k));
  return _mm_popcnt_u32(unsigned(_mm256_movemask_ps(in)));
}

EBGEOM_TARGET_AVX2 inline int order_children8(const float (&d2)[8], float lim,
                                              std::uint32_t (&key)[8]) noexcept {
  const __m256 d = _mm256_loadu_ps(d2);
  return order_keys8(d, _mm256_cmp_ps(d, _mm256_set1_ps(lim), _CMP_LT_OQ), key);
}

/// K = 8 doubles: compared in double, then keyed and sorted as eight floats (two AVX halves).
EBGEOM_TARGET_AVX2 inline int order_children8(const double (&d2)[8], double lim,
                                              std::uint32_t (&key)[8]) noexcept {
  const __m256d lo = _mm256_loadu_pd(d2), hi = _mm256_loadu_pd(d2 + 4), l = _mm256_set1_pd(lim);
  const __m256d in_lo = _mm256_cmp_pd(lo, l, _CMP_LT_OQ), in_hi = _mm256_cmp_pd(hi, l, _CMP_LT_OQ);
  const __m256 d = _mm256_set_m128(_mm256_cvtpd_ps(hi), _mm256_cvtpd_ps(lo));
  // The all-ones lanes of `in` (a quiet NaN) convert to all-ones floats, and zeros to zeros.
  return order_keys8(d, _mm256_set_m128(_mm256_cvtpd_ps(in_hi), _mm256_cvtpd_ps(in_lo)), key);
}

#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
/// One layer of compare-exchanges on sixteen unsigned keys: each lane meets lane
/// `partner[lane]`; the lanes set in `hi` keep the larger key, the others the smaller. Zero-masked
/// forms with all lanes set: GCC 12 warns of an uninitialised value in the plain ones' headers.
EBGEOM_TARGET_AVX512 EBGEOM_FORCE_INLINE __m512i compare_exchange16(__m512i x, __m512i partner,
                                                                    __mmask16 hi) noexcept {
  const __m512i q = _mm512_maskz_permutexvar_epi32(0xffff, partner, x);
  return _mm512_mask_blend_epi32(hi, _mm512_maskz_min_epu32(0xffff, x, q),
                                 _mm512_maskz_max_epu32(0xffff, x, q));
}

/// Sorts sixteen 32-bit keys in one register (`order_children` for K = 16 floats) by Batcher's
/// bitonic network (10 layers, 80 compare-exchanges), each layer one lane permutation, a min, a
/// max and a blend. The keys are distinct, so the order is that of any correct sort.
EBGEOM_TARGET_AVX512 EBGEOM_FORCE_INLINE __m512i sort16_keys(__m512i v) noexcept {
  v = compare_exchange16(v, _mm512_setr_epi32(1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14),
                         0x6666);
  v = compare_exchange16(v, _mm512_setr_epi32(2, 3, 0, 1, 6, 7, 4, 5, 10, 11, 8, 9, 14, 15, 12, 13),
                         0x3c3c);
  v = compare_exchange16(v, _mm512_setr_epi32(1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14),
                         0x5a5a);
  v = compare_exchange16(v, _mm512_setr_epi32(4, 5, 6, 7, 0, 1, 2, 3, 12, 13, 14, 15, 8, 9, 10, 11),
                         0x0ff0);
  v = compare_exchange16(v, _mm512_setr_epi32(2, 3, 0, 1, 6, 7, 4, 5, 10, 11, 8, 9, 14, 15, 12, 13),
                         0x33cc);
  v = compare_exchange16(v, _mm512_setr_epi32(1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14),
                         0x55aa);
  v = compare_exchange16(v, _mm512_setr_epi32(8, 9, 10, 11, 12, 13, 14, 15, 0, 1, 2, 3, 4, 5, 6, 7),
                         0xff00);
  v = compare_exchange16(v, _mm512_setr_epi32(4, 5, 6, 7, 0, 1, 2, 3, 12, 13, 14, 15, 8, 9, 10, 11),
                         0xf0f0);
  v = compare_exchange16(v, _mm512_setr_epi32(2, 3, 0, 1, 6, 7, 4, 5, 10, 11, 8, 9, 14, 15, 12, 13),
                         0xcccc);
  v = compare_exchange16(v, _mm512_setr_epi32(1, 0, 3, 2, 5, 4, 7, 6, 9, 8, 11, 10, 13, 12, 15, 14),
                         0xaaaa);
  return v;
}

EBGEOM_TARGET_AVX512 inline int order_children16(const float (&d2)[16], float lim,
                                                 std::uint32_t (&key)[16]) noexcept {
  const __m512 d = _mm512_loadu_ps(d2);
  const __mmask16 in = _mm512_cmp_ps_mask(d, _mm512_set1_ps(lim), _CMP_LT_OQ);
  const __m512i bits =
      _mm512_or_si512(_mm512_and_si512(_mm512_castps_si512(d), _mm512_set1_epi32(0x7ffffff0)),
                      _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15));
  const __m512i k = _mm512_mask_blend_epi32(in, _mm512_set1_epi32(-1), bits);
  _mm512_storeu_si512(key, sort16_keys(k));
  return __builtin_popcount(unsigned(in));
}

#endif
#endif

/// Sorts the children with `d2[k] < lim` nearest first into `key` (`child_key<K>`, the others last
/// as `excluded_key`; `key[j] & child_mask<K>` is the child) with a branch-free sorting network
/// (odd-even transposition; for K = 8 the 19-comparator network), and returns their count. Replaces
/// an insertion sort whose data-dependent branches mispredicted at every node. K = 4 (float or
/// double) and K = 8 (float or double) on instruction set I with AVX2, and K = 16 (float) with
/// AVX-512, take the vector networks above (same keys, same order).
template <class T, int K, Isa I = native_isa>
inline int order_children(const T (&d2)[K], T lim, std::uint32_t (&key)[K]) noexcept {
#if EBGEOM_ISA_DISPATCH || defined(__AVX2__)
  if constexpr (I >= Isa::avx2 && K == 4 && (std::is_same_v<T, float> || std::is_same_v<T, double>))
    return order_children4(d2, lim, key);
  if constexpr (I >= Isa::avx2 && K == 8 && (std::is_same_v<T, float> || std::is_same_v<T, double>))
    return order_children8(d2, lim, key);
#endif
#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
  if constexpr (I >= Isa::avx512 && K == 16 && std::is_same_v<T, float>)
    return order_children16(d2, lim, key);
#endif
  int m = 0;
  for (int k = 0; k < K; ++k) {
    const bool in = d2[k] < lim;
    m += in;
    key[k] = in ? child_key<K>(d2[k], k) : excluded_key;
  }
  const auto exchange = [&key](int i, int j) noexcept {
    const std::uint32_t a = key[i], b = key[j];
    key[i] = a < b ? a : b;
    key[j] = a < b ? b : a;
  };
  if constexpr (K == 8) { // the 19-comparator network of `sort8_keys` (28 in the loop below)
    constexpr int pairs[19][2] = {{0, 2}, {1, 3}, {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6},
                                  {3, 7}, {0, 1}, {2, 3}, {4, 5}, {6, 7}, {2, 4}, {3, 5},
                                  {1, 4}, {3, 6}, {1, 2}, {3, 4}, {5, 6}};
    for (const auto& q : pairs) exchange(q[0], q[1]);
  } else {
    for (int r = 0; r < K; ++r)
      for (int i = r & 1; i + 1 < K; i += 2) exchange(i, i + 1);
  }
  return m;
}
} // namespace detail

/// No prefetching (the default hook of `nearest`).
struct NoPrefetch {
  void operator()(ChildRef) const noexcept {}
};

/// No second bound (the default hook of `nearest`).
struct NoRefine {
  template <class T, int K> void operator()(std::uint32_t, T (&)[K]) const noexcept {}
};

/// Nearest-first branch and bound (see the file comment). `best2` is in/out: the initial bound and
/// the final best squared distance the leaf callback reported.
/// A point with a NaN or infinite coordinate visits nothing (`best2` is left as it was): its box
/// distances are NaN or inf - inf, which would otherwise select empty children.
/// `I`: the instruction set of the box tests (`core/isa.hpp`; the caller's kernel target).
/// `prefetch(child)` is called for each child that survives a node's box test, nearest first, when
/// the node is expanded (before any of them is visited): a hook to start loading what the visit
/// will read (the search's own order and results do not depend on it).
/// `refine(node, d2)` may raise the children's squared box distances `d2` of inner node `node`
/// to any other lower bound of the distance to their primitives (`NodeObbs`), before they are
/// ordered and pruned.
template <bool Shrink = false, Isa I = native_isa, class T, int K, class BV, class LeafFn,
          class PrefetchFn = NoPrefetch, class RefineFn = NoRefine>
void nearest(const WideBvh<T, K, BV>& bvh, const Vec3<T>& p, T& best2, LeafFn&& leaf,
             T abs_slack = T(0), PrefetchFn prefetch = {}, RefineFn refine = {}) noexcept {
  if (bvh.root.is_empty() || !all_finite(p)) return;
  if (bvh.root.is_leaf()) {
    if (bvh.box.distance2(p) < prune_limit(best2, abs_slack))
      leaf(bvh.root.index, bvh.root.count, best2);
    return;
  }
  // The nearest surviving child is expanded at once (no push/pop round trip); the others wait
  // on the stack, nearest on top, and are re-checked against the bound when popped.
  FixedStack<Pending<T>, WideBvh<T, K, BV>::stack_capacity> todo;
  ChildRef cur = bvh.root;
  bool shrink = Shrink; // until the first leaf: its exact distance is then the tighter bound
  for (;;) {
    if (cur.is_leaf()) {
      leaf(cur.index, cur.count, best2);
      shrink = false;
    } else {
      const auto& n = bvh.nodes[cur.index];
      T d2[K];
      detail::node_dist2<I>(n, p, d2);
      refine(cur.index, d2);
      if (Shrink && shrink) {
        T far2[K];
        detail::node_far_dist2<I>(n, p, far2);
        T m = best2;
        for (int k = 0; k < K; ++k) m = std::min(m, shrink_bound(far2[k]));
        best2 = m;
      }
      // Children that can still hold a closer primitive, nearest first: branch-free sort of
      // (distance, child) keys (`order_children`); the nearest is expanded, the others pushed
      // far to near.
      const T lim = prune_limit(best2, abs_slack);
      std::uint32_t key[K];
      const int m = detail::order_children<T, K, I>(d2, lim, key);
      if (m > 0) {
        constexpr std::uint32_t child = detail::child_mask<K>;
        for (int j = 0; j < m; ++j) prefetch(n.child[key[j] & child]);
        for (int j = m - 1; j > 0; --j) {
          const int k = int(key[j] & child);
          todo.push({n.child[k], d2[k]});
        }
        cur = n.child[key[0] & child];
        continue;
      }
    }
    // Next: the nearest waiting subtree that a closer hit has not ruled out since its push.
    for (;;) {
      if (todo.empty()) return;
      const Pending<T> top = todo.pop();
      if (top.dist2 < prune_limit(best2, abs_slack)) {
        cur = top.ref;
        break;
      }
    }
  }
}

/// Calls `leaf(first, count)` for every leaf all of whose ancestors' boxes, and its own, satisfy
/// `keep(box)`. `leaf` returns false to stop the whole traversal early. Depth first.
template <class T, int K, class BV, class KeepFn, class LeafFn>
void for_each_leaf_if(const WideBvh<T, K, BV>& bvh, KeepFn&& keep, LeafFn&& leaf) {
  if (bvh.root.is_empty() || !keep(bvh.box)) return;
  if (bvh.root.is_leaf()) {
    leaf(bvh.root.index, bvh.root.count);
    return;
  }
  FixedStack<std::uint32_t, WideBvh<T, K, BV>::stack_capacity> todo;
  todo.push(bvh.root.index);
  while (!todo.empty()) {
    const auto& n = bvh.nodes[todo.pop()];
    for (int k = K - 1; k >= 0; --k) {
      const ChildRef r = n.child[k];
      if (r.is_empty() || !keep(n.child_bv(k))) continue;
      if (r.is_leaf()) {
        if (!leaf(r.index, r.count)) return;
      } else {
        todo.push(r.index);
      }
    }
  }
}

/// Calls `fn(slot)` for every primitive slot in a leaf whose box overlaps `region` (a superset of
/// the primitives that overlap it: test the primitive itself in `fn` when that matters).
template <class T, int K, class BV, class Fn>
void for_each_overlapping(const WideBvh<T, K, BV>& bvh, const Aabb<T>& region, Fn&& fn) {
  for_each_leaf_if(
      bvh, [&](const auto& b) { return b.overlaps(region); },
      [&](std::uint32_t first, std::uint32_t count) {
        for (std::uint32_t s = first; s < first + count; ++s) fn(s);
        return true;
      });
}

/// Calls `fn(slot)` for every primitive slot in a leaf whose box is within `radius` of `p`.
template <class T, int K, class BV, class Fn>
void for_each_within(const WideBvh<T, K, BV>& bvh, const Vec3<T>& p, T radius, Fn&& fn) {
  const T r2 = radius * radius;
  for_each_leaf_if(
      bvh, [&](const auto& b) { return b.distance2(p) <= r2; },
      [&](std::uint32_t first, std::uint32_t count) {
        for (std::uint32_t s = first; s < first + count; ++s) fn(s);
        return true;
      });
}

/// One result of `k_nearest`: squared distance, leaf slot, and the tie-break key of that slot.
template <class T> struct Neighbour {
  T dist2;
  std::uint32_t slot;
  std::uint32_t key;
  friend bool operator<(const Neighbour& a, const Neighbour& b) noexcept {
    return a.dist2 < b.dist2 || (a.dist2 == b.dist2 && a.key < b.key);
  }
};

/// Tie-break key of `k_nearest`: the slot itself.
struct SlotKey {
  std::uint32_t operator()(std::uint32_t slot) const noexcept { return slot; }
};

/// The `k` primitives nearest to `p` whose squared distance (`dist2(slot)`, the distance to the
/// primitive itself, >= the distance to its box) is at most `max_dist2`, sorted by distance then
/// by `key(slot)` (e.g. the input index). Exact: equal to sorting all primitives that way and
/// keeping the first k.
template <class T, int K, class BV, class Dist2Fn, class KeyFn = SlotKey>
std::vector<Neighbour<T>>
k_nearest(const WideBvh<T, K, BV>& bvh, const Vec3<T>& p, std::size_t k, Dist2Fn&& dist2,
          T max_dist2 = std::numeric_limits<T>::infinity(), KeyFn&& key = {}) {
  std::vector<Neighbour<T>> heap; // max-heap on (dist2, key)
  if (k == 0) return heap;
  heap.reserve(k + 1);
  T bound = max_dist2;
  // `nearest` prunes boxes with d2 >= best2; a box at exactly the k-th distance may still hold a
  // tie with a smaller key, so the bound handed to the traversal is nudged up one ulp.
  T best2 = std::nextafter(bound, std::numeric_limits<T>::infinity());
  nearest(bvh, p, best2, [&](std::uint32_t first, std::uint32_t count, T& b2) {
    for (std::uint32_t s = first; s < first + count; ++s) {
      const Neighbour<T> c{dist2(s), s, key(s)};
      if (!(c.dist2 <= bound)) continue;
      if (heap.size() < k) {
        heap.push_back(c);
        std::push_heap(heap.begin(), heap.end());
      } else if (c < heap.front()) {
        std::pop_heap(heap.begin(), heap.end());
        heap.back() = c;
        std::push_heap(heap.begin(), heap.end());
      } else {
        continue;
      }
      if (heap.size() == k) {
        bound = heap.front().dist2;
        b2 = std::nextafter(bound, std::numeric_limits<T>::infinity());
      }
    }
  });
  std::sort_heap(heap.begin(), heap.end());
  return heap;
}

} // namespace ebgeom::bvh

EBGEOM_END_EXACT_FP
