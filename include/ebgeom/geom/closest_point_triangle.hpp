// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// The per-triangle kernel shared by every triangle-mesh SDF (brute force and BVH): closest point
/// on a triangle, which feature it lies on, the squared distance, and the signed distance using
/// the pseudonormal of that feature (Bærentzen & Aanæs 2005).

#include <cstdint>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/vec.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

/// The feature of a triangle (v0, v1, v2) on which a closest point lies. Edge k joins vertex k and
/// vertex (k + 1) % 3: edge0 = (v0, v1), edge1 = (v1, v2), edge2 = (v2, v0).
enum class TriangleFeature : std::uint8_t {
  face = 0,
  edge0 = 1,
  edge1 = 2,
  edge2 = 3,
  vertex0 = 4,
  vertex1 = 5,
  vertex2 = 6,
};

constexpr bool is_edge(TriangleFeature f) noexcept {
  return f == TriangleFeature::edge0 || f == TriangleFeature::edge1 || f == TriangleFeature::edge2;
}
constexpr bool is_vertex(TriangleFeature f) noexcept {
  return static_cast<int>(f) >= static_cast<int>(TriangleFeature::vertex0);
}
/// Edge number (0, 1, 2) of an edge feature. Precondition: `is_edge(f)`.
constexpr int edge_index(TriangleFeature f) noexcept { return static_cast<int>(f) - 1; }
/// Vertex number (0, 1, 2) of a vertex feature. Precondition: `is_vertex(f)`.
constexpr int vertex_index(TriangleFeature f) noexcept { return static_cast<int>(f) - 4; }

/// Stable lower-case name of a feature, e.g. "edge1".
inline const char* to_string(TriangleFeature f) noexcept {
  static constexpr const char* names[] = {"face",    "edge0",   "edge1",  "edge2",
                                          "vertex0", "vertex1", "vertex2"};
  const int i = static_cast<int>(f);
  return i >= 0 && i < 7 ? names[i] : "unknown";
}

/// Closest point on a triangle, its squared distance to the query, and its feature.
template <class T> struct TriangleClosestPoint {
  Vec3<T> point;
  T distance2;
  TriangleFeature feature;
};

namespace detail {
/// Closest point on segment [a, a + e] to p, as parameter t in [0, 1]. A zero-length segment
/// gives t = 0 (no division by zero).
template <class T>
EBGEOM_FORCE_INLINE T segment_parameter(const Vec3<T>& ap, const Vec3<T>& e) noexcept {
  const T ee = dot(e, e);
  const T num = dot(ap, e);
  // clamp(num / ee) without dividing by 0: num <= 0 -> 0, num >= ee -> 1.
  return num <= T(0) ? T(0) : (num >= ee ? T(1) : num / ee);
}
} // namespace detail

/// Closest point on the closed triangle (a, b, c) to `p`.
///
/// Method: if `p` projects inside the triangle (edge-function signs, which ignore the normal
/// component of `p`) the closest point is the projection onto the plane; otherwise it is the
/// nearest of the three edge segments (each a clamped projection). Every candidate is computed, so
/// the code is select-based and vectorises per lane; the operation order is fixed, so the result
/// is bitwise reproducible (BVH and brute force call this same function).
///
/// Features: `face` inside; `edgeK` when the segment parameter is strictly inside (0, 1);
/// `vertexK` when it clamps to an end. Ties between segments keep the lower edge number.
/// Degenerate triangles (zero area, repeated vertices) are handled: they reduce to segments or a
/// point, never NaN for finite input. O(1), allocation-free, thread-safe.
template <class T>
EBGEOM_EXACT_KERNEL inline TriangleClosestPoint<T>
closest_point_triangle(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b,
                       const Vec3<T>& c) noexcept {
  const Vec3<T> ab = b - a, bc = c - b, ca = a - c;
  const Vec3<T> ap = p - a, bp = p - b, cp = p - c;
  const Vec3<T> n = cross(ab, c - a);
  const T nn = dot(n, n);

  // Edge 0: a -> b
  const T t0 = detail::segment_parameter(ap, ab);
  const Vec3<T> q0 = t0 >= T(1) ? b : a + ab * t0; // exact end vertex
  const T d0 = norm2(p - q0);
  // Edge 1: b -> c
  const T t1 = detail::segment_parameter(bp, bc);
  const Vec3<T> q1 = t1 >= T(1) ? c : b + bc * t1; // exact end vertex
  const T d1 = norm2(p - q1);
  // Edge 2: c -> a
  const T t2 = detail::segment_parameter(cp, ca);
  const Vec3<T> q2 = t2 >= T(1) ? a : c + ca * t2; // exact end vertex
  const T d2 = norm2(p - q2);

  // Nearest segment (strict < keeps the lower edge on ties).
  TriangleClosestPoint<T> best{q0, d0, TriangleFeature::edge0};
  T tb = t0;
  int eb = 0;
  if (d1 < best.distance2) {
    best = {q1, d1, TriangleFeature::edge1};
    tb = t1;
    eb = 1;
  }
  if (d2 < best.distance2) {
    best = {q2, d2, TriangleFeature::edge2};
    tb = t2;
    eb = 2;
  }
  // A clamped parameter means the end vertex: start of edge k is vertex k, end is vertex k+1.
  if (tb <= T(0)) best.feature = static_cast<TriangleFeature>(4 + eb);
  if (tb >= T(1)) best.feature = static_cast<TriangleFeature>(4 + (eb == 2 ? 0 : eb + 1));

  // Face region: p projects inside when all three edge functions agree with the normal.
  const T w0 = dot(n, cross(ab, ap));
  const T w1 = dot(n, cross(bc, bp));
  const T w2 = dot(n, cross(ca, cp));
  if (nn > T(0) && w0 >= T(0) && w1 >= T(0) && w2 >= T(0)) {
    const T h = dot(n, ap);
    const T fd2 = h * h / nn;
    if (fd2 <= best.distance2) { // guards the projection against rounding in slivers
      best.point = p - n * (h / nn);
      best.distance2 = fd2;
      best.feature = TriangleFeature::face;
    }
  }
  return best;
}

/// Pseudonormal of `feature` given the triangle's face normal, its three edge pseudonormals (edge
/// k as in `TriangleFeature`) and its three vertex pseudonormals.
template <class T>
EBGEOM_FORCE_INLINE const Vec3<T>& feature_normal(TriangleFeature feature, const Vec3<T>& face,
                                                  const Vec3<T>* edge,
                                                  const Vec3<T>* vertex) noexcept {
  const int f = static_cast<int>(feature);
  return f == 0 ? face : (f < 4 ? edge[f - 1] : vertex[f - 4]);
}

/// Signed distance from `p` given its closest point `q` on the surface and the pseudonormal `n`
/// of the feature holding `q`: magnitude |p - q|, sign of n·(p - q) (negative inside). The sign
/// is correct for a closed, consistently oriented, manifold mesh with angle-weighted vertex and
/// averaged edge pseudonormals (Bærentzen & Aanæs 2005, Theorem 1). On the surface: +0.
template <class T>
EBGEOM_FORCE_INLINE T signed_distance_from(const Vec3<T>& p, const Vec3<T>& q, T distance2,
                                           const Vec3<T>& n) noexcept {
  const T d = std::sqrt(distance2);
  return dot(n, p - q) < T(0) ? -d : d;
}

/// Signed distance result: value (< 0 inside), closest point and feature.
template <class T> struct TriangleSignedDistance {
  T distance;
  Vec3<T> point;
  TriangleFeature feature;
};

/// Signed distance from `p` to triangle (v[0], v[1], v[2]) with its pseudonormals: face normal
/// `fn`, edge pseudonormals `en[3]`, vertex pseudonormals `vn[3]` (all unit or at least pointing
/// outward). Deterministic; O(1).
template <class T>
EBGEOM_FORCE_INLINE TriangleSignedDistance<T>
signed_distance_triangle(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c,
                         const Vec3<T>& fn, const Vec3<T>* en, const Vec3<T>* vn) noexcept {
  const TriangleClosestPoint<T> cp = closest_point_triangle(p, a, b, c);
  const Vec3<T>& n = feature_normal(cp.feature, fn, en, vn);
  return {signed_distance_from(p, cp.point, cp.distance2, n), cp.point, cp.feature};
}

} // namespace ebgeom

EBGEOM_END_EXACT_FP
