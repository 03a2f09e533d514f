// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// SIMD helpers shared by the vector kernels: per-lane bit masks of a W-wide block (`LaneMask`,
/// `detail::lane_mask`), the minimum over a block's lanes (`lane_min`), the lowest set bit and a
/// prefetch hint, and square roots of a block's lanes (`lane_sqrt`). On instruction sets with AVX /
/// AVX-512 (the template argument `I`, see `core/isa.hpp`) the masks come from vector compares; the
/// plain loops are the reference and the fallback, with the same results.

#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"

#if defined(__SSE2__) || defined(__AVX__) || EBGEOM_ISA_DISPATCH
#include <immintrin.h>
#endif

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

namespace detail {
/// Index of the lowest set bit of `x` (x != 0).
template <class U> inline int lowest_bit(U x) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  if constexpr (sizeof(U) > sizeof(unsigned))
    return __builtin_ctzll(x);
  else
    return __builtin_ctz(unsigned(x));
#else
  int i = 0;
  while (!((x >> i) & 1)) ++i;
  return i;
#endif
}
} // namespace detail

/// One bit per lane of a W-wide block.
template <int W> using LaneMask = std::conditional_t<(W > 32), std::uint64_t, std::uint32_t>;

namespace detail {
enum class LaneCmp { le, eq };

/// Bytes per register with which `lane_mask` compares W values of T on instruction set I: 64 with
/// AVX-512, 32 with AVX2 (W values filling whole registers), else 0 (the plain loop).
template <class T, int W, Isa I> constexpr int lane_mask_register_bytes() noexcept {
  if constexpr (!std::is_same_v<T, float> && !std::is_same_v<T, double>) return 0;
#if EBGEOM_ISA_DISPATCH || defined(__AVX2__)
  if (I == Isa::avx512 && W * sizeof(T) % 64 == 0) return 64;
  if (I >= Isa::avx2 && W * sizeof(T) % 32 == 0) return 32;
#endif
  return 0;
}

#if EBGEOM_ISA_DISPATCH || defined(__AVX2__)
/// `lane_mask` of the 32 / sizeof(T) values at `v`: a compare and a `movemask`. Not forced inline
/// (an AVX function inlines only into AVX code): it inlines into the kernels of the same target
/// and options (`EBGEOM_VECTOR_KERNEL`) that call it.
template <LaneCmp C, class T>
EBGEOM_TARGET_AVX2 EBGEOM_VECTOR_KERNEL inline std::uint32_t register_mask_avx(const T* v,
                                                                               T b) noexcept {
  constexpr int pred = C == LaneCmp::le ? _CMP_LE_OQ : _CMP_EQ_OQ;
  if constexpr (sizeof(T) == 8)
    return unsigned(_mm256_movemask_pd(_mm256_cmp_pd(_mm256_loadu_pd(v), _mm256_set1_pd(b), pred)));
  else
    return unsigned(_mm256_movemask_ps(_mm256_cmp_ps(_mm256_loadu_ps(v), _mm256_set1_ps(b), pred)));
}
#endif

#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
/// `lane_mask` of the 64 / sizeof(T) values at `v`: one compare into a mask register.
template <LaneCmp C, class T>
EBGEOM_TARGET_AVX512 EBGEOM_VECTOR_KERNEL inline std::uint32_t register_mask_avx512(const T* v,
                                                                                    T b) noexcept {
  constexpr int pred = C == LaneCmp::le ? _CMP_LE_OQ : _CMP_EQ_OQ;
  if constexpr (sizeof(T) == 8)
    return _mm512_cmp_pd_mask(_mm512_loadu_pd(v), _mm512_set1_pd(b), pred);
  else
    return _mm512_cmp_ps_mask(_mm512_loadu_ps(v), _mm512_set1_ps(b), pred);
}
#endif

#if EBGEOM_ISA_DISPATCH || defined(__AVX2__)
/// Square roots of the 32 / sizeof(T) values at `v` into `out` (see `lane_sqrt`).
template <class T>
EBGEOM_TARGET_AVX2 EBGEOM_VECTOR_KERNEL inline void register_sqrt_avx(const T* v, T* out) noexcept {
  if constexpr (sizeof(T) == 8)
    _mm256_storeu_pd(out, _mm256_sqrt_pd(_mm256_loadu_pd(v)));
  else
    _mm256_storeu_ps(out, _mm256_sqrt_ps(_mm256_loadu_ps(v)));
}
#endif

#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
/// Square roots of the 64 / sizeof(T) values at `v` into `out` (see `lane_sqrt`). The zero-masked
/// form with every lane set: GCC 12 warns of an uninitialised value in the plain one's header.
template <class T>
EBGEOM_TARGET_AVX512 EBGEOM_VECTOR_KERNEL inline void register_sqrt_avx512(const T* v,
                                                                           T* out) noexcept {
  if constexpr (sizeof(T) == 8)
    _mm512_storeu_pd(out, _mm512_maskz_sqrt_pd(0xff, _mm512_loadu_pd(v)));
  else
    _mm512_storeu_ps(out, _mm512_maskz_sqrt_ps(0xffff, _mm512_loadu_ps(v)));
}
#endif

/// `out[l] = sqrt(v[l])` for the W lanes, in vector registers on instruction set I. The square
/// root is correctly rounded, so the values are `std::sqrt`'s; but GCC 12 neither inlines
/// `std::sqrt` into a kernel of other options nor vectorises `__builtin_sqrt` while `errno` may
/// be set (the `optimize("no-math-errno")` attribute does not lift it): a loop of `std::sqrt`
/// there is a library call per lane. SSE2 registers where the kernel has neither AVX2 nor
/// AVX-512; the plain loop is the fallback elsewhere.
template <Isa I = native_isa, class T, int W>
EBGEOM_FORCE_INLINE void lane_sqrt(const T (&v)[W], T (&out)[W]) noexcept {
  constexpr int bytes = lane_mask_register_bytes<T, W, I>();
#if defined(__SSE2__)
  if constexpr (bytes == 0 &&
                (std::is_same_v<T, float> || std::is_same_v<T, double>)&&W * sizeof(T) % 16 == 0) {
    constexpr int n = 16 / int(sizeof(T));
    for (int r = 0; r < W / n; ++r) {
      if constexpr (sizeof(T) == 8)
        _mm_storeu_pd(out + r * n, _mm_sqrt_pd(_mm_loadu_pd(v + r * n)));
      else
        _mm_storeu_ps(out + r * n, _mm_sqrt_ps(_mm_loadu_ps(v + r * n)));
    }
    return;
  }
#endif
  if constexpr (bytes > 0) {
    constexpr int n = bytes / int(sizeof(T)); // lanes per register
    for (int r = 0; r < W / n; ++r) {
#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
      if constexpr (bytes == 64) register_sqrt_avx512(v + r * n, out + r * n);
#endif
#if EBGEOM_ISA_DISPATCH || defined(__AVX2__)
      if constexpr (bytes == 32) register_sqrt_avx(v + r * n, out + r * n);
#endif
    }
    return;
  }
  for (int l = 0; l < W; ++l) out[l] = std::sqrt(v[l]);
}

/// Bit l set where `v[l] <= b` (`LaneCmp::le`) or `v[l] == b` (`eq`); false for NaN lanes, as the
/// C++ comparisons. GCC 12 builds such a mask from vector compares with shifts, ors and shuffles
/// (with `lane_min`, 11% of a double ogre query's profile); with AVX-512 one compare gives it (a
/// mask register), with AVX a compare and a `movemask`. The plain loop is the reference and the
/// fallback. `I`: the instruction set of the calling kernel (`core/isa.hpp`).
template <LaneCmp C, Isa I = native_isa, class T, int W>
EBGEOM_FORCE_INLINE LaneMask<W> lane_mask(const T (&v)[W], T b) noexcept {
  LaneMask<W> mask = 0;
  constexpr int bytes = lane_mask_register_bytes<T, W, I>();
  if constexpr (bytes > 0) {
    constexpr int n = bytes / int(sizeof(T)); // lanes per register
    for (int r = 0; r < W / n; ++r) {
      std::uint32_t m = 0;
#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
      if constexpr (bytes == 64) m = register_mask_avx512<C>(v + r * n, b);
#endif
#if EBGEOM_ISA_DISPATCH || defined(__AVX2__)
      if constexpr (bytes == 32) m = register_mask_avx<C>(v + r * n, b);
#endif
      mask |= LaneMask<W>(m) << (r * n);
    }
    return mask;
  }
  for (int l = 0; l < W; ++l) mask |= LaneMask<W>(C == LaneCmp::le ? v[l] <= b : v[l] == b) << l;
  return mask;
}
} // namespace detail

/// The smallest of a block's W lane values and the lanes holding it (bit l of `mask`).
template <class T, int W> struct LaneMin {
  T min;
  LaneMask<W> mask;
};

/// `LaneMin` of W values: a tree of pairwise minima and a compare, plain loops that vectorise,
/// instead of W dependent scalar steps (those were a sixth of a mesh query). Exact: the minimum
/// does not depend on the order. A NaN lane counts as +infinity (a NaN distance never wins, as in
/// the brute force's `d2 < best2`) and hides no other lane.
template <class T, int W, Isa I = native_isa>
EBGEOM_VECTOR_KERNEL inline LaneMin<T, W> lane_min(const T (&v)[W]) noexcept {
  T u[W], t[W];
  for (int l = 0; l < W; ++l) u[l] = v[l] == v[l] ? v[l] : std::numeric_limits<T>::infinity();
  for (int l = 0; l < W; ++l) t[l] = u[l];
  if constexpr ((W & (W - 1)) == 0) { // halvings of constant length: each one vectorises
    if constexpr (W >= 64)
      for (int l = 0; l < 32; ++l) t[l] = t[l + 32] < t[l] ? t[l + 32] : t[l];
    if constexpr (W >= 32)
      for (int l = 0; l < 16; ++l) t[l] = t[l + 16] < t[l] ? t[l + 16] : t[l];
    if constexpr (W >= 16)
      for (int l = 0; l < 8; ++l) t[l] = t[l + 8] < t[l] ? t[l + 8] : t[l];
    if constexpr (W >= 8)
      for (int l = 0; l < 4; ++l) t[l] = t[l + 4] < t[l] ? t[l + 4] : t[l];
    if constexpr (W >= 4)
      for (int l = 0; l < 2; ++l) t[l] = t[l + 2] < t[l] ? t[l + 2] : t[l];
    if constexpr (W >= 2) t[0] = t[1] < t[0] ? t[1] : t[0];
  } else {
    for (int n = W; n > 1;) {
      const int h = n / 2, o = n - h; // pairs l with l + o; an odd middle lane waits a round
      for (int l = 0; l < h; ++l) t[l] = t[l + o] < t[l] ? t[l + o] : t[l];
      n = o;
    }
  }
  const T m = t[0];
  return {m, detail::lane_mask<detail::LaneCmp::eq, I>(u, m)};
}

namespace detail {
/// Hint that `p` will be read soon (no effect where the compiler has no prefetch builtin).
EBGEOM_FORCE_INLINE void prefetch(const void* p) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#else
  (void)p;
#endif
}
} // namespace detail

} // namespace ebgeom

EBGEOM_END_EXACT_FP
