// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Small fixed-size vectors `Vec2<T>` and `Vec3<T>` (plain aggregates, float or double) with the
/// usual arithmetic. All functions are constexpr/noexcept and allocation-free.

#include <algorithm>
#include <cmath>
#include <limits>
#include <ostream>
#include <type_traits>

#include "ebgeom/core/config.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

/// Two-component vector. Plain aggregate: `Vec2<double> v{1, 2};`.
template <class T> struct Vec2 {
  static_assert(std::is_floating_point_v<T>, "Vec2<T> needs a floating-point T");
  using scalar_type = T;
  T x, y;

  constexpr T& operator[](int i) noexcept { return i == 0 ? x : y; }
  constexpr const T& operator[](int i) const noexcept { return i == 0 ? x : y; }
  static constexpr Vec2 zero() noexcept { return {T(0), T(0)}; }
  static constexpr Vec2 constant(T v) noexcept { return {v, v}; }
};

/// Three-component vector. Plain aggregate (12 B float, 24 B double): `Vec3<float> p{1, 2, 3};`.
template <class T> struct Vec3 {
  static_assert(std::is_floating_point_v<T>, "Vec3<T> needs a floating-point T");
  using scalar_type = T;
  T x, y, z;

  constexpr T& operator[](int i) noexcept { return i == 0 ? x : (i == 1 ? y : z); }
  constexpr const T& operator[](int i) const noexcept { return i == 0 ? x : (i == 1 ? y : z); }
  static constexpr Vec3 zero() noexcept { return {T(0), T(0), T(0)}; }
  static constexpr Vec3 one() noexcept { return {T(1), T(1), T(1)}; }
  static constexpr Vec3 constant(T v) noexcept { return {v, v, v}; }
  /// Unit vector along axis `i` (0 = x, 1 = y, 2 = z).
  static constexpr Vec3 unit(int i) noexcept { return {T(i == 0), T(i == 1), T(i == 2)}; }
  /// Converts from another precision.
  template <class U> static constexpr Vec3 from(const Vec3<U>& v) noexcept {
    return {T(v.x), T(v.y), T(v.z)};
  }
};

// ---- Vec2 arithmetic -------------------------------------------------------------------------
template <class T> constexpr Vec2<T> operator+(const Vec2<T>& a, const Vec2<T>& b) noexcept {
  return {a.x + b.x, a.y + b.y};
}
template <class T> constexpr Vec2<T> operator-(const Vec2<T>& a, const Vec2<T>& b) noexcept {
  return {a.x - b.x, a.y - b.y};
}
template <class T> constexpr Vec2<T> operator-(const Vec2<T>& a) noexcept { return {-a.x, -a.y}; }
template <class T> constexpr Vec2<T> operator*(const Vec2<T>& a, T s) noexcept {
  return {a.x * s, a.y * s};
}
template <class T> constexpr Vec2<T> operator*(T s, const Vec2<T>& a) noexcept {
  return {a.x * s, a.y * s};
}
template <class T> constexpr Vec2<T> operator/(const Vec2<T>& a, T s) noexcept {
  return {a.x / s, a.y / s};
}
template <class T> constexpr bool operator==(const Vec2<T>& a, const Vec2<T>& b) noexcept {
  return a.x == b.x && a.y == b.y;
}
template <class T> constexpr bool operator!=(const Vec2<T>& a, const Vec2<T>& b) noexcept {
  return !(a == b);
}
template <class T> constexpr T dot(const Vec2<T>& a, const Vec2<T>& b) noexcept {
  return a.x * b.x + a.y * b.y;
}
/// z-component of the 3D cross product (signed parallelogram area).
template <class T> constexpr T cross(const Vec2<T>& a, const Vec2<T>& b) noexcept {
  return a.x * b.y - a.y * b.x;
}
template <class T> constexpr T norm2(const Vec2<T>& a) noexcept { return dot(a, a); }
template <class T> inline T norm(const Vec2<T>& a) noexcept { return std::sqrt(norm2(a)); }
template <class T> constexpr Vec2<T> min(const Vec2<T>& a, const Vec2<T>& b) noexcept {
  return {std::min(a.x, b.x), std::min(a.y, b.y)};
}
template <class T> constexpr Vec2<T> max(const Vec2<T>& a, const Vec2<T>& b) noexcept {
  return {std::max(a.x, b.x), std::max(a.y, b.y)};
}
template <class T> inline Vec2<T> abs(const Vec2<T>& a) noexcept {
  return {std::abs(a.x), std::abs(a.y)};
}

// ---- Vec3 arithmetic -------------------------------------------------------------------------
template <class T> constexpr Vec3<T> operator+(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T> constexpr Vec3<T> operator-(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T> constexpr Vec3<T> operator-(const Vec3<T>& a) noexcept {
  return {-a.x, -a.y, -a.z};
}
template <class T> constexpr Vec3<T> operator*(const Vec3<T>& a, T s) noexcept {
  return {a.x * s, a.y * s, a.z * s};
}
template <class T> constexpr Vec3<T> operator*(T s, const Vec3<T>& a) noexcept {
  return {a.x * s, a.y * s, a.z * s};
}
template <class T> constexpr Vec3<T> operator/(const Vec3<T>& a, T s) noexcept {
  return {a.x / s, a.y / s, a.z / s};
}
template <class T> constexpr Vec3<T>& operator+=(Vec3<T>& a, const Vec3<T>& b) noexcept {
  a = a + b;
  return a;
}
template <class T> constexpr Vec3<T>& operator-=(Vec3<T>& a, const Vec3<T>& b) noexcept {
  a = a - b;
  return a;
}
template <class T> constexpr Vec3<T>& operator*=(Vec3<T>& a, T s) noexcept {
  a = a * s;
  return a;
}
template <class T> constexpr Vec3<T>& operator/=(Vec3<T>& a, T s) noexcept {
  a = a / s;
  return a;
}
template <class T> constexpr bool operator==(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}
template <class T> constexpr bool operator!=(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return !(a == b);
}
/// Component-wise product and quotient.
template <class T> constexpr Vec3<T> mul(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return {a.x * b.x, a.y * b.y, a.z * b.z};
}
template <class T> constexpr Vec3<T> div(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return {a.x / b.x, a.y / b.y, a.z / b.z};
}
template <class T> constexpr T dot(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T> constexpr Vec3<T> cross(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T> constexpr T norm2(const Vec3<T>& a) noexcept { return dot(a, a); }
template <class T> inline T norm(const Vec3<T>& a) noexcept { return std::sqrt(norm2(a)); }
/// Unit vector along `a`; the zero vector stays zero (no NaN).
template <class T> inline Vec3<T> normalized(const Vec3<T>& a) noexcept {
  const T n = norm(a);
  return n > T(0) ? a / n : Vec3<T>::zero();
}
template <class T> constexpr Vec3<T> min(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return {std::min(a.x, b.x), std::min(a.y, b.y), std::min(a.z, b.z)};
}
template <class T> constexpr Vec3<T> max(const Vec3<T>& a, const Vec3<T>& b) noexcept {
  return {std::max(a.x, b.x), std::max(a.y, b.y), std::max(a.z, b.z)};
}
template <class T> inline Vec3<T> abs(const Vec3<T>& a) noexcept {
  return {std::abs(a.x), std::abs(a.y), std::abs(a.z)};
}
template <class T> constexpr T min_component(const Vec3<T>& a) noexcept {
  return std::min(a.x, std::min(a.y, a.z));
}
template <class T> constexpr T max_component(const Vec3<T>& a) noexcept {
  return std::max(a.x, std::max(a.y, a.z));
}
/// Index (0, 1, 2) of the largest component; the first one on ties.
template <class T> constexpr int arg_max(const Vec3<T>& a) noexcept {
  return (a.x >= a.y && a.x >= a.z) ? 0 : (a.y >= a.z ? 1 : 2);
}
/// Index (0, 1, 2) of the smallest component; the first one on ties.
template <class T> constexpr int arg_min(const Vec3<T>& a) noexcept {
  return (a.x <= a.y && a.x <= a.z) ? 0 : (a.y <= a.z ? 1 : 2);
}
template <class T> inline bool all_finite(const Vec3<T>& a) noexcept {
  return std::isfinite(a.x) && std::isfinite(a.y) && std::isfinite(a.z);
}
template <class T> constexpr Vec3<T> lerp(const Vec3<T>& a, const Vec3<T>& b, T t) noexcept {
  return a + (b - a) * t;
}
template <class T> constexpr T clamp(T v, T lo, T hi) noexcept {
  return v < lo ? lo : (hi < v ? hi : v);
}

template <class T> std::ostream& operator<<(std::ostream& os, const Vec3<T>& v) {
  return os << '(' << v.x << ", " << v.y << ", " << v.z << ')';
}
template <class T> std::ostream& operator<<(std::ostream& os, const Vec2<T>& v) {
  return os << '(' << v.x << ", " << v.y << ')';
}

} // namespace ebgeom

EBGEOM_END_EXACT_FP
