// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/geom/solid_angle.hpp"

#include <gtest/gtest.h>

#include <array>
#include <random>
#include <vector>

#include "test_support.hpp"

using namespace ebgeom;

namespace {

constexpr double pi = 3.14159265358979323846;

// Octahedron |x|+|y|+|z| = 1, outward CCW faces, built here independently of the mesh module.
template <class T> std::vector<std::array<Vec3<T>, 3>> octahedron() {
  std::vector<std::array<Vec3<T>, 3>> tris;
  for (int sx : {-1, 1})
    for (int sy : {-1, 1})
      for (int sz : {-1, 1}) {
        Vec3<T> a{T(sx), 0, 0}, b{0, T(sy), 0}, c{0, 0, T(sz)};
        if (dot(cross(b - a, c - a), Vec3<T>{T(sx), T(sy), T(sz)}) < 0) std::swap(b, c);
        tris.push_back({a, b, c});
      }
  return tris;
}

} // namespace

template <class T> class SolidAngleTest : public ::testing::Test {};
TYPED_TEST_SUITE(SolidAngleTest, test::FloatTypes);

TYPED_TEST(SolidAngleTest, OctantTriangleSubtendsAnEighthOfTheSphere) {
  using T = TypeParam;
  // seen from the origin, the triangle (e_x, e_y, e_z) covers exactly one octant: 4π/8
  const T w = solid_angle<T>({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1});
  EXPECT_NEAR(w, T(pi / 2), test::tol<T>());
  EXPECT_NEAR(solid_angle<T>({0, 0, 0}, {1, 0, 0}, {0, 0, 1}, {0, 1, 0}), T(-pi / 2),
              test::tol<T>());
  // in the plane, outside the triangle: zero
  EXPECT_EQ(solid_angle<T>({5, 5, 0}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}), T(0));
}

TYPED_TEST(SolidAngleTest, ClosedSurfaceGivesOneInsideZeroOutside) {
  using T = TypeParam;
  const auto tris = octahedron<T>();
  for (const auto& p :
       test::random_points(Aabb<T>::of({-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5}), 2000)) {
    const T l1 = std::abs(p.x) + std::abs(p.y) + std::abs(p.z);
    if (std::abs(l1 - 1) < T(1e-3)) continue;
    T w = 0;
    for (const auto& t : tris) w += solid_angle(p, t[0], t[1], t[2]);
    w /= T(4 * pi);
    EXPECT_NEAR(w, l1 < 1 ? T(1) : T(0), T(50) * test::tol<T>()) << p;
  }
}

TYPED_TEST(SolidAngleTest, DipoleExpansionConvergesInTheFarField) {
  using T = TypeParam;
  // a curved patch: half of a tessellated unit sphere (open, so its winding number is non-trivial)
  std::vector<std::array<Vec3<T>, 3>> tris;
  const int nu = 16, nv = 8;
  auto at = [](double u, double v) {
    return Vec3<T>{T(std::cos(u) * std::sin(v)), T(std::sin(u) * std::sin(v)), T(std::cos(v))};
  };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const double u0 = 2 * pi * i / nu, u1 = 2 * pi * (i + 1) / nu;
      const double v0 = 0.5 * pi * j / nv, v1 = 0.5 * pi * (j + 1) / nv;
      tris.push_back({at(u0, v0), at(u0, v1), at(u1, v1)});
      tris.push_back({at(u0, v0), at(u1, v1), at(u1, v0)});
    }
  const auto cl = make_dipole_cluster<T>(0, tris.size(),
                                         [&](std::size_t i, Vec3<T>& a, Vec3<T>& b, Vec3<T>& c) {
                                           a = tris[i][0], b = tris[i][1], c = tris[i][2];
                                         });
  EXPECT_LE(cl.radius, T(1.5));
  std::mt19937_64 rng(3);
  double prev_err = 1e9;
  for (double dist : {4.0, 8.0, 16.0, 32.0}) {
    double worst = 0;
    for (int k = 0; k < 50; ++k) {
      const Vec3<T> p = cl.center + test::random_unit<T>(rng) * T(dist);
      double exact = 0;
      for (const auto& t : tris) exact += double(solid_angle(p, t[0], t[1], t[2]));
      exact /= 4 * pi;
      worst = std::max(worst, std::abs(double(dipole_winding(cl, p)) - exact));
    }
    // the order-2 error decays like (r/d)^3 relative to the leading 1/d^2 term: ~d^-4 absolute
    if (dist > 4.0 && sizeof(T) == 8) {
      EXPECT_LT(worst, prev_err / 8) << "at distance " << dist;
    }
    EXPECT_LT(worst, 2e-3 * std::pow(4.0 / dist, 3) + (sizeof(T) == 4 ? 1e-6 : 0.0));
    prev_err = worst;
  }
}
