// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `evaluate(sdf, points, out, ExecOptions)`: the batch form of `sdf(p)`, threaded (with the
/// SDF's batch `eval` where it has one: `has_batch_eval_v`, sdf/concepts.hpp).

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
/// thread count. An SDF whose batch `eval` sorts its points in space order (`has_ordered_batch_v`:
/// `MeshSdf`) gets instead one span per thread, split in about four for load balance (at least
/// 4096 points each; the whole input on one thread), so that it finds locality among many
/// points. `sdf` must be safe to call concurrently (every ebgeom SDF is).
/// Errors: `invalid_argument` when `out.size() != points.size()`. O(N * cost of one query).
template <class S>
Result<Ok> evaluate(const S& sdf, Span<const Vec3<sdf_scalar_t<S>>> points,
                    Span<sdf_scalar_t<S>> out, const ExecOptions& exec = {}) {
  EBGEOM_REQUIRE_SDF(S);
  if (out.size() != points.size())
    return make_error(ErrorCode::invalid_argument, "evaluate: ", points.size(), " points but ",
                      out.size(), " output values");
  std::size_t batch = 256;
  if constexpr (has_ordered_batch_v<S>) {
    const std::size_t t = std::size_t(resolve_threads(exec));
    batch = t <= 1 ? std::max<std::size_t>(points.size(), 1)
                   : std::max<std::size_t>(4096, (points.size() + 4 * t - 1) / (4 * t));
  }
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
