// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Oriented boxes of a wide BVH node's children: a second, tighter lower bound on the distance to
/// a child's triangles than its axis-aligned box, for nearest searches (`MeshSdf`).
///
/// A leaf of a mesh BVH holds a small surface patch, and an inner node a larger one. Its
/// axis-aligned box is fat wherever the patch is tilted against the axes, and a point far from the
/// surface finds many such boxes within its nearest distance. An oriented box with one axis along
/// the patch's mean normal is about as thin as the patch is curved: on the meshes of
/// docs/performance.md, queries scan 1.6 to 3.8 times fewer leaves with both bounds than with the
/// axis-aligned boxes alone, and (with boxes for the inner children too) expand 1.2 to 1.9 times
/// fewer nodes (docs/dev/performance-log.md has the counts).
///
/// `NodeObbs<T, K>` stores, structure of arrays like `WideNode`, per child: a centre, three unit
/// axes and the half extents along them. `raise_dist2` computes the squared distance from `p` to
/// each child's oriented box and raises the node's box distances to it. Empty children hold a box
/// that never raises anything (zero axes, infinite extents).
///
/// Rounding. The value is a lower bound of the exact squared distance to every triangle of the
/// child, whatever the point (see `fit`): the axes are shortened by 36 ulps and rounded to T, so
/// that the rounded frame shortens every vector by more than the relative rounding of
/// `raise_dist2`; the half extents are computed in double from the rounded frame (widened by the
/// rounding of that computation, `fit_from_sums`), rounded up and widened by 32 ulps of the box's
/// size, which covers the absolute part of the error of `raise_dist2` (one subtraction per
/// coordinate, a three-term dot product). So a child holding the nearest triangle is never
/// skipped on this bound, as on an exact box distance.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"
#include "ebgeom/core/vec.hpp"

#if defined(__SSE2__) || defined(__AVX__) || EBGEOM_ISA_DISPATCH
#include <immintrin.h>
#endif

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom::bvh {

/// What `NodeObbs::fit` needs to orient a box, summed over a patch's corners: their count, sum
/// and second moments about a fixed reference point (any point near the patch; the mesh's centre),
/// and the patch's summed normal. Sums of two patches add up (`merge`): the subtrees of a BVH get
/// theirs from their children's, with one pass over the mesh in all.
struct PatchStats {
  Vec3<double> ref{0, 0, 0};
  double n = 0;
  Vec3<double> sum{0, 0, 0};
  double sxx = 0, syy = 0, szz = 0, sxy = 0, sxz = 0, syz = 0;
  Vec3<double> normal{0, 0, 0};

  void add_point(const Vec3<double>& x) noexcept {
    const Vec3<double> d = x - ref;
    n += 1;
    sum = sum + d;
    sxx += d.x * d.x, syy += d.y * d.y, szz += d.z * d.z;
    sxy += d.x * d.y, sxz += d.x * d.z, syz += d.y * d.z;
  }
  /// A triangle: its corners and its (area-weighted) normal.
  void add_triangle(const Vec3<double>& a, const Vec3<double>& b, const Vec3<double>& c) noexcept {
    add_point(a), add_point(b), add_point(c);
    normal = normal + cross(b - a, c - a);
  }
  /// Adds the sums of `o` (same reference point).
  void merge(const PatchStats& o) noexcept {
    n += o.n;
    sum = sum + o.sum;
    sxx += o.sxx, syy += o.syy, szz += o.szz, sxy += o.sxy, sxz += o.sxz, syz += o.syz;
    normal = normal + o.normal;
  }
  /// n times the covariance of the corners along unit vectors a and b: sum (a·d)(b·d) - n
  /// (a·m)(b·m) with m the mean offset d.
  double scatter(const Vec3<double>& a, const Vec3<double>& b) const noexcept {
    const double s = a.x * (b.x * sxx + b.y * sxy + b.z * sxz) +
                     a.y * (b.x * sxy + b.y * syy + b.z * syz) +
                     a.z * (b.x * sxz + b.y * syz + b.z * szz);
    return n > 0 ? s - dot(a, sum) * dot(b, sum) / n : 0;
  }
};

/// Oriented boxes of the K children of one node (see the file comment).
template <class T, int K> struct NodeObbs {
  T cx[K], cy[K], cz[K]; ///< centres
  T ux[K], uy[K], uz[K]; ///< first tangent axis
  T vx[K], vy[K], vz[K]; ///< second tangent axis
  T nx[K], ny[K], nz[K]; ///< normal axis
  T hu[K], hv[K], hn[K]; ///< half extents along u, v, n

  /// Every child: a box that raises nothing.
  void clear() noexcept {
    for (int k = 0; k < K; ++k) clear(k);
  }
  void clear(int k) noexcept {
    cx[k] = cy[k] = cz[k] = ux[k] = uy[k] = uz[k] = vx[k] = vy[k] = vz[k] = nx[k] = ny[k] = nz[k] =
        T(0);
    hu[k] = hv[k] = hn[k] = std::numeric_limits<T>::infinity();
  }

  /// Child k's box around the points `corner(i)`, i < n (the corners of the child's triangles):
  /// the normal `normal` (their summed triangle normals, any length; a zero or non-finite one
  /// gives the coordinate axes), the tangent axes along the principal directions of the corners
  /// projected on the tangent plane.
  template <class CornerFn>
  void fit(int k, const Vec3<double>& normal, std::size_t n, CornerFn&& corner) noexcept {
    PatchStats st;
    if (n > 0) st.ref = corner(0);
    for (std::size_t i = 0; i < n; ++i) st.add_point(corner(i));
    st.normal = normal;
    fit_from_sums(k, st, n, corner);
  }

  /// As above, oriented by the sums `st` of the same corners (`PatchStats`): the box then takes
  /// one pass over the corners, for its extents. Any `st` gives a box that holds the corners; the
  /// sums only choose its axes.
  template <class CornerFn>
  void fit_from_sums(int k, const PatchStats& st, std::size_t n, CornerFn&& corner) noexcept {
    Vec3<double> a[3]; // u, v, n
    const double len = norm(st.normal);
    if (!(len > 0) || !std::isfinite(len)) {
      a[0] = {1, 0, 0}, a[1] = {0, 1, 0}, a[2] = {0, 0, 1};
    } else {
      a[2] = st.normal / len;
      const Vec3<double> h = std::abs(a[2].x) < 0.9 ? Vec3<double>{1, 0, 0} : Vec3<double>{0, 1, 0};
      const Vec3<double> t0 = normalized(cross(h, a[2])), t1 = cross(a[2], t0);
      // Principal direction in the plane: angle of the 2x2 covariance's main axis (the axes
      // stay t0, t1 when the sums are not finite).
      const double sxx = st.scatter(t0, t0), syy = st.scatter(t1, t1), sxy = st.scatter(t0, t1);
      const double th = std::isfinite(sxx + syy + sxy) ? 0.5 * std::atan2(2 * sxy, sxx - syy) : 0.0;
      a[0] = t0 * std::cos(th) + t1 * std::sin(th);
      a[1] = cross(a[2], a[0]);
    }
    // Axes shortened by 36 ulps, then rounded to T: the rounded frame shortens every vector by a
    // factor below 1 - 32 eps (4 ulps cover the rounding and the frame's departure from
    // orthonormal), so squared distances measured in it are below the exact ones by a factor
    // below 1 - 64 eps, more than the relative rounding of `raise_dist2`.
    constexpr double shorten = 1 - 36 * double(std::numeric_limits<T>::epsilon());
    Vec3<double> r[3];
    for (int q = 0; q < 3; ++q)
      r[q] = {double(T(a[q].x * shorten)), double(T(a[q].y * shorten)),
              double(T(a[q].z * shorten))};
    // Extents in the rounded frame (one pass), then the centre (rounded to T) and the half
    // extents around it. Each computed projection r·x is within 3.01 · 2^-53 · |x|_1 of the exact
    // one (|r| <= 1), and each subtraction within 2^-53 of its result: widening by 2^-50 of the
    // largest |x|_1 (corners and centre) and by 2^-50 of the half extent covers both.
    double lo[3], hi[3], big = 0;
    for (int q = 0; q < 3; ++q) lo[q] = std::numeric_limits<double>::infinity(), hi[q] = -lo[q];
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3<double> x = corner(i);
      for (int q = 0; q < 3; ++q) {
        const double t = dot(r[q], x);
        lo[q] = std::min(lo[q], t), hi[q] = std::max(hi[q], t);
      }
      big = std::max(big, std::abs(x.x) + std::abs(x.y) + std::abs(x.z));
    }
    Vec3<double> c{0, 0, 0};
    for (int q = 0; q < 3; ++q) c = c + r[q] * (0.5 * (lo[q] + hi[q]));
    const Vec3<double> ct{double(T(c.x)), double(T(c.y)), double(T(c.z))};
    big = std::max(big, std::abs(ct.x) + std::abs(ct.y) + std::abs(ct.z));
    double h[3];
    for (int q = 0; q < 3; ++q) {
      const double tc = dot(r[q], ct);
      h[q] = std::max({hi[q] - tc, tc - lo[q], 0.0}) * (1 + 0x1p-50) + 0x1p-50 * big;
    }
    const double margin = 32 * double(std::numeric_limits<T>::epsilon()) * (h[0] + h[1] + h[2]);
    T ht[3];
    for (int q = 0; q < 3; ++q) {
      ht[q] = T(h[q] + margin);
      if (double(ht[q]) < h[q] + margin)
        ht[q] = std::nextafter(ht[q], std::numeric_limits<T>::infinity());
    }
    // A centre or extent beyond the range of T (a patch at the edge of it): no oriented box. A
    // centre at infinity would make NaN distances even for points next to the patch.
    if (!std::isfinite(T(ct.x)) || !std::isfinite(T(ct.y)) || !std::isfinite(T(ct.z)) ||
        !std::isfinite(ht[0]) || !std::isfinite(ht[1]) || !std::isfinite(ht[2])) {
      clear(k);
      return;
    }
    cx[k] = T(ct.x), cy[k] = T(ct.y), cz[k] = T(ct.z);
    ux[k] = T(r[0].x), uy[k] = T(r[0].y), uz[k] = T(r[0].z);
    vx[k] = T(r[1].x), vy[k] = T(r[1].y), vz[k] = T(r[1].z);
    nx[k] = T(r[2].x), ny[k] = T(r[2].y), nz[k] = T(r[2].z);
    hu[k] = ht[0], hv[k] = ht[1], hn[k] = ht[2];
  }
};

/// `d2[k] = max(d2[k], squared distance from p to child k's oriented box)`, generic form.
template <class T, int K>
EBGEOM_FORCE_INLINE void raise_dist2_generic(const NodeObbs<T, K>& o, const Vec3<T>& p,
                                             T (&d2)[K]) noexcept {
  for (int k = 0; k < K; ++k) {
    const T dx = p.x - o.cx[k], dy = p.y - o.cy[k], dz = p.z - o.cz[k];
    const T tu = o.ux[k] * dx + o.uy[k] * dy + o.uz[k] * dz;
    const T tv = o.vx[k] * dx + o.vy[k] * dy + o.vz[k] * dz;
    const T tn = o.nx[k] * dx + o.ny[k] * dy + o.nz[k] * dz;
    const T gu = std::max(std::abs(tu) - o.hu[k], T(0));
    const T gv = std::max(std::abs(tv) - o.hv[k], T(0));
    const T gn = std::max(std::abs(tn) - o.hn[k], T(0));
    const T s = gu * gu + gv * gv + gn * gn;
    d2[k] = std::max(d2[k], s);
  }
}

#if defined(__SSE2__)
/// One axis of `raise_dist2_sse`: the squared gap of the projection of `d` on axis a beyond h.
EBGEOM_FORCE_INLINE __m128 obb_gap2_sse(const float* ax, const float* ay, const float* az,
                                        const float* h, __m128 dx, __m128 dy, __m128 dz) noexcept {
  const __m128 abs_mask = _mm_castsi128_ps(_mm_set1_epi32(0x7fffffff));
  const __m128 t =
      _mm_add_ps(_mm_add_ps(_mm_mul_ps(_mm_loadu_ps(ax), dx), _mm_mul_ps(_mm_loadu_ps(ay), dy)),
                 _mm_mul_ps(_mm_loadu_ps(az), dz));
  const __m128 g =
      _mm_max_ps(_mm_sub_ps(_mm_and_ps(t, abs_mask), _mm_loadu_ps(h)), _mm_setzero_ps());
  return _mm_mul_ps(g, g);
}

/// K = 4 or 8 floats, four per SSE register (baseline x86-64).
template <int K>
EBGEOM_FORCE_INLINE void raise_dist2_sse(const NodeObbs<float, K>& o, const Vec3<float>& p,
                                         float (&d2)[K]) noexcept {
  static_assert(K % 4 == 0);
  for (int j = 0; j < K; j += 4) {
    const __m128 dx = _mm_sub_ps(_mm_set1_ps(p.x), _mm_loadu_ps(o.cx + j));
    const __m128 dy = _mm_sub_ps(_mm_set1_ps(p.y), _mm_loadu_ps(o.cy + j));
    const __m128 dz = _mm_sub_ps(_mm_set1_ps(p.z), _mm_loadu_ps(o.cz + j));
    const __m128 s =
        _mm_add_ps(_mm_add_ps(obb_gap2_sse(o.ux + j, o.uy + j, o.uz + j, o.hu + j, dx, dy, dz),
                              obb_gap2_sse(o.vx + j, o.vy + j, o.vz + j, o.hv + j, dx, dy, dz)),
                   obb_gap2_sse(o.nx + j, o.ny + j, o.nz + j, o.hn + j, dx, dy, dz));
    _mm_storeu_ps(d2 + j, _mm_max_ps(s, _mm_loadu_ps(d2 + j))); // a NaN s keeps d2, as std::max
  }
}
#endif

namespace detail {
#if EBGEOM_ISA_DISPATCH || defined(__AVX__)
/// One axis of `raise_dist2_avx`: the squared gap of the projection of `d` on axis a beyond h.
EBGEOM_TARGET_AVX inline __m256d obb_gap2_avx(const double* ax, const double* ay, const double* az,
                                              const double* h, __m256d dx, __m256d dy,
                                              __m256d dz) noexcept {
  const __m256d abs_mask = _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
  const __m256d t = _mm256_add_pd(
      _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(ax), dx), _mm256_mul_pd(_mm256_loadu_pd(ay), dy)),
      _mm256_mul_pd(_mm256_loadu_pd(az), dz));
  const __m256d g = _mm256_max_pd(_mm256_sub_pd(_mm256_and_pd(t, abs_mask), _mm256_loadu_pd(h)),
                                  _mm256_setzero_pd());
  return _mm256_mul_pd(g, g);
}

/// K = 4 doubles in one AVX register.
EBGEOM_TARGET_AVX inline void raise_dist2_avx(const NodeObbs<double, 4>& o, const Vec3<double>& p,
                                              double (&d2)[4]) noexcept {
  const __m256d dx = _mm256_sub_pd(_mm256_set1_pd(p.x), _mm256_loadu_pd(o.cx));
  const __m256d dy = _mm256_sub_pd(_mm256_set1_pd(p.y), _mm256_loadu_pd(o.cy));
  const __m256d dz = _mm256_sub_pd(_mm256_set1_pd(p.z), _mm256_loadu_pd(o.cz));
  const __m256d s = _mm256_add_pd(_mm256_add_pd(obb_gap2_avx(o.ux, o.uy, o.uz, o.hu, dx, dy, dz),
                                                obb_gap2_avx(o.vx, o.vy, o.vz, o.hv, dx, dy, dz)),
                                  obb_gap2_avx(o.nx, o.ny, o.nz, o.hn, dx, dy, dz));
  _mm256_storeu_pd(d2, _mm256_max_pd(s, _mm256_loadu_pd(d2))); // a NaN s keeps d2
}

/// One axis of `raise_dist2_avx` for eight floats.
EBGEOM_TARGET_AVX inline __m256 obb_gap2_avx(const float* ax, const float* ay, const float* az,
                                             const float* h, __m256 dx, __m256 dy,
                                             __m256 dz) noexcept {
  const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
  const __m256 t = _mm256_add_ps(
      _mm256_add_ps(_mm256_mul_ps(_mm256_loadu_ps(ax), dx), _mm256_mul_ps(_mm256_loadu_ps(ay), dy)),
      _mm256_mul_ps(_mm256_loadu_ps(az), dz));
  const __m256 g = _mm256_max_ps(_mm256_sub_ps(_mm256_and_ps(t, abs_mask), _mm256_loadu_ps(h)),
                                 _mm256_setzero_ps());
  return _mm256_mul_ps(g, g);
}

/// K = 8 floats in one AVX register.
EBGEOM_TARGET_AVX inline void raise_dist2_avx(const NodeObbs<float, 8>& o, const Vec3<float>& p,
                                              float (&d2)[8]) noexcept {
  const __m256 dx = _mm256_sub_ps(_mm256_set1_ps(p.x), _mm256_loadu_ps(o.cx));
  const __m256 dy = _mm256_sub_ps(_mm256_set1_ps(p.y), _mm256_loadu_ps(o.cy));
  const __m256 dz = _mm256_sub_ps(_mm256_set1_ps(p.z), _mm256_loadu_ps(o.cz));
  const __m256 s = _mm256_add_ps(_mm256_add_ps(obb_gap2_avx(o.ux, o.uy, o.uz, o.hu, dx, dy, dz),
                                               obb_gap2_avx(o.vx, o.vy, o.vz, o.hv, dx, dy, dz)),
                                 obb_gap2_avx(o.nx, o.ny, o.nz, o.hn, dx, dy, dz));
  _mm256_storeu_ps(d2, _mm256_max_ps(s, _mm256_loadu_ps(d2))); // a NaN s keeps d2
}
#endif
#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
// The AVX-512 forms (K = 16 floats, K = 8 doubles): zero-masked maxima with all lanes set (GCC 12
// warns of an uninitialised value in the plain forms' headers), never contracted (the scalar
// formula's values, as the AVX forms).
/// One axis of `raise_dist2_avx512`: the squared gap of the projection of `d` on axis a beyond h.
EBGEOM_TARGET_AVX512 EBGEOM_EXACT_KERNEL inline __m512
obb_gap2_avx512(const float* ax, const float* ay, const float* az, const float* h, __m512 dx,
                __m512 dy, __m512 dz) noexcept {
  const __m512 t = _mm512_add_ps(
      _mm512_add_ps(_mm512_mul_ps(_mm512_loadu_ps(ax), dx), _mm512_mul_ps(_mm512_loadu_ps(ay), dy)),
      _mm512_mul_ps(_mm512_loadu_ps(az), dz));
  const __m512 g = _mm512_maskz_max_ps(0xffff, _mm512_sub_ps(_mm512_abs_ps(t), _mm512_loadu_ps(h)),
                                       _mm512_setzero_ps());
  return _mm512_mul_ps(g, g);
}

/// K = 16 floats in one AVX-512 register.
EBGEOM_TARGET_AVX512 EBGEOM_EXACT_KERNEL inline void
raise_dist2_avx512(const NodeObbs<float, 16>& o, const Vec3<float>& p, float (&d2)[16]) noexcept {
  const __m512 dx = _mm512_sub_ps(_mm512_set1_ps(p.x), _mm512_loadu_ps(o.cx));
  const __m512 dy = _mm512_sub_ps(_mm512_set1_ps(p.y), _mm512_loadu_ps(o.cy));
  const __m512 dz = _mm512_sub_ps(_mm512_set1_ps(p.z), _mm512_loadu_ps(o.cz));
  const __m512 s = _mm512_add_ps(_mm512_add_ps(obb_gap2_avx512(o.ux, o.uy, o.uz, o.hu, dx, dy, dz),
                                               obb_gap2_avx512(o.vx, o.vy, o.vz, o.hv, dx, dy, dz)),
                                 obb_gap2_avx512(o.nx, o.ny, o.nz, o.hn, dx, dy, dz));
  _mm512_storeu_ps(d2, _mm512_maskz_max_ps(0xffff, s, _mm512_loadu_ps(d2))); // a NaN s keeps d2
}

/// One axis of `raise_dist2_avx512` for eight doubles.
EBGEOM_TARGET_AVX512 EBGEOM_EXACT_KERNEL inline __m512d
obb_gap2_avx512(const double* ax, const double* ay, const double* az, const double* h, __m512d dx,
                __m512d dy, __m512d dz) noexcept {
  const __m512d t = _mm512_add_pd(
      _mm512_add_pd(_mm512_mul_pd(_mm512_loadu_pd(ax), dx), _mm512_mul_pd(_mm512_loadu_pd(ay), dy)),
      _mm512_mul_pd(_mm512_loadu_pd(az), dz));
  const __m512d g = _mm512_maskz_max_pd(0xff, _mm512_sub_pd(_mm512_abs_pd(t), _mm512_loadu_pd(h)),
                                        _mm512_setzero_pd());
  return _mm512_mul_pd(g, g);
}

/// K = 8 doubles in one AVX-512 register.
EBGEOM_TARGET_AVX512 EBGEOM_EXACT_KERNEL inline void
raise_dist2_avx512(const NodeObbs<double, 8>& o, const Vec3<double>& p, double (&d2)[8]) noexcept {
  const __m512d dx = _mm512_sub_pd(_mm512_set1_pd(p.x), _mm512_loadu_pd(o.cx));
  const __m512d dy = _mm512_sub_pd(_mm512_set1_pd(p.y), _mm512_loadu_pd(o.cy));
  const __m512d dz = _mm512_sub_pd(_mm512_set1_pd(p.z), _mm512_loadu_pd(o.cz));
  const __m512d s =
      _mm512_add_pd(_mm512_add_pd(obb_gap2_avx512(o.ux, o.uy, o.uz, o.hu, dx, dy, dz),
                                  obb_gap2_avx512(o.vx, o.vy, o.vz, o.hv, dx, dy, dz)),
                    obb_gap2_avx512(o.nx, o.ny, o.nz, o.hn, dx, dy, dz));
  _mm512_storeu_pd(d2, _mm512_maskz_max_pd(0xff, s, _mm512_loadu_pd(d2))); // a NaN s keeps d2
}
#endif
} // namespace detail

/// `d2[k] = max(d2[k], squared distance from p to child k's oriented box)` on
/// instruction set I. The forms compute the same operations in the same order: same values, except
/// where GCC fuses a multiply and an add into one rounding (with FMA enabled it does so in
/// intrinsics too). A fused form is still a lower bound: fewer roundings, within the same error
/// bound.
template <Isa I = native_isa, class T, int K>
EBGEOM_FORCE_INLINE void raise_dist2(const NodeObbs<T, K>& o, const Vec3<T>& p,
                                     T (&d2)[K]) noexcept {
#if EBGEOM_ISA_DISPATCH || defined(__AVX512F__)
  // One AVX-512 register per coordinate: eight doubles or sixteen floats.
  if constexpr (I >= Isa::avx512 &&
                ((std::is_same_v<T, double> && K == 8) || (std::is_same_v<T, float> && K == 16)))
    return detail::raise_dist2_avx512(o, p, d2);
#endif
#if EBGEOM_ISA_DISPATCH || defined(__AVX__)
  // One AVX register per coordinate: four doubles or eight floats.
  if constexpr (I >= Isa::avx2 &&
                ((std::is_same_v<T, double> && K == 4) || (std::is_same_v<T, float> && K == 8)))
    return detail::raise_dist2_avx(o, p, d2);
#endif
#if defined(__SSE2__)
  if constexpr (std::is_same_v<T, float> && (K == 4 || K == 8)) return raise_dist2_sse(o, p, d2);
#endif
  raise_dist2_generic(o, p, d2);
}

} // namespace ebgeom::bvh

EBGEOM_END_EXACT_FP
