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
///
/// Optional members, each detected here and nowhere else, let the evaluators take faster paths:
///  - batch `void eval(Span<const Vec3<T>>, Span<T>) const` (`has_batch_eval_v`), with
///    `static constexpr bool batch_in_space_order = true` when it orders the points itself
///    (`has_ordered_batch_v`),
///  - `T bounded(const Vec3<T>&, T max_abs) const` (`has_bounded_query_v`),
///  - tile `void eval_lattice(Span<const Vec3<T>>, const std::array<std::size_t, 3>&, Span<T>)
///    const` (`has_lattice_eval_v`),
///  - run-time kind `SdfKind dynamic_kind() const` and prunability `bool dynamic_prunable() const`
///    (`kind_of`, `may_prune_v`, `is_prunable`),
///  - a free `Vec3<T> analytic_gradient(const S&, const Vec3<T>&)` found by argument-dependent
///    lookup (`has_analytic_gradient_v`, used by `normal`).

#include <array>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/span.hpp"
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

template <class S, class = void> struct has_batch_eval : std::false_type {};
template <class S>
struct has_batch_eval<S, std::void_t<decltype(std::declval<const S&>().eval(
                             std::declval<Span<const Vec3<typename S::scalar_type>>>(),
                             std::declval<Span<typename S::scalar_type>>()))>> : std::true_type {};

template <class S, class = void> struct has_ordered_batch : std::false_type {};
template <class S>
struct has_ordered_batch<S, std::void_t<decltype(S::batch_in_space_order)>>
    : std::bool_constant<has_batch_eval<S>::value&& bool(S::batch_in_space_order)> {};

template <class S, class = void> struct has_bounded_query : std::false_type {};
template <class S>
struct has_bounded_query<S, std::void_t<decltype(std::declval<const S&>().bounded(
                                std::declval<const Vec3<typename S::scalar_type>&>(),
                                std::declval<typename S::scalar_type>()))>>
    : std::is_convertible<decltype(std::declval<const S&>().bounded(
                              std::declval<const Vec3<typename S::scalar_type>&>(),
                              std::declval<typename S::scalar_type>())),
                          typename S::scalar_type> {};

template <class S, class = void> struct has_lattice_eval : std::false_type {};
template <class S>
struct has_lattice_eval<S, std::void_t<decltype(std::declval<const S&>().eval_lattice(
                               std::declval<Span<const Vec3<typename S::scalar_type>>>(),
                               std::declval<const std::array<std::size_t, 3>&>(),
                               std::declval<Span<typename S::scalar_type>>()))>> : std::true_type {
};

// `analytic_gradient` is found by argument-dependent lookup at instantiation (the overloads for
// the shapes are in sdf/normal.hpp).
template <class S, class = void> struct has_analytic_gradient : std::false_type {};
template <class S>
struct has_analytic_gradient<
    S, std::void_t<decltype(analytic_gradient(std::declval<const S&>(),
                                              std::declval<const Vec3<sdf_scalar_t<S>>&>()))>>
    : std::true_type {};
} // namespace detail

/// True when `S` has a batch member `void eval(Span<const Vec3<T>>, Span<T>) const` (as
/// `AnySdf<T>` and `CachedUnion` do). Batch evaluators then call it once per batch instead of
/// `S::operator()` once per point.
template <class S> inline constexpr bool has_batch_eval_v = detail::has_batch_eval<S>::value;

/// True when `S` has a batch `eval` that visits the points in its own space order
/// (`static constexpr bool batch_in_space_order = true`, as `MeshSdf`): locality across queries
/// then grows with the batch, so `evaluate` hands it a few large spans per thread instead of
/// batches of 256 points.
template <class S> inline constexpr bool has_ordered_batch_v = detail::has_ordered_batch<S>::value;

/// True when `S` (an `exact` SDF) has a bounded query
/// `T bounded(const Vec3<T>& p, T max_abs) const noexcept` that returns exactly `S(p)` (bit for
/// bit) whenever |S(p)| <= max_abs, and otherwise any value v with |v| > max_abs whose sign is not
/// trusted (`MeshSdf` has one). Grid samplers then seed each search with a neighbour's value
/// (1-Lipschitz) and narrow-band searches with the band.
template <class S> inline constexpr bool has_bounded_query_v = detail::has_bounded_query<S>::value;

/// True when `S` has a tile evaluation `void eval_lattice(Span<const Vec3<T>> pts, const
/// std::array<std::size_t, 3>& dims, Span<T> out) const` writing, bit for bit, `out[l] =
/// S(pts[l])` for a tile of `dims` lattice samples (x fastest). `sample_grid` then makes one call
/// per 8^3 tile with `GridSearch::tile` (the default) in dense mode (`MeshSdf`, `SignedMeshSdf`).
template <class S> inline constexpr bool has_lattice_eval_v = detail::has_lattice_eval<S>::value;

/// True when `analytic_gradient(s, p)` exists for `S`.
template <class S>
inline constexpr bool has_analytic_gradient_v = detail::has_analytic_gradient<S>::value;

/// The kind of `sdf`: `sdf.dynamic_kind()` when `S` provides it (runtime-composed SDFs whose
/// static `kind` must be conservative), otherwise `S::kind`.
template <class S> constexpr SdfKind kind_of(const S& sdf) noexcept {
  if constexpr (detail::has_dynamic_kind_member<S>::value)
    return sdf.dynamic_kind();
  else
    return (void)sdf, S::kind;
}

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
