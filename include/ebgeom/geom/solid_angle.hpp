// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Solid angles and dipole-cluster approximations: the kernels of the generalized winding number
/// (Jacobson, Kavan & Sorkine-Hornung 2013) and of its fast hierarchical approximation
/// (Barill, Dickson, Schmidt, Levin & Jacobson 2018, "Fast winding numbers for soups and clouds").

#include <cmath>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/vec.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

/// Signed solid angle subtended at `p` by triangle (a, b, c), in [-2π, 2π]. Positive when `p` is
/// behind the triangle (on the side opposite to its normal (b - a) x (c - a)), so a closed,
/// outward-oriented surface subtends +4π at interior points and 0 at exterior ones.
/// Van Oosterom & Strackee (1983), with a, b, c taken relative to p:
/// tan(Ω/2) = a·(b×c) / (|a||b||c| + (a·b)|c| + (b·c)|a| + (c·a)|b|).
/// Finite everywhere (atan2 never divides); 0 in the triangle's plane outside it.
template <class T>
inline T solid_angle(const Vec3<T>& p, const Vec3<T>& a, const Vec3<T>& b,
                     const Vec3<T>& c) noexcept {
  const Vec3<T> ra = a - p, rb = b - p, rc = c - p;
  const T la = norm(ra), lb = norm(rb), lc = norm(rc);
  const T num = dot(ra, cross(rb, rc));
  const T den = la * lb * lc + dot(ra, rb) * lc + dot(rb, rc) * la + dot(rc, ra) * lb;
  return T(2) * std::atan2(num, den);
}

/// Moments of a cluster of oriented triangles, enough for the order-2 far-field expansion of its
/// winding number (Barill et al. 2018, §3.2). Fill with `add_triangle`, then `finish`.
template <class T> struct DipoleCluster {
  Vec3<T> center{0, 0, 0}; ///< area-weighted centroid of the triangles
  Vec3<T> normal{0, 0, 0}; ///< Σ area_t n_t (order-1 moment)
  T m[3][3] = {};          ///< Σ area_t n_t,i (centroid_t - center)_j (order-2 moment)
  T radius = 0;            ///< max distance from `center` to any vertex of the cluster
  T area = 0;              ///< Σ area_t
};

/// Builds the moments of triangles `[first, last)` given by a callable `tri(i, a, b, c)` that
/// writes triangle i's vertices. Two passes (centre, then moments). O(n).
template <class T, class TriFn>
DipoleCluster<T> make_dipole_cluster(std::size_t first, std::size_t last, TriFn&& tri) {
  DipoleCluster<T> cl;
  Vec3<T> a, b, c, weighted{0, 0, 0}, box_center{0, 0, 0};
  T area = 0;
  for (std::size_t i = first; i < last; ++i) {
    tri(i, a, b, c);
    const T ar = T(0.5) * norm(cross(b - a, c - a));
    weighted += (a + b + c) * (ar / T(3));
    area += ar;
    box_center += a + b + c;
  }
  // area-weighted centroid; plain vertex mean when every triangle is degenerate
  cl.center =
      area > T(0) ? weighted / area : box_center / T(3 * std::max<std::size_t>(last - first, 1));
  cl.area = area;
  for (std::size_t i = first; i < last; ++i) {
    tri(i, a, b, c);
    const Vec3<T> an = T(0.5) * cross(b - a, c - a); // area * unit normal
    const Vec3<T> d = (a + b + c) / T(3) - cl.center;
    cl.normal += an;
    const T nv[3] = {an.x, an.y, an.z}, dv[3] = {d.x, d.y, d.z};
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) cl.m[r][s] += nv[r] * dv[s];
    cl.radius =
        std::max({cl.radius, norm(a - cl.center), norm(b - cl.center), norm(c - cl.center)});
  }
  return cl;
}

/// Far-field winding number of a cluster seen from `p`, to order 2:
/// w ≈ N·g(r) + Σ_ij M_ij ∂_j g_i(r), with r = center - p, g(r) = r / (4π|r|³) and
/// ∂_j g_i = (δ_ij / |r|³ - 3 r_i r_j / |r|⁵) / 4π. The error decays like (radius / |r|)³, so it
/// is used when |r| > β · radius (β ≈ 2 as in Barill et al.). Precondition: p != center.
template <class T> inline T dipole_winding(const DipoleCluster<T>& c, const Vec3<T>& p) noexcept {
  constexpr T inv4pi = T(0.07957747154594767); // 1 / (4π)
  const Vec3<T> r = c.center - p;
  const T inv_r = T(1) / norm(r);
  const T inv_r3 = inv_r * inv_r * inv_r;
  const T inv_r5 = inv_r3 * inv_r * inv_r;
  T w = dot(c.normal, r) * inv_r3;
  const T rv[3] = {r.x, r.y, r.z};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      w += c.m[i][j] * ((i == j ? inv_r3 : T(0)) - T(3) * rv[i] * rv[j] * inv_r5);
  return w * inv4pi;
}

} // namespace ebgeom

EBGEOM_END_EXACT_FP
