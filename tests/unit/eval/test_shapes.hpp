// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Tiny closed-form SDFs used by the eval tests (independent of the sdf module).

#include <cmath>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom::test {

/// Exact sphere.
template <class T> struct Ball {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> c;
  T r;
  T operator()(const Vec3<T>& p) const noexcept { return norm(p - c) - r; }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(c).grown(r); }
};

/// The same ball through a batch member (exercises the batch path) and counting nothing.
template <class T> struct BatchBall {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit; // conservative static kind
  Ball<T> ball;
  SdfKind dynamic_kind() const noexcept { return SdfKind::exact; }
  T operator()(const Vec3<T>& p) const noexcept { return ball(p); }
  void eval(Span<const Vec3<T>> p, Span<T> out) const {
    for (std::size_t i = 0; i < p.size(); ++i) out[i] = ball(p[i]);
  }
  Aabb<T> bounds() const noexcept { return ball.bounds(); }
};

/// Implicit (not a distance): 2 * (|p|^2 - r^2); same zero set and sign as a ball.
template <class T> struct ImplicitBall {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit;
  T r;
  T operator()(const Vec3<T>& p) const noexcept { return T(2) * (norm2(p) - r * r); }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(Vec3<T>::zero()).grown(r); }
};

} // namespace ebgeom::test
