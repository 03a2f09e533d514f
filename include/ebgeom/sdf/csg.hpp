// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Constructive solid geometry over SDFs, composed statically (operands held by value in a
/// `std::tuple`, the whole tree inlined; no allocation, no virtual call):
///  - `unite(a, b, ...)` = min, `intersect(a, b, ...)` = max, `subtract(a, b, ...)` = a minus the
///    others = max(a, -b, ...), over any number of operands of one scalar type;
///  - `smooth_unite`, `smooth_intersect`, `smooth_subtract` (polynomial smooth minimum, blend
///    radius k) and `exp_smooth_unite`, `exp_smooth_intersect`, `exp_smooth_subtract`
///    (exponential / log-sum-exp smooth minimum);
///  - `disjoint_unite(a, b, ...)`: EBGeometry's union of non-touching objects, exact.
///
/// Kinds (STYLE.md section 3): min and max of 1-Lipschitz functions are 1-Lipschitz, so unions,
/// intersections and differences of exact or bound operands are `bound` (a union of exact
/// shapes is exact outside and only a bound inside; an intersection the reverse). Both smooth
/// minima are convex combinations of the operands' gradients, hence 1-Lipschitz: `bound` too. A
/// single operand keeps its kind; any `implicit` operand makes the result `implicit`.

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <type_traits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

namespace detail {
template <class... Ss> constexpr SdfKind weakest_of() noexcept {
  SdfKind k = SdfKind::exact;
  ((k = weakest(k, Ss::kind)), ...);
  return k;
}
/// Kind of a min/max combination: the operand's kind for one operand, else at best `bound`.
template <class... Ss> constexpr SdfKind combined_kind() noexcept {
  return sizeof...(Ss) == 1 ? weakest_of<Ss...>() : weakest(weakest_of<Ss...>(), SdfKind::bound);
}
template <class S0, class... Ss> struct csg_check {
  static_assert((is_sdf_v<S0> && ... && is_sdf_v<Ss>),
                "ebgeom: every CSG operand must be an SDF (see sdf/concepts.hpp)");
  static_assert((std::is_same_v<sdf_scalar_t<S0>, sdf_scalar_t<Ss>> && ...),
                "ebgeom: CSG operands must share one scalar type (float or double)");
  using type = sdf_scalar_t<S0>;
};
/// Intersection of boxes (empty when disjoint).
template <class T> constexpr Aabb<T> intersection(const Aabb<T>& a, const Aabb<T>& b) noexcept {
  const Aabb<T> r{max(a.lo, b.lo), min(a.hi, b.hi)};
  return r.is_empty() ? Aabb<T>{} : r;
}
} // namespace detail

/// Union: min_i S_i. Bounds: the merged operand boxes. O(number of operands).
template <class... Ss> struct Union {
  using T = typename detail::csg_check<Ss...>::type;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::combined_kind<Ss...>();
  std::tuple<Ss...> shapes;

  T operator()(const Vec3<T>& p) const noexcept {
    return std::apply(
        [&p](const auto&... s) {
          T r = std::numeric_limits<T>::infinity();
          ((r = std::min(r, T(s(p)))), ...);
          return r;
        },
        shapes);
  }
  Aabb<T> bounds() const noexcept {
    return std::apply(
        [](const auto&... s) {
          Aabb<T> b;
          ((b.extend(s.bounds())), ...);
          return b;
        },
        shapes);
  }
};

/// Union of operands the caller asserts are pairwise disjoint (not touching): EBGeometry's
/// union, which returns the value of the closest object (smallest |S_i|). For disjoint operands
/// that equals min_i S_i, which is what is evaluated (it keeps the right sign even if the
/// assertion is wrong). Kind: the weakest operand kind, so `exact` for exact operands; when the
/// operands overlap, the value is still a `bound` but the declared kind is wrong.
template <class... Ss> struct DisjointUnion {
  using T = typename detail::csg_check<Ss...>::type;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::weakest_of<Ss...>();
  Union<Ss...> u;

  T operator()(const Vec3<T>& p) const noexcept { return u(p); }
  Aabb<T> bounds() const noexcept { return u.bounds(); }
};

/// Intersection: max_i S_i. Bounds: the intersection of the operand boxes.
template <class... Ss> struct Intersection {
  using T = typename detail::csg_check<Ss...>::type;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::combined_kind<Ss...>();
  std::tuple<Ss...> shapes;

  T operator()(const Vec3<T>& p) const noexcept {
    return std::apply(
        [&p](const auto&... s) {
          T r = -std::numeric_limits<T>::infinity();
          ((r = std::max(r, T(s(p)))), ...);
          return r;
        },
        shapes);
  }
  Aabb<T> bounds() const noexcept {
    return std::apply(
        [](const auto&... s) {
          Aabb<T> b = Aabb<T>::infinite();
          ((b = detail::intersection(b, s.bounds())), ...);
          return b;
        },
        shapes);
  }
};

/// Difference: the first operand minus all others, max(S_0, -S_1, -S_2, ...). Bounds: the first
/// operand's box.
template <class S0, class... Ss> struct Difference {
  using T = typename detail::csg_check<S0, Ss...>::type;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::combined_kind<S0, Ss...>();
  S0 first;
  std::tuple<Ss...> others;

  T operator()(const Vec3<T>& p) const noexcept {
    return std::apply(
        [&](const auto&... s) {
          T r = first(p);
          ((r = std::max(r, -T(s(p)))), ...);
          return r;
        },
        others);
  }
  Aabb<T> bounds() const noexcept { return first.bounds(); }
};

// ---- smooth blends ---------------------------------------------------------------------------

/// Polynomial (quadratic) smooth minimum (Quilez): min(a, b) - h^2 k / 4 with
/// h = max(k - |a - b|, 0) / k. Equals min when |a - b| >= k; at most k / 4 below it. k <= 0 is
/// the sharp min.
struct PolynomialBlend {
  template <class T> static T smin(T a, T b, T k) noexcept {
    if (!(k > T(0))) return std::min(a, b);
    const T h = std::max(k - std::abs(a - b), T(0)) / k;
    return std::min(a, b) - h * h * k * T(0.25);
  }
  /// The largest amount smin falls below min.
  template <class T> static constexpr T max_gap(T k) noexcept { return k > T(0) ? k / T(4) : T(0); }
};

/// Exponential smooth minimum: -k log(exp(-a/k) + exp(-b/k)), evaluated stably as
/// min(a, b) - k log1p(exp(-|a - b| / k)). Never equals min; at most k log 2 below it. k <= 0 is
/// the sharp min.
struct ExponentialBlend {
  template <class T> static T smin(T a, T b, T k) noexcept {
    if (!(k > T(0))) return std::min(a, b);
    return std::min(a, b) - k * std::log1p(std::exp(-std::abs(a - b) / k));
  }
  template <class T> static constexpr T max_gap(T k) noexcept {
    return k > T(0) ? k * T(0.69314718055994531) : T(0);
  }
};

/// Smooth union of two SDFs with blend radius k: Blend::smin(A, B, k). Kind: at best `bound`.
/// Bounds: the merged boxes grown by the largest gap (k/4 or k log 2), valid when operand values
/// outside their boxes are at least the box distance (true for exact and bound shapes built
/// here).
template <class A, class B, class Blend = PolynomialBlend> struct SmoothUnion {
  using T = typename detail::csg_check<A, B>::type;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::combined_kind<A, B>();
  A a;
  B b;
  T k;

  T operator()(const Vec3<T>& p) const noexcept { return Blend::smin(T(a(p)), T(b(p)), k); }
  Aabb<T> bounds() const noexcept { return merge(a.bounds(), b.bounds()).grown(Blend::max_gap(k)); }
};

/// Smooth intersection: -smin(-A, -B, k) (the shape only shrinks). Bounds: the boxes' overlap.
template <class A, class B, class Blend = PolynomialBlend> struct SmoothIntersection {
  using T = typename detail::csg_check<A, B>::type;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::combined_kind<A, B>();
  A a;
  B b;
  T k;

  T operator()(const Vec3<T>& p) const noexcept { return -Blend::smin(-T(a(p)), -T(b(p)), k); }
  Aabb<T> bounds() const noexcept { return detail::intersection(a.bounds(), b.bounds()); }
};

/// Smooth difference A minus B: -smin(-A, B, k). Bounds: A's box.
template <class A, class B, class Blend = PolynomialBlend> struct SmoothDifference {
  using T = typename detail::csg_check<A, B>::type;
  using scalar_type = T;
  static constexpr SdfKind kind = detail::combined_kind<A, B>();
  A a;
  B b;
  T k;

  T operator()(const Vec3<T>& p) const noexcept { return -Blend::smin(-T(a(p)), T(b(p)), k); }
  Aabb<T> bounds() const noexcept { return a.bounds(); }
};

// ---- free functions ------------------------------------------------------------------------

/// Union of one or more SDFs (min).
template <class... Ss> Union<Ss...> unite(Ss... shapes) noexcept {
  return {std::tuple<Ss...>(std::move(shapes)...)};
}
/// Union of SDFs the caller asserts do not touch: exact for exact operands.
template <class... Ss> DisjointUnion<Ss...> disjoint_unite(Ss... shapes) noexcept {
  return {Union<Ss...>{std::tuple<Ss...>(std::move(shapes)...)}};
}
/// Intersection of one or more SDFs (max).
template <class... Ss> Intersection<Ss...> intersect(Ss... shapes) noexcept {
  return {std::tuple<Ss...>(std::move(shapes)...)};
}
/// `a` minus every other operand.
template <class S0, class... Ss> Difference<S0, Ss...> subtract(S0 a, Ss... others) noexcept {
  return {std::move(a), std::tuple<Ss...>(std::move(others)...)};
}
/// Polynomial smooth union with blend radius `k`.
template <class A, class B> SmoothUnion<A, B> smooth_unite(A a, B b, sdf_scalar_t<A> k) noexcept {
  return {std::move(a), std::move(b), k};
}
template <class A, class B>
SmoothIntersection<A, B> smooth_intersect(A a, B b, sdf_scalar_t<A> k) noexcept {
  return {std::move(a), std::move(b), k};
}
template <class A, class B>
SmoothDifference<A, B> smooth_subtract(A a, B b, sdf_scalar_t<A> k) noexcept {
  return {std::move(a), std::move(b), k};
}
/// Exponential smooth union with blend radius `k`.
template <class A, class B>
SmoothUnion<A, B, ExponentialBlend> exp_smooth_unite(A a, B b, sdf_scalar_t<A> k) noexcept {
  return {std::move(a), std::move(b), k};
}
template <class A, class B>
SmoothIntersection<A, B, ExponentialBlend> exp_smooth_intersect(A a, B b,
                                                                sdf_scalar_t<A> k) noexcept {
  return {std::move(a), std::move(b), k};
}
template <class A, class B>
SmoothDifference<A, B, ExponentialBlend> exp_smooth_subtract(A a, B b, sdf_scalar_t<A> k) noexcept {
  return {std::move(a), std::move(b), k};
}

} // namespace ebgeom
