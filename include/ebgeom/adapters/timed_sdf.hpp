// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `TimedSdf<S>`: an SDF that forwards to `S` and counts how often it is called and how long the
/// calls take, to see where an EB code's geometry generation spends its time (the example
/// programs' `mesh_sdf.profile = 1`). Wrap the geometry before handing it to an adapter:
///
/// ```cpp
/// auto times = std::make_shared<ebgeom::SdfTimes>();
/// ebgeom::TimedSdf<ebgeom::SignedMeshSdf<double>> timed(mesh, times);
/// ebgeom::AmrexImplicitFunction<decltype(timed)> f(timed);   // build the EB with f
/// // times->calls, times->lattice_points, times->seconds() afterwards
/// ```
///
/// Each call reads a steady clock twice (tens of nanoseconds), so the times include that
/// overhead: negligible next to a mesh query (microseconds), not next to an analytic shape.

#include <array>
#include <atomic>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <type_traits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

/// Counters shared by every copy of a `TimedSdf` (atomic: copies may run on several threads).
struct SdfTimes {
  std::atomic<std::uint64_t> calls{0};          ///< per-point calls
  std::atomic<std::uint64_t> lattice_calls{0};  ///< `eval_lattice` calls (tiles)
  std::atomic<std::uint64_t> lattice_points{0}; ///< points evaluated by those calls
  std::atomic<std::uint64_t> nanoseconds{0};    ///< time inside `S`, both kinds of call
  /// Points evaluated, one way or the other.
  std::uint64_t points() const noexcept { return calls + lattice_points; }
  double seconds() const noexcept { return double(nanoseconds) * 1e-9; }
};

/// Forwards to the shared `S` (same values, bit for bit; same kind and bounds) and adds each
/// call's count and duration to the shared `SdfTimes`. Has `eval_lattice` and `dynamic_kind`
/// exactly when `S` has them. Thread-safe when `S` is.
template <class S> class TimedSdf {
  EBGEOM_REQUIRE_SDF(S);
  using clock = std::chrono::steady_clock;

 public:
  using scalar_type = sdf_scalar_t<S>;
  static constexpr SdfKind kind = S::kind;

  /// Precondition: neither pointer is null.
  TimedSdf(std::shared_ptr<const S> sdf, std::shared_ptr<SdfTimes> times)
      : sdf_(std::move(sdf)), times_(std::move(times)) {
    EBGEOM_ASSERT(sdf_ != nullptr && times_ != nullptr);
  }

  scalar_type operator()(const Vec3<scalar_type>& p) const noexcept {
    const auto t0 = clock::now();
    const scalar_type v = (*sdf_)(p);
    add(t0, times_->calls, 1);
    return v;
  }

  template <class U = S, std::enable_if_t<has_lattice_eval_v<U>, int> = 0>
  void eval_lattice(Span<const Vec3<scalar_type>> pts, const std::array<std::size_t, 3>& dims,
                    Span<scalar_type> out) const {
    const auto t0 = clock::now();
    sdf_->eval_lattice(pts, dims, out);
    times_->lattice_points.fetch_add(pts.size(), std::memory_order_relaxed);
    add(t0, times_->lattice_calls, 1);
  }

  template <class U = S>
  auto dynamic_kind() const noexcept -> decltype(std::declval<const U&>().dynamic_kind()) {
    return sdf_->dynamic_kind();
  }

  Aabb<scalar_type> bounds() const noexcept { return sdf_->bounds(); }
  const S& sdf() const noexcept { return *sdf_; }
  const SdfTimes& times() const noexcept { return *times_; }

 private:
  void add(clock::time_point t0, std::atomic<std::uint64_t>& counter,
           std::uint64_t n) const noexcept {
    const auto ns = std::chrono::duration_cast<std::chrono::nanoseconds>(clock::now() - t0);
    times_->nanoseconds.fetch_add(std::uint64_t(ns.count()), std::memory_order_relaxed);
    counter.fetch_add(n, std::memory_order_relaxed);
  }

  std::shared_ptr<const S> sdf_;
  std::shared_ptr<SdfTimes> times_;
};

} // namespace ebgeom
