// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Geometries and helpers shared by the adapter tests (tests/unit/adapters and, through a relative
// include, tests/integrations): a mesh SDF, an analytic CSG scene, an SDF that counts its own
// copies, deterministic points and a "run on many threads" helper. No gtest dependency.

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <random>
#include <thread>
#include <vector>

#include "ebgeom/adapters/shared_mesh_sdf.hpp"
#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"

namespace ebgeom::adapter_test {

/// A closed-form test geometry (ball of radius 1 around c), independent of the shapes module.
template <class T> struct Ball {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> c{0, 0, 0};
  T operator()(const Vec3<T>& p) const noexcept { return norm(p - c) - T(1); }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(c).grown(T(1)); }
};

/// A ball that counts how often it is copied (copy construction and assignment), to prove that
/// the adapters never deep-copy their geometry. Thread-safe counter.
struct CopyCountingBall {
  using scalar_type = double;
  static constexpr SdfKind kind = SdfKind::exact;
  static std::atomic<long>& copies() {
    static std::atomic<long> n{0};
    return n;
  }
  CopyCountingBall() = default;
  CopyCountingBall(const CopyCountingBall&) noexcept { ++copies(); }
  CopyCountingBall(CopyCountingBall&&) noexcept = default;
  CopyCountingBall& operator=(const CopyCountingBall&) noexcept {
    ++copies();
    return *this;
  }
  CopyCountingBall& operator=(CopyCountingBall&&) noexcept = default;
  ~CopyCountingBall() = default;
  double operator()(const Vec3<double>& p) const noexcept { return norm(p) - 1.0; }
  Aabb<double> bounds() const noexcept { return Aabb<double>::of({-1, -1, -1}, {1, 1, 1}); }
};

/// Icosphere mesh (radius 0.8, 1280 triangles) through a BVH, built once and shared.
template <class T> SharedMeshSdf<T> icosphere_sdf(int subdivisions = 3) {
  return make_shared_mesh_sdf(make_icosphere<T>(subdivisions, T(0.8)).value()).value();
}

/// An analytic CSG scene: a box with a spherical bite, a rotated capsule and a torus ring.
inline auto csg_scene() {
  using T = double;
  const auto part = subtract(Box<T>{{0.6, 0.4, 0.3}}, Sphere<T>{{0.6, 0.4, 0.3}, 0.35});
  const auto arm = rotate(Capsule<T>{{-0.9, 0, 0}, {0.9, 0, 0}, 0.12}, Axis::z, T(30));
  const auto ring = Torus<T>{{0.0, 0.0, -0.5}, 0.5, 0.08};
  return unite(part, arm, ring);
}

/// Deterministic uniform points in `box`.
template <class T>
std::vector<Vec3<T>> points_in(const Aabb<T>& box, std::size_t n, std::uint64_t seed = 7) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3<T>> pts(n);
  for (auto& p : pts)
    p = {T(box.lo.x + (box.hi.x - box.lo.x) * u(rng)), T(box.lo.y + (box.hi.y - box.lo.y) * u(rng)),
         T(box.lo.z + (box.hi.z - box.lo.z) * u(rng))};
  return pts;
}

/// Runs `fn(t)` on `threads` threads at once (they start together) and joins them.
template <class Fn> void on_threads(int threads, Fn fn) {
  std::atomic<int> ready{0};
  std::vector<std::thread> pool;
  pool.reserve(std::size_t(threads));
  for (int t = 0; t < threads; ++t)
    pool.emplace_back([&, t] {
      ++ready;
      while (ready.load() < threads) std::this_thread::yield(); // maximise overlap
      fn(t);
    });
  for (auto& th : pool) th.join();
}

/// Number of threads the concurrency tests use: more than the cores, to force interleaving.
inline int test_threads() {
  const unsigned hw = std::thread::hardware_concurrency();
  return int(hw < 4 ? 8 : 2 * hw > 32 ? 32 : 2 * hw);
}

} // namespace ebgeom::adapter_test
