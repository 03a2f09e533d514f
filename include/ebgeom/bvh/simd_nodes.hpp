// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// SIMD versions of the per-node child box distances of `wide_bvh.hpp` for the common widths:
/// K = 4 floats (SSE), K = 8 floats and K = 4 doubles (AVX). GCC does not vectorise the generic
/// `std::max` loops there (scalar compares and branches: a quarter of a mesh query's
/// instructions), so these overloads, more specialised than the generic templates, take over
/// when the compiler targets the instruction set. Same values as the generic loops (max/min of
/// non-NaN operands are exact; ±0 squares to +0); the generic code remains the reference and the
/// fallback on other targets.

#include "ebgeom/bvh/wide_bvh.hpp"

#if defined(__SSE2__) || defined(__AVX__)
#include <immintrin.h>
#endif

namespace ebgeom::bvh {

#if defined(__SSE2__)
EBGEOM_FORCE_INLINE void child_dist2(const WideNode<float, 4>& n, const Vec3<float>& p,
                                     float (&d2)[4]) noexcept {
  const __m128 z = _mm_setzero_ps();
  const __m128 px = _mm_set1_ps(p.x), py = _mm_set1_ps(p.y), pz = _mm_set1_ps(p.z);
  const __m128 dx = _mm_max_ps(
      _mm_max_ps(_mm_sub_ps(_mm_loadu_ps(n.lo_x), px), _mm_sub_ps(px, _mm_loadu_ps(n.hi_x))), z);
  const __m128 dy = _mm_max_ps(
      _mm_max_ps(_mm_sub_ps(_mm_loadu_ps(n.lo_y), py), _mm_sub_ps(py, _mm_loadu_ps(n.hi_y))), z);
  const __m128 dz = _mm_max_ps(
      _mm_max_ps(_mm_sub_ps(_mm_loadu_ps(n.lo_z), pz), _mm_sub_ps(pz, _mm_loadu_ps(n.hi_z))), z);
  _mm_storeu_ps(d2,
                _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz)));
}

EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<float, 4>& n, const Vec3<float>& p,
                                         float (&d2)[4]) noexcept {
  const __m128 px = _mm_set1_ps(p.x), py = _mm_set1_ps(p.y), pz = _mm_set1_ps(p.z);
  const __m128 dx =
      _mm_max_ps(_mm_sub_ps(px, _mm_loadu_ps(n.lo_x)), _mm_sub_ps(_mm_loadu_ps(n.hi_x), px));
  const __m128 dy =
      _mm_max_ps(_mm_sub_ps(py, _mm_loadu_ps(n.lo_y)), _mm_sub_ps(_mm_loadu_ps(n.hi_y), py));
  const __m128 dz =
      _mm_max_ps(_mm_sub_ps(pz, _mm_loadu_ps(n.lo_z)), _mm_sub_ps(_mm_loadu_ps(n.hi_z), pz));
  _mm_storeu_ps(d2,
                _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz)));
}
#endif

#if defined(__AVX__)
EBGEOM_FORCE_INLINE void child_dist2(const WideNode<float, 8>& n, const Vec3<float>& p,
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

EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<float, 8>& n, const Vec3<float>& p,
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

EBGEOM_FORCE_INLINE void child_dist2(const WideNode<double, 4>& n, const Vec3<double>& p,
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

EBGEOM_FORCE_INLINE void child_far_dist2(const WideNode<double, 4>& n, const Vec3<double>& p,
                                         double (&d2)[4]) noexcept {
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

} // namespace ebgeom::bvh
