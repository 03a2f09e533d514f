// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// The split-sign protocol: an SDF whose value is an unsigned distance d with a sign decided
/// apart from it (a winding number, or no sign at all), S(p) = -d where d > 0 and the sign is
/// negative, else d. Grid samplers use it to keep narrow bands fast for SDFs whose sign cannot
/// be propagated between far samples (`SdfKind::implicit`, e.g. a winding sign on an open mesh):
/// boxes of samples proven farther than the band from the surface by the distance (1-Lipschitz) are
/// signed by `sign_over` without any distance search. `SignedMeshSdf` implements it.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <type_traits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom {

/// The sign of an SDF's value at a point or over a box; `unknown` where it is not proven.
enum class Sign : std::int8_t { negative = -1, unknown = 0, positive = 1 };

/// S(p) from its unsigned distance `d` and the sign the SDF has there: -d when d > 0 and `s` is
/// negative, else d (so points on the surface and NaN distances keep d).
template <class T> constexpr T apply_sign(T d, Sign s) noexcept {
  return d > T(0) && s == Sign::negative ? -d : d;
}

namespace detail {
template <class S, class = void> struct has_split_sign : std::false_type {};
template <class S>
struct has_split_sign<S, std::void_t<decltype(std::declval<const S&>().unsigned_distance(
                                         std::declval<const Vec3<typename S::scalar_type>&>())),
                                     decltype(std::declval<const S&>().unsigned_within(
                                         std::declval<const Vec3<typename S::scalar_type>&>(),
                                         std::declval<typename S::scalar_type>())),
                                     decltype(std::declval<const S&>().sign_at(
                                         std::declval<const Vec3<typename S::scalar_type>&>())),
                                     decltype(std::declval<const S&>().sign_over(
                                         std::declval<const Aabb<typename S::scalar_type>&>()))>>
    : std::true_type {};
} // namespace detail

/// True when `S` follows the split-sign protocol, all const, thread-safe members:
/// - `T unsigned_distance(const Vec3<T>& p)`: |S(p)| bit for bit (NaN for a non-finite p);
/// - `T unsigned_within(const Vec3<T>& p, T max)`: |S(p)| bit for bit when |S(p)| <= max, else
///   any value > max (a search bounded by `max`);
/// - `Sign sign_at(const Vec3<T>& p)`: the sign S has at p if |S(p)| > 0 (never `unknown`), so
///   that `S(p) == apply_sign(unsigned_distance(p), sign_at(p))` bit for bit;
/// - `Sign sign_over(const Aabb<T>& box)`: a sign every point of `box` gets from `sign_at`, or
///   `unknown` when none is proven (never a wrong one).
template <class S> inline constexpr bool has_split_sign_v = detail::has_split_sign<S>::value;

namespace detail {
template <class S, class = void> struct has_batch_sign : std::false_type {};
template <class S>
struct has_batch_sign<
    S, std::void_t<decltype(std::declval<const S&>().signs_at(
           std::declval<Span<const Vec3<typename S::scalar_type>>>(), std::declval<Span<Sign>>()))>>
    : std::true_type {};
} // namespace detail

/// True when a split-sign `S` also has the batch form `void signs_at(Span<const Vec3<T>> pts,
/// Span<Sign> out) const`: `out[i] = sign_at(pts[i])` for every i, faster for runs of nearby
/// points (grid samplers pass a tile's unsigned samples in groups of neighbours).
template <class S> inline constexpr bool has_batch_sign_v = detail::has_batch_sign<S>::value;

namespace detail {
template <class S, class = void> struct has_sign_scope : std::false_type {};
template <class S>
struct has_sign_scope<S,
                      std::void_t<typename S::SignScope,
                                  decltype(std::declval<const S&>().sign_scope(
                                      std::declval<const Aabb<typename S::scalar_type>&>(),
                                      std::declval<typename S::SignScope&>())),
                                  decltype(std::declval<const typename S::SignScope&>().sign_over(
                                      std::declval<const Aabb<typename S::scalar_type>&>()))>>
    : std::true_type {};
} // namespace detail

/// True when a split-sign `S` also has scoped box signs: a type `S::SignScope` with `Sign
/// sign_over(const Aabb<T>& box) const`, filled by `void sign_scope(const Aabb<T>& scope,
/// SignScope& out) const`, whose answers for boxes inside the scope mean what `S::sign_over`'s
/// do (grid samplers use it for the boxes inside one far tile).
template <class S> inline constexpr bool has_sign_scope_v = detail::has_sign_scope<S>::value;

namespace detail {
/// Calls `f(x, y, z)` for every sample of a block of `dims[0] x dims[1] x dims[2]` lattice
/// samples, in groups of 4x4x2 neighbours (x fastest inside a group and between groups): the
/// order in which a batch sign's caller lists samples, so that the packets of `signs_at` (32
/// points) hold nearby points.
template <class F> void for_each_in_sign_groups(const std::array<std::size_t, 3>& dims, F&& f) {
  for (std::size_t gz = 0; gz < dims[2]; gz += 2)
    for (std::size_t gy = 0; gy < dims[1]; gy += 4)
      for (std::size_t gx = 0; gx < dims[0]; gx += 4)
        for (std::size_t z = gz; z < std::min(dims[2], gz + 2); ++z)
          for (std::size_t y = gy; y < std::min(dims[1], gy + 4); ++y)
            for (std::size_t x = gx; x < std::min(dims[0], gx + 4); ++x) f(x, y, z);
}
} // namespace detail

} // namespace ebgeom
