// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// The SDF contract. An SDF is any copyable type `S` with
///  - `using scalar_type = T;`
///  - `T operator()(const Vec3<T>&) const noexcept` (S < 0 inside, > 0 outside),
///  - `Aabb<T> bounds() const noexcept` (a box containing the zero level set and the inside;
///    `Aabb<T>::infinite()` for unbounded shapes such as half-spaces),
///  - `static constexpr SdfKind kind`.
/// `is_sdf_v<S>` checks it (C++17 detection); with C++20 concepts, `ebgeom::Sdf` too.

#include <type_traits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom {

/// What the value of an SDF means.
enum class SdfKind {
  exact,   ///< the true signed Euclidean distance
  bound,   ///< 1-Lipschitz with |value| <= true distance and the correct sign: safe to sphere-trace
  implicit ///< only the sign is meaningful
};

/// The weaker of two kinds (exact > bound > implicit).
constexpr SdfKind weakest(SdfKind a, SdfKind b) noexcept {
  return (a == SdfKind::implicit || b == SdfKind::implicit)
             ? SdfKind::implicit
             : ((a == SdfKind::bound || b == SdfKind::bound) ? SdfKind::bound : SdfKind::exact);
}

namespace detail {
template <class S, class = void> struct is_sdf : std::false_type {};
template <class S>
struct is_sdf<S, std::void_t<typename S::scalar_type, decltype(S::kind),
                             decltype(std::declval<const S&>()(
                                 std::declval<const Vec3<typename S::scalar_type>&>())),
                             decltype(std::declval<const S&>().bounds())>>
    : std::bool_constant<
          std::is_copy_constructible_v<S> &&
          std::is_same_v<std::remove_cv_t<decltype(S::kind)>, SdfKind> &&
          std::is_convertible_v<decltype(std::declval<const S&>()(
                                    std::declval<const Vec3<typename S::scalar_type>&>())),
                                typename S::scalar_type> &&
          std::is_same_v<decltype(std::declval<const S&>().bounds()),
                         Aabb<typename S::scalar_type>>> {};
} // namespace detail

/// True when `S` satisfies the SDF contract above.
template <class S> inline constexpr bool is_sdf_v = detail::is_sdf<S>::value;

/// Scalar type of an SDF.
template <class S> using sdf_scalar_t = typename S::scalar_type;

/// True when S(p) >= the distance from p to S.bounds() for every p outside the box, so a union
/// may skip the object when its box is farther than the best value found (`BvhUnion`,
/// `CachedUnion`). True for exact SDFs whose box contains the zero level set and the inside;
/// specialise it for other types that qualify.
template <class S> struct prunable_in_union : std::bool_constant<S::kind == SdfKind::exact> {};

namespace detail {
template <class S, class = void> struct has_dynamic_kind_member : std::false_type {};
template <class S>
struct has_dynamic_kind_member<S, std::void_t<decltype(std::declval<const S&>().dynamic_kind())>>
    : std::true_type {};
template <class S, class = void> struct has_dynamic_prunable_member : std::false_type {};
template <class S>
struct has_dynamic_prunable_member<
    S, std::void_t<decltype(bool(std::declval<const S&>().dynamic_prunable()))>> : std::true_type {
};
} // namespace detail

/// True when a union may prune some objects of type `S`: statically (`prunable_in_union<S>`) or,
/// for run-time composed types that report their own kind (`dynamic_kind()`, e.g. `AnySdf`,
/// `SignedMeshSdf`) or prunability (`dynamic_prunable()`), object by object (`is_prunable`).
template <class S>
inline constexpr bool may_prune_v =
    prunable_in_union<S>::value || detail::has_dynamic_prunable_member<S>::value ||
    detail::has_dynamic_kind_member<S>::value;

/// Whether the object `s` may be pruned by a union (see `prunable_in_union`):
/// `s.dynamic_prunable()` when `S` has it, else `prunable_in_union<S>`, else `s.dynamic_kind() ==
/// exact` when `S` reports its kind at run time, else false.
template <class S> constexpr bool is_prunable(const S& s) noexcept {
  if constexpr (detail::has_dynamic_prunable_member<S>::value)
    return bool(s.dynamic_prunable());
  else if constexpr (prunable_in_union<S>::value)
    return (void)s, true;
  else if constexpr (detail::has_dynamic_kind_member<S>::value)
    return s.dynamic_kind() == SdfKind::exact;
  else
    return (void)s, false;
}

#if defined(__cpp_concepts)
template <class S>
concept Sdf = is_sdf_v<S>;
#endif

} // namespace ebgeom

/// Inside combinators: `EBGEOM_REQUIRE_SDF(S);` gives a readable error for a non-SDF operand.
#define EBGEOM_REQUIRE_SDF(S)                                                                      \
  static_assert(::ebgeom::is_sdf_v<S>,                                                             \
                "ebgeom: operand is not an SDF: it needs scalar_type, a const noexcept "           \
                "operator()(const Vec3<T>&), bounds() returning Aabb<T>, and a static "            \
                "constexpr SdfKind kind (see sdf/concepts.hpp)")
