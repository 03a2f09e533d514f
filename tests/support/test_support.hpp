// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Shared helpers for ebgeom tests: typed-test lists, seeded random points, mesh paths.

#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom::test {

using FloatTypes = ::testing::Types<float, double>;

/// Tolerance scaled to the precision: about 1e-4 for float, 1e-10 for double.
template <class T> constexpr T tol() { return sizeof(T) == 4 ? T(1e-4) : T(1e-10); }

/// Deterministic uniform points in `box`.
template <class T>
std::vector<Vec3<T>> random_points(const Aabb<T>& box, std::size_t n, std::uint64_t seed = 42) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3<T>> pts(n);
  for (auto& p : pts) {
    p = {T(box.lo.x + (box.hi.x - box.lo.x) * u(rng)), T(box.lo.y + (box.hi.y - box.lo.y) * u(rng)),
         T(box.lo.z + (box.hi.z - box.lo.z) * u(rng))};
  }
  return pts;
}

/// Deterministic random unit vector stream.
template <class T> Vec3<T> random_unit(std::mt19937_64& rng) {
  std::normal_distribution<double> g(0.0, 1.0);
  for (;;) {
    const Vec3<double> v{g(rng), g(rng), g(rng)};
    const double n = norm(v);
    if (n > 1e-6) return Vec3<T>::from(v / n);
  }
}

/// True in the sanitizer builds (the compilers' own macros: GCC's __SANITIZE_*__, clang's
/// __has_feature). Their code runs 3 to 20 times slower, so the tests whose cost is the size of
/// their input (grid resolution, sample count, triangle count) use a smaller one there, through
/// `full_or_sanitized`: the same cases and code paths, fewer samples. The optimised builds check
/// every value at the full size.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
inline constexpr bool sanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
inline constexpr bool sanitized = true;
#else
inline constexpr bool sanitized = false;
#endif
#else
inline constexpr bool sanitized = false;
#endif

/// `full` in the optimised builds, `small` in the sanitizer builds.
template <class N> constexpr N full_or_sanitized(N full, N small) {
  return sanitized ? small : full;
}

/// Path of a shared test mesh, e.g. mesh_path("stanford-bunny.obj").
inline std::string mesh_path(const std::string& name) {
  return std::string(EBGEOM_TEST_MESH_DIR) + "/" + name;
}

inline bool file_exists(const std::string& path) { return std::ifstream(path).good(); }

} // namespace ebgeom::test

/// Skips the current test, saying why, when a shared mesh is not present.
#define EBGEOM_REQUIRE_MESH(name)                                                                  \
  do {                                                                                             \
    if (!::ebgeom::test::file_exists(::ebgeom::test::mesh_path(name)))                             \
      GTEST_SKIP() << "shared mesh " << ::ebgeom::test::mesh_path(name)                            \
                   << " is absent (tests read ../shared/meshes when it exists)";                   \
  } while (0)
