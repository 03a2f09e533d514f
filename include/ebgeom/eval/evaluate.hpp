// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `evaluate(sdf, points, out, ExecOptions)`: the batch form of `sdf(p)`, threaded, plus the
/// trait that lets runtime (type-erased) SDFs take whole batches.

#include <algorithm>
#include <cstddef>
#include <type_traits>
#include <utility>

#include "ebgeom/core/error.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

namespace detail {
template <class S, class = void> struct has_batch_eval : std::false_type {};
template <class S>
struct has_batch_eval<S, std::void_t<decltype(std::declval<const S&>().eval(
                             std::declval<Span<const Vec3<typename S::scalar_type>>>(),
                             std::declval<Span<typename S::scalar_type>>()))>> : std::true_type {};

template <class S, class = void> struct has_bounded_query : std::false_type {};
template <class S>
struct has_bounded_query<S, std::void_t<decltype(std::declval<const S&>().bounded(
                                std::declval<const Vec3<typename S::scalar_type>&>(),
                                std::declval<typename S::scalar_type>()))>>
    : std::is_convertible<decltype(std::declval<const S&>().bounded(
                              std::declval<const Vec3<typename S::scalar_type>&>(),
                              std::declval<typename S::scalar_type>())),
                          typename S::scalar_type> {};

template <class S, class = void> struct has_dynamic_kind : std::false_type {};
template <class S>
struct has_dynamic_kind<S, std::void_t<decltype(std::declval<const S&>().dynamic_kind())>>
    : std::true_type {};
} // namespace detail

/// True when `S` has a batch member `void eval(Span<const Vec3<T>>, Span<T>) const` (as
/// `AnySdf<T>` and the CLI's scene programs do). Batch evaluators then call it once per batch
/// instead of `S::operator()` once per point.
template <class S> inline constexpr bool has_batch_eval_v = detail::has_batch_eval<S>::value;

/// True when `S` (an `exact` SDF) has a bounded query
/// `T bounded(const Vec3<T>& p, T max_abs) const noexcept` that returns exactly `S(p)` (bit for
/// bit) whenever |S(p)| <= max_abs, and otherwise any value v with |v| > max_abs whose sign is not
/// trusted (`MeshSdf` has one). Grid samplers then seed each search with a neighbour's value
/// (1-Lipschitz) and narrow-band searches with the band.
template <class S> inline constexpr bool has_bounded_query_v = detail::has_bounded_query<S>::value;

/// The kind of `sdf`: `sdf.dynamic_kind()` when `S` provides it (runtime-composed SDFs whose
/// static `kind` must be conservative), otherwise `S::kind`.
template <class S> constexpr SdfKind kind_of(const S& sdf) noexcept {
  if constexpr (detail::has_dynamic_kind<S>::value)
    return sdf.dynamic_kind();
  else
    return (void)sdf, S::kind;
}

/// Writes `sdf(points[i])` to `out[i]` for a contiguous batch, serially. Uses the batch member
/// `eval` when `S` has one. Precondition: `out.size() >= points.size()`.
template <class S>
inline void evaluate_serial(const S& sdf, Span<const Vec3<sdf_scalar_t<S>>> points,
                            Span<sdf_scalar_t<S>> out) {
  if constexpr (has_batch_eval_v<S>) {
    sdf.eval(points, out.first(points.size()));
  } else {
    for (std::size_t i = 0; i < points.size(); ++i) out[i] = sdf(points[i]);
  }
}

/// Evaluates `sdf` at every point: `out[i] = S(points[i])` (S < 0 inside, > 0 outside).
/// Threads over batches of 256 points (`exec.threads`, 0 = all cores); results do not depend on the
/// thread count. `sdf` must be safe to call concurrently (every ebgeom SDF is).
/// Errors: `invalid_argument` when `out.size() != points.size()`. O(N * cost of one query).
template <class S>
Result<Ok> evaluate(const S& sdf, Span<const Vec3<sdf_scalar_t<S>>> points,
                    Span<sdf_scalar_t<S>> out, const ExecOptions& exec = {}) {
  EBGEOM_REQUIRE_SDF(S);
  if (out.size() != points.size())
    return make_error(ErrorCode::invalid_argument, "evaluate: ", points.size(), " points but ",
                      out.size(), " output values");
  constexpr std::size_t batch = 256;
  parallel_for(
      0, points.size(), batch,
      [&](std::size_t b, std::size_t e) {
        for (std::size_t s = b; s < e; s += batch) {
          const std::size_t n = std::min(batch, e - s);
          evaluate_serial(sdf, points.subspan(s, n), out.subspan(s, n));
        }
      },
      exec);
  return Ok{};
}

} // namespace ebgeom
