// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// SIMD versions of the per-node child box distances of `wide_bvh.hpp` for the common widths:
/// K = 4 and 8 floats (SSE; K = 8 in one register with AVX) and K = 4 doubles (AVX), and for the
/// wider nodes a user may choose, K = 16 floats and K = 8 doubles (AVX-512). GCC does not
/// vectorise the generic `std::max` loops there (scalar compares and branches: a quarter of a mesh
/// query's instructions), so these overloads, more specialised than the generic templates, take
/// over when the compiler targets the instruction set. Same values as the generic loops (max/min of
/// non-NaN operands are exact; ±0 squares to +0); the generic code remains the reference and the
/// fallback on other targets. The dispatched kernels (`core/isa.hpp`) reach the AVX forms through
/// `detail::node_dist2<I>` whatever the translation unit's flags.

#include <type_traits>

#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"

#if defined(__SSE2__) || defined(__AVX__) || EBGEOM_ISA_DISPATCH
#include <immintrin.h>
#endif

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom::bvh::detail {
/// True for the node types with an AVX form of the child distances.
template <class T, int K, class BV>
inline constexpr bool has_avx_form = std::is_same_v<BV, Aabb<T>> &&
                                     ((std::is_same_v<T, float> && K == 8) ||
                                      (std::is_same_v<T, double> && K == 4));
/// True for the node types with an AVX-512 form of the child distances (16 floats, 8 doubles).
template <class T, int K, class BV>
inline constexpr bool has_avx512_form = std::is_same_v<BV, Aabb<T>> &&
                                        ((std::is_same_v<T, float> && K == 16) ||
                                         (std::is_same_v<T, double> && K == 8));
} // namespace ebgeom::bvh::detail

namespace ebgeom::bvh {

#if defined(__SSE2__)
namespace detail {
/// Children j..j+3 of a float node, in one SSE register: the squared distance from `p` to each box.
template <int K>
EBGEOM_FORCE_INLINE void child_dist2_sse(const WideNode<float, K>& n, int j, const Vec3<float>& p,
                                         float* d2) noexcept {
  const __m128 z = _mm_setzero_ps();
  const __m128 px = _mm_set1_ps(p.x), py = _mm_set1_ps(p.y), pz = _mm_set1_ps(p.z);
  const __m128 dx = _mm_max_ps(_mm_max_ps(_mm_sub_ps(_mm_loadu_ps(n.lo_x + j), px),
                                          _mm_sub_ps(px, _mm_loadu_ps(n.hi_x + j))),
                               z);
  const __m128 dy = _mm_max_ps(_mm_max_ps(_mm_sub_ps(_mm_loadu_ps(n.lo_y + j), py),
                                          _mm_sub_ps(py, _mm_loadu_ps(n.hi_y + j))),
                               z);
  const __m128 dz = _mm_max_ps(_mm_max_ps(_mm_sub_ps(_mm_loadu_ps(n.lo_z + j), pz),
                                          _mm_sub_ps(pz, _mm_loadu_ps(n.hi_z + j))),
                               z);
  _mm_storeu_ps(d2 + j,
                _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz)));
}

/// Children j..j+3 of a float node: the squared distance from `p` to each box's farthest point.
template <int K>
EBGEOM_FORCE_INLINE void child_far_dist2_sse(const WideNode<float, K>& n, int j,
                                             const Vec3<float>& p, float* d2) noexcept {
  const __m128 px = _mm_set1_ps(p.x), py = _mm_set1_ps(p.y), pz = _mm_set1_ps(p.z);
  const __m128 dx = _mm_max_ps(_mm_sub_ps(px, _mm_loadu_ps(n.lo_x + j)),
                               _mm_sub_ps(_mm_loadu_ps(n.hi_x + j), px));
  const __m128 dy = _mm_max_ps(_mm_sub_ps(py, _mm_loadu_ps(n.lo_y + j)),
                               _mm_sub_ps(_mm_loadu_ps(n.hi_y + j), py));
  const __m128 dz = _mm_max_ps(_mm_sub_ps(pz, _mm_loadu_ps(n.lo_z + j)),
                               _mm_sub_ps(_mm_loadu_ps(n.hi_z + j), pz));
  _mm_storeu_ps(d2 + j,
                _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz)));
}
} // namespace detail

EBGEOM_FORCE_INLINE void child_dist2(const WideNode<float, 4>& n, const Vec3<float>& p,
                                     float (&d2)[4]) noexcept {
  detail::child_dist2_sse(n, 0, p, d2);
}
EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<float, 4>& n, const Vec3<float>& p,
                                         float (&d2)[4]) noexcept {
  detail::child_far_dist2_sse(n, 0, p, d2);
}
#if !defined(__AVX__)
// K = 8 floats without AVX: two SSE halves (the AVX forms below replace them under AVX).
EBGEOM_FORCE_INLINE void child_dist2(const WideNode<float, 8>& n, const Vec3<float>& p,
                                     float (&d2)[8]) noexcept {
  detail::child_dist2_sse(n, 0, p, d2);
  detail::child_dist2_sse(n, 4, p, d2);
}
EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<float, 8>& n, const Vec3<float>& p,
                                         float (&d2)[8]) noexcept {
  detail::child_far_dist2_sse(n, 0, p, d2);
  detail::child_far_dist2_sse(n, 4, p, d2);
}
#endif
#endif

namespace detail {
#if EBGEOM_ISA_DISPATCH || defined(__AVX__)
// The AVX forms (K = 8 floats, K = 4 doubles). Not forced inline, with the AVX target attribute:
// they inline into the dispatched AVX2 / AVX-512 kernels, and into every caller when the
// translation unit itself targets AVX.
EBGEOM_TARGET_AVX inline void child_dist2_avx(const WideNode<float, 8>& n, const Vec3<float>& p,
                                              float (&d2)[8]) noexcept {
  const __m256 z = _mm256_setzero_ps();
  const __m256 px = _mm256_set1_ps(p.x), py = _mm256_set1_ps(p.y), pz = _mm256_set1_ps(p.z);
  const __m256 dx = _mm256_max_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_loadu_ps(n.lo_x), px),
                                                _mm256_sub_ps(px, _mm256_loadu_ps(n.hi_x))),
                                  z);
  const __m256 dy = _mm256_max_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_loadu_ps(n.lo_y), py),
                                                _mm256_sub_ps(py, _mm256_loadu_ps(n.hi_y))),
                                  z);
  const __m256 dz = _mm256_max_ps(_mm256_max_ps(_mm256_sub_ps(_mm256_loadu_ps(n.lo_z), pz),
                                                _mm256_sub_ps(pz, _mm256_loadu_ps(n.hi_z))),
                                  z);
  _mm256_storeu_ps(d2, _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                     _mm256_mul_ps(dz, dz)));
}

EBGEOM_TARGET_AVX inline void child_far_dist2_avx(const WideNode<float, 8>& n, const Vec3<float>& p,
                                                  float (&d2)[8]) noexcept {
  const __m256 px = _mm256_set1_ps(p.x), py = _mm256_set1_ps(p.y), pz = _mm256_set1_ps(p.z);
  const __m256 dx = _mm256_max_ps(_mm256_sub_ps(px, _mm256_loadu_ps(n.lo_x)),
                                  _mm256_sub_ps(_mm256_loadu_ps(n.hi_x), px));
  const __m256 dy = _mm256_max_ps(_mm256_sub_ps(py, _mm256_loadu_ps(n.lo_y)),
                                  _mm256_sub_ps(_mm256_loadu_ps(n.hi_y), py));
  const __m256 dz = _mm256_max_ps(_mm256_sub_ps(pz, _mm256_loadu_ps(n.lo_z)),
                                  _mm256_sub_ps(_mm256_loadu_ps(n.hi_z), pz));
  _mm256_storeu_ps(d2, _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)),
                                     _mm256_mul_ps(dz, dz)));
}

EBGEOM_TARGET_AVX inline void child_dist2_avx(const WideNode<double, 4>& n, const Vec3<double>& p,
                                              double (&d2)[4]) noexcept {
  const __m256d z = _mm256_setzero_pd();
  const __m256d px = _mm256_set1_pd(p.x), py = _mm256_set1_pd(p.y), pz = _mm256_set1_pd(p.z);
  const __m256d dx = _mm256_max_pd(_mm256_max_pd(_mm256_sub_pd(_mm256_loadu_pd(n.lo_x), px),
                                                 _mm256_sub_pd(px, _mm256_loadu_pd(n.hi_x))),
                                   z);
  const __m256d dy = _mm256_max_pd(_mm256_max_pd(_mm256_sub_pd(_mm256_loadu_pd(n.lo_y), py),
                                                 _mm256_sub_pd(py, _mm256_loadu_pd(n.hi_y))),
                                   z);
  const __m256d dz = _mm256_max_pd(_mm256_max_pd(_mm256_sub_pd(_mm256_loadu_pd(n.lo_z), pz),
                                                 _mm256_sub_pd(pz, _mm256_loadu_pd(n.hi_z))),
                                   z);
  _mm256_storeu_pd(d2, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)),
                                     _mm256_mul_pd(dz, dz)));
}

EBGEOM_TARGET_AVX inline void child_far_dist2_avx(const WideNode<double, 4>& n,
                                                  const Vec3<double>& p, double (&d2)[4]) noexcept {
  const __m256d px = _mm256_set1_pd(p.x), py = _mm256_set1_pd(p.y), pz = _mm256_set1_pd(p.z);
  const __m256d dx = _mm256_max_pd(_mm256_sub_pd(px, _mm256_loadu_pd(n.lo_x)),
                                   _mm256_sub_pd(_mm256_loadu_pd(n.hi_x), px));
  const __m256d dy = _mm256_max_pd(_mm256_sub_pd(py, _mm256_loadu_pd(n.lo_y)),
                                   _mm256_sub_pd(_mm256_loadu_pd(n.hi_y), py));
  const __m256d dz = _mm256_max_pd(_mm256_sub_pd(pz, _mm256_loadu_pd(n.lo_z)),
                                   _mm256_sub_pd(_mm256_loadu_pd(n.hi_z), pz));
  _mm256_storeu_pd(d2, _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(dx, dx), _mm256_mul_pd(dy, dy)),
                                     _mm256_mul_pd(dz, dz)));
}

#endif

#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
// The AVX-512 forms: K = 16 floats or K = 8 doubles in one 512-bit register per coordinate. Every
// operation takes the zero-masked form with all lanes set: GCC 12 warns of an uninitialised value
// in the plain forms' headers. Not contracted into fused multiply-adds: the same values as the
// generic loops, as the AVX forms.
EBGEOM_TARGET_AVX512 EBGEOM_EXACT_KERNEL inline void
child_dist2_avx512(const WideNode<float, 16>& n, const Vec3<float>& p, float (&d2)[16]) noexcept {
  const __m512 z = _mm512_setzero_ps();
  const __m512 px = _mm512_set1_ps(p.x), py = _mm512_set1_ps(p.y), pz = _mm512_set1_ps(p.z);
  const __m512 dx =
      _mm512_maskz_max_ps(0xffff,
                          _mm512_maskz_max_ps(0xffff, _mm512_sub_ps(_mm512_loadu_ps(n.lo_x), px),
                                              _mm512_sub_ps(px, _mm512_loadu_ps(n.hi_x))),
                          z);
  const __m512 dy =
      _mm512_maskz_max_ps(0xffff,
                          _mm512_maskz_max_ps(0xffff, _mm512_sub_ps(_mm512_loadu_ps(n.lo_y), py),
                                              _mm512_sub_ps(py, _mm512_loadu_ps(n.hi_y))),
                          z);
  const __m512 dz =
      _mm512_maskz_max_ps(0xffff,
                          _mm512_maskz_max_ps(0xffff, _mm512_sub_ps(_mm512_loadu_ps(n.lo_z), pz),
                                              _mm512_sub_ps(pz, _mm512_loadu_ps(n.hi_z))),
                          z);
  _mm512_storeu_ps(d2, _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)),
                                     _mm512_mul_ps(dz, dz)));
}

EBGEOM_TARGET_AVX512 EBGEOM_EXACT_KERNEL inline void
child_far_dist2_avx512(const WideNode<float, 16>& n, const Vec3<float>& p,
                       float (&d2)[16]) noexcept {
  const __m512 px = _mm512_set1_ps(p.x), py = _mm512_set1_ps(p.y), pz = _mm512_set1_ps(p.z);
  const __m512 dx = _mm512_maskz_max_ps(0xffff, _mm512_sub_ps(px, _mm512_loadu_ps(n.lo_x)),
                                        _mm512_sub_ps(_mm512_loadu_ps(n.hi_x), px));
  const __m512 dy = _mm512_maskz_max_ps(0xffff, _mm512_sub_ps(py, _mm512_loadu_ps(n.lo_y)),
                                        _mm512_sub_ps(_mm512_loadu_ps(n.hi_y), py));
  const __m512 dz = _mm512_maskz_max_ps(0xffff, _mm512_sub_ps(pz, _mm512_loadu_ps(n.lo_z)),
                                        _mm512_sub_ps(_mm512_loadu_ps(n.hi_z), pz));
  _mm512_storeu_ps(d2, _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)),
                                     _mm512_mul_ps(dz, dz)));
}

EBGEOM_TARGET_AVX512 EBGEOM_EXACT_KERNEL inline void
child_dist2_avx512(const WideNode<double, 8>& n, const Vec3<double>& p, double (&d2)[8]) noexcept {
  const __m512d z = _mm512_setzero_pd();
  const __m512d px = _mm512_set1_pd(p.x), py = _mm512_set1_pd(p.y), pz = _mm512_set1_pd(p.z);
  const __m512d dx =
      _mm512_maskz_max_pd(0xff,
                          _mm512_maskz_max_pd(0xff, _mm512_sub_pd(_mm512_loadu_pd(n.lo_x), px),
                                              _mm512_sub_pd(px, _mm512_loadu_pd(n.hi_x))),
                          z);
  const __m512d dy =
      _mm512_maskz_max_pd(0xff,
                          _mm512_maskz_max_pd(0xff, _mm512_sub_pd(_mm512_loadu_pd(n.lo_y), py),
                                              _mm512_sub_pd(py, _mm512_loadu_pd(n.hi_y))),
                          z);
  const __m512d dz =
      _mm512_maskz_max_pd(0xff,
                          _mm512_maskz_max_pd(0xff, _mm512_sub_pd(_mm512_loadu_pd(n.lo_z), pz),
                                              _mm512_sub_pd(pz, _mm512_loadu_pd(n.hi_z))),
                          z);
  _mm512_storeu_pd(d2, _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                     _mm512_mul_pd(dz, dz)));
}

EBGEOM_TARGET_AVX512 EBGEOM_EXACT_KERNEL inline void
child_far_dist2_avx512(const WideNode<double, 8>& n, const Vec3<double>& p,
                       double (&d2)[8]) noexcept {
  const __m512d px = _mm512_set1_pd(p.x), py = _mm512_set1_pd(p.y), pz = _mm512_set1_pd(p.z);
  const __m512d dx = _mm512_maskz_max_pd(0xff, _mm512_sub_pd(px, _mm512_loadu_pd(n.lo_x)),
                                         _mm512_sub_pd(_mm512_loadu_pd(n.hi_x), px));
  const __m512d dy = _mm512_maskz_max_pd(0xff, _mm512_sub_pd(py, _mm512_loadu_pd(n.lo_y)),
                                         _mm512_sub_pd(_mm512_loadu_pd(n.hi_y), py));
  const __m512d dz = _mm512_maskz_max_pd(0xff, _mm512_sub_pd(pz, _mm512_loadu_pd(n.lo_z)),
                                         _mm512_sub_pd(_mm512_loadu_pd(n.hi_z), pz));
  _mm512_storeu_pd(d2, _mm512_add_pd(_mm512_add_pd(_mm512_mul_pd(dx, dx), _mm512_mul_pd(dy, dy)),
                                     _mm512_mul_pd(dz, dz)));
}
#endif

/// `child_dist2` as the kernels of instruction set I compute it: the AVX forms where I (or the
/// translation unit) has AVX, else the overloads above or the generic loops. Same values.
template <Isa I, class T, int K, class BV>
EBGEOM_FORCE_INLINE void node_dist2(const WideNode<T, K, BV>& n, const Vec3<T>& p,
                                    T (&d2)[K]) noexcept {
#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
  if constexpr (I >= Isa::avx512 && has_avx512_form<T, K, BV>) return child_dist2_avx512(n, p, d2);
#endif
#if EBGEOM_ISA_DISPATCH
  if constexpr (I >= Isa::avx2 && has_avx_form<T, K, BV>) return child_dist2_avx(n, p, d2);
#endif
  child_dist2(n, p, d2);
}

/// `child_far_dist2` as the kernels of instruction set I compute it (see `node_dist2`).
template <Isa I, class T, int K, class BV>
EBGEOM_FORCE_INLINE void node_far_dist2(const WideNode<T, K, BV>& n, const Vec3<T>& p,
                                        T (&d2)[K]) noexcept {
#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
  if constexpr (I >= Isa::avx512 && has_avx512_form<T, K, BV>)
    return child_far_dist2_avx512(n, p, d2);
#endif
#if EBGEOM_ISA_DISPATCH
  if constexpr (I >= Isa::avx2 && has_avx_form<T, K, BV>) return child_far_dist2_avx(n, p, d2);
#endif
  child_far_dist2(n, p, d2);
}
} // namespace detail

#if defined(__AVX__)
// The translation unit targets AVX: the AVX forms for every caller.
EBGEOM_FORCE_INLINE void child_dist2(const WideNode<float, 8>& n, const Vec3<float>& p,
                                     float (&d2)[8]) noexcept {
  detail::child_dist2_avx(n, p, d2);
}
EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<float, 8>& n, const Vec3<float>& p,
                                         float (&d2)[8]) noexcept {
  detail::child_far_dist2_avx(n, p, d2);
}
EBGEOM_FORCE_INLINE void child_dist2(const WideNode<double, 4>& n, const Vec3<double>& p,
                                     double (&d2)[4]) noexcept {
  detail::child_dist2_avx(n, p, d2);
}
EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<double, 4>& n, const Vec3<double>& p,
                                         double (&d2)[4]) noexcept {
  detail::child_far_dist2_avx(n, p, d2);
}
#endif

} // namespace ebgeom::bvh

EBGEOM_END_EXACT_FP
