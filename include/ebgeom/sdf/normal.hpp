// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Gradients and normals of SDFs. The normal is n = grad S / |grad S| (pointing out of the
/// object). `fd_gradient` uses central differences as EBGeometry does,
/// n_i = (S(x + h e_i) - S(x - h e_i)) / (2 h); `analytic_gradient` gives closed forms for
/// Sphere, Box, Plane, Capsule, CappedCylinder and Torus, and `normal` uses them when available.
/// All O(1) (6 evaluations for differences), noexcept, allocation-free.

#include <cmath>
#include <type_traits>
#include <utility>

#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/shapes.hpp"

namespace ebgeom {

/// Central-difference gradient of `s` at `p` with step `h` (> 0). Not normalised.
template <class S>
Vec3<sdf_scalar_t<S>> fd_gradient(const S& s, const Vec3<sdf_scalar_t<S>>& p,
                                  sdf_scalar_t<S> h) noexcept {
  using T = sdf_scalar_t<S>;
  Vec3<T> g;
  for (int a = 0; a < 3; ++a) {
    Vec3<T> lo = p, hi = p;
    lo[a] -= h;
    hi[a] += h;
    g[a] = (s(hi) - s(lo)) / (hi[a] - lo[a]); // the actual step, after rounding
  }
  return g;
}

/// Unit normal by central differences with step `h`; zero where the differences vanish.
template <class S>
Vec3<sdf_scalar_t<S>> fd_normal(const S& s, const Vec3<sdf_scalar_t<S>>& p,
                                sdf_scalar_t<S> h) noexcept {
  return normalized(fd_gradient(s, p, h));
}

// ---- analytic gradients: unit vectors, defined everywhere (a fixed choice on the medial axis)

/// Sphere: (p - c) / |p - c|; +z at the centre.
template <class T> Vec3<T> analytic_gradient(const Sphere<T>& s, const Vec3<T>& p) noexcept {
  const Vec3<T> d = p - s.center;
  return norm2(d) > T(0) ? normalized(d) : Vec3<T>::unit(2);
}

/// Plane: the unit normal.
template <class T> Vec3<T> analytic_gradient(const Plane<T>& s, const Vec3<T>&) noexcept {
  return normalized(s.normal);
}

/// Box: outside, the direction from the closest box point; inside, the normal of the nearest
/// face (the first axis on ties).
template <class T> Vec3<T> analytic_gradient(const Box<T>& s, const Vec3<T>& p) noexcept {
  const Vec3<T> d = p - s.center;
  const Vec3<T> q = abs(d) - s.half;
  const Vec3<T> sgn{d.x < T(0) ? T(-1) : T(1), d.y < T(0) ? T(-1) : T(1),
                    d.z < T(0) ? T(-1) : T(1)};
  if (max_component(q) > T(0)) return normalized(mul(max(q, Vec3<T>::zero()), sgn));
  const int a = arg_max(q);
  Vec3<T> g = Vec3<T>::zero();
  g[a] = sgn[a];
  return g;
}

/// Capsule: direction from the closest point of the segment (a perpendicular on the axis).
template <class T> Vec3<T> analytic_gradient(const Capsule<T>& s, const Vec3<T>& p) noexcept {
  const Vec3<T> ab = s.b - s.a, ap = p - s.a;
  const T l2 = dot(ab, ab);
  const T h = l2 > T(0) ? clamp(dot(ap, ab) / l2, T(0), T(1)) : T(0);
  const Vec3<T> d = ap - ab * h;
  if (norm2(d) > T(0)) return normalized(d);
  // on the segment: any perpendicular direction
  const Vec3<T> k = std::abs(ab.x) < std::abs(ab.y) ? Vec3<T>::unit(0) : Vec3<T>::unit(1);
  const Vec3<T> perp = normalized(cross(ab, k));
  return perp == Vec3<T>::zero() ? Vec3<T>::unit(2) : perp;
}

/// Capped cylinder: radial, axial, or the rim direction, from the 2D box in the meridian.
template <class T>
Vec3<T> analytic_gradient(const CappedCylinder<T>& s, const Vec3<T>& p) noexcept {
  const Vec3<T> ab = s.b - s.a;
  const T len = norm(ab);
  const Vec3<T> w = len > T(0) ? ab / len : Vec3<T>::unit(2);
  const Vec3<T> ap = p - s.a;
  const T h = dot(ap, w);
  Vec3<T> radial = ap - w * h;
  const T rho = norm(radial);
  radial = rho > T(0)
               ? radial / rho
               : normalized(cross(w, std::abs(w.x) < T(0.9) ? Vec3<T>::unit(0) : Vec3<T>::unit(1)));
  const T axial_sign = h < len * T(0.5) ? T(-1) : T(1);
  const T qx = rho - s.radius, qy = std::abs(h - len * T(0.5)) - len * T(0.5);
  if (qx > T(0) || qy > T(0)) {
    const T ox = std::max(qx, T(0)), oy = std::max(qy, T(0));
    return normalized(radial * ox + w * (axial_sign * oy));
  }
  return qx > qy ? radial : w * axial_sign;
}

/// Torus (axis z): direction from the closest point of the core circle.
template <class T> Vec3<T> analytic_gradient(const Torus<T>& s, const Vec3<T>& p) noexcept {
  const Vec3<T> q = p - s.center;
  const T r = std::sqrt(q.x * q.x + q.y * q.y);
  const Vec3<T> ring =
      r > T(0) ? Vec3<T>{q.x / r, q.y / r, T(0)} * s.major : Vec3<T>{s.major, T(0), T(0)};
  const Vec3<T> d = q - ring;
  return norm2(d) > T(0) ? normalized(d) : Vec3<T>::unit(2);
}

/// Outward unit normal of `s` at `p`: the analytic gradient when `S` has one, otherwise central
/// differences with step `h`.
template <class S>
Vec3<sdf_scalar_t<S>> normal(const S& s, const Vec3<sdf_scalar_t<S>>& p,
                             sdf_scalar_t<S> h) noexcept {
  if constexpr (has_analytic_gradient_v<S>)
    return (void)h, analytic_gradient(s, p);
  else
    return fd_normal(s, p, h);
}

} // namespace ebgeom
