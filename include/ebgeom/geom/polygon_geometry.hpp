// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Geometry of one planar polygon given by a corner accessor: Newell normal, area, centroid,
/// interior corner angle, and the 2D projection used by the point-in-polygon tests.

#include <cmath>
#include <cstddef>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom {

/// Newell's normal of the polygon with `k` corners `corner(0..k-1)`: twice the vector area,
/// sum_i (v_i - v_0) x (v_{i+1} - v_0) (origin-independent, so taken at v_0 for conditioning).
/// Points outward for counter-clockwise corners; |result| = 2 * area for planar polygons; exact
/// cross((v1 - v0), (v2 - v0)) for a triangle. Zero for degenerate polygons. O(k). Never fused
/// into FMAs (`EBGEOM_EXACT_KERNEL`): face normals, and `validate`'s zero-area test, are the same
/// in `-march=native` builds as in baseline ones.
template <class T, class CornerFn>
EBGEOM_EXACT_KERNEL Vec3<T> newell_normal(std::size_t k, const CornerFn& corner) noexcept {
  Vec3<T> n = Vec3<T>::zero();
  if (k < 3) return n;
  const Vec3<T> o = corner(0);
  Vec3<T> prev = corner(1) - o;
  for (std::size_t i = 2; i < k; ++i) {
    const Vec3<T> cur = corner(i) - o;
    n += cross(prev, cur);
    prev = cur;
  }
  return n;
}

/// Area-weighted centroid of the polygon (fan triangles weighted by their signed area along the
/// Newell normal); the vertex average when the area is zero. O(k).
template <class T, class CornerFn>
Vec3<T> polygon_centroid(std::size_t k, const CornerFn& corner) noexcept {
  if (k == 0) return Vec3<T>::zero();
  Vec3<T> avg = Vec3<T>::zero();
  for (std::size_t i = 0; i < k; ++i) avg += corner(i);
  avg = avg / T(k);
  const Vec3<T> n = newell_normal<T>(k, corner);
  const T nn = dot(n, n);
  if (!(nn > T(0))) return avg;
  const Vec3<T> o = corner(0);
  Vec3<T> acc = Vec3<T>::zero();
  T wsum = 0;
  for (std::size_t i = 1; i + 1 < k; ++i) {
    const Vec3<T> a = corner(i), b = corner(i + 1);
    const T w = dot(cross(a - o, b - o), n); // signed, proportional to area
    acc += (o + a + b) * (w / T(3));
    wsum += w;
  }
  return wsum != T(0) ? acc / wsum : avg;
}

/// Interior angle at a corner between the edges to its neighbours `prev` and `next`, in [0, π].
/// atan2 form (stable near 0 and π); 0 when an edge has zero length.
template <class T>
inline T corner_angle(const Vec3<T>& prev, const Vec3<T>& v, const Vec3<T>& next) noexcept {
  const Vec3<T> u = prev - v, w = next - v;
  return std::atan2(norm(cross(u, w)), dot(u, w));
}

/// The two coordinates kept when a polygon with normal `n` is projected to 2D: the axis of the
/// largest |n| component is dropped, and the other two are ordered (x, y) so that the projected
/// polygon keeps its counter-clockwise orientation. `drop` is that axis.
struct PlaneProjection {
  int u = 0, v = 1, drop = 2;

  template <class T> static PlaneProjection for_normal(const Vec3<T>& n) noexcept {
    const int d = arg_max(abs(n));
    PlaneProjection p;
    p.drop = d;
    p.u = (d + 1) % 3;
    p.v = (d + 2) % 3;
    // (u, v, drop) is a cyclic permutation of (x, y, z): CCW about +drop stays CCW in (u, v).
    if (n[d] < T(0)) {
      const int t = p.u;
      p.u = p.v;
      p.v = t;
    }
    return p;
  }
  template <class T> Vec2<T> operator()(const Vec3<T>& x) const noexcept { return {x[u], x[v]}; }
};

} // namespace ebgeom
