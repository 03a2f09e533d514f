// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Generalized winding numbers of triangle meshes (Jacobson, Kavan & Sorkine-Hornung 2013):
/// w(p) = Σ_t Ω_t(p) / 4π, the signed solid angles of the triangles seen from p over the full
/// sphere. w = 1 inside and 0 outside a closed, outward-oriented surface; it degrades gracefully
/// on holes, duplicates, flipped patches and self-intersections, so "inside where w > 1/2" is a
/// robust inside test for imperfect meshes.
///
/// - `winding_number(mesh, p)`: the exact sum, O(n) per query (the oracle).
/// - `FastWindingNumber<T, K>`: the hierarchical approximation of Barill, Dickson, Schmidt,
///   Levin & Jacobson 2018 ("Fast winding numbers for soups and clouds"): a K-wide BVH over the
///   triangles, one order-2 dipole cluster (`DipoleCluster`, geom/solid_angle.hpp) per child of
///   every node; a child whose cluster centre is farther from p than β times its radius
///   contributes its far-field expansion, a near leaf its exact solid angles. O(log n) per query
///   for points away from the surface; the error decays like β⁻³.
/// - `winding_range(mesh, box)` and `FastWindingNumber::range_over(box)`: an interval holding
///   every value the exact sum or the fast evaluation computes at any point of a box (rounding
///   included), from the value at the box's centre and bounds on each term's gradient. Grid
///   samplers use it to sign whole boxes of samples far from the surface at once
///   (`WindingRange::side`).

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/solid_angle.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"

#if defined(__SSE2__) || defined(__AVX__) || defined(__AVX512F__)
#include <immintrin.h>
#endif

/// The fast winding number's kernels (`FastWindingNumber::operator()`, `eval_packet`): as
/// `EBGEOM_VECTOR_KERNEL` (no contraction into fused multiply-adds, so the per-point and the
/// packet evaluations round alike; selects may become blends), and square roots that never set
/// `errno` (their arguments are never negative), so the loops over a packet's points vectorise.
/// None of this changes a value.
#if defined(__GNUC__) && !defined(__clang__)
#define EBGEOM_WINDING_KERNEL                                                                      \
  __attribute__((optimize("no-trapping-math", "fp-contract=off", "no-math-errno")))
#else
#define EBGEOM_WINDING_KERNEL
#endif

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

/// Exact generalized winding number at `p` of the triangles `tri(i, a, b, c)`, i in [0, n): the sum
/// of their signed solid angles (`solid_angle`) over 4π, accumulated in double. Finite for every
/// finite p (on the surface it is some finite value; the distance there is 0 anyway). O(n).
template <class T, class TriFn>
T winding_number(std::size_t n, TriFn&& tri, const Vec3<T>& p) noexcept {
  constexpr double inv4pi = 0.07957747154594767;
  double sum = 0;
  Vec3<T> a, b, c;
  for (std::size_t i = 0; i < n; ++i) {
    tri(i, a, b, c);
    sum += double(solid_angle(p, a, b, c));
  }
  return T(sum * inv4pi);
}

/// Exact generalized winding number of `mesh` at `p` (1 inside, 0 outside a closed outward
/// surface). O(n), thread-safe.
/// Computed in double whatever T.
template <class T> T winding_number(const TriangleMesh<T>& mesh, const Vec3<T>& p) noexcept {
  const auto d = [](const Vec3<T>& v) {
    return Vec3<double>{double(v.x), double(v.y), double(v.z)};
  };
  return T(winding_number<double>(
      mesh.triangle_count(),
      [&](std::size_t t, Vec3<double>& a, Vec3<double>& b, Vec3<double>& c) {
        a = d(mesh.corner(t, 0)), b = d(mesh.corner(t, 1)), c = d(mesh.corner(t, 2));
      },
      d(p)));
}

/// An interval [lo, hi] holding every value a winding-number evaluation computes at any point of
/// a box, rounding included (`winding_range`, `FastWindingNumber::range_over`). Unbounded
/// (-inf, +inf) when the box touches or nearly touches the mesh.
struct WindingRange {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  /// +1 when every value is > 1/2 (inside everywhere), -1 when every value is < 1/2 (outside
  /// everywhere), 0 when the interval holds 1/2.
  int side() const noexcept { return lo > 0.5 ? 1 : hi < 0.5 ? -1 : 0; }
};

namespace detail {

/// The box a range is taken over, in double: its centre, half extents and a radius every point
/// is within.
struct RangeBox {
  Aabb<double> box;
  Vec3<double> c, e;
  double rho;
  template <class T> explicit RangeBox(const Aabb<T>& b) noexcept : box(Aabb<double>::from(b)) {
    c = box.center();
    e = box.extent() * 0.5 * (1 + 1e-12);
    rho = norm(box.extent()) * 0.5 * (1 + 1e-12);
  }
};

/// Accumulator of a winding number's terms over a box (all in units of w, i.e. over 4π). Terms
/// valid on the whole box are models: value and gradient at the centre c, a bound `grad1` on the
/// gradient's norm and a bound `hess` on the Hessian's norm over the box, so the sum lies within
/// value ± min(rho Σ grad1, Σ_a |gradient_a| e_a + rho² Σ hess / 2) (first- or second-order Taylor
/// bound; the second keeps the cancellations between the terms' gradients). Terms that differ
/// between points (a cluster far from some points and opened for others) add an interval.
struct RangeSum {
  double value = 0;
  Vec3<double> grad{0, 0, 0};
  double grad1 = 0, hess = 0;
  double ilo = 0, ihi = 0;
  double mag = 0;        ///< Σ of bounds on each term's intermediate magnitudes (for rounding)
  double cond = 0;       ///< Σ of exact solid angles' conditioning (1 + size / distance)
  std::size_t terms = 0; ///< terms summed per point (bounds the accumulated rounding)
  bool ok = true;

  void add(const RangeSum& o) noexcept {
    value += o.value, grad += o.grad, grad1 += o.grad1, hess += o.hess;
    ilo += o.ilo, ihi += o.ihi;
    mag += o.mag, cond += o.cond, terms += o.terms, ok = ok && o.ok;
  }
  /// The sum's interval over the box, without rounding margins.
  void interval(const RangeBox& x, double& lo, double& hi) const noexcept {
    const double lin =
        std::abs(grad.x) * x.e.x + std::abs(grad.y) * x.e.y + std::abs(grad.z) * x.e.z;
    const double w = std::min(x.rho * grad1, lin + 0.5 * x.rho * x.rho * hess) * (1 + 1e-9) +
                     1e-12 * (std::abs(value) + x.rho * grad1);
    lo = value + ilo - w, hi = value + ihi + w;
  }
  /// The hull of two alternatives (a point takes one or the other), as an interval term;
  /// rounding counts both.
  static RangeSum hull(const RangeBox& x, const RangeSum& a, const RangeSum& b) noexcept {
    RangeSum h;
    double alo, ahi, blo, bhi;
    a.interval(x, alo, ahi);
    b.interval(x, blo, bhi);
    h.ilo = std::min(alo, blo), h.ihi = std::max(ahi, bhi);
    h.mag = a.mag + b.mag, h.cond = a.cond + b.cond, h.terms = a.terms + b.terms;
    h.ok = a.ok && b.ok;
    return h;
  }
};

/// Gradient of the solid angle of triangle (a, b, c) seen from p (as `solid_angle`): the sum over
/// the edges (u, v) = (a - p, b - p), ... of (u × v) (|u| + |v|) / (|u| |v| (|u| |v| + u·v)), the
/// field of a unit current around the triangle (Biot-Savart).
inline Vec3<double> solid_angle_gradient(const Vec3<double>& p, const Vec3<double>& a,
                                         const Vec3<double>& b, const Vec3<double>& c) noexcept {
  const auto edge = [](const Vec3<double>& u, const Vec3<double>& v) {
    const double lu = norm(u), lv = norm(v);
    return cross(u, v) * ((lu + lv) / (lu * lv * (lu * lv + dot(u, v))));
  };
  return edge(a - p, b - p) + edge(b - p, c - p) + edge(c - p, a - p);
}

/// Adds the exact solid angle of triangle (a, b, c) as a model over the box. The solid angle is
/// ∫ n·∇_p (1 / |y - p|) dA(y) over the triangle, so at distance >= d from it (every point of
/// the box is at least the distance d between the triangle's box and the box away) its gradient
/// is at most 2 area / d³ and its Hessian at most 6 area / d⁴: as multilinear forms on unit
/// vectors, |∂ᵏ(1/r)| <= k! / r^(k+1) (a symmetric form is largest on equal arguments (Banach),
/// and the k-th derivative of 1/r along a unit vector is ±k! P_k(cos θ) / r^(k+1), |P_k| <= 1).
inline void add_triangle_range(RangeSum& s, const RangeBox& x, const Vec3<double>& a,
                               const Vec3<double>& b, const Vec3<double>& c) noexcept {
  constexpr double inv4pi = 0.07957747154594767;
  const Aabb<double> tb = Aabb<double>::of(a, b, c);
  double d2 = 0;
  for (int i = 0; i < 3; ++i) {
    const double g = std::max({tb.lo[i] - x.box.hi[i], x.box.lo[i] - tb.hi[i], 0.0});
    d2 += g * g;
  }
  const double d = std::sqrt(d2) * (1 - 1e-12);
  if (!(d > 0)) {
    s.ok = false;
    return;
  }
  const double area = 0.5 * norm(cross(b - a, c - a)) * (1 + 1e-12);
  const double w = solid_angle(x.c, a, b, c) * inv4pi;
  s.value += w;
  s.grad += solid_angle_gradient(x.c, a, b, c) * inv4pi;
  s.grad1 += 2 * area / (d * d * d) * inv4pi;
  s.hess += 6 * area / (d * d * d * d) * inv4pi;
  s.mag += std::abs(w) + x.rho * 2 * area / (d * d * d) * inv4pi;
  s.cond += 1 + norm(tb.extent()) / d;
  s.terms += 1;
}

/// The final interval: the sum widened by its rounding. A point's value is a sum of `terms`
/// terms, each computed with a few dozen roundings of at most `mag` (in precision `eps`, the
/// evaluation's precision), accumulated one by one, then rounded to the output precision; the
/// exact solid angles are computed in double, with an error that grows with size / distance.
inline WindingRange finish_range(const RangeSum& s, const RangeBox& x, double eps) noexcept {
  WindingRange r;
  if (!s.ok) return r;
  double lo, hi;
  s.interval(x, lo, hi);
  if (!std::isfinite(lo) || !std::isfinite(hi)) return r;
  const double dbl = std::numeric_limits<double>::epsilon();
  const double margin = (double(s.terms) + 64) * eps * (s.mag + 1) + 1024 * dbl * s.cond;
  r.lo = lo - margin;
  r.hi = hi + margin;
  return r;
}

} // namespace detail

/// Every value `winding_number(mesh, p)` computes for p in `box` lies in the returned interval
/// (see `WindingRange`). O(n): one exact sum at the box's centre plus a gradient bound per
/// triangle; unbounded when the box touches a triangle's bounding box. Thread-safe.
template <class T>
WindingRange winding_range(const TriangleMesh<T>& mesh, const Aabb<T>& box) noexcept {
  const detail::RangeBox x(box);
  detail::RangeSum s;
  for (std::size_t t = 0; t < mesh.triangle_count() && s.ok; ++t)
    detail::add_triangle_range(s, x, Vec3<double>::from(mesh.corner(t, 0)),
                               Vec3<double>::from(mesh.corner(t, 1)),
                               Vec3<double>::from(mesh.corner(t, 2)));
  // The exact sum runs in double whatever T, then rounds once to T.
  const double eps = std::numeric_limits<double>::epsilon();
  WindingRange r = detail::finish_range(s, x, eps);
  const double out =
      4 * double(std::numeric_limits<T>::epsilon()) * (std::abs(r.lo) + std::abs(r.hi) + 1);
  r.lo -= out, r.hi += out;
  return r;
}

/// Options of `FastWindingNumber`.
struct WindingOptions {
  /// Accuracy: a cluster is approximated when |p - centre| > beta · radius. Larger is more
  /// accurate and slower; the error decays like beta⁻³. Barill et al. use 2. Must be > 0.
  double beta = 2;
  /// Triangles per BVH leaf (exact solid angles are summed in near leaves).
  std::uint32_t max_leaf_size = 8;
};

/// Dipole data of the K children of one BVH node, structure of arrays so one loop evaluates all
/// K far fields: centre (3), order-1 moment (3), order-2 moment (9) and (beta·radius)² (1):
/// 16·K scalars (K = 4, float: 256 B). Empty slots have `far2 = +inf` and zero moments.
template <class T, int K> struct WindingNode {
  T cx[K], cy[K], cz[K];
  T nx[K], ny[K], nz[K];
  T m[9][K]; ///< m[3 i + j][k] = M_ij of child k
  T far2[K];
};

namespace detail {
/// Correctly rounded square root (as `std::sqrt`) that inlines into `EBGEOM_WINDING_KERNEL`s.
template <class T> EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE T winding_sqrt(T x) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  if constexpr (sizeof(T) == sizeof(float))
    return __builtin_sqrtf(x);
  else
    return __builtin_sqrt(x);
#else
  return std::sqrt(x);
#endif
}

/// x[j] = sqrt(x[j]) for j < N (N a multiple of 8), correctly rounded as `std::sqrt`, with the
/// translation unit's own instruction set: vector square roots where it has them (the loop with
/// `std::sqrt` does not vectorise where `errno` is set).
template <int N, class T>
EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void sqrt_lanes_native(T* EBGEOM_RESTRICT x) noexcept {
  static_assert(N % 8 == 0, "sqrt_lanes: N must be a multiple of 8");
#if defined(__AVX512F__)
  if constexpr (sizeof(T) == sizeof(float) && N % 16 != 0) {
    for (int j = 0; j < N; j += 8) _mm256_storeu_ps(x + j, _mm256_sqrt_ps(_mm256_loadu_ps(x + j)));
  } else if constexpr (sizeof(T) == sizeof(float)) {
    for (int j = 0; j < N; j += 16)
      _mm512_storeu_ps(x + j, _mm512_maskz_sqrt_ps(__mmask16(0xFFFF), _mm512_loadu_ps(x + j)));
  } else {
    for (int j = 0; j < N; j += 8)
      _mm512_storeu_pd(x + j, _mm512_maskz_sqrt_pd(__mmask8(0xFF), _mm512_loadu_pd(x + j)));
  }
#elif defined(__AVX__)
  if constexpr (sizeof(T) == sizeof(float)) {
    for (int j = 0; j < N; j += 8) _mm256_storeu_ps(x + j, _mm256_sqrt_ps(_mm256_loadu_ps(x + j)));
  } else {
    for (int j = 0; j < N; j += 4) _mm256_storeu_pd(x + j, _mm256_sqrt_pd(_mm256_loadu_pd(x + j)));
  }
#elif defined(__SSE2__)
  if constexpr (sizeof(T) == sizeof(float)) {
    for (int j = 0; j < N; j += 4) _mm_storeu_ps(x + j, _mm_sqrt_ps(_mm_loadu_ps(x + j)));
  } else {
    for (int j = 0; j < N; j += 2) _mm_storeu_pd(x + j, _mm_sqrt_pd(_mm_loadu_pd(x + j)));
  }
#else
  for (int j = 0; j < N; ++j) x[j] = winding_sqrt(x[j]);
#endif
}

#if EBGEOM_ISA_DISPATCH
/// `sqrt_lanes_native` with AVX (the dispatched AVX2 kernels). Not forced inline (an AVX function
/// inlines only into AVX code): it inlines into the kernels of the same target and options.
template <int N, class T>
EBGEOM_TARGET_AVX2 EBGEOM_WINDING_KERNEL inline void
sqrt_lanes_avx2(T* EBGEOM_RESTRICT x) noexcept {
  if constexpr (sizeof(T) == sizeof(float)) {
    for (int j = 0; j < N; j += 8) _mm256_storeu_ps(x + j, _mm256_sqrt_ps(_mm256_loadu_ps(x + j)));
  } else {
    for (int j = 0; j < N; j += 4) _mm256_storeu_pd(x + j, _mm256_sqrt_pd(_mm256_loadu_pd(x + j)));
  }
}

/// `sqrt_lanes_native` with AVX-512 (the dispatched AVX-512 kernels), as `sqrt_lanes_avx2`.
template <int N, class T>
EBGEOM_TARGET_AVX512 EBGEOM_WINDING_KERNEL inline void
sqrt_lanes_avx512(T* EBGEOM_RESTRICT x) noexcept {
  if constexpr (sizeof(T) == sizeof(float) && N % 16 != 0) {
    for (int j = 0; j < N; j += 8) _mm256_storeu_ps(x + j, _mm256_sqrt_ps(_mm256_loadu_ps(x + j)));
  } else if constexpr (sizeof(T) == sizeof(float)) {
    for (int j = 0; j < N; j += 16)
      _mm512_storeu_ps(x + j, _mm512_maskz_sqrt_ps(__mmask16(0xFFFF), _mm512_loadu_ps(x + j)));
  } else {
    for (int j = 0; j < N; j += 8)
      _mm512_storeu_pd(x + j, _mm512_maskz_sqrt_pd(__mmask8(0xFF), _mm512_loadu_pd(x + j)));
  }
}

/// Bit j set where b[j] != 0, j < 32, for b[j] in {0, 1}: the byte compare and movemask of AVX2.
EBGEOM_TARGET_AVX2 inline std::uint32_t lane_bits_avx2(const std::uint8_t* b) noexcept {
  const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(b));
  return std::uint32_t(_mm256_movemask_epi8(_mm256_cmpgt_epi8(v, _mm256_setzero_si256())));
}

/// `rsqrt_lanes_f`'s estimate and Newton step with AVX2.
template <int N>
EBGEOM_TARGET_AVX2 EBGEOM_WINDING_KERNEL inline void
rsqrt_lanes_f_avx2(float* EBGEOM_RESTRICT x) noexcept {
  const __m256 half = _mm256_set1_ps(0.5f), three = _mm256_set1_ps(3.0f);
  for (int j = 0; j < N; j += 8) {
    const __m256 v = _mm256_loadu_ps(x + j), y = _mm256_rsqrt_ps(v);
    const __m256 t = _mm256_sub_ps(three, _mm256_mul_ps(_mm256_mul_ps(v, y), y));
    _mm256_storeu_ps(x + j, _mm256_mul_ps(_mm256_mul_ps(half, y), t));
  }
}

/// `rsqrt_lanes_f`'s estimate and Newton step with AVX-512.
template <int N>
EBGEOM_TARGET_AVX512 EBGEOM_WINDING_KERNEL inline void
rsqrt_lanes_f_avx512(float* EBGEOM_RESTRICT x) noexcept {
  const __m512 half = _mm512_set1_ps(0.5f), three = _mm512_set1_ps(3.0f);
  for (int j = 0; j < N; j += 16) {
    const __m512 v = _mm512_loadu_ps(x + j), y = _mm512_maskz_rsqrt14_ps(__mmask16(0xFFFF), v);
    const __m512 t = _mm512_sub_ps(three, _mm512_mul_ps(_mm512_mul_ps(v, y), y));
    _mm512_storeu_ps(x + j, _mm512_mul_ps(_mm512_mul_ps(half, y), t));
  }
}
#endif

/// x[j] = sqrt(x[j]) for j < N (N a multiple of 8), correctly rounded as `std::sqrt` (the same
/// values on every instruction set), in the kernels of instruction set I (`core/isa.hpp`).
template <Isa I, int N, class T>
EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void sqrt_lanes(T* EBGEOM_RESTRICT x) noexcept {
  static_assert(N % 8 == 0, "sqrt_lanes: N must be a multiple of 8");
#if EBGEOM_ISA_DISPATCH
  if constexpr (I == Isa::avx512)
    sqrt_lanes_avx512<N>(x);
  else if constexpr (I == Isa::avx2)
    sqrt_lanes_avx2<N>(x);
  else
    sqrt_lanes_native<N>(x);
#else
  sqrt_lanes_native<N>(x);
#endif
}

/// Bit j set where b[j] != 0 for j < 32 (b[j] in {0, 1}), in the kernels of instruction set I:
/// one byte compare and movemask per 16 or 32 lanes where the instruction set has them (the loop
/// of shifts and ors does not vectorise well), else that loop.
template <Isa I>
EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE std::uint32_t
lane_bits32(const std::uint8_t* b) noexcept {
#if EBGEOM_ISA_DISPATCH
  if constexpr (I == Isa::avx2 || I == Isa::avx512) return lane_bits_avx2(b);
#endif
#if defined(__SSE2__)
  const __m128i z = _mm_setzero_si128();
  const __m128i lo = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b));
  const __m128i hi = _mm_loadu_si128(reinterpret_cast<const __m128i*>(b + 16));
  return std::uint32_t(_mm_movemask_epi8(_mm_cmpgt_epi8(lo, z))) |
         (std::uint32_t(_mm_movemask_epi8(_mm_cmpgt_epi8(hi, z))) << 16);
#else
  std::uint32_t bits = 0;
  for (int j = 0; j < 32; ++j) bits |= std::uint32_t(b[j] != 0) << j;
  return bits;
#endif
}

/// Relative error bound of `rsqrt_lanes_f`, in units of u = 2⁻²⁴.
inline constexpr double rsqrt_lanes_f_error_u = 12;

/// x[j] = 1 / sqrt(x[j]) for j < N (N a multiple of 16) in float, for the bounds of
/// `FastWindingNumber::bound_batch` only: with AVX-512 (`rsqrt14`, relative error < 2⁻¹⁴) or AVX2
/// (`rsqrt`, documented < 1.5 · 2⁻¹² by Intel; 2⁻¹¹ allowed here), the estimate y then one Newton
/// step y (3 - x y²) / 2, whose relative error is 1.5 e² + e³ / 2 for an estimate's e (<= 6 u)
/// plus the step's four roundings (<= 4 u): within `rsqrt_lanes_f_error_u` u of 1 / √x for
/// positive normal x (x = +inf or a denormal may give NaN or inf, which the bounds then reject).
/// Elsewhere 1 / sqrt(x), correctly rounded twice (2 u).
template <Isa I, int N>
EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void rsqrt_lanes_f(float* EBGEOM_RESTRICT x) noexcept {
  static_assert(N % 16 == 0, "rsqrt_lanes_f: N must be a multiple of 16");
#if EBGEOM_ISA_DISPATCH
  if constexpr (I == Isa::avx512) {
    rsqrt_lanes_f_avx512<N>(x);
    return;
  } else if constexpr (I == Isa::avx2) {
    rsqrt_lanes_f_avx2<N>(x);
    return;
  }
#endif
  sqrt_lanes<I, N>(x);
  for (int j = 0; j < N; ++j) x[j] = 1.0f / x[j];
}

/// Largest |`atan2_bounded(y, x)` - `std::atan2(y, x)`| over all finite (y, x), both rounded as
/// computed: see `atan2_bounded`.
inline constexpr double atan2_bounded_error = 3e-7;

/// atan2(y, x) to within `atan2_bounded_error` of `std::atan2` for every finite y and x, branch
/// free so that loops over a packet's lanes vectorise; NaN when y or x is infinite or NaN. The
/// octant reduction a = min(|x|, |y|) / max(|x|, |y|) in [0, 1], then atan(a) by the polynomial
/// a (1 + c1 a² + ... + c8 a¹⁶) of Abramowitz & Stegun 4.4.49 (published error <= 2e-8 on
/// [0, 1]), then π/2 - t when |y| > |x|, π - t when x is negative (or -0), and the sign of y, as
/// `std::atan2` does for signed zeros (atan2(±0, -0) = ±π, atan2(±0, +0) = ±0).
/// The bound: the polynomial's error e(a) = p(a) - atan(a) has |e'| <= |p'| + 1 <= 7.64 on
/// [0, 1] (|p'| <= Σ (2k + 1) |c_k| = 6.64); its largest magnitude at the 2²⁴ + 1 points a =
/// i 2⁻²⁴ is 1.36e-8 (computed in double against atan), so |e| <= 1.36e-8 + 7.64 · 2⁻²⁵ <=
/// 2.4e-7 on [0, 1]. The division, the Horner steps (no contraction in these kernels), the
/// reflections and the constants π/2, π add at most a few ulps of π (< 4e-15), and `std::atan2`
/// (glibc: correctly rounded in practice, at most 1 ulp) differs from atan by at most 4.5e-16:
/// 2.4e-7 + 5e-15 < 3e-7. tests/unit/sign/winding_test.cpp checks it at 2²⁰ points, signed zeros,
/// denormals and huge ratios.
EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE double atan2_bounded(double y, double x) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  // The builtins: GCC does not inline std::abs and std::copysign into these kernels (their
  // optimisation attributes differ), which would keep the loops from vectorising.
  const auto fabs = [](double v) { return __builtin_fabs(v); };
  const auto copysign = [](double m, double sg) { return __builtin_copysign(m, sg); };
#else
  const auto fabs = [](double v) { return std::abs(v); };
  const auto copysign = [](double m, double sg) { return std::copysign(m, sg); };
#endif
  constexpr double c1 = -0.3333314528, c2 = 0.1999355085, c3 = -0.1420889944, c4 = 0.1065626393,
                   c5 = -0.0752896400, c6 = 0.0429096138, c7 = -0.0161657367, c8 = 0.0028662257;
  constexpr double pi_2 = 1.5707963267948966, pi_1 = 3.141592653589793;
  const double ax = fabs(x), ay = fabs(y);
  const double hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
  const double a = lo / (hi > 0 ? hi : 1.0); // 0 / 1 for x = y = 0
  const double a2 = a * a;
  double t = c8;
  t = t * a2 + c7;
  t = t * a2 + c6;
  t = t * a2 + c5;
  t = t * a2 + c4;
  t = t * a2 + c3;
  t = t * a2 + c2;
  t = t * a2 + c1;
  t = (t * a2 + 1.0) * a;
  t = ay > ax ? pi_2 - t : t;
  t = copysign(1.0, x) < 0 ? pi_1 - t : t;
  // x - x and y - y: 0 for finite inputs, NaN for infinite or NaN ones (the sign of y kept).
  return copysign(t + ((x - x) + (y - y)), y);
}

/// a b + c in float for the bounds of `FastWindingNumber::bound_batch`: one fused multiply-add
/// (one rounding) in the kernels of instruction sets that have it (AVX2, AVX-512, or a build
/// whose own flags include FMA), a b then + c elsewhere. Only for values whose error bounds hold
/// either way: every bound below counts at most the roundings of the unfused form, and a fused
/// step rounds once where that form rounds twice, with no larger error.
template <Isa I> EBGEOM_FORCE_INLINE float fmadd_f(float a, float b, float c) noexcept {
#if (defined(__GNUC__) || defined(__clang__)) && defined(__FMA__)
  return __builtin_fmaf(a, b, c);
#elif EBGEOM_ISA_DISPATCH
  if constexpr (I == Isa::avx2 || I == Isa::avx512)
    return __builtin_fmaf(a, b, c);
  else
    return a * b + c;
#else
  return a * b + c;
#endif
}

/// Largest |`atan2_bounded_f(y, x)` - atan2(y, x)| over all finite float (y, x): see
/// `atan2_bounded_f`.
inline constexpr double atan2_bounded_f_error = 2e-5;

/// atan2(y, x) in float for the float lanes of `FastWindingNumber::bound_batch`, whose bounds
/// need far less than float's precision: the octant reduction of `atan2_bounded` with a = lo ·
/// (1 / hi), `inv_hi` = 1 / hi (1 for x = y = 0, +inf where 1 / hi overflows) returned for the
/// caller's own use, then atan(a) by the degree-9 polynomial of Abramowitz & Stegun 4.4.47
/// (Horner steps by `fmadd_f<I>`). The bound: the polynomial with its coefficients as written errs
/// by at most 1.15e-5 at the 2²⁴ + 1 points a = i 2⁻²⁴ of [0, 1] (computed in double against atan),
/// and |e'| <= Σ (2k + 1) |c_k| + 1
/// <= 4.68, so |e| <= 1.15e-5 + 4.68 · 2⁻²⁵ <= 1.17e-5 on [0, 1]; the coefficients rounded to
/// float add u Σ |c_k| <= 1e-7 (u = 2⁻²⁴), a's two roundings 2 u a |p'| <= 4.4e-7, the Horner
/// steps (|t| <= 1 throughout, at most two roundings per step, propagated through factors a² <=
/// 1) and the last product at most 9 u <= 5.4e-7, the reflections π/2 - t and π - t 3e-7: 1.3e-5
/// < 2e-5. tests/unit/sign/winding_test.cpp checks it at 2²⁰ ratios against `std::atan2` in
/// double.
template <Isa I = Isa::baseline>
EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE float atan2_bounded_f(float y, float x,
                                                                float& inv_hi) noexcept {
#if defined(__GNUC__) || defined(__clang__)
  const auto fabs = [](float v) { return __builtin_fabsf(v); };
  const auto copysign = [](float m, float sg) { return __builtin_copysignf(m, sg); };
#else
  const auto fabs = [](float v) { return std::abs(v); };
  const auto copysign = [](float m, float sg) { return std::copysign(m, sg); };
#endif
  constexpr float c1 = 0.9998660f, c3 = -0.3302995f, c5 = 0.1801410f, c7 = -0.0851330f,
                  c9 = 0.0208351f;
  constexpr float pi_2 = 1.5707963267948966f, pi_1 = 3.141592653589793f;
  const float ax = fabs(x), ay = fabs(y);
  const float hi = ax > ay ? ax : ay, lo = ax > ay ? ay : ax;
  // Below 1e-30, both scaled by 2⁶⁴ (exactly) so that 1 / hi does not overflow.
  const float sc = hi < 1e-30f ? 18446744073709551616.0f : 1.0f;
  inv_hi = 1.0f / (hi > 0 ? hi * sc : 1.0f);
  const float a = (lo * sc) * inv_hi;
  inv_hi *= sc; // 1 / hi, or +inf where that overflows
  const float a2 = a * a;
  float t = c9;
  t = fmadd_f<I>(t, a2, c7);
  t = fmadd_f<I>(t, a2, c5);
  t = fmadd_f<I>(t, a2, c3);
  t = fmadd_f<I>(t, a2, c1);
  t = t * a;
  t = ay > ax ? pi_2 - t : t;
  t = copysign(1.0f, x) < 0 ? pi_1 - t : t;
  return copysign(t + ((x - x) + (y - y)), y);
}

#if EBGEOM_ISA_DISPATCH
/// The 4 values at p as doubles, for the AVX2 kernels.
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE __m256d load4_pd(const float* p) noexcept {
  return _mm256_cvtps_pd(_mm_loadu_ps(p));
}
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE __m256d load4_pd(const double* p) noexcept {
  return _mm256_loadu_pd(p);
}
/// a < 0 ? -a : a per lane, as the scalar kernels write it, for the AVX2 kernels.
EBGEOM_TARGET_AVX2 EBGEOM_FORCE_INLINE __m256d abs_lt_pd(__m256d a) noexcept {
  const __m256d zero = _mm256_setzero_pd();
  return _mm256_blendv_pd(a, zero - a, _mm256_cmp_pd(a, zero, _CMP_LT_OQ));
}
#endif

/// `atan2_bounded_f` without the reciprocal.
template <Isa I = Isa::baseline>
EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE float atan2_bounded_f(float y, float x) noexcept {
  float inv_hi;
  return atan2_bounded_f<I>(y, x, inv_hi);
}
} // namespace detail

namespace detail {
/// The fast winding number's packet traversal (`FastWindingNumber::eval_packet`, `bound_packet`)
/// compiled for instruction set I (`core/isa.hpp`): one out-of-line function with I's target
/// attribute, so that the loops over a packet's points vectorise for that target. The same values
/// on every instruction set (no contraction into fused multiply-adds, correctly rounded square
/// roots and divisions).
#define EBGEOM_WINDING_KERNELS(I, TARGET)                                                          \
  template <bool Approx, class W, class T>                                                         \
  TARGET EBGEOM_WINDING_KERNEL EBGEOM_NOINLINE static void packet_sums(                            \
      const W& w, const Vec3<T>* pts, int n, T* far_sum, double* near, double* cnt) noexcept {     \
    w.template packet_sums_inline<Approx, I>(pts, n, far_sum, near, cnt);                          \
  }                                                                                                \
  template <class W, class X, class F>                                                             \
  TARGET EBGEOM_WINDING_KERNEL EBGEOM_NOINLINE static bool frontier(const W& w, const X& x,        \
                                                                    F& fr) noexcept {              \
    return w.template frontier_inline<I>(x, fr);                                                   \
  }                                                                                                \
  template <class W, class X>                                                                      \
  TARGET EBGEOM_WINDING_KERNEL EBGEOM_NOINLINE static RangeSum node_range(                         \
      const W& w, std::uint32_t ni, const X& x) noexcept {                                         \
    return w.template node_range_inline<I>(ni, x);                                                 \
  }                                                                                                \
  template <class W, class X, class F>                                                             \
  TARGET EBGEOM_WINDING_KERNEL EBGEOM_NOINLINE static bool sub_frontier(                           \
      const W& w, const F& pa, const X& x, F& fr) noexcept {                                       \
    return w.template sub_frontier_inline<I>(pa, x, fr);                                           \
  }                                                                                                \
  template <class W, class F, class X, class T>                                                    \
  TARGET EBGEOM_WINDING_KERNEL EBGEOM_NOINLINE static void chunk_bounds2(                          \
      const W& w, const F& fr, const X& x, const Vec3<T>* pts, std::size_t n, T* lo, T* hi,        \
      const F& pm, const X& px) noexcept {                                                         \
    w.template chunk_bounds_inline<I>(fr, x, pts, n, lo, hi, &pm, &px);                            \
  }                                                                                                \
  template <class W, class F, class X, class T>                                                    \
  TARGET EBGEOM_WINDING_KERNEL EBGEOM_NOINLINE static void chunk_bounds(                           \
      const W& w, const F& fr, const X& x, const Vec3<T>* pts, std::size_t n, T* lo,               \
      T* hi) noexcept {                                                                            \
    w.template chunk_bounds_inline<I>(fr, x, pts, n, lo, hi);                                      \
  }

template <Isa I> struct WindingKernels { EBGEOM_WINDING_KERNELS(I, ) };
#if EBGEOM_ISA_DISPATCH
template <> struct WindingKernels<Isa::avx2> {
  EBGEOM_WINDING_KERNELS(Isa::avx2, EBGEOM_TARGET_AVX2)
};
template <> struct WindingKernels<Isa::avx512> {
  EBGEOM_WINDING_KERNELS(Isa::avx512, EBGEOM_TARGET_AVX512)
};
#endif
#undef EBGEOM_WINDING_KERNELS
} // namespace detail

/// BVH-accelerated generalized winding number (Barill et al. 2018; see the file comment).
/// Owns a copy of the triangles in leaf order (structure of arrays, 36 B per triangle in float),
/// the BVH and one `WindingNode` per BVH node. Immutable; queries are const, allocation-free and
/// thread-safe. `exact(p)` is the O(n) oracle over the same triangles.
template <class T, int K = 4> class FastWindingNumber {
 public:
  static_assert(K >= 2 && K <= 16, "FastWindingNumber<T, K> needs 2 <= K <= 16");
  using scalar_type = T;

  /// Builds over `mesh`'s triangles. Errors: `empty` (no triangles), `invalid_argument`
  /// (beta <= 0 or not finite), `non_finite` (a NaN/inf coordinate). O(n log n).
  static Result<FastWindingNumber> make(const TriangleMesh<T>& mesh,
                                        const WindingOptions& options = {}) {
    const std::size_t n = mesh.triangle_count();
    if (n == 0) return Error{ErrorCode::empty, "winding number: the mesh has no triangles"};
    if (n >= std::size_t(std::numeric_limits<std::uint32_t>::max()))
      return Error{ErrorCode::size_mismatch, "winding number: too many triangles"};
    if (!(options.beta > 0) || !std::isfinite(options.beta))
      return Error{ErrorCode::invalid_argument, "winding number: beta must be finite and > 0"};
    for (const auto& t : mesh.triangles)
      for (Index i : t)
        if (i >= mesh.vertices.size())
          return Error{ErrorCode::bad_index, "winding number: vertex index out of range"};
    for (std::size_t v = 0; v < mesh.vertices.size(); ++v)
      if (!all_finite(mesh.vertices[v]))
        return Error{ErrorCode::non_finite, "winding number: vertex " + std::to_string(v) +
                                                " has a NaN or infinite coordinate"};
    FastWindingNumber w;
    w.beta_ = options.beta;
    std::vector<Aabb<T>> boxes(n);
    std::vector<Vec3<T>> centroids(n);
    for (std::size_t t = 0; t < n; ++t) {
      boxes[t] = mesh.triangle_bounds(t);
      centroids[t] = boxes[t].center();
    }
    bvh::BuildOptions bo;
    bo.max_leaf_size = std::max<std::uint32_t>(1, options.max_leaf_size);
    w.bvh_ =
        bvh::flatten<K>(bvh::build(Span<const Aabb<T>>(boxes), Span<const Vec3<T>>(centroids), bo));
    // Triangles in leaf order: every leaf (and every subtree) is a contiguous range of slots.
    w.tri_.resize(9 * n);
    for (std::size_t s = 0; s < n; ++s) {
      const std::uint32_t t = w.bvh_.prim[s];
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) w.tri_[(3 * k + a) * n + s] = mesh.corner(t, k)[a];
    }
    w.n_ = n;
    w.nodes_.resize(w.bvh_.nodes.size());
    w.range_nodes_.resize(w.bvh_.nodes.size());
    if (w.bvh_.root.is_inner()) w.fill_node(w.bvh_.root.index);
    return w;
  }

  /// Approximate winding number at `p`. Exact (to rounding) when every cluster is near; error
  /// O(beta⁻³) per far cluster otherwise (beta = 2: mean |error| about 0.004, largest about 0.06
  /// on the test meshes; see docs/sign.md). Finite for finite p with coordinates below ~1e100.
  EBGEOM_WINDING_KERNEL T operator()(const Vec3<T>& p) const noexcept {
    const bvh::ChildRef root = bvh_.root;
    if (root.is_leaf()) return T(leaf_sum(root.index, root.count, p) * inv4pi);
    if (!root.is_inner()) return T(0);
    constexpr T inv4pi_t = T(0.07957747154594767);
    bvh::FixedStack<std::uint32_t, bvh::WideBvh<T, K>::stack_capacity> todo;
    todo.push(root.index);
    T far_sum = 0;   // Σ far-field terms (already divided by 4π)
    double near = 0; // Σ exact solid angles
    while (!todo.empty()) {
      const std::uint32_t ni = todo.pop();
      const WindingNode<T, K>& c = nodes_[ni];
      const bvh::WideNode<T, K>& node = bvh_.nodes[ni];
      bool is_far[K];
      T f = 0;
      for (int k = 0; k < K; ++k) { // branch-free over the K children: vectorisable
        const T rx = c.cx[k] - p.x, ry = c.cy[k] - p.y, rz = c.cz[k] - p.z;
        const T r2 = rx * rx + ry * ry + rz * rz;
        is_far[k] = r2 > c.far2[k];
        // With u = r/|r|: N·r/|r|³ + Σ M_ij (δ_ij/|r|³ - 3 r_i r_j/|r|⁵)
        //              = (N·u)/|r|² + (tr M - 3 u·M·u)/|r|³.
        // Written with u so that nothing overflows far away (|r|² = inf gives u = 0, term 0).
        const T inv_r = T(1) / detail::winding_sqrt(is_far[k] ? r2 : T(1));
        const T ux = rx * inv_r, uy = ry * inv_r, uz = rz * inv_r;
        const T inv_r2 = inv_r * inv_r;
        const T order1 = (c.nx[k] * ux + c.ny[k] * uy + c.nz[k] * uz) * inv_r2;
        const T trace = c.m[0][k] + c.m[4][k] + c.m[8][k];
        const T quad = ux * (c.m[0][k] * ux + c.m[1][k] * uy + c.m[2][k] * uz) +
                       uy * (c.m[3][k] * ux + c.m[4][k] * uy + c.m[5][k] * uz) +
                       uz * (c.m[6][k] * ux + c.m[7][k] * uy + c.m[8][k] * uz);
        const T v = order1 + (trace - T(3) * quad) * inv_r2 * inv_r;
        f += is_far[k] ? v : T(0);
      }
      far_sum += f * inv4pi_t;
      for (int k = 0; k < K; ++k) {
        if (is_far[k]) continue;
        const bvh::ChildRef r = node.child[k];
        if (r.is_leaf())
          near += leaf_sum(r.index, r.count, p);
        else if (r.is_inner())
          todo.push(r.index);
      }
    }
    return T(near * inv4pi) + far_sum;
  }

  /// Points per `eval_packet` call: one traversal serves up to this many points (32 measured
  /// faster than 16 or 8 on the bunny's band, whose packets are 4x4x2 groups of samples).
  static constexpr int packet_width = 32;
  static_assert(packet_width % 8 == 0 && packet_width <= 32, "one bit per point in a mask");

  /// Winding numbers at `n` points (0 <= n <= `packet_width`), bit for bit `(*this)(pts[j])`,
  /// with one traversal of the tree for all of them: a node is opened while any point needs it,
  /// and each point adds, in the order `operator()` does, exactly the far fields and leaf sums its
  /// own traversal adds (the same far-field test, the same child order, the same arithmetic;
  /// both without contraction into fused multiply-adds). Fast for nearby points (a 4x4x2
  /// group of grid samples), which open nearly the same nodes. Thread-safe.
  EBGEOM_WINDING_KERNEL void eval_packet(const Vec3<T>* pts, int n, T* out) const noexcept {
    constexpr int P = packet_width;
    if (n <= 0) return;
    EBGEOM_ASSERT(n <= P);
    const bvh::ChildRef root = bvh_.root;
    if (!root.is_inner() || n == 1) {
      for (int j = 0; j < n; ++j) out[j] = (*this)(pts[j]);
      return;
    }
    alignas(64) T far_sum[P];
    alignas(64) double near[P];
    with_active_isa([&](auto isa) {
      detail::WindingKernels<decltype(isa)::value>::template packet_sums<false>(
          *this, pts, n, far_sum, near, nullptr);
    });
    for (int j = 0; j < n; ++j) out[j] = T(near[j] * inv4pi) + far_sum[j];
  }

  /// Bounds on the winding numbers at `n` points (0 <= n <= `packet_width`): lo[j] <=
  /// `(*this)(pts[j])` <= hi[j] for every j whose bounds are finite (-inf, +inf where nothing is
  /// claimed: a NaN or huge point). One traversal as `eval_packet` with the same far fields
  /// (the same arithmetic: bit for bit its far-field sums), but the near leaves' solid angles
  /// with `detail::atan2_bounded` over all the lanes at once instead of `std::atan2` per lane;
  /// see `sign_bound` for the margin. Thread-safe.
  EBGEOM_WINDING_KERNEL void bound_packet(const Vec3<T>* pts, int n, T* lo, T* hi) const noexcept {
    constexpr int P = packet_width;
    if (n <= 0) return;
    EBGEOM_ASSERT(n <= P);
    alignas(64) T far_sum[P];
    alignas(64) double near[P], cnt[P];
    with_active_isa([&](auto isa) {
      detail::WindingKernels<decltype(isa)::value>::template packet_sums<true>(*this, pts, n,
                                                                               far_sum, near, cnt);
    });
    const T inf = std::numeric_limits<T>::infinity();
    for (int j = 0; j < n; ++j) {
      const double e = sign_bound(near[j], cnt[j]);
      // `operator()` returns T(near * inv4pi) + far_sum: every step is a correctly rounded,
      // non-decreasing function of near, so the same steps from near - e and near + e bound it.
      const T l = T((near[j] - e) * inv4pi) + far_sum[j];
      const T h = T((near[j] + e) * inv4pi) + far_sum[j];
      const bool ok = std::isfinite(l) && std::isfinite(h);
      lo[j] = ok ? l : -inf;
      hi[j] = ok ? h : inf;
    }
  }

  /// above[j] = `(*this)(pts[j]) > 1/2` (inside by the winding number) at `n` points (0 <= n <=
  /// `packet_width`), exactly as the values `eval_packet` gives would decide: from `bound_packet`
  /// where its interval lies on one side of 1/2, from `eval_packet` (over the undecided points
  /// only) elsewhere (about |w - 1/2| < 1e-5: near holes' fills, NaN points). Thread-safe.
  void above_half_packet(const Vec3<T>* pts, int n, bool* above) const noexcept {
    constexpr int P = packet_width;
    if (n <= 0) return;
    EBGEOM_ASSERT(n <= P);
    alignas(64) T lo[P], hi[P];
    bound_packet(pts, n, lo, hi);
    Vec3<T> rest[P];
    int idx[P], m = 0;
    for (int j = 0; j < n; ++j) {
      if (lo[j] > T(0.5)) {
        above[j] = true;
      } else if (hi[j] <= T(0.5)) {
        above[j] = false;
      } else {
        idx[m] = j;
        rest[m++] = pts[j];
      }
    }
    if (m == 0) return;
    T w[P];
    eval_packet(rest, m, w);
    for (int i = 0; i < m; ++i) above[idx[i]] = w[i] > T(0.5);
  }

  /// Points per chunk of `bound_batch` (one box each).
  static constexpr std::size_t batch_size = 512;
  /// `bound_batch` models the far field of a cluster for the whole box when the cluster is at
  /// least this many times the box's radius away (closer ones are tested per point).
  static constexpr double batch_kappa = 2;
  /// Chunks of at least this many points are bounded by the octants of their box (a second,
  /// nested frontier per octant, `bound_octants`); smaller ones by one frontier.
  static constexpr std::size_t nest_min = 256;

  /// Bounds on the winding numbers at `n` points (any n), as `bound_packet`: lo[i] <=
  /// `(*this)(pts[i])` <= hi[i] where both are finite. For batches of nearby points (the samples
  /// of a grid tile), cheaper than `bound_packet`: per chunk of `batch_size` points, the clusters
  /// far from the chunk's whole box are evaluated once, at the box's centre, as a first-order
  /// model with a bound on its second-order remainder over the box (`far_range`); in chunks of
  /// at least `nest_min` points, so are those far from the box of each octant's points, from
  /// where the chunk's walk stopped (`bound_octants`); each point
  /// evaluates the rest (its own far tests, far fields and near leaves) in packets of
  /// `packet_width`; with T = float, the near solid angles in float (`leaf_lanes_f`) and the far
  /// fields from an approximate reciprocal square root (`detail::rsqrt_lanes_f`). The
  /// interval is wider than `bound_packet`'s by the model's remainder, the far sums' rounding and
  /// the float angles' error (a few hundredths on average on the bunny's tiles). Batches of at
  /// most `packet_width` points, a root leaf or a NaN point take `bound_packet`. Thread-safe.
  void bound_batch(const Vec3<T>* pts, std::size_t n, T* lo, T* hi) const noexcept {
    for (std::size_t i = 0; i < n; i += batch_size)
      bound_chunk(pts + i, std::min(n - i, batch_size), lo + i, hi + i);
  }

  /// above[i] = `(*this)(pts[i]) > 1/2` at `n` points (any n), exactly as the per-point values
  /// decide: `bound_batch` where its interval lies on one side of 1/2, `above_half_packet` (its
  /// narrower bound, then the exact values) for the others. Thread-safe, allocation-free.
  void above_half(const Vec3<T>* pts, std::size_t n, bool* above) const noexcept {
    constexpr int P = packet_width;
    alignas(64) T lo[batch_size], hi[batch_size];
    Vec3<T> rest[batch_size];
    std::uint16_t idx[batch_size];
    bool got[P];
    for (std::size_t i = 0; i < n; i += batch_size) {
      const std::size_t m = std::min(n - i, batch_size);
      bound_chunk(pts + i, m, lo, hi);
      std::size_t r = 0;
      for (std::size_t j = 0; j < m; ++j) {
        if (lo[j] > T(0.5)) {
          above[i + j] = true;
        } else if (hi[j] <= T(0.5)) {
          above[i + j] = false;
        } else {
          idx[r] = std::uint16_t(j);
          rest[r++] = pts[i + j];
        }
      }
      for (std::size_t j = 0; j < r; j += std::size_t(P)) {
        const int q = int(std::min(r - j, std::size_t(P)));
        above_half_packet(rest + j, q, got);
        for (int k = 0; k < q; ++k) above[i + idx[j + std::size_t(k)]] = got[k];
      }
    }
  }

  /// The margin of `bound_packet` on a point's near sum `near` (Σ of `cnt` solid angles, each
  /// 2 `atan2_bounded`): the exact path sums 2 `std::atan2` of the same num and den (the same
  /// arithmetic, bit for bit) in the same order, so the two sums differ by at most cnt · 2 ·
  /// `atan2_bounded_error` in their terms plus both sums' rounding: a recursive sum of N <= 2
  /// cnt additions (the leaves' partial sums, then the point's) of terms of magnitude <= 2π errs
  /// by at most N u Σ |terms| <= 2 cnt · u · 2π cnt each (u = 2⁻⁵³). The result is widened
  /// so that near ± margin, rounded, still bounds the exact sum.
  static double sign_bound(double near, double cnt) noexcept {
    constexpr double u = 1.1102230246251565e-16, two_pi = 6.283185307179586;
    const double e = cnt * 2 * detail::atan2_bounded_error + 2 * (2 * cnt * u * two_pi * cnt);
    return e * (1 + 1e-9) + 4 * u * std::abs(near) + 1e-300;
  }

 private:
  template <Isa> friend struct detail::WindingKernels;

  /// The far-field sums (in T) and near sums (in double, radians) of `eval_packet`'s traversal
  /// at `n` points, 1 <= n <= `packet_width`; with `Approx`, the near leaves' angles from
  /// `detail::atan2_bounded` and cnt[j] the number of solid angles summed at point j. Inlined into
  /// the kernels of instruction set I (`detail::WindingKernels`); the same values on every one.
  template <bool Approx, Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void packet_sums_inline(const Vec3<T>* pts, int n,
                                                                    T* far_sum, double* near,
                                                                    double* cnt) const noexcept {
    constexpr int P = packet_width;
    alignas(64) T px[P], py[P], pz[P];
    alignas(64) double dx[P], dy[P], dz[P];
    for (int j = 0; j < P; ++j) {
      const Vec3<T>& q = pts[j < n ? j : n - 1]; // spare lanes repeat the last point, masked
      px[j] = q.x, py[j] = q.y, pz[j] = q.z;
      dx[j] = double(q.x), dy[j] = double(q.y), dz[j] = double(q.z);
      far_sum[j] = T(0), near[j] = 0;
      if constexpr (Approx) cnt[j] = 0;
    }
    const std::uint32_t all = n >= 32 ? ~std::uint32_t(0) : (std::uint32_t(1) << n) - 1;
    const bvh::ChildRef root = bvh_.root;
    if (root.is_leaf()) {
      leaf_sum_packet<Approx, I>(root.index, root.count, dx, dy, dz, all, near, cnt);
      return;
    }
    if (!root.is_inner()) return;
    Stack todo;
    todo.push({root.index, all});
    std::uint32_t pops = 0;
    drain<Approx, false, I>(todo, px, py, pz, dx, dy, dz, far_sum, near, cnt, nullptr, nullptr,
                            pops);
  }

  /// A node of a packet's traversal, and the points that open it (bit j: point j).
  struct Item {
    std::uint32_t node, mask;
  };
  using Stack = bvh::FixedStack<Item, bvh::WideBvh<T, K>::stack_capacity>;

  /// The far-field test of child `k` of cluster node `c` at the packet's points (the arithmetic
  /// of `operator()`), and f[j] += its far field at the points that take it as far; returns
  /// those points' bits. With `Mag`, also mag[j] += `magk` at those points. Skips the far fields
  /// when no point of `mask` takes the child as far.
  template <bool Mag, Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE std::uint32_t
  child_far_lanes(const WindingNode<T, K>& c, int k, const T* px, const T* py, const T* pz,
                  std::uint32_t mask, T* f, T* mag, T magk) const noexcept {
    constexpr int P = packet_width;
    const T cx = c.cx[k], cy = c.cy[k], cz = c.cz[k], far2 = c.far2[k];
    const T nx = c.nx[k], ny = c.ny[k], nz = c.nz[k];
    const T m0 = c.m[0][k], m1 = c.m[1][k], m2 = c.m[2][k], m3 = c.m[3][k], m4 = c.m[4][k],
            m5 = c.m[5][k], m6 = c.m[6][k], m7 = c.m[7][k], m8 = c.m[8][k];
    const T trace = m0 + m4 + m8;
    alignas(64) std::uint8_t is_far[P];
    alignas(64) T rx[P], ry[P], rz[P], len[P];
    for (int j = 0; j < P; ++j) { // the arithmetic of `operator()`, over the points
      rx[j] = cx - px[j], ry[j] = cy - py[j], rz[j] = cz - pz[j];
      const T r2 = rx[j] * rx[j] + ry[j] * ry[j] + rz[j] * rz[j];
      is_far[j] = r2 > far2;
      len[j] = is_far[j] ? r2 : T(1);
    }
    static_assert(P == 32, "lane_bits32 reads 32 lanes");
    const std::uint32_t bits = detail::lane_bits32<I>(is_far);
    // A child no point of the packet takes as far adds +0 to every f[j], which leaves it as
    // it is (f starts at +0 and a sum is -0 only when both terms are): skip its far fields.
    if ((bits & mask) == 0) return bits;
    if constexpr (Mag && std::is_same_v<T, float>) {
      // For `bound_batch`'s bounds only (the same far tests; the values within its margin):
      // an approximate reciprocal square root (`rsqrt_lanes_f`) and fused multiply-adds.
      const auto fma = [](float x, float y, float z) { return detail::fmadd_f<I>(x, y, z); };
      detail::rsqrt_lanes_f<I, P>(len);
      for (int j = 0; j < P; ++j) {
        const T inv_r = len[j];
        const T ux = rx[j] * inv_r, uy = ry[j] * inv_r, uz = rz[j] * inv_r;
        const T inv_r2 = inv_r * inv_r;
        const T order1 = fma(nz, uz, fma(ny, uy, nx * ux)) * inv_r2;
        const T qx = fma(m2, uz, fma(m1, uy, m0 * ux)), qy = fma(m5, uz, fma(m4, uy, m3 * ux)),
                qz = fma(m8, uz, fma(m7, uy, m6 * ux));
        const T quad = fma(uz, qz, fma(uy, qy, ux * qx));
        const T v = fma(fma(T(-3), quad, trace), inv_r2 * inv_r, order1);
        f[j] += is_far[j] ? v : T(0);
      }
    } else {
      detail::sqrt_lanes<I, P>(len);
      for (int j = 0; j < P; ++j) {
        const T inv_r = T(1) / len[j];
        const T ux = rx[j] * inv_r, uy = ry[j] * inv_r, uz = rz[j] * inv_r;
        const T inv_r2 = inv_r * inv_r;
        const T order1 = (nx * ux + ny * uy + nz * uz) * inv_r2;
        const T quad = ux * (m0 * ux + m1 * uy + m2 * uz) + uy * (m3 * ux + m4 * uy + m5 * uz) +
                       uz * (m6 * ux + m7 * uy + m8 * uz);
        const T v = order1 + (trace - T(3) * quad) * inv_r2 * inv_r;
        f[j] += is_far[j] ? v : T(0);
      }
    }
    if constexpr (Mag)
      for (int j = 0; j < P; ++j) mag[j] += is_far[j] ? magk : T(0);
    return bits;
  }

  /// Runs a packet's traversal from the nodes on `todo` to the end (see `packet_sums_inline`);
  /// with `Mag`, mag[j] sums `RangeNode::magf` over the children point j takes as far. `pops`
  /// counts the nodes taken from the stack.
  template <bool Approx, bool Mag, Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  drain(Stack& todo, const T* px, const T* py, const T* pz, const double* dx, const double* dy,
        const double* dz, T* far_sum, double* near, double* cnt, T* mag, double* errn,
        std::uint32_t& pops) const noexcept {
    constexpr int P = packet_width;
    constexpr T inv4pi_t = T(0.07957747154594767);
    alignas(64) T f[P];
    while (!todo.empty()) {
      const Item it = todo.pop();
      ++pops;
      const WindingNode<T, K>& c = nodes_[it.node];
      const bvh::WideNode<T, K>& node = bvh_.nodes[it.node];
      std::uint32_t far_bits[K];
      for (int j = 0; j < P; ++j) f[j] = T(0);
      for (int k = 0; k < K; ++k) {
        T magk = T(0);
        if constexpr (Mag) magk = range_nodes_[it.node].magf[k];
        far_bits[k] = child_far_lanes<Mag, I>(c, k, px, py, pz, it.mask, f, mag, magk);
      }
      for (int j = 0; j < P; ++j) {
        const T a = far_sum[j] + f[j] * inv4pi_t;
        far_sum[j] = (it.mask >> j) & 1u ? a : far_sum[j];
      }
      for (int k = 0; k < K; ++k) {
        const std::uint32_t open = it.mask & ~far_bits[k];
        if (open == 0) continue;
        const bvh::ChildRef r = node.child[k];
        if (r.is_leaf())
          leaf_any<Approx, Mag, I>(r.index, r.count, px, py, pz, dx, dy, dz, open, near, cnt, errn);
        else if (r.is_inner())
          todo.push({r.index, open});
      }
    }
  }

  /// What `bound_batch` shares between the points of a batch (a box `x`): the far fields of the
  /// children far from every point of the box (at least `batch_kappa` times the box's radius
  /// away, and far by the query's test with its rounding margin) as one model, the value and
  /// gradient of their sum at the box's centre and a bound on the sum's Hessian over the box;
  /// the leaves every point opens; and the children some points take as far and others open
  /// (`item_node`, `item_k`), which each point tests itself.
  struct Frontier {
    static constexpr std::uint32_t capacity = 512;
    double value = 0, hess = 0;
    Vec3<double> grad{0, 0, 0};
    double mag = 0;   ///< Σ `RangeNode::magf` of the model's children
    double slack = 0; ///< Σ magnitudes of the model's terms (for its rounding in double)
    std::uint32_t nodes = 0, items = 0, leaves = 0;
    std::uint32_t item_node[capacity];
    std::uint8_t item_k[capacity];
    bvh::ChildRef leaf[capacity];
  };

#if EBGEOM_ISA_DISPATCH
  /// The far fields of the K = 4 children of `c` at the point `p`, over 4π: values `v` and
  /// gradients with respect to p (`gx`, `gy`, `gz`), as `far_range` computes them (the same
  /// operations in the same order, no fused multiply-adds, so the same values), at the lanes set
  /// in `use` (harmless arguments elsewhere). For the AVX2 and AVX-512 kernels.
  EBGEOM_TARGET_AVX2 EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE static void
  fields4_avx2(const WindingNode<T, K>& c, const Vec3<double>& p, __m256d use, __m256d& v,
               __m256d& gx, __m256d& gy, __m256d& gz) noexcept {
    // GCC's and Clang's vector operators on __m256d: one rounding per operation, no
    // contraction in these kernels (`EBGEOM_WINDING_KERNEL`).
    using V = __m256d;
    const V one = _mm256_set1_pd(1.0);
    const V i4p = _mm256_set1_pd(0.07957747154594767);
    const V m0 = detail::load4_pd(c.m[0]), m1 = detail::load4_pd(c.m[1]),
            m2 = detail::load4_pd(c.m[2]), m3 = detail::load4_pd(c.m[3]),
            m4 = detail::load4_pd(c.m[4]), m5 = detail::load4_pd(c.m[5]),
            m6 = detail::load4_pd(c.m[6]), m7 = detail::load4_pd(c.m[7]),
            m8 = detail::load4_pd(c.m[8]);
    const V tr = m0 + m4 + m8;
    const V nx = detail::load4_pd(c.nx), ny = detail::load4_pd(c.ny), nz = detail::load4_pd(c.nz);
    const V rx = detail::load4_pd(c.cx) - p.x, ry = detail::load4_pd(c.cy) - p.y,
            rz = detail::load4_pd(c.cz) - p.z;
    const V r2 = rx * rx + ry * ry + rz * rz;
    const V ir = one / _mm256_sqrt_pd(_mm256_blendv_pd(one, r2, use)), ir2 = ir * ir;
    const V ir3 = ir2 * ir, ir5 = ir3 * ir2, ir7 = ir5 * ir2;
    const V mrx = m0 * rx + m1 * ry + m2 * rz, mry = m3 * rx + m4 * ry + m5 * rz,
            mrz = m6 * rx + m7 * ry + m8 * rz;
    const V mtx = m0 * rx + m3 * ry + m6 * rz, mty = m1 * rx + m4 * ry + m7 * rz,
            mtz = m2 * rx + m5 * ry + m8 * rz;
    const V g = tr * r2 - 3.0 * (rx * mrx + ry * mry + rz * mrz);
    const V nr = nx * rx + ny * ry + nz * rz;
    v = (nr * ir3 + g * ir5) * i4p;
    const V a1 = 3.0 * nr * ir5, a2 = 5.0 * g * ir7;
    const V grx = nx * ir3 - rx * a1 + (rx * (2.0 * tr) - (mrx + mtx) * 3.0) * ir5 - rx * a2;
    const V gry = ny * ir3 - ry * a1 + (ry * (2.0 * tr) - (mry + mty) * 3.0) * ir5 - ry * a2;
    const V grz = nz * ir3 - rz * a1 + (rz * (2.0 * tr) - (mrz + mtz) * 3.0) * ir5 - rz * a2;
    gx = grx * -i4p, gy = gry * -i4p, gz = grz * -i4p;
  }

  /// The models of `frontier_node_inline`'s children for K = 4 with AVX2 (4 doubles per
  /// register; GCC 12 leaves that function's loop over the children scalar): the same
  /// operations in the same order, no fused multiply-adds, so the same values, at the children
  /// whose `model` is set (0 elsewhere). `ok` becomes false where a model's distance is not
  /// positive. In the AVX2 and AVX-512 kernels.
  template <class RN>
  EBGEOM_TARGET_AVX2 EBGEOM_WINDING_KERNEL static void
  models4_avx2(const WindingNode<T, K>& c, const RN& rc, const std::uint8_t* model,
               const double* dmin2a, const detail::RangeBox& x, double* val, double* gx, double* gy,
               double* gz, double* hs, double* sl, bool& ok) noexcept {
    // GCC's and Clang's vector operators on __m256d: one rounding per operation, no
    // contraction in these kernels (`EBGEOM_WINDING_KERNEL`).
    using V = __m256d;
    const V one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
    const V i4p = _mm256_set1_pd(0.07957747154594767);
    const V is_model = _mm256_castsi256_pd(_mm256_cmpgt_epi64(
        _mm256_cvtepu8_epi64(_mm_cvtsi32_si128(int(model[0]) | int(model[1]) << 8 |
                                               int(model[2]) << 16 | int(model[3]) << 24)),
        _mm256_setzero_si256()));
    const V dmin =
        _mm256_sqrt_pd(_mm256_blendv_pd(one, _mm256_loadu_pd(dmin2a), is_model)) * (1 - 1e-12);
    const V dfar = detail::load4_pd(rc.dfar);
    const V dlow = _mm256_blendv_pd(dfar, dmin, _mm256_cmp_pd(dmin, dfar, _CMP_GT_OQ));
    const V nrm = detail::load4_pd(rc.nrm), fro = detail::load4_pd(rc.fro);
    const V tr = detail::load4_pd(c.m[0]) + detail::load4_pd(c.m[4]) + detail::load4_pd(c.m[8]);
    const V il = one / _mm256_blendv_pd(one, dlow, is_model), il2 = il * il, il3 = il2 * il;
    const V mag = (nrm * il2 + (detail::abs_lt_pd(tr) + 9.0 * fro) * il3) * i4p;
    V v, ggx, ggy, ggz;
    fields4_avx2(c, x.c, is_model, v, ggx, ggy, ggz);
    const V id = one / _mm256_blendv_pd(one, dmin, is_model), id3 = id * id * id, id4 = id3 * id;
    const V h = (6.0 * nrm * id4 + 41.6 * fro * (id4 * id)) * i4p;
    const V slack =
        detail::abs_lt_pd(v) + mag +
        x.rho * (detail::abs_lt_pd(ggx) + detail::abs_lt_pd(ggy) + detail::abs_lt_pd(ggz));
    _mm256_storeu_pd(val, _mm256_blendv_pd(zero, v, is_model));
    _mm256_storeu_pd(gx, _mm256_blendv_pd(zero, ggx, is_model));
    _mm256_storeu_pd(gy, _mm256_blendv_pd(zero, ggy, is_model));
    _mm256_storeu_pd(gz, _mm256_blendv_pd(zero, ggz, is_model));
    _mm256_storeu_pd(hs, _mm256_blendv_pd(zero, h, is_model));
    _mm256_storeu_pd(sl, _mm256_blendv_pd(zero, slack, is_model));
    // ok &= !is_model | (dlow > 0)
    const int bad =
        _mm256_movemask_pd(_mm256_andnot_pd(_mm256_cmp_pd(dlow, zero, _CMP_GT_OQ), is_model));
    ok = ok & (bad == 0);
  }

  /// `far_range` for the K = 4 children of a node at once, for those whose bit is set in `need`
  /// (the others' `fv` untouched): `dmin2s[k]` the squared distance from the box to child k's
  /// centre, `whole[k]` as `far_range`'s. The same operations in the same order, no fused
  /// multiply-adds, so the same terms bit for bit. In the AVX2 and AVX-512 kernels
  /// (`node_range_inline`; GCC 12 leaves the scalar `far_range` scalar).
  template <class RN>
  EBGEOM_TARGET_AVX2 EBGEOM_WINDING_KERNEL static void
  far_range4_avx2(detail::RangeSum* fv, const detail::RangeBox& x, const WindingNode<T, K>& c,
                  const RN& rc, const double* dmin2s, const std::uint8_t* whole,
                  unsigned need) noexcept {
    using V = __m256d;
    const V one = _mm256_set1_pd(1.0), zero = _mm256_setzero_pd();
    const V i4p = _mm256_set1_pd(0.07957747154594767);
    const V dmin = _mm256_sqrt_pd(_mm256_loadu_pd(dmin2s)) * (1 - 1e-12);
    const V dfar = detail::load4_pd(rc.dfar);
    const V dlow = _mm256_blendv_pd(dfar, dmin, _mm256_cmp_pd(dmin, dfar, _CMP_GT_OQ));
    const V okm = _mm256_cmp_pd(dlow, zero, _CMP_GT_OQ),
            pos = _mm256_cmp_pd(dmin, zero, _CMP_GT_OQ);
    const V nrm = detail::load4_pd(rc.nrm), fro = detail::load4_pd(rc.fro);
    const V atr = detail::abs_lt_pd(detail::load4_pd(c.m[0]) + detail::load4_pd(c.m[4]) +
                                    detail::load4_pd(c.m[8]));
    const V il = one / _mm256_blendv_pd(one, dlow, okm), il2 = il * il, il3 = il2 * il;
    const V mag = (nrm * il2 + (atr + 9.0 * fro) * il3) * i4p;
    V v, gx, gy, gz;
    fields4_avx2(c, x.c, pos, v, gx, gy, gz);
    const V id = one / _mm256_blendv_pd(one, dmin, pos), id3 = id * id * id, id4 = id3 * id;
    const V g1 = (2.0 * nrm * id3 + 10.4 * fro * id4) * i4p;
    const V hs = (6.0 * nrm * id4 + 41.6 * fro * (id4 * id)) * i4p;
    // The interval where some points only take the child as far: the cap, and where dmin > 0
    // the model's interval (`RangeSum::interval`) within it.
    const V cap = (nrm * il2 + (atr + 3.0 * fro) * il3) * i4p * (1 + 1e-12), ncap = -cap;
    const V lin = detail::abs_lt_pd(gx) * x.e.x + detail::abs_lt_pd(gy) * x.e.y +
                  detail::abs_lt_pd(gz) * x.e.z;
    const V w1 = x.rho * g1, w2 = lin + 0.5 * x.rho * x.rho * hs;
    const V w = _mm256_blendv_pd(w1, w2, _mm256_cmp_pd(w2, w1, _CMP_LT_OQ)) * (1 + 1e-9) +
                1e-12 * (detail::abs_lt_pd(v) + x.rho * g1);
    const V mlo = v + 0.0 - w, mhi = v + 0.0 + w;
    const V lo = _mm256_blendv_pd(
        ncap, _mm256_blendv_pd(mlo, ncap, _mm256_cmp_pd(ncap, mlo, _CMP_GT_OQ)), pos);
    const V hi =
        _mm256_blendv_pd(cap, _mm256_blendv_pd(mhi, cap, _mm256_cmp_pd(cap, mhi, _CMP_LT_OQ)), pos);
    alignas(32) double a_mag[4], a_v[4], a_gx[4], a_gy[4], a_gz[4], a_g1[4], a_hs[4], a_lo[4],
        a_hi[4];
    _mm256_store_pd(a_mag, mag), _mm256_store_pd(a_v, v), _mm256_store_pd(a_gx, gx);
    _mm256_store_pd(a_gy, gy), _mm256_store_pd(a_gz, gz), _mm256_store_pd(a_g1, g1);
    _mm256_store_pd(a_hs, hs), _mm256_store_pd(a_lo, lo), _mm256_store_pd(a_hi, hi);
    const int okb = _mm256_movemask_pd(okm), posb = _mm256_movemask_pd(pos);
    for (int k = 0; k < 4; ++k) {
      if (!((need >> k) & 1u)) continue;
      detail::RangeSum& f = fv[k];
      f = detail::RangeSum{};
      if (!((okb >> k) & 1)) { // `far_range` claims nothing where dlow is not positive
        f.ok = false;
        continue;
      }
      f.mag = a_mag[k];
      f.terms = 2;
      if (((posb >> k) & 1) && whole[k]) {
        f.value = a_v[k], f.grad = {a_gx[k], a_gy[k], a_gz[k]}, f.grad1 = a_g1[k];
        f.hess = a_hs[k];
      } else {
        f.ilo = a_lo[k], f.ihi = a_hi[k];
      }
    }
  }
#endif

  /// One node `ni` of a frontier's walk over the box `x` (`frontier_inline`), for its children
  /// whose bit is set in `kmask`: the K children's box distances and tests, then the models
  /// (`far_range`'s, with `whole`) of those far from every point of the box (at least
  /// `batch_kappa` box radii away) added to `fr`, the leaves near every point added to `fr`'s
  /// leaves, the subtrees near every point pushed on `todo`, the others added to `fr`'s items.
  /// False when `fr` is full. Inlined into the kernels of instruction set I.
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE bool
  frontier_node_inline(const detail::RangeBox& x, Frontier& fr, std::uint32_t ni,
                       std::uint32_t kmask,
                       bvh::FixedStack<std::uint32_t, bvh::WideBvh<T, K>::stack_capacity>& todo,
                       bool& ok) const noexcept {
    constexpr double i4p = 0.07957747154594767;
    const double e = 16 * double(std::numeric_limits<T>::epsilon()); // as in `node_range`
    const double kr = batch_kappa * x.rho, kr2 = kr * kr;
    const double blx = x.box.lo.x, bly = x.box.lo.y, blz = x.box.lo.z;
    const double bhx = x.box.hi.x, bhy = x.box.hi.y, bhz = x.box.hi.z;
    const double xcx = x.c.x, xcy = x.c.y, xcz = x.c.z;
    const WindingNode<T, K>& c = nodes_[ni];
    const RangeNode& rc = range_nodes_[ni];
    const bvh::WideNode<T, K>& node = bvh_.nodes[ni];
    alignas(64) double val[K], gx[K], gy[K], gz[K], hs[K], sl[K];
    std::uint8_t model[K], all_near[K];
    alignas(64) double dmin2a[K];
    std::uint32_t any_model = 0;
    for (int k = 0; k < K; ++k) { // the tests
      const double cx = double(c.cx[k]), cy = double(c.cy[k]), cz = double(c.cz[k]);
      const double far2 = double(c.far2[k]);
      double dmin2, dmax2;
      box_dist2_range(blx, bly, blz, bhx, bhy, bhz, cx, cy, cz, dmin2, dmax2);
      // far for every point (and 2 box radii away): the model; empty slots have far2 = inf.
      const bool is_model = (dmin2 * (1 - e) > far2) & (dmin2 >= kr2);
      model[k] = is_model;
      all_near[k] = dmax2 * (1 + e) <= far2;
      dmin2a[k] = dmin2;
      any_model |= std::uint32_t(is_model) << k;
    }
    if ((any_model & kmask) != 0) {
#if EBGEOM_ISA_DISPATCH
      if constexpr (K == 4 && (I == Isa::avx2 || I == Isa::avx512)) {
        models4_avx2(c, rc, model, dmin2a, x, val, gx, gy, gz, hs, sl, ok);
      } else
#endif
      {
        for (int k = 0; k < K; ++k) { // the models, branch-free over the children
          const double cx = double(c.cx[k]), cy = double(c.cy[k]), cz = double(c.cz[k]);
          const double dmin2 = dmin2a[k];
          const bool is_model = model[k];
          // `far_range` with `whole` (dmin > 0 there), at harmless arguments elsewhere.
          const double dmin = detail::winding_sqrt(is_model ? dmin2 : 1.0) * (1 - 1e-12);
          const double dfar = double(rc.dfar[k]);
          const double dlow = dmin > dfar ? dmin : dfar;
          const double nrm = double(rc.nrm[k]), fro = double(rc.fro[k]);
          const double tr = double(c.m[0][k]) + double(c.m[4][k]) + double(c.m[8][k]);
          const double atr = tr < 0 ? -tr : tr;
          const double il = 1 / (is_model ? dlow : 1.0), il2 = il * il, il3 = il2 * il;
          const double mag = (nrm * il2 + (atr + 9 * fro) * il3) * i4p;
          const double nx = double(c.nx[k]), ny = double(c.ny[k]), nz = double(c.nz[k]);
          const double m0 = double(c.m[0][k]), m1 = double(c.m[1][k]), m2 = double(c.m[2][k]);
          const double m3 = double(c.m[3][k]), m4 = double(c.m[4][k]), m5 = double(c.m[5][k]);
          const double m6 = double(c.m[6][k]), m7 = double(c.m[7][k]), m8 = double(c.m[8][k]);
          const double rx = cx - xcx, ry = cy - xcy, rz = cz - xcz;
          const double r2 = rx * rx + ry * ry + rz * rz;
          const double ir = 1 / detail::winding_sqrt(is_model ? r2 : 1.0), ir2 = ir * ir;
          const double ir3 = ir2 * ir, ir5 = ir3 * ir2, ir7 = ir5 * ir2;
          // M r and Mᵀ r
          const double mrx = m0 * rx + m1 * ry + m2 * rz, mry = m3 * rx + m4 * ry + m5 * rz,
                       mrz = m6 * rx + m7 * ry + m8 * rz;
          const double mtx = m0 * rx + m3 * ry + m6 * rz, mty = m1 * rx + m4 * ry + m7 * rz,
                       mtz = m2 * rx + m5 * ry + m8 * rz;
          const double g = tr * r2 - 3 * (rx * mrx + ry * mry + rz * mrz);
          const double nr = nx * rx + ny * ry + nz * rz;
          const double v = (nr * ir3 + g * ir5) * i4p;
          // ∇_r of the term; ∇_p = -∇_r.
          const double a1 = 3 * nr * ir5, a2 = 5 * g * ir7;
          const double grx =
              nx * ir3 - rx * a1 + (rx * (2 * tr) - (mrx + mtx) * 3.0) * ir5 - rx * a2;
          const double gry =
              ny * ir3 - ry * a1 + (ry * (2 * tr) - (mry + mty) * 3.0) * ir5 - ry * a2;
          const double grz =
              nz * ir3 - rz * a1 + (rz * (2 * tr) - (mrz + mtz) * 3.0) * ir5 - rz * a2;
          const double id = 1 / (is_model ? dmin : 1.0), id3 = id * id * id, id4 = id3 * id;
          const double h = (6 * nrm * id4 + 41.6 * fro * (id4 * id)) * i4p;
          const double ggx = grx * -i4p, ggy = gry * -i4p, ggz = grz * -i4p;
          const double agx = ggx < 0 ? -ggx : ggx, agy = ggy < 0 ? -ggy : ggy,
                       agz = ggz < 0 ? -ggz : ggz;
          const double av = v < 0 ? -v : v;
          val[k] = is_model ? v : 0.0;
          gx[k] = is_model ? ggx : 0.0, gy[k] = is_model ? ggy : 0.0, gz[k] = is_model ? ggz : 0.0;
          hs[k] = is_model ? h : 0.0;
          sl[k] = is_model ? av + mag + x.rho * (agx + agy + agz) : 0.0;
          // `far_range` claims nothing where dlow is not positive.
          ok = ok & (!is_model | (dlow > 0));
        }
      }
    }
    for (int k = 0; k < K; ++k) {
      const bvh::ChildRef r = node.child[k];
      if (r.is_empty() || !((kmask >> k) & 1u)) continue;
      if (model[k]) {
        fr.value += val[k], fr.hess += hs[k];
        fr.grad.x += gx[k], fr.grad.y += gy[k], fr.grad.z += gz[k];
        fr.mag += double(rc.magf[k]);
        fr.slack += sl[k];
      } else if (all_near[k]) {
        if (r.is_leaf()) {
          if (fr.leaves == Frontier::capacity) return false;
          fr.leaf[fr.leaves++] = r;
        } else if (r.is_inner()) {
          todo.push(r.index);
        }
      } else {
        if (fr.items == Frontier::capacity) return false;
        fr.item_node[fr.items] = ni;
        fr.item_k[fr.items++] = std::uint8_t(k);
      }
    }
    return true;
  }

  /// Fills `fr` for the box `x` (a walk of the tree as one query at the box would make, in
  /// double, by `frontier_node_inline`); false when it does not fit or a bound fails (the caller
  /// then takes the packets). Inlined into the kernels of instruction set I
  /// (`detail::WindingKernels`).
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE bool frontier_inline(const detail::RangeBox& x,
                                                                 Frontier& fr) const noexcept {
    bvh::FixedStack<std::uint32_t, bvh::WideBvh<T, K>::stack_capacity> todo;
    todo.push(bvh_.root.index);
    bool ok = true;
    return walk_inline<I>(x, fr, todo, ok) && finished(fr, ok);
  }

  /// Walks the subtrees on `todo` into `fr` (`frontier_node_inline` per node, counted in
  /// `fr.nodes`) until `todo` is empty; false when `fr` is full.
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE bool
  walk_inline(const detail::RangeBox& x, Frontier& fr,
              bvh::FixedStack<std::uint32_t, bvh::WideBvh<T, K>::stack_capacity>& todo,
              bool& ok) const noexcept {
    while (!todo.empty()) {
      const std::uint32_t ni = todo.pop();
      ++fr.nodes;
      if (!frontier_node_inline<I>(x, fr, ni, ~0u, todo, ok)) return false;
    }
    return true;
  }

  /// A walk's result: `ok` (every model's bound holds) and every sum of `fr` finite.
  static bool finished(const Frontier& fr, bool ok) noexcept {
    const auto finite = [](double v) { return v - v == 0; };
    return ok && finite(fr.value) && finite(fr.hess) && finite(fr.mag) && finite(fr.slack) &&
           finite(fr.grad.x) && finite(fr.grad.y) && finite(fr.grad.z);
  }

  /// Fills `fr` (empty) for a box `x2` inside the box of the frontier `pa`, continuing `pa`'s walk
  /// instead of starting again at the root: `pa`'s leaves (near every point of x2 too), then
  /// `pa`'s items tested against x2 (`frontier_node_inline`, the items of one node together) and
  /// the subtrees near every point of x2 walked. `fr`'s model holds the clusters far from x2 that
  /// are not in `pa`'s model; the points of x2 take both models (`chunk_bounds_inline` with `pm`).
  /// `fr.nodes` counts `pa`'s nodes too (for the rounding margin). False as `frontier_inline`.
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE bool
  sub_frontier_inline(const Frontier& pa, const detail::RangeBox& x2, Frontier& fr) const noexcept {
    bvh::FixedStack<std::uint32_t, bvh::WideBvh<T, K>::stack_capacity> todo;
    bool ok = true;
    for (std::uint32_t i = 0; i < pa.leaves; ++i) fr.leaf[fr.leaves++] = pa.leaf[i];
    fr.nodes = pa.nodes;
    for (std::uint32_t i = 0; i < pa.items;) {
      const std::uint32_t ni = pa.item_node[i];
      std::uint32_t km = 0;
      for (; i < pa.items && pa.item_node[i] == ni; ++i) km |= 1u << pa.item_k[i];
      if (!frontier_node_inline<I>(x2, fr, ni, km, todo, ok)) return false;
      // Walked before the next node's items, so that the stack holds at most what a walk from
      // the root would (at most K children of one node, then depth-first below them).
      if (!walk_inline<I>(x2, fr, todo, ok)) return false;
    }
    return finished(fr, ok);
  }

  /// A packet's part of `bound_batch` for the points of `fr`'s box: the near sums of `fr`'s
  /// leaves (with `detail::atan2_bounded`, counted in cnt), and for each of its children the
  /// query's far test per point, the far field at the points that take it as far (added to
  /// far_sum, in T) and a traversal below it for the others, as `packet_sums_inline`; mag[j]
  /// sums `RangeNode::magf` over the children point j takes as far here, `pops` counts the
  /// nodes and children visited.
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  frontier_sums_inline(const Frontier& fr, const Vec3<T>* pts, int n, T* far_sum, double* near,
                       double* cnt, T* mag, double* errn, std::uint32_t& pops) const noexcept {
    constexpr int P = packet_width;
    constexpr T inv4pi_t = T(0.07957747154594767);
    alignas(64) T px[P], py[P], pz[P], f[P];
    alignas(64) double dx[P], dy[P], dz[P];
    for (int j = 0; j < P; ++j) {
      const Vec3<T>& q = pts[j < n ? j : n - 1]; // spare lanes repeat the last point, masked
      px[j] = q.x, py[j] = q.y, pz[j] = q.z;
      dx[j] = double(q.x), dy[j] = double(q.y), dz[j] = double(q.z);
      far_sum[j] = T(0), near[j] = 0, cnt[j] = 0, mag[j] = T(0), errn[j] = 0;
    }
    const std::uint32_t all = n >= 32 ? ~std::uint32_t(0) : (std::uint32_t(1) << n) - 1;
    for (std::uint32_t i = 0; i < fr.leaves; ++i)
      leaf_any<true, true, I>(fr.leaf[i].index, fr.leaf[i].count, px, py, pz, dx, dy, dz, all, near,
                              cnt, errn);
    Stack todo;
    pops = 0;
    for (std::uint32_t i = 0; i < fr.items; ++i) {
      const std::uint32_t ni = fr.item_node[i];
      const int k = fr.item_k[i];
      for (int j = 0; j < P; ++j) f[j] = T(0);
      const std::uint32_t bits = child_far_lanes<true, I>(nodes_[ni], k, px, py, pz, all, f, mag,
                                                          range_nodes_[ni].magf[k]);
      ++pops;
      for (int j = 0; j < P; ++j) far_sum[j] += f[j] * inv4pi_t;
      const std::uint32_t open = all & ~bits;
      if (open == 0) continue;
      const bvh::ChildRef r = bvh_.nodes[ni].child[k];
      if (r.is_leaf()) {
        leaf_any<true, true, I>(r.index, r.count, px, py, pz, dx, dy, dz, open, near, cnt, errn);
      } else if (r.is_inner()) {
        todo.push({r.index, open});
        drain<true, true, I>(todo, px, py, pz, dx, dy, dz, far_sum, near, cnt, mag, errn, pops);
      }
    }
  }

  /// `bound_batch` over n <= `batch_size` points.
  void bound_chunk(const Vec3<T>* pts, std::size_t n, T* lo, T* hi) const noexcept {
    constexpr int P = packet_width;
    const auto by_packets = [&] {
      for (std::size_t i = 0; i < n; i += std::size_t(P))
        bound_packet(pts + i, int(std::min(n - i, std::size_t(P))), lo + i, hi + i);
    };
    if (n <= std::size_t(P) || !bvh_.root.is_inner()) return by_packets();
    Aabb<double> box;
    for (std::size_t i = 0; i < n; ++i) {
      if (!all_finite(pts[i])) return by_packets(); // NaN: no claim, per point
      box.extend(Vec3<double>::from(pts[i]));
    }
    const detail::RangeBox x(box);
    Frontier fr;
    bool fits = false;
    with_active_isa([&](auto isa) {
      fits = detail::WindingKernels<decltype(isa)::value>::frontier(*this, x, fr);
    });
    if (!fits) return by_packets();
    if (n >= nest_min) return bound_octants(fr, x, pts, n, lo, hi);
    with_active_isa([&](auto isa) {
      detail::WindingKernels<decltype(isa)::value>::chunk_bounds(*this, fr, x, pts, n, lo, hi);
    });
  }

  /// `bound_chunk`'s bounds at its n points, from their frontier `fr` over their box `x`, by the
  /// octants of the box: the points of each octant (in their order) get a frontier of their own
  /// box that continues `fr`'s walk (`sub_frontier_inline`: clusters far from the octant but not
  /// from the whole box become a second model, subtrees near every point of it are opened once),
  /// and their bounds take both models; where that frontier does not fit, `fr` alone.
  void bound_octants(const Frontier& fr, const detail::RangeBox& x, const Vec3<T>* pts,
                     std::size_t n, T* lo, T* hi) const noexcept {
    const Vec3<double> c = x.c;
    Vec3<T> sp[batch_size];
    T slo[batch_size], shi[batch_size];
    std::uint16_t from[batch_size];
    std::uint8_t oct[batch_size];
    std::size_t first[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0};
    for (std::size_t i = 0; i < n; ++i) { // a counting sort by octant
      const Vec3<double> q = Vec3<double>::from(pts[i]);
      oct[i] = std::uint8_t(int(q.x > c.x) | int(q.y > c.y) << 1 | int(q.z > c.z) << 2);
      ++first[oct[i] + 1];
    }
    for (int o = 0; o < 8; ++o) first[o + 1] += first[o];
    std::size_t next[8];
    std::copy(first, first + 8, next);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t d = next[oct[i]]++;
      sp[d] = pts[i], from[d] = std::uint16_t(i);
    }
    for (int o = 0; o < 8; ++o) {
      const std::size_t b = first[o], m = first[o + 1] - b;
      if (m == 0) continue;
      Aabb<double> box;
      for (std::size_t i = b; i < b + m; ++i) box.extend(Vec3<double>::from(sp[i]));
      const detail::RangeBox x2(box);
      Frontier fr2;
      with_active_isa([&](auto isa) {
        using Kernels = detail::WindingKernels<decltype(isa)::value>;
        if (Kernels::sub_frontier(*this, fr, x2, fr2))
          Kernels::chunk_bounds2(*this, fr2, x2, sp + b, m, slo + b, shi + b, fr, x);
        else
          Kernels::chunk_bounds(*this, fr, x, sp + b, m, slo + b, shi + b);
      });
    }
    for (std::size_t i = 0; i < n; ++i) lo[from[i]] = slo[i], hi[from[i]] = shi[i];
  }

  /// The bounds of `bound_chunk` at its n points from the shared part `fr` over their box `x`:
  /// per packet of `packet_width` points, `frontier_sums_inline`, then each point's interval.
  /// With `pm`, the frontier of a box containing x (`bound_octants`; `pxb` its box) whose model
  /// the points take as well, and whose nodes `fr.nodes` already counts. Inlined into the kernels
  /// of instruction set I (`detail::WindingKernels`).
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  chunk_bounds_inline(const Frontier& fr, const detail::RangeBox& x, const Vec3<T>* pts,
                      std::size_t n, T* lo, T* hi, const Frontier* pm = nullptr,
                      const detail::RangeBox* pxb = nullptr) const noexcept {
    constexpr int P = packet_width;
    const double eps = double(std::numeric_limits<T>::epsilon());
    const double pmag = pm ? pm->mag : 0.0, pslack = pm ? pm->slack : 0.0;
    const T inf = std::numeric_limits<T>::infinity();
    alignas(64) T far_sum[P], mag[P];
    alignas(64) double near[P], cnt[P], errn[P];
    const auto fabs = [](double v) { return v < 0 ? -v : v; };
    const auto finite = [](double v) { return v - v == 0; };
    for (std::size_t i = 0; i < n; i += std::size_t(P)) {
      const int m = int(n - i < std::size_t(P) ? n - i : std::size_t(P));
      std::uint32_t pops = 0;
      frontier_sums_inline<I>(fr, pts + i, m, far_sum, near, cnt, mag, errn, pops);
      // Rounding: `operator()` sums the far fields of the point's far children in T, each
      // computed with at most 64 roundings relative to its `magf` and then added through at most
      // K + 2 + (nodes visited) sums; our far_sum adds those of the items the same way, each
      // computed (T = float) from a reciprocal square root within 12 u (`rsqrt_lanes_f`, u = eps
      // / 2) instead of 2 u, raised to powers up to 5 in the terms: at most 25 eps more. Both are
      // within (nodes + K + 96) eps Σ magf of the exact sum of the same terms (with the model's
      // terms exact up to their Taylor remainder and their own rounding in double).
      static_assert(detail::rsqrt_lanes_f_error_u <= 12, "the margin below assumes 12 u");
      const double steps = double(fr.nodes) + double(pops) + K + 96;
      const double mag_slack = 1 + 2 * (double(pops) * K + K) * eps; // mag[j] summed in T
      for (int j = 0; j < m; ++j) {
        const Vec3<T>& q = pts[i + std::size_t(j)];
        const double ddx = double(q.x) - x.c.x, ddy = double(q.y) - x.c.y,
                     ddz = double(q.z) - x.c.z;
        // The near sum: as `bound_packet`'s, plus (T = float) the float angles' own error.
        const double e = sign_bound_inline(near[j], cnt[j]) + errn[j] * (1 + 1e-9);
        const double alo = double(T((near[j] - e) * inv4pi));
        const double ahi = double(T((near[j] + e) * inv4pi));
        double model = fr.value + (fr.grad.x * ddx + fr.grad.y * ddy + fr.grad.z * ddz);
        const double fs = double(far_sum[j]);
        double r = 2 * steps * eps * (fr.mag + pmag + double(mag[j]) * mag_slack) +
                   0.5 * fr.hess * (ddx * ddx + ddy * ddy + ddz * ddz) * (1 + 1e-9) +
                   1e-12 * (fr.slack + pslack);
        if (pm) {
          const double ex = double(q.x) - pxb->c.x, ey = double(q.y) - pxb->c.y,
                       ez = double(q.z) - pxb->c.z;
          model += pm->value + (pm->grad.x * ex + pm->grad.y * ey + pm->grad.z * ez);
          r += 0.5 * pm->hess * (ex * ex + ey * ey + ez * ez) * (1 + 1e-9);
        }
        const double sl = 1e-12 * (fabs(alo) + fabs(ahi) + fabs(fs) + fabs(model) + r) + 1e-300;
        const double l = alo + fs + model - r - sl, h = ahi + fs + model + r + sl;
        const bool ok = finite(l) & finite(h);
        // `operator()` returns T(a + far) with a in [alo, ahi], far in [fs + model - r, ...]:
        // its rounding to T is non-decreasing, so T rounded outwards bounds it.
        lo[i + std::size_t(j)] = ok ? round_down_inline(l) : -inf;
        hi[i + std::size_t(j)] = ok ? round_up_inline(h) : inf;
      }
    }
  }

  /// The squared distances from the point (cx, cy, cz) to the nearest and the farthest points of
  /// the box [bl, bh] (per axis, branch free: it inlines into the kernels' loops over a node's
  /// children, which vectorise).
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE static void
  box_dist2_range(double blx, double bly, double blz, double bhx, double bhy, double bhz, double cx,
                  double cy, double cz, double& dmin2, double& dmax2) noexcept {
    const double ax = blx - cx > cx - bhx ? blx - cx : cx - bhx;
    const double ay = bly - cy > cy - bhy ? bly - cy : cy - bhy;
    const double az = blz - cz > cz - bhz ? blz - cz : cz - bhz;
    const double mx = ax > 0 ? ax : 0.0, my = ay > 0 ? ay : 0.0, mz = az > 0 ? az : 0.0;
    dmin2 = mx * mx + my * my + mz * mz;
    const double fx = cx - blx > bhx - cx ? cx - blx : bhx - cx;
    const double fy = cy - bly > bhy - cy ? cy - bly : bhy - cy;
    const double fz = cz - blz > bhz - cz ? cz - blz : bhz - cz;
    dmax2 = fx * fx + fy * fy + fz * fz;
  }

  /// `sign_bound`, branch free (it inlines into the kernels).
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE static double sign_bound_inline(double near,
                                                                            double cnt) noexcept {
    constexpr double u = 1.1102230246251565e-16, two_pi = 6.283185307179586;
    const double e = cnt * 2 * detail::atan2_bounded_error + 2 * (2 * cnt * u * two_pi * cnt);
    return e * (1 + 1e-9) + 4 * u * (near < 0 ? -near : near) + 1e-300;
  }

  /// The largest T <= v (v finite), as `round_down`, branch free: for float, T(v) or the float
  /// below it (one step down in the ordered bit patterns; -0 steps to the negative
  /// denormal_min, +inf to the largest finite float).
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE static T round_down_inline(double v) noexcept {
    if constexpr (std::is_same_v<T, float>) {
      const float f = float(v);
      std::int32_t b;
      std::memcpy(&b, &f, sizeof b);
      // |b| - 1 with the sign bit kept, for b != ±0; ±0 -> 0x80000001 (-denormal_min).
      const std::int32_t mag = b & 0x7fffffff;
      const std::int32_t down = mag == 0 ? std::int32_t(0x80000001) : b > 0 ? b - 1 : b + 1;
      const std::int32_t pick = double(f) > v ? down : b;
      float g;
      std::memcpy(&g, &pick, sizeof g);
      return g;
    } else {
      return T(v); // exact for double
    }
  }

  /// The smallest T >= v (v finite), as `round_up`, branch free (`round_down_inline` of -v).
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE static T round_up_inline(double v) noexcept {
    return -round_down_inline(-v);
  }

 public:
  /// Winding numbers at every point of `pts`, bit for bit `(*this)(pts[i])`: `eval_packet` over
  /// runs of `packet_width` consecutive points (order the points so that neighbours are near).
  void eval(Span<const Vec3<T>> pts, Span<T> out) const noexcept {
    EBGEOM_ASSERT(pts.size() == out.size());
    for (std::size_t i = 0; i < pts.size(); i += std::size_t(packet_width)) {
      const std::size_t m = std::min(pts.size() - i, std::size_t(packet_width));
      eval_packet(pts.data() + i, int(m), out.data() + i);
    }
  }

  /// Exact winding number over the same triangles (the oracle), O(n).
  T exact(const Vec3<T>& p) const noexcept { return T(leaf_sum(0, std::uint32_t(n_), p) * inv4pi); }

  /// Every value `(*this)(p)` computes for p in `box` lies in the returned interval, rounding
  /// included (see `WindingRange`). Walks the tree as a query would, for the whole box at once:
  /// a cluster far from every point of the box adds its far field at the box's centre plus or
  /// minus the radius times a bound on its gradient; one near every point is opened; one that is
  /// far for some points and near for others adds the hull of both. Near leaves add their exact
  /// solid angles the same way (`winding_range`). Unbounded when the box touches a near leaf's
  /// triangles. Costs about one query at the box's centre. Thread-safe.
  WindingRange range_over(const Aabb<T>& box) const noexcept {
    const detail::RangeBox x(box);
    detail::RangeSum s;
    const bvh::ChildRef root = bvh_.root;
    if (root.is_leaf())
      leaf_range(s, x, root.index, root.count);
    else if (root.is_inner())
      with_active_isa([&](auto isa) {
        s = detail::WindingKernels<decltype(isa)::value>::node_range(*this, root.index, x);
      });
    return detail::finish_range(s, x, double(std::numeric_limits<T>::epsilon()));
  }

  /// The part of `range_over`'s walk that every box inside one box (the scope) shares: the
  /// clusters far from every point of the scope (at least `batch_kappa` times its radius away),
  /// summed into one model at its centre with a bound on the model's Hessian over the scope; the
  /// leaves every point of the scope opens; and the children that some of its points take as far
  /// and others open, which each box tests itself (`bound_batch`'s frontier). Made by `scope`,
  /// used by `range_over(scope, box)`. About 7 KB; make it once per scope, on the stack.
  class RangeScope {
   public:
    /// False when the shared walk did not fit (then `range_over(scope, box)` walks alone).
    bool shared() const noexcept { return ok_; }

   private:
    friend class FastWindingNumber;
    Aabb<T> box_;
    Frontier fr_;
    bool ok_ = false;
  };

  /// Fills `out` for boxes inside `box` (see `RangeScope`). Costs about one `range_over(box)`.
  void scope(const Aabb<T>& box, RangeScope& out) const noexcept {
    out.box_ = box;
    out.fr_ = Frontier{};
    out.ok_ = false;
    if (!bvh_.root.is_inner() || !all_finite(box.lo) || !all_finite(box.hi) || box.is_empty())
      return;
    const detail::RangeBox x(box);
    with_active_isa([&](auto isa) {
      out.ok_ = detail::WindingKernels<decltype(isa)::value>::frontier(*this, x, out.fr_);
    });
  }

  /// `range_over(box)` for a box inside the scope `sc` (see `RangeScope`): the same guarantee,
  /// every value `(*this)(p)` computes for p in `box` lies in the interval, from the scope's
  /// shared model (its Taylor expansion at the scope's centre, moved to the box's), the scope's
  /// leaves and the children the scope's points decide for themselves, each over `box` as
  /// `range_over` bounds them. Cheaper than `range_over(box)` when several boxes share a scope;
  /// a box not inside the scope, or a scope whose walk did not fit, takes `range_over(box)`.
  WindingRange range_over(const RangeScope& sc, const Aabb<T>& box) const noexcept {
    if (!sc.ok_ || !sc.box_.contains(box)) return range_over(box);
    const detail::RangeBox xs(sc.box_), y(box);
    const Frontier& fr = sc.fr_;
    detail::RangeSum s;
    // The model f(p) = value + grad·(p - cs) + R(p), |R(p)| <= hess |p - cs|² / 2 over the
    // scope (hess bounds the Hessian's norm there), written at the box's centre cy: f(cy) lies
    // within value + grad·(cy - cs) ± hess dc² / 2 (dc = |cy - cs|), its gradient within
    // grad ± hess dc there (so grad·(p - cy) errs by at most hess dc rho), and the gradient's
    // norm is at most |grad| + hess (dc + rho) over the box.
    const Vec3<double> dcv = y.c - xs.c;
    const double dc = norm(dcv) * (1 + 1e-12), h = fr.hess;
    s.value = fr.value + dot(fr.grad, dcv);
    s.grad = fr.grad;
    s.hess = h;
    s.grad1 = (norm(fr.grad) + h * (dc + y.rho)) * (1 + 1e-12);
    const double off = (0.5 * h * dc * dc + h * dc * y.rho) * (1 + 1e-9) +
                       1e-11 * (fr.slack + std::abs(s.value)) + 1e-300;
    s.ilo = -off, s.ihi = off;
    // Rounding: each modelled child counts as `far_range` counts it (two terms, its magnitude
    // bound at the distance where queries take it as far, `RangeNode::magf`).
    s.mag = fr.mag;
    s.terms = 2 * std::size_t(K) * fr.nodes;
    with_active_isa([&](auto isa) {
      constexpr Isa I = decltype(isa)::value;
      for (std::uint32_t i = 0; i < fr.leaves && s.ok; ++i)
        leaf_range(s, y, fr.leaf[i].index, fr.leaf[i].count);
      // The children the scope's points decide for themselves, tested as `node_range_inline`
      // tests them, over the box.
      const double e = 16 * double(std::numeric_limits<T>::epsilon());
      for (std::uint32_t i = 0; i < fr.items && s.ok; ++i) {
        const std::uint32_t ni = fr.item_node[i];
        const int k = fr.item_k[i];
        const WindingNode<T, K>& c = nodes_[ni];
        double dmin2, dmax2;
        box_dist2_range(y.box.lo.x, y.box.lo.y, y.box.lo.z, y.box.hi.x, y.box.hi.y, y.box.hi.z,
                        double(c.cx[k]), double(c.cy[k]), double(c.cz[k]), dmin2, dmax2);
        const double far2 = double(c.far2[k]);
        s.add(child_range_inline<I>(ni, k, y, dmin2 * (1 - e) > far2, dmax2 * (1 + e) <= far2,
                                    dmin2));
      }
    });
    return detail::finish_range(s, y, double(std::numeric_limits<T>::epsilon()));
  }

  double beta() const noexcept { return beta_; }
  std::size_t triangle_count() const noexcept { return n_; }
  const bvh::WideBvh<T, K>& tree() const noexcept { return bvh_; }
  /// Heap bytes: triangles, BVH nodes and slots, cluster data.
  std::size_t memory_bytes() const noexcept {
    return tri_.size() * sizeof(T) + bvh_.memory_bytes() + nodes_.size() * sizeof(nodes_[0]) +
           range_nodes_.size() * sizeof(RangeNode);
  }

 private:
  static constexpr double inv4pi = 0.07957747154594767;

  /// tan(Ω/2) = num / den for the triangle (a, b, c) seen from p, from la = |a - p| etc.: the
  /// arithmetic of `solid_angle` (geom/solid_angle.hpp), written out so that the per-point and the
  /// packet evaluations compile it alike (no contraction into fused multiply-adds).
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE static void
  solid_angle_terms(double px, double py, double pz, double ax, double ay, double az, double bx,
                    double by, double bz, double cx, double cy, double cz, double la, double lb,
                    double lc, double& num, double& den) noexcept {
    const double rax = ax - px, ray = ay - py, raz = az - pz;
    const double rbx = bx - px, rby = by - py, rbz = bz - pz;
    const double rcx = cx - px, rcy = cy - py, rcz = cz - pz;
    const double kx = rby * rcz - rbz * rcy, ky = rbz * rcx - rbx * rcz, kz = rbx * rcy - rby * rcx;
    num = rax * kx + ray * ky + raz * kz;
    den = la * lb * lc + (rax * rbx + ray * rby + raz * rbz) * lc +
          (rbx * rcx + rby * rcy + rbz * rcz) * la + (rcx * rax + rcy * ray + rcz * raz) * lb;
  }

  /// |a - p|², as `solid_angle` computes it before its square root.
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE static double
  dist2(double px, double py, double pz, double ax, double ay, double az) noexcept {
    const double rx = ax - px, ry = ay - py, rz = az - pz;
    return rx * rx + ry * ry + rz * rz;
  }

  /// Σ of the exact solid angles of slots [first, first + count) (in double: no overflow for
  /// float coordinates, and one rounding less).
  EBGEOM_WINDING_KERNEL double leaf_sum(std::uint32_t first, std::uint32_t count,
                                        const Vec3<T>& p) const noexcept {
    const T* t = tri_.data();
    const std::size_t n = n_;
    const double px = double(p.x), py = double(p.y), pz = double(p.z);
    double s = 0;
    for (std::size_t i = first; i < std::size_t(first) + count; ++i) {
      const double ax = double(t[0 * n + i]), ay = double(t[1 * n + i]), az = double(t[2 * n + i]);
      const double bx = double(t[3 * n + i]), by = double(t[4 * n + i]), bz = double(t[5 * n + i]);
      const double cx = double(t[6 * n + i]), cy = double(t[7 * n + i]), cz = double(t[8 * n + i]);
      const double la = detail::winding_sqrt(dist2(px, py, pz, ax, ay, az));
      const double lb = detail::winding_sqrt(dist2(px, py, pz, bx, by, bz));
      const double lc = detail::winding_sqrt(dist2(px, py, pz, cx, cy, cz));
      double num, den;
      solid_angle_terms(px, py, pz, ax, ay, az, bx, by, bz, cx, cy, cz, la, lb, lc, num, den);
      s += 2.0 * std::atan2(num, den);
    }
    return s;
  }

  /// s[j] = Σ of the exact solid angles of slots [first, first + count) at point j of (px, py,
  /// pz), j < N, as `leaf_sum` sums them, for the points whose bit is set in `open` (the others'
  /// s[j] mean nothing); with `Approx`, the angles from `detail::atan2_bounded`.
  template <bool Approx, Isa I, int N>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  leaf_lanes(std::uint32_t first, std::uint32_t count, const double* px, const double* py,
             const double* pz, std::uint32_t open, double* s) const noexcept {
    const T* t = tri_.data();
    const std::size_t n = n_;
    alignas(64) double num[N], den[N], la[N], lb[N], lc[N];
    for (int j = 0; j < N; ++j) s[j] = 0;
    for (std::size_t i = first; i < std::size_t(first) + count; ++i) {
      const double ax = double(t[0 * n + i]), ay = double(t[1 * n + i]), az = double(t[2 * n + i]);
      const double bx = double(t[3 * n + i]), by = double(t[4 * n + i]), bz = double(t[5 * n + i]);
      const double cx = double(t[6 * n + i]), cy = double(t[7 * n + i]), cz = double(t[8 * n + i]);
      for (int j = 0; j < N; ++j) {
        la[j] = dist2(px[j], py[j], pz[j], ax, ay, az);
        lb[j] = dist2(px[j], py[j], pz[j], bx, by, bz);
        lc[j] = dist2(px[j], py[j], pz[j], cx, cy, cz);
      }
      detail::sqrt_lanes<I, N>(la);
      detail::sqrt_lanes<I, N>(lb);
      detail::sqrt_lanes<I, N>(lc);
      for (int j = 0; j < N; ++j)
        solid_angle_terms(px[j], py[j], pz[j], ax, ay, az, bx, by, bz, cx, cy, cz, la[j], lb[j],
                          lc[j], num[j], den[j]);
      if constexpr (Approx) {
        for (int j = 0; j < N; ++j) {
          const double a = 2.0 * detail::atan2_bounded(num[j], den[j]);
          s[j] += (open >> j) & 1u ? a : 0.0;
        }
      } else {
        for (int j = 0; j < N; ++j)
          if ((open >> j) & 1u) s[j] += 2.0 * std::atan2(num[j], den[j]);
      }
    }
  }

  /// `leaf_sum` at the packet's points whose bit is set in `open`, added to their `near`; with
  /// `Approx`, the angles from `detail::atan2_bounded` and the count of angles in `cnt`. When at
  /// most `packet_width` - 8 points open the leaf (most leaves: a packet's points open 13 of 32
  /// lanes on average on the bunny), they are first gathered into the fewest groups of 8 lanes
  /// (the last point repeated), so the lanes of the other points cost nothing; each point's sum
  /// is the same, term by term in the same order.
  template <bool Approx, Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  leaf_sum_packet(std::uint32_t first, std::uint32_t count, const double* px, const double* py,
                  const double* pz, std::uint32_t open, double* near, double* cnt) const noexcept {
    constexpr int P = packet_width;
    alignas(64) double s[P];
    int idx[P], m = 0;
    for (int j = 0; j < P; ++j)
      if ((open >> j) & 1u) idx[m++] = j;
    if (m > P - 8) {
      leaf_lanes<Approx, I, P>(first, count, px, py, pz, open, s);
      for (int j = 0; j < P; ++j)
        if ((open >> j) & 1u) near[j] += s[j];
    } else {
      alignas(64) double qx[P], qy[P], qz[P];
      const int nv = (m + 7) / 8 * 8;
      for (int k = 0; k < nv; ++k) {
        const int j = idx[k < m ? k : m - 1];
        qx[k] = px[j], qy[k] = py[j], qz[k] = pz[j];
      }
      const std::uint32_t lanes = (std::uint32_t(1) << m) - 1; // m <= P - 8 < 32
      if (nv == 8)
        leaf_lanes<Approx, I, 8>(first, count, qx, qy, qz, lanes, s);
      else if (nv == 16)
        leaf_lanes<Approx, I, 16>(first, count, qx, qy, qz, lanes, s);
      else
        leaf_lanes<Approx, I, 24>(first, count, qx, qy, qz, lanes, s);
      for (int k = 0; k < m; ++k) near[idx[k]] += s[k];
    }
    if constexpr (Approx) {
      const double c = double(count);
      for (int j = 0; j < P; ++j) cnt[j] += (open >> j) & 1u ? c : 0.0;
    }
  }

  /// For `bound_batch` (T = float): s[j] = Σ of the solid angles of slots [first, first + count)
  /// at point j, computed in float with `detail::atan2_bounded_f`, and err[j] a bound on its
  /// distance to `leaf_sum`'s terms (before their sum). Per triangle: the float num and den (the
  /// arithmetic of `solid_angle_terms`, inputs a - p etc. rounded; products and sums fused by
  /// `detail::fmadd_f` where the instruction set has it) are within 15.6 u M and 53 u M of the
  /// exact ones (u = 2⁻²⁴, M = |a||b||c|: the triple product's six terms sum to at most √3 M, the
  /// four terms of den to 4 M; ≤ 5 roundings deep, fewer where fused), so (num, den) is within
  /// D = 128 u M (computed M, rounded) of the exact point, and the angle 2 atan2 within π D / R
  /// <= π D / H, R = |(num, den)| >= H = max(|num|, |den|), when D < H / 2 and the disk does not
  /// reach the branch cut (num = 0, den < 0); otherwise, or where M is tiny (underflow), err is
  /// +inf. Plus twice `atan2_bounded_f_error` and `std::atan2`'s own 1 ulp.
  template <Isa I, int N>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  leaf_lanes_f(std::uint32_t first, std::uint32_t count, const float* px, const float* py,
               const float* pz, float* s, float* err) const noexcept {
    const T* t = tri_.data();
    const std::size_t n = n_;
    constexpr float kd = float(128 * 5.9604644775390625e-08);
    constexpr float kpi = float(3.141592653589793 * 1.001);
    constexpr float kat = float(2 * (detail::atan2_bounded_f_error + 1e-15));
    constexpr float inf = std::numeric_limits<float>::infinity();
    const auto fma = [](float x, float y, float z) { return detail::fmadd_f<I>(x, y, z); };
    alignas(64) float la[N], lb[N], lc[N];
    for (int j = 0; j < N; ++j) s[j] = 0, err[j] = 0;
    for (std::size_t i = first; i < std::size_t(first) + count; ++i) {
      const float ax = float(t[0 * n + i]), ay = float(t[1 * n + i]), az = float(t[2 * n + i]);
      const float bx = float(t[3 * n + i]), by = float(t[4 * n + i]), bz = float(t[5 * n + i]);
      const float cx = float(t[6 * n + i]), cy = float(t[7 * n + i]), cz = float(t[8 * n + i]);
      for (int j = 0; j < N; ++j) {
        const float rax = ax - px[j], ray = ay - py[j], raz = az - pz[j];
        const float rbx = bx - px[j], rby = by - py[j], rbz = bz - pz[j];
        const float rcx = cx - px[j], rcy = cy - py[j], rcz = cz - pz[j];
        la[j] = fma(raz, raz, fma(ray, ray, rax * rax));
        lb[j] = fma(rbz, rbz, fma(rby, rby, rbx * rbx));
        lc[j] = fma(rcz, rcz, fma(rcy, rcy, rcx * rcx));
      }
      detail::sqrt_lanes<I, N>(la);
      detail::sqrt_lanes<I, N>(lb);
      detail::sqrt_lanes<I, N>(lc);
      for (int j = 0; j < N; ++j) {
        const float rax = ax - px[j], ray = ay - py[j], raz = az - pz[j];
        const float rbx = bx - px[j], rby = by - py[j], rbz = bz - pz[j];
        const float rcx = cx - px[j], rcy = cy - py[j], rcz = cz - pz[j];
        const float kx = fma(rby, rcz, -(rbz * rcy)), ky = fma(rbz, rcx, -(rbx * rcz)),
                    kz = fma(rbx, rcy, -(rby * rcx));
        const float num = fma(raz, kz, fma(ray, ky, rax * kx));
        const float m = la[j] * lb[j] * lc[j];
        const float ab = fma(raz, rbz, fma(ray, rby, rax * rbx));
        const float bc = fma(rbz, rcz, fma(rby, rcy, rbx * rcx));
        const float ca = fma(rcz, raz, fma(rcy, ray, rcx * rax));
        const float den = fma(ca, lb[j], fma(bc, la[j], fma(ab, lc[j], m)));
        const float an = num < 0 ? -num : num, ad = den < 0 ? -den : den;
        const float d = kd * m, h = an > ad ? an : ad;
        // Bitwise, not short-circuit: the loop stays branch-free (it vectorises).
        const bool ok = (h > 2 * d) & ((an > d) | (den > d)) & (m > 1e-30f);
        float inv_h;
        s[j] += 2.0f * detail::atan2_bounded_f<I>(num, den, inv_h);
        err[j] += ok ? fma(kpi * d, inv_h, kat) : inf;
      }
    }
  }

  /// `leaf_sum_packet` for `bound_batch` with float lanes (`leaf_lanes_f`, T = float): adds to
  /// near[j] the leaf's float sum, to cnt[j] its count and to errn[j] its error (the terms'
  /// bounds, summed in float and widened for that sum, plus the float sum's own rounding: at most
  /// count u Σ |terms| <= count² u 2π), at the points whose bit is set in `open`, gathered into
  /// 16 lanes when at most 16 points open the leaf.
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  leaf_sum_packet_f(std::uint32_t first, std::uint32_t count, const float* px, const float* py,
                    const float* pz, std::uint32_t open, double* near, double* cnt,
                    double* errn) const noexcept {
    constexpr int P = packet_width;
    alignas(64) float s[P], e[P];
    int idx[P], m = 0;
    for (int j = 0; j < P; ++j)
      if ((open >> j) & 1u) idx[m++] = j;
    const double c = double(count);
    const double sum_err = c * c * 5.9604644775390625e-08 * 6.283185307179586 * 1.01;
    const double widen = 1 + 2 * (c + 1) * 5.9604644775390625e-08;
    if (m > 16) {
      leaf_lanes_f<I, P>(first, count, px, py, pz, s, e);
      for (int j = 0; j < P; ++j)
        if ((open >> j) & 1u) {
          near[j] += double(s[j]);
          cnt[j] += c;
          errn[j] += double(e[j]) * widen + sum_err;
        }
    } else {
      alignas(64) float qx[16], qy[16], qz[16];
      for (int k = 0; k < 16; ++k) {
        const int j = idx[k < m ? k : m - 1];
        qx[k] = px[j], qy[k] = py[j], qz[k] = pz[j];
      }
      leaf_lanes_f<I, 16>(first, count, qx, qy, qz, s, e);
      for (int k = 0; k < m; ++k) {
        near[idx[k]] += double(s[k]);
        cnt[idx[k]] += c;
        errn[idx[k]] += double(e[k]) * widen + sum_err;
      }
    }
  }

  /// The near sum of a leaf in a packet's traversal: `leaf_sum_packet`, or for `bound_batch`
  /// (`Mag`) with T = float, `leaf_sum_packet_f`.
  template <bool Approx, bool Mag, Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  leaf_any(std::uint32_t first, std::uint32_t count, const T* px, const T* py, const T* pz,
           const double* dx, const double* dy, const double* dz, std::uint32_t open, double* near,
           double* cnt, double* errn) const noexcept {
    if constexpr (Mag && std::is_same_v<T, float>)
      leaf_sum_packet_f<I>(first, count, px, py, pz, open, near, cnt, errn);
    else
      leaf_sum_packet<Approx, I>(first, count, dx, dy, dz, open, near, cnt);
  }

  /// Adds the exact solid angles of slots [first, first + count) over the box.
  void leaf_range(detail::RangeSum& s, const detail::RangeBox& x, std::uint32_t first,
                  std::uint32_t count) const noexcept {
    const T* t = tri_.data();
    const std::size_t n = n_;
    for (std::size_t i = first; i < std::size_t(first) + count && s.ok; ++i)
      detail::add_triangle_range(
          s, x, {double(t[0 * n + i]), double(t[1 * n + i]), double(t[2 * n + i])},
          {double(t[3 * n + i]), double(t[4 * n + i]), double(t[5 * n + i])},
          {double(t[6 * n + i]), double(t[7 * n + i]), double(t[8 * n + i])});
  }

  /// Per child of a node, the constants of `far_range` that cost square roots, in T (the
  /// moments' own precision) rounded outwards: |N| and the Frobenius norm |M| of the stored
  /// moments rounded up, and the distance beyond which every query takes the child's far field
  /// rounded down (12 B per child in float).
  struct RangeNode {
    T nrm[K], fro[K], dfar[K];
    /// A bound on the magnitudes inside a query's float evaluation of the child's far field
    /// (|N| / r² + (|tr M| + 9 |M|) / r³ over 4π at r >= dfar, rounded up), plus an absolute
    /// 1e-30 (1 / dfar² + 1 / dfar³) for underflow: `bound_batch`'s rounding margins.
    T magf[K];
  };
  static T round_up(double v) noexcept {
    const T f = T(v);
    return double(f) < v ? std::nextafter(f, std::numeric_limits<T>::infinity()) : f;
  }
  static T round_down(double v) noexcept {
    const T f = T(v);
    return double(f) > v ? std::nextafter(f, -std::numeric_limits<T>::infinity()) : f;
  }

  /// Adds the far field of child `k` of cluster node `c` (constants `rc`) over the box, at points
  /// farther than `rc.dfar[k]` from its centre and `dmin` from the box (`whole`: every point of
  /// the box).
  /// With r = centre - p, the term is N·r / r³ + g(r) / r⁵, g = tr M r² - 3 rᵀ M r (`operator()`):
  /// = -N·∇(1/r) - Σ M_ij ∂_ij(1/r): a model with gradient bound 2 |N| / r³ + 6 √3 |M| / r⁴ and
  /// Hessian bound 6 |N| / r⁴ + 24 √3 |M| / r⁵ (|∂ᵏ(1/r)| <= k! / r^(k+1), `add_triangle_range`;
  /// a contraction with M is at most its nuclear norm <= √3 |M|, the Frobenius norm); for some
  /// points only (`whole` false) an interval capped by |term| <= |N| / r² + (|tr M| + 3 |M|) / r³.
  /// Plain scalar arithmetic, so that it inlines into the kernels (`node_range_inline`; its AVX2
  /// and AVX-512 kernels take `far_range4_avx2`, the same arithmetic 4 children at a time).
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE void
  far_range(detail::RangeSum& fv, const detail::RangeBox& x, const WindingNode<T, K>& c,
            const RangeNode& rc, int k, bool whole, double dmin_raw) const noexcept {
    constexpr double i4p = 0.07957747154594767;
    const auto fabs = [](double v) { return v < 0 ? -v : v; };
    const double cx = double(c.cx[k]), cy = double(c.cy[k]), cz = double(c.cz[k]);
    const double dmin = dmin_raw * (1 - 1e-12);
    const double dfar = double(rc.dfar[k]);
    const double dlow = dmin > dfar ? dmin : dfar;
    const double nrm = double(rc.nrm[k]), fro = double(rc.fro[k]);
    const double tr = double(c.m[0][k]) + double(c.m[4][k]) + double(c.m[8][k]);
    if (!(dlow > 0)) {
      fv.ok = false;
      return;
    }
    const double il = 1 / dlow, il2 = il * il, il3 = il2 * il;
    fv.mag = (nrm * il2 + (fabs(tr) + 9 * fro) * il3) * i4p;
    fv.terms = 2; // the term and its share of the per-node sum
    double value = 0, gx = 0, gy = 0, gz = 0, g1 = 0, hs = 0;
    if (dmin > 0) {
      const double nx = double(c.nx[k]), ny = double(c.ny[k]), nz = double(c.nz[k]);
      const double m0 = double(c.m[0][k]), m1 = double(c.m[1][k]), m2 = double(c.m[2][k]);
      const double m3 = double(c.m[3][k]), m4 = double(c.m[4][k]), m5 = double(c.m[5][k]);
      const double m6 = double(c.m[6][k]), m7 = double(c.m[7][k]), m8 = double(c.m[8][k]);
      const double rx = cx - x.c.x, ry = cy - x.c.y, rz = cz - x.c.z;
      const double r2 = rx * rx + ry * ry + rz * rz;
      const double ir = 1 / detail::winding_sqrt(r2), ir2 = ir * ir;
      const double ir3 = ir2 * ir, ir5 = ir3 * ir2, ir7 = ir5 * ir2;
      const double mrx = m0 * rx + m1 * ry + m2 * rz, mry = m3 * rx + m4 * ry + m5 * rz,
                   mrz = m6 * rx + m7 * ry + m8 * rz;
      const double mtx = m0 * rx + m3 * ry + m6 * rz, mty = m1 * rx + m4 * ry + m7 * rz,
                   mtz = m2 * rx + m5 * ry + m8 * rz;
      const double g = tr * r2 - 3 * (rx * mrx + ry * mry + rz * mrz);
      const double nr = nx * rx + ny * ry + nz * rz;
      value = (nr * ir3 + g * ir5) * i4p;
      // ∇_r of the term; ∇_p = -∇_r.
      const double a1 = 3 * nr * ir5, a2 = 5 * g * ir7;
      const double grx = nx * ir3 - rx * a1 + (rx * (2 * tr) - (mrx + mtx) * 3.0) * ir5 - rx * a2;
      const double gry = ny * ir3 - ry * a1 + (ry * (2 * tr) - (mry + mty) * 3.0) * ir5 - ry * a2;
      const double grz = nz * ir3 - rz * a1 + (rz * (2 * tr) - (mrz + mtz) * 3.0) * ir5 - rz * a2;
      gx = grx * -i4p, gy = gry * -i4p, gz = grz * -i4p;
      const double id = 1 / dmin, id3 = id * id * id, id4 = id3 * id;
      g1 = (2 * nrm * id3 + 10.4 * fro * id4) * i4p;
      hs = (6 * nrm * id4 + 41.6 * fro * (id4 * id)) * i4p;
      if (whole) {
        fv.value = value, fv.grad = {gx, gy, gz}, fv.grad1 = g1, fv.hess = hs;
        return;
      }
    }
    const double cap = (nrm * il2 + (fabs(tr) + 3 * fro) * il3) * i4p * (1 + 1e-12);
    double lo = -cap, hi = cap;
    if (dmin > 0) { // `RangeSum::interval` of the model alone
      const double lin = fabs(gx) * x.e.x + fabs(gy) * x.e.y + fabs(gz) * x.e.z;
      const double w1 = x.rho * g1, w2 = lin + 0.5 * x.rho * x.rho * hs;
      const double w = (w2 < w1 ? w2 : w1) * (1 + 1e-9) + 1e-12 * (fabs(value) + x.rho * g1);
      const double mlo = value + 0.0 - w, mhi = value + 0.0 + w;
      lo = lo > mlo ? lo : mlo, hi = hi < mhi ? hi : mhi;
    }
    fv.ilo = lo, fv.ihi = hi;
  }

  /// The interval of node `ni`'s children over the box (see `range_over`): per child, a cluster
  /// far from every point of the box adds its far field's model (`far_range` with `whole`), one
  /// near every point its leaf's or subtree's interval, one far for some points only the hull of
  /// both. The children's box distances and tests in a loop over the children that vectorises;
  /// then, in order, each child's terms (`far_range` where a point may take it as far),
  /// the subtrees through the kernel of instruction set I again
  /// (`detail::WindingKernels::node_range`).
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE detail::RangeSum
  node_range_inline(std::uint32_t ni, const detail::RangeBox& x) const noexcept {
    // A query's squared distance r2 is within a relative 8 eps of the exact one (three rounded
    // squares, two sums, the rounded differences): classify only with that margin.
    const double e = 16 * double(std::numeric_limits<T>::epsilon());
    const double blx = x.box.lo.x, bly = x.box.lo.y, blz = x.box.lo.z;
    const double bhx = x.box.hi.x, bhy = x.box.hi.y, bhz = x.box.hi.z;
    const WindingNode<T, K>& c = nodes_[ni];
    const bvh::WideNode<T, K>& node = bvh_.nodes[ni];
    alignas(64) double dmin2s[K];
    std::uint8_t all_far[K], all_near[K];
    for (int k = 0; k < K; ++k) { // branch-free over the children: vectorisable
      const double cx = double(c.cx[k]), cy = double(c.cy[k]), cz = double(c.cz[k]);
      const double far2 = double(c.far2[k]);
      double dmin2, dmax2;
      box_dist2_range(blx, bly, blz, bhx, bhy, bhz, cx, cy, cz, dmin2, dmax2);
      dmin2s[k] = dmin2;
      all_far[k] = dmin2 * (1 - e) > far2;
      all_near[k] = dmax2 * (1 + e) <= far2;
    }
    detail::RangeSum s;
    const auto add = [&s](const detail::RangeSum& o) { // `RangeSum::add`, inlined here
      s.value += o.value, s.grad.x += o.grad.x, s.grad.y += o.grad.y, s.grad.z += o.grad.z;
      s.grad1 += o.grad1, s.hess += o.hess, s.ilo += o.ilo, s.ihi += o.ihi;
      s.mag += o.mag, s.cond += o.cond, s.terms += o.terms, s.ok = s.ok && o.ok;
    };
#if EBGEOM_ISA_DISPATCH
    if constexpr (K == 4 && (I == Isa::avx2 || I == Isa::avx512)) {
      // The far fields' terms of the 4 children at once (`far_range4_avx2`).
      unsigned need = 0;
      for (int k = 0; k < K; ++k) need |= unsigned(!node.child[k].is_empty() && !all_near[k]) << k;
      detail::RangeSum fv[K];
      if (need != 0) far_range4_avx2(fv, x, c, range_nodes_[ni], dmin2s, all_far, need);
      for (int k = 0; k < K && s.ok; ++k) {
        if (node.child[k].is_empty()) continue;
        add(child_range_inline<I>(ni, k, x, all_far[k], all_near[k], dmin2s[k], &fv[k]));
      }
      return s;
    }
#endif
    for (int k = 0; k < K && s.ok; ++k) {
      if (node.child[k].is_empty()) continue;
      add(child_range_inline<I>(ni, k, x, all_far[k], all_near[k], dmin2s[k]));
    }
    return s;
  }

  /// The term of child `k` of node `ni` over the box (see `node_range_inline`), from the tests of
  /// its cluster's distances to the box (`all_far`: far for every point, `all_near`: near for
  /// every point; `dmin2` the squared distance from the box to its centre): its far field's model
  /// (`far_range`, or `*far` where given: its result), its leaf's or subtree's interval, or the
  /// hull of both.
  template <Isa I>
  EBGEOM_WINDING_KERNEL EBGEOM_FORCE_INLINE detail::RangeSum
  child_range_inline(std::uint32_t ni, int k, const detail::RangeBox& x, bool all_far,
                     bool all_near, double dmin2,
                     const detail::RangeSum* far = nullptr) const noexcept {
    const bvh::ChildRef r = bvh_.nodes[ni].child[k];
    detail::RangeSum fv, nv;
    if (!all_near) {
      if (far != nullptr)
        fv = *far;
      else
        far_range(fv, x, nodes_[ni], range_nodes_[ni], k, all_far, detail::winding_sqrt(dmin2));
    }
    if (!all_far) {
      if (r.is_leaf())
        leaf_range(nv, x, r.index, r.count);
      else if (r.is_inner())
        nv = detail::WindingKernels<I>::node_range(*this, r.index, x);
    }
    return all_far ? fv : all_near ? nv : detail::RangeSum::hull(x, fv, nv);
  }

  /// Slot range [lo, hi) covered by a child (subtrees are contiguous in leaf order).
  std::pair<std::uint32_t, std::uint32_t> range_of(const bvh::ChildRef& r) const {
    if (r.is_leaf()) return {r.index, r.index + r.count};
    std::uint32_t lo = std::numeric_limits<std::uint32_t>::max(), hi = 0;
    for (const auto& c : bvh_.nodes[r.index].child) {
      if (c.is_empty()) continue;
      const auto sub = range_of(c);
      lo = std::min(lo, sub.first);
      hi = std::max(hi, sub.second);
    }
    return {lo, hi};
  }

  /// Fills the cluster data of node `ni` and, recursively, of its descendants. The moments of
  /// each child are computed in double from its triangles directly: O(n log n) in all, exact
  /// radii (not a bound from the grandchildren).
  void fill_node(std::uint32_t ni) {
    WindingNode<T, K> wn{};
    const std::size_t n = n_;
    const T* t = tri_.data();
    auto tri = [&](std::size_t i, Vec3<double>& a, Vec3<double>& b, Vec3<double>& c) {
      a = {double(t[0 * n + i]), double(t[1 * n + i]), double(t[2 * n + i])};
      b = {double(t[3 * n + i]), double(t[4 * n + i]), double(t[5 * n + i])};
      c = {double(t[6 * n + i]), double(t[7 * n + i]), double(t[8 * n + i])};
    };
    for (int k = 0; k < K; ++k) {
      const bvh::ChildRef r = bvh_.nodes[ni].child[k];
      if (r.is_empty()) {
        wn.far2[k] = std::numeric_limits<T>::infinity();
        continue;
      }
      const auto [lo, hi] = range_of(r);
      const DipoleCluster<double> cl = make_dipole_cluster<double>(lo, hi, tri);
      wn.cx[k] = T(cl.center.x), wn.cy[k] = T(cl.center.y), wn.cz[k] = T(cl.center.z);
      wn.nx[k] = T(cl.normal.x), wn.ny[k] = T(cl.normal.y), wn.nz[k] = T(cl.normal.z);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) wn.m[3 * i + j][k] = T(cl.m[i][j]);
      // Rounded up a little so float centres never make a near cluster look far.
      const double fr = beta_ * cl.radius * (1 + 1e-5);
      wn.far2[k] = T(fr * fr);
      if (r.is_inner()) fill_node(r.index);
    }
    nodes_[ni] = wn;
    // The constants of `far_range`, from the stored (rounded) moments.
    RangeNode rn{};
    const double e = 16 * double(std::numeric_limits<T>::epsilon()); // as in `node_range`
    for (int k = 0; k < K; ++k) {
      double fro2 = 0;
      for (int i = 0; i < 9; ++i) fro2 += double(wn.m[i][k]) * double(wn.m[i][k]);
      const Vec3<double> nn{double(wn.nx[k]), double(wn.ny[k]), double(wn.nz[k])};
      rn.nrm[k] = round_up(norm(nn) * (1 + 1e-12));
      rn.fro[k] = round_up(std::sqrt(fro2) * (1 + 1e-12));
      // A query calls a cluster far beyond sqrt(far2) / (1 + e) at least (`node_range`).
      rn.dfar[k] = round_down(std::sqrt(double(wn.far2[k]) / (1 + e)) * (1 - 1e-12));
      const double tr = double(wn.m[0][k]) + double(wn.m[4][k]) + double(wn.m[8][k]);
      const double il = 1 / double(rn.dfar[k]), il2 = il * il, il3 = il2 * il;
      const double mg =
          (double(rn.nrm[k]) * il2 + (std::abs(tr) + 9 * double(rn.fro[k])) * il3) * inv4pi +
          1e-30 * (il2 + il3);
      // Empty slots (never far) add nothing; a zero dfar gives +inf (no claim).
      rn.magf[k] = bvh_.nodes[ni].child[k].is_empty() ? T(0)
                   : double(rn.dfar[k]) > 0 && std::isfinite(mg)
                       ? round_up(mg * (1 + 1e-12))
                       : std::numeric_limits<T>::infinity();
    }
    range_nodes_[ni] = rn;
  }

  bvh::WideBvh<T, K> bvh_;
  std::vector<WindingNode<T, K>> nodes_; ///< parallel to bvh_.nodes
  std::vector<RangeNode> range_nodes_;   ///< parallel to bvh_.nodes
  std::vector<T> tri_;                   ///< 9 arrays of n: ax, ay, az, bx, ..., cz in leaf order
  std::size_t n_ = 0;
  double beta_ = 2;
};

} // namespace ebgeom

EBGEOM_END_EXACT_FP
