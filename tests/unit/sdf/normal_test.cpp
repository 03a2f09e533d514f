// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/normal.hpp"

#include <gtest/gtest.h>

#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"
#include "sdf_reference.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using test::V3;

template <class T> class NormalTest : public ::testing::Test {};
TYPED_TEST_SUITE(NormalTest, test::FloatTypes);

static_assert(has_analytic_gradient_v<Sphere<float>> && has_analytic_gradient_v<Box<double>> &&
              has_analytic_gradient_v<Plane<float>> && has_analytic_gradient_v<Capsule<double>> &&
              has_analytic_gradient_v<CappedCylinder<float>> &&
              has_analytic_gradient_v<Torus<double>>);
static_assert(!has_analytic_gradient_v<Ellipsoid<double>>);
static_assert(!has_analytic_gradient_v<Translated<Sphere<double>>>);

namespace {
template <class T> Vec3<T> v3(double x, double y, double z) { return {T(x), T(y), T(z)}; }

// Analytic gradient vs the test's own double-precision differences, away from kinks.
template <class S> void expect_analytic_matches_fd(const S& s, const Aabb<sdf_scalar_t<S>>& box) {
  using T = sdf_scalar_t<S>;
  const double h = sizeof(T) == 4 ? 2e-3 : 1e-6;
  const double tol = sizeof(T) == 4 ? 1e-2 : 1e-5;
  int checked = 0;
  for (const auto& p : test::random_points(box, 400, 31)) {
    const V3 fd = test::fd_gradient(s, p, h);
    if (std::abs(norm(fd) - 1) > 0.1 * tol) continue; // a kink inside the stencil
    ++checked;
    const V3 g = V3::from(analytic_gradient(s, p));
    EXPECT_NEAR(norm(g), 1.0, 1e-5);
    EXPECT_NEAR(norm(g - fd), 0.0, tol) << "at " << p;
  }
  EXPECT_GT(checked, 200);
}
} // namespace

TYPED_TEST(NormalTest, AnalyticGradientsMatchDifferences) {
  using T = TypeParam;
  const Aabb<T> cube = Aabb<T>::of(v3<T>(-2, -2, -2), v3<T>(2, 2, 2));
  expect_analytic_matches_fd(Sphere<T>{v3<T>(0.1, 0.2, 0.3), T(1)}, cube);
  expect_analytic_matches_fd(Box<T>{v3<T>(0.5, 0.8, 0.3), v3<T>(0.1, 0, 0)}, cube);
  expect_analytic_matches_fd(Plane<T>{v3<T>(1, 2, -2), T(0.5)}, cube);
  expect_analytic_matches_fd(Capsule<T>{v3<T>(-0.5, 0, 0), v3<T>(0.5, 0.7, 0.2), T(0.3)}, cube);
  expect_analytic_matches_fd(CappedCylinder<T>{v3<T>(-0.5, 0, 0), v3<T>(0.5, 0.7, 0.2), T(0.4)},
                             cube);
  expect_analytic_matches_fd(Torus<T>{v3<T>(0, 0.1, 0), T(1), T(0.3)}, cube);
}

TYPED_TEST(NormalTest, KnownNormalsAndFiniteDifferences) {
  using T = TypeParam;
  const Sphere<T> s{Vec3<T>::zero(), T(1)};
  const T tol = sizeof(T) == 4 ? T(1e-3) : T(1e-8);
  // on a sphere the normal is the radial direction
  std::mt19937_64 rng(2);
  for (int i = 0; i < 100; ++i) {
    const Vec3<T> u = test::random_unit<T>(rng);
    const Vec3<T> p = u * T(1.3);
    const Vec3<T> n = fd_normal(s, p, sizeof(T) == 4 ? T(1e-2) : T(1e-5));
    EXPECT_NEAR(norm(n - u), T(0), tol);
    EXPECT_NEAR(norm(normal(s, p, T(1e-3)) - u), T(0), test::tol<T>() * 10);
    // a translated sphere has no closed form here: normal() falls back to differences
    const auto moved = translate(s, v3<T>(1, 0, 0));
    EXPECT_NEAR(norm(normal(moved, p + v3<T>(1, 0, 0), sizeof(T) == 4 ? T(1e-2) : T(1e-5)) - u),
                T(0), tol);
  }
  // box faces, edges (diagonal) and inside (nearest face)
  const Box<T> b{v3<T>(1, 1, 1)};
  EXPECT_EQ(analytic_gradient(b, v3<T>(2, 0.3, -0.2)), v3<T>(1, 0, 0));
  EXPECT_EQ(analytic_gradient(b, v3<T>(0.1, -0.9, 0.2)), v3<T>(0, -1, 0));
  const Vec3<T> e = analytic_gradient(b, v3<T>(2, 2, 0));
  EXPECT_NEAR(e.x, T(std::sqrt(0.5)), test::tol<T>());
  EXPECT_NEAR(e.y, T(std::sqrt(0.5)), test::tol<T>());
  // a plane's normal is its unit normal everywhere
  EXPECT_EQ(analytic_gradient(Plane<T>{v3<T>(0, 0, 2), T(1)}, v3<T>(5, 5, 5)), v3<T>(0, 0, 1));
  // medial-axis points still give unit vectors
  EXPECT_NEAR(norm(analytic_gradient(s, Vec3<T>::zero())), T(1), test::tol<T>());
  EXPECT_NEAR(
      norm(analytic_gradient(Capsule<T>{Vec3<T>::zero(), v3<T>(1, 0, 0), T(1)}, v3<T>(0.5, 0, 0))),
      T(1), test::tol<T>());
  // fd_gradient of a linear field is exact up to rounding
  const Plane<T> pl{v3<T>(3, 0, 4), T(0)};
  const Vec3<T> g = fd_gradient(pl, v3<T>(0.3, 0.1, 0.2), T(0.01));
  EXPECT_NEAR(g.x, T(0.6), tol);
  EXPECT_NEAR(g.z, T(0.8), tol);
}
