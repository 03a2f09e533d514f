// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Point-in-polygon tests for a planar polygon already projected to 2D (see `PlaneProjection`):
/// crossing number (the default, as in EBGeometry), winding number and subtended angle. All three
/// agree away from the boundary; on the boundary the answer is unspecified (the signed distance
/// does not depend on it: the face and edge cases then give the same distance).

#include <cmath>
#include <cstddef>
#include <cstdint>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom {

/// Which point-in-polygon algorithm to use.
enum class InsideTest : std::uint8_t {
  crossing_number, ///< parity of the crossings of a ray to +x (even-odd rule). Default.
  winding_number,  ///< nonzero winding number (Sunday's integer algorithm, no trigonometry)
  subtended_angle, ///< sum of the signed angles subtended by the edges, inside when |sum| > π
};

/// Crossing number of the ray from `p` towards +x with the closed polygon of `k` corners
/// `corner(0..k-1)` (each returning `Vec2<T>`). Odd means inside. Half-open edge rule, so a vertex
/// on the ray is counted once. O(k).
template <class T, class CornerFn>
int crossing_number(const Vec2<T>& p, std::size_t k, const CornerFn& corner) noexcept {
  int crossings = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec2<T> a = corner(i), b = corner(i + 1 == k ? 0 : i + 1);
    if ((a.y > p.y) != (b.y > p.y)) {
      // x of the edge at height p.y, compared without dividing by a possibly tiny dy
      const T dy = b.y - a.y;
      const T lhs = (p.x - a.x) * dy, rhs = (b.x - a.x) * (p.y - a.y);
      if (dy > T(0) ? lhs < rhs : lhs > rhs) ++crossings;
    }
  }
  return crossings;
}

/// Winding number of the closed polygon around `p` (positive for counter-clockwise), by signed
/// upward/downward crossings (Sunday 2001). O(k), integer result, no trigonometry.
template <class T, class CornerFn>
int winding_number(const Vec2<T>& p, std::size_t k, const CornerFn& corner) noexcept {
  int w = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec2<T> a = corner(i), b = corner(i + 1 == k ? 0 : i + 1);
    const T side = cross(b - a, p - a); // > 0: p left of a->b
    if (a.y <= p.y) {
      if (b.y > p.y && side > T(0)) ++w;
    } else if (b.y <= p.y && side < T(0)) {
      --w;
    }
  }
  return w;
}

/// Sum of the signed angles subtended at `p` by the polygon's edges, in radians: ±2π (times the
/// winding number) inside, 0 outside. O(k) with one atan2 per edge.
template <class T, class CornerFn>
T subtended_angle(const Vec2<T>& p, std::size_t k, const CornerFn& corner) noexcept {
  T sum = 0;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec2<T> a = corner(i) - p, b = corner(i + 1 == k ? 0 : i + 1) - p;
    sum += std::atan2(cross(a, b), dot(a, b));
  }
  return sum;
}

/// True when `m` is one of the listed `InsideTest` values.
constexpr bool is_valid(InsideTest m) noexcept {
  return m == InsideTest::crossing_number || m == InsideTest::winding_number ||
         m == InsideTest::subtended_angle;
}

/// True when `p` is inside the polygon by the chosen test. Precondition: `is_valid(method)` (a
/// value outside the enumeration aborts with a message, in every build: it never silently picks
/// another test).
template <class T, class CornerFn>
bool point_in_polygon(const Vec2<T>& p, std::size_t k, const CornerFn& corner,
                      InsideTest method = InsideTest::crossing_number) noexcept {
  EBGEOM_PRECONDITION(is_valid(method), "point_in_polygon: InsideTest value out of range");
  switch (method) {
  case InsideTest::winding_number:
    return winding_number(p, k, corner) != 0;
  case InsideTest::subtended_angle:
    return std::abs(subtended_angle(p, k, corner)) > T(3.14159265358979323846);
  case InsideTest::crossing_number:
    break;
  }
  return (crossing_number(p, k, corner) & 1) != 0;
}

} // namespace ebgeom
