// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Axis-aligned bounding box `Aabb<T>`.

#include <limits>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/vec.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

/// Axis-aligned box [lo, hi]. The default-constructed box is *empty* (lo = +inf, hi = -inf), so
/// `extend` from it gives the tight box of what was added. 24 B (float), 48 B (double).
template <class T> struct Aabb {
  using scalar_type = T;
  Vec3<T> lo{Vec3<T>::constant(std::numeric_limits<T>::infinity())};
  Vec3<T> hi{Vec3<T>::constant(-std::numeric_limits<T>::infinity())};

  constexpr Aabb() noexcept = default;
  constexpr Aabb(const Vec3<T>& lo_, const Vec3<T>& hi_) noexcept : lo(lo_), hi(hi_) {}

  static constexpr Aabb empty() noexcept { return {}; }
  /// The whole space; distance from it is always 0.
  static constexpr Aabb infinite() noexcept {
    return {Vec3<T>::constant(-std::numeric_limits<T>::infinity()),
            Vec3<T>::constant(std::numeric_limits<T>::infinity())};
  }
  /// Tight box of one, two or three points.
  static constexpr Aabb of(const Vec3<T>& a) noexcept { return {a, a}; }
  static constexpr Aabb of(const Vec3<T>& a, const Vec3<T>& b) noexcept {
    return {min(a, b), max(a, b)};
  }
  static constexpr Aabb of(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) noexcept {
    return {min(min(a, b), c), max(max(a, b), c)};
  }
  /// Tight box of a range of points (anything iterable yielding `Vec3<T>`).
  template <class Range> static Aabb of_range(const Range& points) noexcept {
    Aabb b;
    for (const auto& p : points) b.extend(p);
    return b;
  }

  constexpr bool is_empty() const noexcept {
    return !(lo.x <= hi.x && lo.y <= hi.y && lo.z <= hi.z);
  }
  constexpr Aabb& extend(const Vec3<T>& p) noexcept {
    lo = min(lo, p);
    hi = max(hi, p);
    return *this;
  }
  constexpr Aabb& extend(const Aabb& b) noexcept {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
    return *this;
  }
  /// Enclosing union.
  friend constexpr Aabb merge(const Aabb& a, const Aabb& b) noexcept { return Aabb(a).extend(b); }
  /// Box grown by `r` on every side (shrunk for r < 0).
  constexpr Aabb grown(T r) const noexcept {
    return {lo - Vec3<T>::constant(r), hi + Vec3<T>::constant(r)};
  }
  constexpr Vec3<T> extent() const noexcept { return hi - lo; }
  constexpr Vec3<T> center() const noexcept { return (lo + hi) * T(0.5); }
  constexpr Vec3<T> centroid() const noexcept { return center(); }
  /// Longest axis (0, 1, 2).
  constexpr int longest_axis() const noexcept { return arg_max(extent()); }
  constexpr T volume() const noexcept {
    if (is_empty()) return T(0);
    const Vec3<T> e = extent();
    return e.x * e.y * e.z;
  }
  constexpr T surface_area() const noexcept {
    if (is_empty()) return T(0);
    const Vec3<T> e = extent();
    return T(2) * (e.x * e.y + e.y * e.z + e.z * e.x);
  }
  /// Half the surface area: enough for SAH cost ratios.
  constexpr T half_area() const noexcept {
    const Vec3<T> e = extent();
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
  constexpr bool contains(const Vec3<T>& p) const noexcept {
    return lo.x <= p.x && p.x <= hi.x && lo.y <= p.y && p.y <= hi.y && lo.z <= p.z && p.z <= hi.z;
  }
  constexpr bool contains(const Aabb& b) const noexcept { return contains(b.lo) && contains(b.hi); }
  /// True when the closed boxes share at least one point.
  constexpr bool overlaps(const Aabb& b) const noexcept {
    return lo.x <= b.hi.x && b.lo.x <= hi.x && lo.y <= b.hi.y && b.lo.y <= hi.y && lo.z <= b.hi.z &&
           b.lo.z <= hi.z;
  }
  /// Squared distance from `p` to the box; 0 inside.
  constexpr T distance2(const Vec3<T>& p) const noexcept {
    const T dx = std::max(std::max(lo.x - p.x, p.x - hi.x), T(0));
    const T dy = std::max(std::max(lo.y - p.y, p.y - hi.y), T(0));
    const T dz = std::max(std::max(lo.z - p.z, p.z - hi.z), T(0));
    return dx * dx + dy * dy + dz * dz;
  }
  /// Distance from `p` to the box; 0 inside.
  T distance(const Vec3<T>& p) const noexcept { return std::sqrt(distance2(p)); }
  /// Squared distance from `p` to the farthest point of the box (an upper bound on the distance
  /// to anything inside it).
  constexpr T max_distance2(const Vec3<T>& p) const noexcept {
    const T dx = std::max(p.x - lo.x, hi.x - p.x);
    const T dy = std::max(p.y - lo.y, hi.y - p.y);
    const T dz = std::max(p.z - lo.z, hi.z - p.z);
    return dx * dx + dy * dy + dz * dz;
  }
  template <class U> static constexpr Aabb from(const Aabb<U>& b) noexcept {
    return {Vec3<T>::from(b.lo), Vec3<T>::from(b.hi)};
  }
  friend constexpr bool operator==(const Aabb& a, const Aabb& b) noexcept {
    return a.lo == b.lo && a.hi == b.hi;
  }
};

} // namespace ebgeom

EBGEOM_END_EXACT_FP
