// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Rotations: `Mat3<T>` (3x3, row-major) and unit `Quaternion<T>`. Angles about a coordinate axis
/// are in degrees, as in EBGeometry's `rotate(angle, axis)`; angles about an arbitrary axis are in
/// radians unless the function name says `degrees`. Rotations are active and right-handed: a
/// positive angle turns x towards y about z.

#include <cmath>
#include <limits>

#include "ebgeom/core/axis.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom {

namespace detail {
/// cos and sin of `degrees`, exact (0, +-1) at multiples of 90 degrees so that quarter turns
/// map the grid onto itself without rounding.
template <class T> inline void cos_sin_degrees(T degrees, T& c, T& s) noexcept {
  const double d = std::fmod(double(degrees), 360.0);
  const double q = d / 90.0;
  if (std::isfinite(q) && q == std::floor(q)) {
    const int k = ((int(q) % 4) + 4) % 4;
    static constexpr T cs[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
    c = cs[k][0];
    s = cs[k][1];
    return;
  }
  const double r = d * (3.14159265358979323846 / 180.0);
  c = T(std::cos(r));
  s = T(std::sin(r));
}
} // namespace detail

/// Converts degrees to radians.
template <class T> constexpr T radians(T degrees) noexcept {
  return degrees * T(3.14159265358979323846 / 180.0);
}

/// 3x3 matrix, row-major: `m[3 * row + col]`. Plain aggregate (36 B float, 72 B double); the
/// default value is the identity.
template <class T> struct Mat3 {
  static_assert(std::is_floating_point_v<T>, "Mat3<T> needs a floating-point T");
  using scalar_type = T;
  T m[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};

  constexpr T& operator()(int r, int c) noexcept { return m[3 * r + c]; }
  constexpr const T& operator()(int r, int c) const noexcept { return m[3 * r + c]; }
  constexpr Vec3<T> row(int r) const noexcept { return {m[3 * r], m[3 * r + 1], m[3 * r + 2]}; }
  constexpr Vec3<T> col(int c) const noexcept { return {m[c], m[3 + c], m[6 + c]}; }

  static constexpr Mat3 identity() noexcept { return {}; }
  static constexpr Mat3 from_rows(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) noexcept {
    return {{a.x, a.y, a.z, b.x, b.y, b.z, c.x, c.y, c.z}};
  }
  static constexpr Mat3 from_cols(const Vec3<T>& a, const Vec3<T>& b, const Vec3<T>& c) noexcept {
    return {{a.x, b.x, c.x, a.y, b.y, c.y, a.z, b.z, c.z}};
  }
  /// Rotation by `radians` about `axis` (any non-zero length). Rodrigues' formula. A zero or
  /// non-finite axis has no direction: the result is all NaN (never a silent identity).
  static Mat3 axis_angle(const Vec3<T>& axis, T radians) noexcept {
    return axis_cos_sin(axis, std::cos(radians), std::sin(radians));
  }
  /// Rotation by `degrees` about `axis` (exact at multiples of 90 degrees). A zero or non-finite
  /// axis gives all NaN.
  static Mat3 axis_degrees(const Vec3<T>& axis, T degrees) noexcept {
    T c, s;
    detail::cos_sin_degrees(degrees, c, s);
    return axis_cos_sin(axis, c, s);
  }
  /// Rotation by `degrees` about coordinate axis `axis` (EBGeometry's `rotate(angle, axis)` with
  /// the arguments in ebgeom's order: `coordinate_axis(Axis::z, 90)`). An `Axis` forced out of
  /// range by a cast gives all NaN.
  static Mat3 coordinate_axis(Axis axis, T degrees) noexcept {
    if (!is_valid(axis)) return nan();
    return axis_degrees(Vec3<T>::unit(index(axis)), degrees);
  }
  /// All nine entries NaN: the result of a rotation without a valid axis.
  static constexpr Mat3 nan() noexcept {
    constexpr T n = std::numeric_limits<T>::quiet_NaN();
    return {{n, n, n, n, n, n, n, n, n}};
  }

  constexpr Mat3 transposed() const noexcept {
    return {{m[0], m[3], m[6], m[1], m[4], m[7], m[2], m[5], m[8]}};
  }
  constexpr T determinant() const noexcept { return dot(row(0), cross(row(1), row(2))); }

  friend constexpr Vec3<T> operator*(const Mat3& a, const Vec3<T>& v) noexcept {
    return {a.m[0] * v.x + a.m[1] * v.y + a.m[2] * v.z, a.m[3] * v.x + a.m[4] * v.y + a.m[5] * v.z,
            a.m[6] * v.x + a.m[7] * v.y + a.m[8] * v.z};
  }
  friend constexpr Mat3 operator*(const Mat3& a, const Mat3& b) noexcept {
    Mat3 r;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        r.m[3 * i + j] =
            a.m[3 * i] * b.m[j] + a.m[3 * i + 1] * b.m[3 + j] + a.m[3 * i + 2] * b.m[6 + j];
    return r;
  }
  friend constexpr bool operator==(const Mat3& a, const Mat3& b) noexcept {
    for (int i = 0; i < 9; ++i)
      if (a.m[i] != b.m[i]) return false;
    return true;
  }

 private:
  static Mat3 axis_cos_sin(const Vec3<T>& axis, T c, T s) noexcept {
    const Vec3<T> u = normalized(axis);
    if (u == Vec3<T>::zero() || !std::isfinite(u.x + u.y + u.z)) return nan();
    const T t = T(1) - c;
    return {{c + u.x * u.x * t, u.x * u.y * t - u.z * s, u.x * u.z * t + u.y * s,
             u.y * u.x * t + u.z * s, c + u.y * u.y * t, u.y * u.z * t - u.x * s,
             u.z * u.x * t - u.y * s, u.z * u.y * t + u.x * s, c + u.z * u.z * t}};
  }
};

/// Quaternion w + xi + yj + zk. Rotations use unit quaternions; `rotate` and `to_mat3` assume
/// unit length (call `normalized()` after long products). 16 B (float), 32 B (double).
template <class T> struct Quaternion {
  static_assert(std::is_floating_point_v<T>, "Quaternion<T> needs a floating-point T");
  using scalar_type = T;
  T w = 1, x = 0, y = 0, z = 0;

  static constexpr Quaternion identity() noexcept { return {}; }
  /// Rotation by `radians` about `axis` (a zero or non-finite axis gives all NaN).
  static Quaternion axis_angle(const Vec3<T>& axis, T radians) noexcept {
    return axis_cos_sin_half(axis, std::cos(radians / T(2)), std::sin(radians / T(2)));
  }
  /// Rotation by `degrees` about `axis` (exact at multiples of 180 degrees).
  static Quaternion axis_degrees(const Vec3<T>& axis, T degrees) noexcept {
    T c, s;
    detail::cos_sin_degrees(degrees / T(2), c, s);
    return axis_cos_sin_half(axis, c, s);
  }
  /// Rotation by `degrees` about coordinate axis `axis` (an `Axis` forced out of range by a cast
  /// gives all NaN).
  static Quaternion coordinate_axis(Axis axis, T degrees) noexcept {
    if (!is_valid(axis)) return nan();
    return axis_degrees(Vec3<T>::unit(index(axis)), degrees);
  }
  /// All four components NaN: the result of a rotation without a valid axis.
  static constexpr Quaternion nan() noexcept {
    constexpr T n = std::numeric_limits<T>::quiet_NaN();
    return {n, n, n, n};
  }

  constexpr Vec3<T> vec() const noexcept { return {x, y, z}; }
  constexpr Quaternion conjugate() const noexcept { return {w, -x, -y, -z}; }
  constexpr T norm2() const noexcept { return w * w + x * x + y * y + z * z; }
  /// Unit quaternion along this one; zero (or non-finite) gives all NaN, never a silent
  /// identity.
  Quaternion normalized() const noexcept {
    const T n = std::sqrt(norm2());
    if (!(n > T(0)) || !std::isfinite(n)) return nan();
    return {w / n, x / n, y / n, z / n};
  }
  /// Hamilton product: `(a * b).rotate(v) == a.rotate(b.rotate(v))` (b first, then a).
  friend constexpr Quaternion operator*(const Quaternion& a, const Quaternion& b) noexcept {
    return {a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
            a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
            a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
            a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
  }
  /// Rotates `v` (unit quaternion): v + 2w (q x v) + 2 q x (q x v).
  constexpr Vec3<T> rotate(const Vec3<T>& v) const noexcept {
    const Vec3<T> q = vec();
    const Vec3<T> t = cross(q, v) * T(2);
    return v + t * w + cross(q, t);
  }
  /// The rotation matrix of a unit quaternion.
  constexpr Mat3<T> to_mat3() const noexcept {
    const T xx = x * x, yy = y * y, zz = z * z, xy = x * y, xz = x * z, yz = y * z;
    const T wx = w * x, wy = w * y, wz = w * z;
    return {{T(1) - T(2) * (yy + zz), T(2) * (xy - wz), T(2) * (xz + wy), T(2) * (xy + wz),
             T(1) - T(2) * (xx + zz), T(2) * (yz - wx), T(2) * (xz - wy), T(2) * (yz + wx),
             T(1) - T(2) * (xx + yy)}};
  }

 private:
  static Quaternion axis_cos_sin_half(const Vec3<T>& axis, T c, T s) noexcept {
    const Vec3<T> u = ebgeom::normalized(axis);
    if (u == Vec3<T>::zero() || !std::isfinite(u.x + u.y + u.z)) return nan();
    return {c, u.x * s, u.y * s, u.z * s};
  }
};

} // namespace ebgeom
