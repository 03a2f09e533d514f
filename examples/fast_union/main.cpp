// The EBGeometry seeds' union example: M^3 spheres of radius r on a lattice in [-1, 1]^3, their
// standard union (every sphere per query) against the BVH-accelerated union. Prints the times per
// query and the speedups, and checks that every union gives the same value bit for bit.
//
// Two standard unions are timed: the seeds' design (a vector of shared_ptr to a polymorphic SDF
// base, one virtual call per sphere per query: EBGeometry's `Union<T>`), which the seeds' 7,580x
// figure is measured against, and ebgeom's own inlined linear loop over a vector of value-type
// spheres (no virtual call; vectorised), a much faster baseline.
//
// Usage: ebgeom_example_fast_union [M=40] [samples=1000] [repetitions=5]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <random>
#include <vector>

#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/shapes.hpp"

namespace {
using T = double;
using ebgeom::Aabb;
using ebgeom::SdfKind;
using ebgeom::Vec3;

using Ball = ebgeom::Sphere<T>; // exact

/// The seeds' SDF interface: a polymorphic base held through shared_ptr.
struct SignedDistanceFunction {
  virtual ~SignedDistanceFunction() = default;
  virtual T signedDistance(const Vec3<T>& p) const noexcept = 0;
};
struct SphereSdf final : SignedDistanceFunction {
  explicit SphereSdf(const Ball& b) : ball(b) {}
  T signedDistance(const Vec3<T>& p) const noexcept override { return ball(p); }
  Ball ball;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <class Fn> double seconds(Fn&& fn) {
  const auto t0 = std::chrono::steady_clock::now();
  fn();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
} // namespace

int main(int argc, char** argv) {
  const int M = argc > 1 ? std::atoi(argv[1]) : 40;
  const int samples = argc > 2 ? std::atoi(argv[2]) : 1000;
  const int reps = argc > 3 ? std::atoi(argv[3]) : 5;
  constexpr T radius = 0.02;
  const T delta = (2.0 - 2 * M * radius) / (M + 1);
  if (M < 1 || samples < 1 || reps < 1 || delta < 0) {
    std::fprintf(stderr, "usage: %s [M >= 1, 2 M r <= 2] [samples >= 1] [repetitions >= 1]\n",
                 argv[0]);
    return 2;
  }
  std::vector<Ball> spheres;
  for (int i = 1; i <= M; ++i)
    for (int j = 1; j <= M; ++j)
      for (int k = 1; k <= M; ++k)
        spheres.push_back(
            {{-1. + i * (delta + 2 * radius) - radius, -1. + j * (delta + 2 * radius) - radius,
              -1. + k * (delta + 2 * radius) - radius},
             radius});
  std::printf("%zu spheres of radius %g, delta = %g\n", spheres.size(), radius, delta);

  // The seeds' standard union: shared_ptr<SDF> objects, one virtual call per sphere.
  std::vector<std::shared_ptr<const SignedDistanceFunction>> poly;
  for (const Ball& b : spheres) poly.push_back(std::make_shared<const SphereSdf>(b));
  auto seeds_union = [&](const Vec3<T>& p) {
    T d = std::numeric_limits<T>::infinity();
    for (const auto& s : poly) d = std::min(d, s->signedDistance(p));
    return d;
  };
  // ebgeom's linear union: value types, inlined.
  const std::vector<Ball> linear = spheres;
  auto linear_union = [&](const Vec3<T>& p) {
    T d = std::numeric_limits<T>::infinity();
    for (const Ball& b : linear) d = std::min(d, b(p));
    return d;
  };
  ebgeom::BvhUnion<Ball> fast;
  const double build = seconds([&] { fast = ebgeom::BvhUnion<Ball>(spheres); });
  std::printf("BVH build: %.2f ms\n", build * 1e3);

  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<T> u(-1, 1);
  std::vector<Vec3<T>> pts(static_cast<std::size_t>(samples));
  for (auto& p : pts) p = {u(rng), u(rng), u(rng)};

  std::vector<T> a(pts.size()), b(pts.size()), c(pts.size());
  std::vector<double> t_seeds, t_linear, t_fast;
  for (int r = 0; r < reps; ++r) {
    t_seeds.push_back(seconds([&] {
      for (std::size_t i = 0; i < pts.size(); ++i) a[i] = seeds_union(pts[i]);
    }));
    t_linear.push_back(seconds([&] {
      for (std::size_t i = 0; i < pts.size(); ++i) b[i] = linear_union(pts[i]);
    }));
    t_fast.push_back(seconds([&] {
      for (std::size_t i = 0; i < pts.size(); ++i) c[i] = fast(pts[i]);
    }));
  }
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < pts.size(); ++i)
    mismatches +=
        std::memcmp(&a[i], &c[i], sizeof(T)) != 0 || std::memcmp(&b[i], &c[i], sizeof(T)) != 0;
  const double n = double(samples);
  const double seeds_q = median(t_seeds) / n, linear_q = median(t_linear) / n,
               fast_q = median(t_fast) / n;
  std::printf("medians of %d runs of %d queries\n", reps, samples);
  std::printf("standard union (virtual, as the seeds): %.6f ms per query\n", seeds_q * 1e3);
  std::printf("linear union (inlined value types):     %.6f ms per query\n", linear_q * 1e3);
  std::printf("BVH union:                              %.6f ms per query\n", fast_q * 1e3);
  std::printf("speedup = %.1f (vs the seeds' standard union)\n", seeds_q / fast_q);
  std::printf("speedup = %.1f (vs the inlined linear union)\n", linear_q / fast_q);
  std::printf("identical values: %zu of %d%s\n", pts.size() - mismatches, samples,
              mismatches ? "  MISMATCH" : "");
  return mismatches ? 1 : 0;
}
