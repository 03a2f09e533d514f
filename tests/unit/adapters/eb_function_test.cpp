// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/adapters/eb_function.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <type_traits>
#include <vector>

#include "eb_test_scenes.hpp"
#include "ebgeom/sdf/any_sdf.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using adapter_test::Ball;

namespace {

const Aabb<double> probe_box = Aabb<double>::of({-1.5, -1.5, -1.5}, {1.5, 1.5, 1.5});

// The adapter's value equals sign * S bit for bit at every probe point, in 3D and on a 2D slice.
template <class S> void expect_signed_copy_of(const S& sdf, int sign, double z_slice) {
  EbOptions opt;
  opt.fluid = sign < 0 ? FluidSide::outside : FluidSide::inside;
  opt.z_slice = z_slice;
  const EbFunction<S> f(sdf, opt);
  using T = sdf_scalar_t<S>;
  for (const auto& p : test::random_points(probe_box, 500, 3)) {
    const T s3 = sdf(Vec3<T>{T(p.x), T(p.y), T(p.z)});
    const T s2 = sdf(Vec3<T>{T(p.x), T(p.y), T(z_slice)});
    EXPECT_EQ(f(p.x, p.y, p.z), double(T(sign) * s3));
    EXPECT_EQ(f(p.x, p.y), double(T(sign) * s2));
  }
}

} // namespace

TEST(EbFunction, FluidOutsideFlipsTheSign) {
  const EbFunction<Ball<double>> f(Ball<double>{});
  EXPECT_EQ(f.fluid_side(), FluidSide::outside);
  EXPECT_DOUBLE_EQ(f(3.0, 0.0, 0.0), -2.0); // outside the ball: fluid, negative for the EB code
  EXPECT_DOUBLE_EQ(f(0.0, 0.0, 0.0), 1.0);  // inside the ball: covered, positive
  EXPECT_DOUBLE_EQ(f(1.0, 0.0, 0.0), 0.0);  // boundary
}

TEST(EbFunction, FluidInsideKeepsTheSign) {
  EbOptions opt;
  opt.fluid = FluidSide::inside;
  const EbFunction<Ball<double>> f(Ball<double>{}, opt);
  EXPECT_EQ(f.fluid_side(), FluidSide::inside);
  EXPECT_DOUBLE_EQ(f(3.0, 0.0, 0.0), 2.0);
  EXPECT_DOUBLE_EQ(f(0.0, 0.0, 0.0), -1.0);
}

TEST(EbFunction, EbSignMatchesTheDocumentedConvention) {
  static_assert(eb_sign(FluidSide::outside) == -1 && eb_sign(FluidSide::inside) == 1);
  const EbOptions defaults;
  EXPECT_EQ(defaults.fluid, FluidSide::outside);
  EXPECT_EQ(defaults.z_slice, 0.0);
}

TEST(EbFunction, OutOfRangeFluidSideIsNaNNotASide) {
  static_assert(eb_sign(static_cast<FluidSide>(2)) == 0);
  EbOptions opt;
  opt.fluid = static_cast<FluidSide>(2);
  const EbFunction<Ball<double>> f(Ball<double>{}, opt);
  EXPECT_TRUE(std::isnan(f(3.0, 0.0, 0.0)));
  EXPECT_TRUE(std::isnan(f(0.0, 0.0, 0.0)));
  EXPECT_TRUE(std::isnan(f(0.5, 0.5)));
}

TEST(EbFunction, TwoDimensionalCallsEvaluateTheConfiguredSlice) {
  EbOptions opt;
  opt.z_slice = 0.6;
  const EbFunction<Ball<double>> f(Ball<double>{}, opt);
  EXPECT_EQ(f.z_slice(), 0.6);
  for (const auto& p : test::random_points(Aabb<double>::of({-2, -2, -2}, {2, 2, 2}), 200)) {
    // An independent formula: equal up to rounding (FMA builds round the norm differently, and
    // 1 - |p| cancels), so a tolerance rather than 4 ulps.
    EXPECT_NEAR(f(p.x, p.y), -(norm(Vec3<double>{p.x, p.y, 0.6}) - 1.0), 1e-14);
    const double xy[2] = {p.x, p.y};
    const double xyz[3] = {p.x, p.y, p.z};
    EXPECT_EQ(f.value(xy, 2), f(p.x, p.y));
    EXPECT_EQ(f.value(xyz, 3), f(p.x, p.y, p.z));
  }
  // the slice misses the ball entirely above |z| = 1: every 2D point is fluid
  opt.z_slice = 1.25;
  const EbFunction<Ball<double>> above(Ball<double>{}, opt);
  EXPECT_LT(above(0.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(above(0.0, 0.0), -0.25);
}

TEST(EbFunction, FloatGeometryWithDoubleCoordinates) {
  const EbFunction<Ball<float>> f(Ball<float>{{0.5f, 0, 0}});
  EXPECT_NEAR(f(2.5, 0.0, 0.0), -1.0, 1e-6);
  EXPECT_NEAR(f(2.5f, 0.0f, 0.0f), -1.0f, 1e-6f);
}

TEST(EbFunction, MeshSdfSignAndSliceAreExactCopiesOfS) {
  const auto mesh = adapter_test::icosphere_sdf<double>();
  expect_signed_copy_of(*mesh, -1, 0.0);
  expect_signed_copy_of(*mesh, +1, 0.3);
  const auto meshf = adapter_test::icosphere_sdf<float>();
  expect_signed_copy_of(*meshf, -1, 0.25);
  // inside the icosphere (radius 0.8) is covered when the fluid is outside
  const auto f = make_eb_function(mesh);
  EXPECT_GT(f(0.0, 0.0, 0.0), 0.7);
  EXPECT_LT(f(1.5, 0.0, 0.0), -0.6);
}

TEST(EbFunction, CsgSceneAndTypeErasedSdf) {
  const auto scene = adapter_test::csg_scene();
  expect_signed_copy_of(scene, -1, 0.0);
  expect_signed_copy_of(scene, +1, -0.5);
  const AnySdf<double> erased(scene);
  expect_signed_copy_of(erased, -1, 0.1);
  const auto f = make_eb_function(scene);
  const auto g = make_eb_function(erased);
  for (const auto& p : test::random_points(probe_box, 200, 5))
    EXPECT_EQ(f(p.x, p.y, p.z), g(p.x, p.y, p.z));
}

TEST(EbFunction, CopiesShareOneImmutableGeometry) {
  const EbFunction<Ball<double>> f(Ball<double>{{1, 2, 3}});
  EXPECT_EQ(f.shared_sdf().use_count(), 1);
  const EbFunction<Ball<double>> g = f; // what AMReX does when it stores the function
  const auto h = std::make_unique<EbFunction<Ball<double>>>(g); // what a Chombo clone does
  EXPECT_EQ(&g.sdf(), &f.sdf());
  EXPECT_EQ(&h->sdf(), &f.sdf());
  EXPECT_EQ(f.shared_sdf().use_count(), 3);
  EXPECT_LE(sizeof(f), 2 * sizeof(void*) + 2 * sizeof(double));
  // one geometry shared between two adapters with different fluid sides (e.g. two AMR codes)
  EbOptions inside;
  inside.fluid = FluidSide::inside;
  const EbFunction<Ball<double>> k(f.shared_sdf(), inside);
  EXPECT_EQ(&k.sdf(), &f.sdf());
  EXPECT_DOUBLE_EQ(k(0.0, 0.0, 0.0), -f(0.0, 0.0, 0.0));
  const auto m = f.with_options(inside);
  EXPECT_EQ(&m.sdf(), &f.sdf());
  EXPECT_EQ(m.fluid_side(), FluidSide::inside);
  EXPECT_EQ(m(0.5, 2.0, 3.0), k(0.5, 2.0, 3.0));
}

TEST(EbFunction, CopyingTheAdapterNeverCopiesTheGeometry) {
  using adapter_test::CopyCountingBall;
  const long before = CopyCountingBall::copies();
  const EbFunction<CopyCountingBall> f{CopyCountingBall{}}; // moved in, not copied
  EXPECT_EQ(CopyCountingBall::copies(), before);
  std::vector<EbFunction<CopyCountingBall>> copies(1000, f);
  EbFunction<CopyCountingBall> assigned = copies.back();
  assigned = f;
  const auto other = f.with_options(EbOptions{FluidSide::inside, 0.5});
  EXPECT_EQ(CopyCountingBall::copies(), before);
  EXPECT_EQ(f.shared_sdf().use_count(), 1003);
  EXPECT_EQ(other(0.0, 0.0, 0.0), -1.0);
}

TEST(EbFunction, MakeEbFunctionDeducesAndShares) {
  auto owned = std::make_shared<Ball<double>>(Ball<double>{{0, 0, 1}});
  const auto f = make_eb_function(owned); // shared_ptr<S> -> shared_ptr<const S>
  EXPECT_EQ(&f.sdf(), owned.get());
  static_assert(std::is_same_v<decltype(f), const EbFunction<Ball<double>>>);
  const auto g = make_eb_function(Ball<double>{}, EbOptions{FluidSide::inside, 0.0});
  EXPECT_EQ(g.options().fluid, FluidSide::inside);
  EXPECT_EQ(g(0.0, 0.0, 0.0), -1.0);
  const Aabb<double> b = f.bounds();
  EXPECT_EQ(b.lo.z, 0.0);
  EXPECT_EQ(b.hi.z, 2.0);
}
