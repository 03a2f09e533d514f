// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The union of type-erased SDFs on EBGeometry's union example (M^3 spheres of radius 0.02 on a
// lattice in [-1, 1]^3; M = 40 gives 64,000): time per query of
//  - BvhUnion<Sphere<double>>          the statically typed union (reference),
//  - BvhUnion<AnySdf<double>>          the type-erased union, which prunes: each AnySdf carries
//                                      its wrapped shape's kind and bounds,
//  - the same objects with the kind hidden (a wrapper that reports only `implicit`, as AnySdf did
//    before it carried the kind): BvhUnion cannot prune and evaluates every object per query.
// Every union must give the same values as the typed one, bit for bit (exit 1 otherwise).
//
// Usage: ebgeom_bench_any_union_bench [M=40] [points=2000] [repetitions=5]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <vector>

#include "ebgeom/sdf/any_sdf.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/shapes.hpp"

namespace {
using T = double;
using ebgeom::Vec3;

/// An AnySdf whose kind is hidden: what a type-erased union saw before AnySdf carried its kind.
struct KindHidden {
  using scalar_type = T;
  static constexpr ebgeom::SdfKind kind = ebgeom::SdfKind::implicit;
  ebgeom::AnySdf<T> any;
  T operator()(const Vec3<T>& p) const noexcept { return any(p); }
  ebgeom::Aabb<T> bounds() const noexcept { return any.bounds(); }
};

template <class U>
double time_per_query(const U& u, const std::vector<Vec3<T>>& pts, int reps, std::vector<T>& out) {
  double best = 1e300;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < pts.size(); ++i) out[i] = u(pts[i]);
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count() / double(pts.size()));
  }
  return best;
}
} // namespace

int main(int argc, char** argv) {
  const int M = argc > 1 ? std::atoi(argv[1]) : 40;
  const std::size_t n = argc > 2 ? std::size_t(std::atol(argv[2])) : 2000;
  const int reps = argc > 3 ? std::atoi(argv[3]) : 5;
  constexpr T radius = 0.02;
  const T delta = (2.0 - 2 * M * radius) / (M + 1);
  std::vector<ebgeom::Sphere<T>> spheres;
  for (int i = 1; i <= M; ++i)
    for (int j = 1; j <= M; ++j)
      for (int k = 1; k <= M; ++k)
        spheres.push_back(
            {{-1. + i * (delta + 2 * radius) - radius, -1. + j * (delta + 2 * radius) - radius,
              -1. + k * (delta + 2 * radius) - radius},
             radius});
  std::vector<ebgeom::AnySdf<T>> any(spheres.begin(), spheres.end());
  std::vector<KindHidden> hidden;
  for (const auto& a : any) hidden.push_back({a});

  const ebgeom::BvhUnion<ebgeom::Sphere<T>> typed(spheres);
  const ebgeom::BvhUnion<ebgeom::AnySdf<T>> erased(any);
  const ebgeom::BvhUnion<KindHidden> opaque(hidden);
  static_assert(!ebgeom::BvhUnion<KindHidden>::prunes);

  std::mt19937_64 rng(1);
  std::uniform_real_distribution<T> u(-1, 1);
  std::vector<Vec3<T>> pts(n);
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};
  std::vector<T> a(n), b(n), c(n);
  const double t_typed = time_per_query(typed, pts, reps, a);
  const double t_erased = time_per_query(erased, pts, reps, b);
  const double t_opaque = time_per_query(opaque, pts, std::max(1, reps / 5), c);
  std::printf("%zu spheres, %zu random points in [-1, 1]^3, best of %d runs\n", spheres.size(), n,
              reps);
  std::printf("BvhUnion<Sphere<double>>                  %10.3f us/query\n", t_typed * 1e6);
  std::printf("BvhUnion<AnySdf<double>>, kind carried    %10.3f us/query (prunes)\n",
              t_erased * 1e6);
  std::printf("BvhUnion<AnySdf<double>>, kind hidden     %10.3f us/query (no pruning, as before)\n",
              t_opaque * 1e6);
  std::printf("speedup from carrying the kind: %.0fx\n", t_opaque / t_erased);
  const bool same = std::memcmp(a.data(), b.data(), n * sizeof(T)) == 0 &&
                    std::memcmp(a.data(), c.data(), n * sizeof(T)) == 0;
  std::printf("%s\n", same ? "identical values, bit for bit" : "VALUES DIFFER");
  return same ? 0 : 1;
}
