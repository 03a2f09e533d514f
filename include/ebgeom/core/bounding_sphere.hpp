// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `BoundingSphere<T>`: a ball {center, radius} used as a bounding volume. Built from points with
/// Ritter's algorithm (Ritter 1990, "An efficient bounding sphere", Graphics Gems) followed by an
/// enclosing pass, so every input point is inside even after rounding.

#include <cmath>
#include <cstddef>
#include <limits>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom {

/// Closed ball of `radius` around `center`. A negative radius means *empty* (the default).
/// Plain aggregate: 16 B (float), 32 B (double). All members are O(1) unless stated.
template <class T> struct BoundingSphere {
  static_assert(std::is_floating_point_v<T>, "BoundingSphere<T> needs a floating-point T");
  using scalar_type = T;
  Vec3<T> center = Vec3<T>::zero();
  T radius = T(-1);

  static constexpr BoundingSphere empty() noexcept { return {}; }
  constexpr bool is_empty() const noexcept { return !(radius >= T(0)); }

  /// A sphere enclosing every point (Ritter's algorithm: an initial diameter from two far
  /// points, one growing pass, then an enclosing pass whose radius is inflated by a few ulps so
  /// that `contains(p)` holds for every input point). Typically 5-20% larger than the minimal
  /// sphere. Empty input gives an empty sphere; non-finite coordinates give a
  /// non-finite sphere. O(n), no allocation.
  static BoundingSphere of_points(Span<const Vec3<T>> pts) noexcept {
    return ritter(pts.size(), [&pts](std::size_t i) { return pts[i]; });
  }

  /// A sphere enclosing every box (Ritter's algorithm over the eight corners of each; empty
  /// boxes are skipped). O(n), no allocation.
  static BoundingSphere of_boxes(Span<const Aabb<T>> boxes) noexcept {
    // skip empty boxes by mapping their corners onto a corner of the first non-empty box
    std::size_t first = 0;
    while (first < boxes.size() && boxes[first].is_empty()) ++first;
    if (first == boxes.size()) return {};
    return ritter(boxes.size() * 8, [&](std::size_t i) {
      const Aabb<T>& b = boxes[i / 8].is_empty() ? boxes[first] : boxes[i / 8];
      const std::size_t c = i % 8;
      return Vec3<T>{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y,
                     (c & 4) ? b.hi.z : b.lo.z};
    });
  }

  /// The sphere circumscribing a box (center, half diagonal). Empty box gives an empty sphere.
  static BoundingSphere of(const Aabb<T>& b) noexcept {
    if (b.is_empty()) return {};
    const T eps = std::numeric_limits<T>::epsilon();
    const Vec3<T> c = b.center();
    return {c,
            norm(b.extent()) * T(0.5) * (T(1) + T(8) * eps) + T(8) * eps * max_component(abs(c))};
  }

  /// Smallest sphere enclosing both spheres (exact construction, inflated by a few ulps).
  friend BoundingSphere merge(const BoundingSphere& a, const BoundingSphere& b) noexcept {
    if (a.is_empty()) return b;
    if (b.is_empty()) return a;
    const Vec3<T> d = b.center - a.center;
    const T dist = norm(d);
    const T eps = std::numeric_limits<T>::epsilon();
    const auto inflated = [eps](const Vec3<T>& c, T r) {
      return BoundingSphere{c, r * (T(1) + T(8) * eps) + T(8) * eps * max_component(abs(c))};
    };
    if (dist + b.radius <= a.radius) return inflated(a.center, a.radius); // b inside a
    if (dist + a.radius <= b.radius) return inflated(b.center, b.radius); // a inside b
    const T r = (dist + a.radius + b.radius) * T(0.5);
    return inflated(a.center + d * ((r - a.radius) / dist), r);
  }

  /// A sphere enclosing both the sphere `a` and the box `b`.
  friend BoundingSphere merge(const BoundingSphere& a, const Aabb<T>& b) noexcept {
    return merge(a, of(b));
  }

  /// Squared distance from `p` to the ball; 0 inside.
  T distance2(const Vec3<T>& p) const noexcept {
    const T d = distance(p);
    return d * d;
  }
  /// Distance from `p` to the ball; 0 inside. Infinite for an empty sphere.
  T distance(const Vec3<T>& p) const noexcept {
    if (is_empty()) return std::numeric_limits<T>::infinity();
    return std::max(norm(p - center) - radius, T(0));
  }
  constexpr bool contains(const Vec3<T>& p) const noexcept {
    return !is_empty() && norm2(p - center) <= radius * radius;
  }
  /// True when the closed balls share a point.
  bool overlaps(const BoundingSphere& o) const noexcept {
    if (is_empty() || o.is_empty()) return false;
    const T r = radius + o.radius;
    return norm2(o.center - center) <= r * r;
  }
  /// True when the closed ball and the closed box share a point.
  constexpr bool overlaps(const Aabb<T>& b) const noexcept {
    return !is_empty() && !b.is_empty() && b.distance2(center) <= radius * radius;
  }
  constexpr Vec3<T> centroid() const noexcept { return center; }
  T volume() const noexcept {
    return is_empty() ? T(0) : T(4.0 / 3.0 * 3.14159265358979323846) * radius * radius * radius;
  }
  T surface_area() const noexcept {
    return is_empty() ? T(0) : T(4.0 * 3.14159265358979323846) * radius * radius;
  }
  /// The axis-aligned box of the ball.
  constexpr Aabb<T> bounds() const noexcept {
    return is_empty() ? Aabb<T>{} : Aabb<T>::of(center).grown(radius);
  }

 private:
  /// Ritter's algorithm over the points get(0), ..., get(n - 1).
  template <class Get> static BoundingSphere ritter(std::size_t n, const Get& get) noexcept {
    if (n == 0) return {};
    // 1. Far pair: x -> farthest y -> farthest z.
    const Vec3<T> x = get(0);
    Vec3<T> y = x;
    T best = T(-1);
    for (std::size_t i = 0; i < n; ++i)
      if (norm2(get(i) - x) > best) best = norm2(get(i) - x), y = get(i);
    Vec3<T> z = y;
    best = T(-1);
    for (std::size_t i = 0; i < n; ++i)
      if (norm2(get(i) - y) > best) best = norm2(get(i) - y), z = get(i);
    BoundingSphere s{(y + z) * T(0.5), norm(z - y) * T(0.5)};
    // 2. Ritter growth: each outside point moves the far side of the ball onto it.
    for (std::size_t i = 0; i < n; ++i) {
      const Vec3<T> p = get(i);
      const T d = norm(p - s.center);
      if (d > s.radius) {
        const T r = (s.radius + d) * T(0.5);
        s.center = s.center + (p - s.center) * ((r - s.radius) / d);
        s.radius = r;
      }
    }
    // 3. Enclosing pass: the radius is the largest computed distance, inflated for rounding in
    //    the distance itself (relative) and in the center coordinates (absolute, scale of |c|).
    T r2 = T(0);
    for (std::size_t i = 0; i < n; ++i) r2 = std::max(r2, norm2(get(i) - s.center));
    const T eps = std::numeric_limits<T>::epsilon();
    const T scale = max_component(abs(s.center));
    s.radius = std::sqrt(r2) * (T(1) + T(8) * eps) + T(8) * eps * scale;
    return s;
  }
};

} // namespace ebgeom
