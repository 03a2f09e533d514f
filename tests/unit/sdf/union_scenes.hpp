// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Scenes shared by the union tests (BvhUnion, CachedUnion).

#include <cstring>
#include <vector>

#include "ebgeom/sdf/shapes.hpp"

namespace ebgeom::test {

/// The same ball declared as a bound: a union may not prune it.
template <class T> struct SoftBall : Sphere<T> { static constexpr SdfKind kind = SdfKind::bound; };

template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof(T)) == 0; }

/// EBGeometry's lattice: M^3 spheres of radius r in [-1, 1]^3.
template <class T> std::vector<Sphere<T>> lattice(int M, T r) {
  const T delta = (T(2) - T(2) * T(M) * r) / T(M + 1);
  std::vector<Sphere<T>> v;
  for (int i = 1; i <= M; ++i)
    for (int j = 1; j <= M; ++j)
      for (int k = 1; k <= M; ++k)
        v.push_back({{T(-1) + T(i) * (delta + 2 * r) - r, T(-1) + T(j) * (delta + 2 * r) - r,
                      T(-1) + T(k) * (delta + 2 * r) - r},
                     r});
  return v;
}

} // namespace ebgeom::test
