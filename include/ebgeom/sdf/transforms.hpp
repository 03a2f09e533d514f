// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Transforms and modifiers of one SDF. Each is a small struct holding its operand by value and
/// deriving its `kind` from the operand's (STYLE.md section 3); the free functions (`translate`,
/// `rotate`, `transform`, `scale`, `offset`, `shell`, `elongate`, `reflect`, `mirror`,
/// `complement`, `mollify`, `repeat`) build them. Everything is inlined: no allocation and no
/// virtual call per point.
///
/// Kinds, and why:
///  - isometries (translate, rotate, rigid transform, reflect) and uniform scale keep the kind;
///  - complement (-S) keeps the kind (the distance to the boundary is unchanged);
///  - offset (S - r), shell (|S| - t), elongate, mirror, mollify and repetition turn `exact` into
///    `bound`: each result is 1-Lipschitz when the operand is, and a 1-Lipschitz function never
///    exceeds, in magnitude, the distance to its own zero set; they are not exact in general
///    (e.g. offsetting a non-convex shape outwards is exact outside but not inside);
///  - an `implicit` operand gives an `implicit` result.
/// Rotations take degrees about a coordinate axis given as an `Axis` (`rotate(s, Axis::x, 90)`
/// is EBGeometry's `rotate(90, 0)`: the shape comes first, then the axis, then the angle) or an
/// arbitrary axis, a `Quaternion` or a `Mat3`; they rotate the *shape* (the point is rotated back).
///
/// No silent identity: an EBGeometry-order call `rotate(s, 90, 0)` does not compile (a number is
/// not an `Axis`; the error message names the right call), and arguments that describe no
/// transform (an `Axis` forced out of range by a cast, a zero or non-finite rotation axis or
/// quaternion, a zero reflection normal, a scale factor that is not positive and finite) give an
/// SDF whose every value is NaN, so the mistake shows in the first output instead of leaving the
/// shape where it was.

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/axis.hpp"
#include "ebgeom/core/rotation.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

namespace detail {
/// Box of the eight corners of `b` mapped by `f`; an unbounded or empty box stays so.
template <class T, class F> inline Aabb<T> map_box(const Aabb<T>& b, F&& f) noexcept {
  if (b.is_empty()) return b;
  if (!all_finite(b.lo) || !all_finite(b.hi)) return Aabb<T>::infinite();
  Aabb<T> r;
  for (int c = 0; c < 8; ++c)
    r.extend(f(
        Vec3<T>{(c & 1) ? b.hi.x : b.lo.x, (c & 2) ? b.hi.y : b.lo.y, (c & 4) ? b.hi.z : b.lo.z}));
  return r;
}
template <class S> constexpr SdfKind at_best_bound() noexcept {
  return weakest(S::kind, SdfKind::bound);
}
template <class T> constexpr T quiet_nan() noexcept { return std::numeric_limits<T>::quiet_NaN(); }
template <class... A> inline constexpr bool always_false_v = false;
} // namespace detail

/// `shape` moved by `t`: S(p - t). Keeps the kind.
template <class S> struct Translated {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = S::kind;
  S shape;
  Vec3<T> t;

  T operator()(const Vec3<T>& p) const noexcept { return shape(p - t); }
  Aabb<T> bounds() const noexcept {
    const Aabb<T> b = shape.bounds();
    return b.is_empty() ? b : Aabb<T>{b.lo + t, b.hi + t};
  }
};

/// `shape` rotated by the rotation matrix `r` (orthonormal, det +1): S(r^T p). Keeps the kind.
/// Bounds: the box of the rotated corners of the operand's box.
template <class S> struct Rotated {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = S::kind;
  S shape;
  Mat3<T> r;

  T operator()(const Vec3<T>& p) const noexcept { return shape(r.transposed() * p); }
  Aabb<T> bounds() const noexcept {
    return detail::map_box(shape.bounds(), [this](const Vec3<T>& q) { return r * q; });
  }
};

/// `shape` under the rigid motion x -> r x + t (rotation first, then translation):
/// S(r^T (p - t)). Keeps the kind.
template <class S> struct RigidTransformed {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = S::kind;
  S shape;
  Mat3<T> r;
  Vec3<T> t;

  T operator()(const Vec3<T>& p) const noexcept { return shape(r.transposed() * (p - t)); }
  Aabb<T> bounds() const noexcept {
    return detail::map_box(shape.bounds(), [this](const Vec3<T>& q) { return r * q + t; });
  }
};

/// `shape` scaled uniformly about the origin by `factor` (> 0): factor * S(p / factor). Keeps the
/// kind (a similarity scales every distance by the same factor). Non-uniform scaling is not
/// offered: it does not preserve distances.
template <class S> struct Scaled {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = S::kind;
  S shape;
  T factor;

  T operator()(const Vec3<T>& p) const noexcept { return factor * shape(p / factor); }
  Aabb<T> bounds() const noexcept {
    const Aabb<T> b = shape.bounds();
    return b.is_empty() ? b : Aabb<T>::of(b.lo * factor, b.hi * factor);
  }
};

/// Offset (rounding, "RoundedSDF" in EBGeometry): S - r, which grows the shape by r (shrinks it
/// for r < 0). Exact outside for r >= 0 and inside for r <= 0, and everywhere when a convex
/// operand grows (r >= 0); in general `bound` (kind: exact -> bound).
template <class S> struct Offset {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::at_best_bound<S>();
  S shape;
  T r;

  T operator()(const Vec3<T>& p) const noexcept { return shape(p) - r; }
  Aabb<T> bounds() const noexcept {
    const Aabb<T> b = shape.bounds();
    return r > T(0) && !b.is_empty() ? b.grown(r) : b;
  }
};

/// Shell (annulus, onion): |S| - t, the set within t of the operand's surface. Exact at points
/// farther than t from the surface, `bound` inside the shell (kind: exact -> bound).
template <class S> struct Shell {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::at_best_bound<S>();
  S shape;
  T t;

  T operator()(const Vec3<T>& p) const noexcept { return std::abs(shape(p)) - t; }
  Aabb<T> bounds() const noexcept {
    const Aabb<T> b = shape.bounds();
    return b.is_empty() ? b : b.grown(std::abs(t));
  }
};

/// Elongation by half-lengths `h` (>= 0) along x, y, z: the operand is cut at the coordinate
/// planes through the origin and the halves pulled apart by 2h, the gap filled with the
/// extruded cross-section. Value S(q+) + min(max_i q_i, 0) with q = |p| - h, q+ = max(q, 0)
/// (Quilez's exact-interior form), falling back to S(q+) when the origin is outside the operand
/// (so the sign stays right). 1-Lipschitz: kind exact -> bound. Bounds grow by h.
template <class S> struct Elongated {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::at_best_bound<S>();
  S shape;
  Vec3<T> h;

  T operator()(const Vec3<T>& p) const noexcept {
    const Vec3<T> q = abs(p) - h;
    const Vec3<T> qp = max(q, Vec3<T>::zero());
    // collapse keeps the sign of p on each axis so asymmetric operands elongate correctly
    const Vec3<T> c{std::copysign(qp.x, p.x), std::copysign(qp.y, p.y), std::copysign(qp.z, p.z)};
    const T v = shape(c);
    return v < T(0) ? v + std::min(max_component(q), T(0)) : v;
  }
  Aabb<T> bounds() const noexcept {
    const Aabb<T> b = shape.bounds();
    if (b.is_empty()) return b;
    // each half moves outwards by h; the box of the union also covers the filled gap
    return {min(b.lo - h, b.lo + h), max(b.hi + h, b.hi - h)};
  }
};

/// Mirror image of `shape` across the plane {x : dot(n, x) = d} (n non-zero): S(p - 2 (n.p - d)
/// n / |n|^2). An isometry: keeps the kind. A zero or non-finite `n` defines no plane: every value
/// and the bounds are NaN.
template <class S> struct Reflected {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = S::kind;
  S shape;
  Vec3<T> n;
  T d;

  Vec3<T> reflect_point(const Vec3<T>& p) const noexcept {
    const T nn = dot(n, n);
    if (!(nn > T(0)) || !std::isfinite(nn)) return Vec3<T>::constant(detail::quiet_nan<T>());
    const T k = T(2) * (dot(n, p) - d * std::sqrt(nn)) / nn;
    return p - n * k;
  }
  T operator()(const Vec3<T>& p) const noexcept { return shape(reflect_point(p)); }
  Aabb<T> bounds() const noexcept {
    const T nn = dot(n, n);
    if (!(nn > T(0)) || !std::isfinite(nn)) {
      const Vec3<T> q = Vec3<T>::constant(detail::quiet_nan<T>());
      return {q, q};
    }
    return detail::map_box(shape.bounds(), [this](const Vec3<T>& q) { return reflect_point(q); });
  }
};

/// Mirror symmetry about the coordinate plane `axis` = 0: the part of `shape` on the positive
/// side plus its mirror image, S(p with p[axis] -> |p[axis]|). Exact for operands lying on the
/// positive side; in general `bound` (kind: exact -> bound). An `Axis` forced out of range by a
/// cast gives NaN values and bounds.
template <class S> struct Mirrored {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::at_best_bound<S>();
  S shape;
  Axis axis;

  T operator()(const Vec3<T>& p) const noexcept {
    if (!is_valid(axis)) return detail::quiet_nan<T>();
    const int a = index(axis);
    Vec3<T> q = p;
    q[a] = std::abs(q[a]);
    return shape(q);
  }
  Aabb<T> bounds() const noexcept {
    Aabb<T> b = shape.bounds();
    if (!is_valid(axis)) {
      const Vec3<T> n = Vec3<T>::constant(detail::quiet_nan<T>());
      return {n, n};
    }
    const int a = index(axis);
    if (b.is_empty()) return b;
    const T m = std::max(std::abs(b.lo[a]), std::abs(b.hi[a]));
    b.lo[a] = -m;
    b.hi[a] = m;
    return b;
  }
};

/// Complement: -S, inside and outside swapped. Keeps the kind. Bounds: infinite.
template <class S> struct Complement {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = S::kind;
  S shape;

  T operator()(const Vec3<T>& p) const noexcept { return -shape(p); }
  Aabb<T> bounds() const noexcept { return Aabb<T>::infinite(); }
};

/// Mollification (smoothing): the weighted average of S over the 27 points p + radius * (i, j, k),
/// i, j, k in {-1, 0, 1}, with binomial weights (1/4, 1/2, 1/4) per axis. An average of
/// 1-Lipschitz functions is 1-Lipschitz, so kind exact -> bound (convex edges are rounded, so the
/// value is no longer the distance to the operand). 27 operand evaluations per point. Bounds grow
/// by radius * sqrt(3) (at all 27 samples the operand is positive beyond that).
template <class S> struct Mollified {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::at_best_bound<S>();
  S shape;
  T radius;

  T operator()(const Vec3<T>& p) const noexcept {
    constexpr T w[3] = {T(0.25), T(0.5), T(0.25)};
    T sum = 0;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          sum += w[i] * w[j] * w[k] *
                 shape(p + Vec3<T>{T(i - 1) * radius, T(j - 1) * radius, T(k - 1) * radius});
    return sum;
  }
  Aabb<T> bounds() const noexcept {
    const Aabb<T> b = shape.bounds();
    return b.is_empty() ? b : b.grown(std::abs(radius) * T(1.7320508075688772));
  }
};

/// Infinite repetition with cell size `period` (a component <= 0 leaves that axis unrepeated):
/// copies of the operand at every multiple of the period. The value is the minimum over the copy
/// in the point's cell and its neighbours (up to 27 evaluations), which is the union of all
/// copies provided the operand lies within its cell, |x_i| <= period_i / 2 (precondition). A
/// union of copies: kind exact -> bound (exact when the copies do not touch). Bounds: infinite
/// along repeated axes.
template <class S> struct Repeated {
  EBGEOM_REQUIRE_SDF(S);
  using T = sdf_scalar_t<S>;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::at_best_bound<S>();
  S shape;
  Vec3<T> period;
  /// Copies per side along each axis; negative = unlimited. `repeat(s, period)` sets -1,
  /// `repeat(s, period, count)` a finite grid of 2 * count + 1 copies per repeated axis.
  std::array<int, 3> count{{-1, -1, -1}};

  T operator()(const Vec3<T>& p) const noexcept {
    T cell[3];
    int lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      if (period[a] > T(0)) {
        T c = std::round(p[a] / period[a]);
        if (count[a] >= 0) c = clamp(c, T(-count[a]), T(count[a]));
        cell[a] = c;
        lo[a] = (count[a] >= 0 && c <= T(-count[a])) ? 0 : -1;
        hi[a] = (count[a] >= 0 && c >= T(count[a])) ? 0 : 1;
      } else {
        cell[a] = T(0);
        lo[a] = hi[a] = 0;
      }
    }
    T best = std::numeric_limits<T>::infinity();
    for (int i = lo[0]; i <= hi[0]; ++i)
      for (int j = lo[1]; j <= hi[1]; ++j)
        for (int k = lo[2]; k <= hi[2]; ++k) {
          const Vec3<T> c{(cell[0] + T(i)) * std::max(period.x, T(0)),
                          (cell[1] + T(j)) * std::max(period.y, T(0)),
                          (cell[2] + T(k)) * std::max(period.z, T(0))};
          best = std::min(best, shape(p - c));
        }
    return best;
  }
  Aabb<T> bounds() const noexcept {
    Aabb<T> b = shape.bounds();
    if (b.is_empty()) return b;
    const T inf = std::numeric_limits<T>::infinity();
    for (int a = 0; a < 3; ++a) {
      if (!(period[a] > T(0))) continue;
      if (count[a] < 0) {
        b.lo[a] = -inf;
        b.hi[a] = inf;
      } else {
        b.lo[a] -= T(count[a]) * period[a];
        b.hi[a] += T(count[a]) * period[a];
      }
    }
    return b;
  }
};

// ---- free functions ------------------------------------------------------------------------

/// `shape` moved by `t`.
template <class S> Translated<S> translate(S shape, const Vec3<sdf_scalar_t<S>>& t) noexcept {
  return {std::move(shape), t};
}
/// `shape` rotated by the matrix `r`.
template <class S> Rotated<S> rotate(S shape, const Mat3<sdf_scalar_t<S>>& r) noexcept {
  return {std::move(shape), r};
}
/// `shape` rotated by the quaternion `q` (normalised here; a zero quaternion gives NaN values).
template <class S> Rotated<S> rotate(S shape, const Quaternion<sdf_scalar_t<S>>& q) noexcept {
  return {std::move(shape), q.normalized().to_mat3()};
}
/// `shape` rotated by `degrees` about coordinate axis `axis`, right-handed: EBGeometry's
/// `rotate(angle, axis)` is `rotate(shape, Axis::..., angle)` (shape, axis, angle, in that order).
/// Quarter turns are exact.
template <class S> Rotated<S> rotate(S shape, Axis axis, sdf_scalar_t<S> degrees) noexcept {
  return {std::move(shape), Mat3<sdf_scalar_t<S>>::coordinate_axis(axis, degrees)};
}
/// Catches a coordinate axis given as a number, in either order (`rotate(s, 90, 0)` as
/// EBGeometry's `rotate(angle, axis)`, or `rotate(s, 2, 90)`): a compile error that names the right
/// call, never a silent identity.
template <class S, class A, class D,
          class = std::enable_if_t<std::is_arithmetic_v<A> && std::is_arithmetic_v<D>>>
void rotate(S, A, D) noexcept {
  static_assert(detail::always_false_v<S, A, D>,
                "ebgeom: rotate takes (shape, Axis, degrees), e.g. rotate(s, ebgeom::Axis::x, 90);"
                " a number is not an axis. EBGeometry's rotate(angle, axis) is "
                "rotate(s, ebgeom::Axis::{x,y,z}, angle)");
}
/// `shape` rotated by `degrees` about the direction `axis` through the origin (a zero or
/// non-finite `axis` gives NaN values).
template <class S>
Rotated<S> rotate(S shape, const Vec3<sdf_scalar_t<S>>& axis, sdf_scalar_t<S> degrees) noexcept {
  return {std::move(shape), Mat3<sdf_scalar_t<S>>::axis_degrees(axis, degrees)};
}
/// `shape` under x -> r x + t.
template <class S>
RigidTransformed<S> transform(S shape, const Mat3<sdf_scalar_t<S>>& r,
                              const Vec3<sdf_scalar_t<S>>& t) noexcept {
  return {std::move(shape), r, t};
}
/// `shape` under x -> q.rotate(x) + t.
template <class S>
RigidTransformed<S> transform(S shape, const Quaternion<sdf_scalar_t<S>>& q,
                              const Vec3<sdf_scalar_t<S>>& t) noexcept {
  return {std::move(shape), q.normalized().to_mat3(), t};
}
/// `shape` scaled by `factor` (> 0) about the origin. A factor that is not positive and finite
/// (0 would collapse the shape, a negative one would mirror it and flip the sign) gives NaN values.
template <class S> Scaled<S> scale(S shape, sdf_scalar_t<S> factor) noexcept {
  using T = sdf_scalar_t<S>;
  const bool ok = factor > T(0) && std::isfinite(factor);
  return {std::move(shape), ok ? factor : detail::quiet_nan<T>()};
}
/// S - r (rounding / offset).
template <class S> Offset<S> offset(S shape, sdf_scalar_t<S> r) noexcept {
  return {std::move(shape), r};
}
/// |S| - t.
template <class S> Shell<S> shell(S shape, sdf_scalar_t<S> t) noexcept {
  return {std::move(shape), t};
}
/// Elongation by half-lengths `h`.
template <class S> Elongated<S> elongate(S shape, const Vec3<sdf_scalar_t<S>>& h) noexcept {
  return {std::move(shape), max(h, Vec3<sdf_scalar_t<S>>::zero())};
}
/// Mirror image across the plane dot(n, x) = d (n non-zero, any length; zero gives NaN values).
template <class S>
Reflected<S> reflect(S shape, const Vec3<sdf_scalar_t<S>>& n, sdf_scalar_t<S> d = 0) noexcept {
  return {std::move(shape), n, d};
}
/// Symmetrise about the coordinate plane `axis` = 0: `mirror(s, Axis::x)`.
template <class S> Mirrored<S> mirror(S shape, Axis axis) noexcept {
  return {std::move(shape), axis};
}
/// Catches a coordinate axis given as a number: a compile error naming the right call.
template <class S, class A, class = std::enable_if_t<std::is_arithmetic_v<A>>>
void mirror(S, A) noexcept {
  static_assert(detail::always_false_v<S, A>,
                "ebgeom: mirror takes (shape, Axis), e.g. mirror(s, ebgeom::Axis::x); a number is "
                "not an axis");
}
/// -S.
template <class S> Complement<S> complement(S shape) noexcept { return {std::move(shape)}; }
/// Smoothing over a 27-point kernel of half-width `radius`.
template <class S> Mollified<S> mollify(S shape, sdf_scalar_t<S> radius) noexcept {
  return {std::move(shape), radius};
}
/// Infinite repetition with cell size `period` (components <= 0: not repeated).
template <class S> Repeated<S> repeat(S shape, const Vec3<sdf_scalar_t<S>>& period) noexcept {
  return {std::move(shape), period, {{-1, -1, -1}}};
}
/// Finite repetition: 2 * count[a] + 1 copies along each repeated axis a, centred on the origin.
template <class S>
Repeated<S> repeat(S shape, const Vec3<sdf_scalar_t<S>>& period,
                   const std::array<int, 3>& count) noexcept {
  return {std::move(shape),
          period,
          {{std::max(count[0], 0), std::max(count[1], 0), std::max(count[2], 0)}}};
}

} // namespace ebgeom
