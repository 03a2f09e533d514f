// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Compiles the AMReX and Chombo adapters against minimal stand-ins of the APIs they use (in
// mock/, with the real headers' names and signatures), once with SPACEDIM 3 and once with 2, and
// checks through them: the sign convention (negative = fluid), 2D slicing, copies and clones that
// share the geometry (no deep copy), and concurrent calls equal to serial ones, with a mesh SDF
// and an analytic CSG scene. The 2D build also compiles Chombo in a namespace (CH_NAMESPACE).
#if AMREX_SPACEDIM == 2
#define CH_NAMESPACE
#endif

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <vector>

#include "../unit/adapters/eb_test_scenes.hpp"
#include "ebgeom_amrex.hpp"
#include "ebgeom_chombo.hpp"

#include <AMReX_EB2.H>

#include "GeometryShop.H"

using ebgeom::EbOptions;
using ebgeom::FluidSide;
using ebgeom::Vec3;
using namespace ebgeom::adapter_test;

namespace {

constexpr int dim = AMREX_SPACEDIM;
static_assert(CH_SPACEDIM == AMREX_SPACEDIM);

// The z that the EB codes' points have: their own in 3D, the slice in 2D.
double point_z(double z, const EbOptions& opt) { return dim == 3 ? z : opt.z_slice; }

amrex::RealArray real_array(double x, double y, double z) {
  amrex::RealArray p{};
  p[0] = x;
  p[1] = y;
  if constexpr (dim == 3) p[dim - 1] = z; // p[2] only exists in 3D
  (void)z;
  return p;
}

RealVect real_vect(double x, double y, double z) {
#if CH_SPACEDIM == 2
  (void)z;
  return RealVect(x, y);
#else
  return RealVect(x, y, z);
#endif
}

// AMReX's two call forms.
template <class F> amrex::Real amrex_call(const F& f, double x, double y, double z) {
#if AMREX_SPACEDIM == 2
  (void)z;
  return f(amrex::Real(x), amrex::Real(y));
#else
  return f(amrex::Real(x), amrex::Real(y), amrex::Real(z));
#endif
}

const ebgeom::Aabb<double> probe_box =
    ebgeom::Aabb<double>::of({-1.2, -1.2, -1.2}, {1.2, 1.2, 1.2});

// Both adapters give sign * S(x, y, z or slice), bit for bit, through every call form.
template <class S> void expect_adapters_match(const S& sdf, const EbOptions& opt) {
  const auto shared = std::make_shared<const S>(sdf);
  const ebgeom::AmrexImplicitFunction<S> a(shared, opt);
  const ebgeom::ChomboImplicitFunction<S> c(shared, opt);
  const BaseIF& base = c;
  const double sign = opt.fluid == FluidSide::outside ? -1.0 : 1.0;
  using T = ebgeom::sdf_scalar_t<S>;
  for (const auto& p : points_in(probe_box, 400, 23)) {
    const double z = point_z(p.z, opt);
    const double expected = double(T(sign) * sdf(Vec3<T>{T(p.x), T(p.y), T(z)}));
    EXPECT_EQ(amrex_call(a, p.x, p.y, p.z), expected);
    EXPECT_EQ(a(real_array(p.x, p.y, p.z)), expected);
    EXPECT_EQ(base.value(real_vect(p.x, p.y, p.z)), expected);
  }
}

} // namespace

TEST(AmrexAdapter, NegativeIsFluidOnTheChosenSide) {
  EbOptions opt;
  opt.z_slice = 0.5;
  const ebgeom::AmrexImplicitFunction<Ball<double>> f(Ball<double>{}, opt);
  const double z = dim == 3 ? 0.0 : 0.5; // 2D evaluates the slice
  EXPECT_DOUBLE_EQ(f(real_array(2.0, 0.0, 0.0)), -(std::sqrt(4.0 + z * z) - 1.0));
  EXPECT_GT(f(real_array(0.0, 0.0, 0.0)), 0.0); // inside the ball: body
  opt.fluid = FluidSide::inside;
  const auto g = ebgeom::make_amrex_implicit_function(Ball<double>{}, opt);
  EXPECT_LT(g(real_array(0.0, 0.0, 0.0)), 0.0); // inside the ball: fluid
  EXPECT_DOUBLE_EQ(g(real_array(2.0, 0.0, 0.0)), std::sqrt(4.0 + z * z) - 1.0);
  EXPECT_EQ(amrex_call(g, 2.0, 0.0, 0.0), g(real_array(2.0, 0.0, 0.0)));
}

TEST(AmrexAdapter, MakeShopCopiesShareTheGeometry) {
  const long before = CopyCountingBall::copies();
  const ebgeom::AmrexImplicitFunction<CopyCountingBall> f{CopyCountingBall{}};
  const ebgeom::AmrexImplicitFunction<CopyCountingBall> copy = f; // AMReX stores it by value
  auto gshop = amrex::EB2::makeShop(f);                           // and copies it into its shop
  auto gshop2 = amrex::EB2::makeShop(copy);
  const auto& held = gshop.GetImpFunc();
  EXPECT_EQ(&held.function().sdf(), &f.function().sdf());
  EXPECT_EQ(&gshop2.GetImpFunc().function().sdf(), &f.function().sdf());
  EXPECT_EQ(f.function().shared_sdf().use_count(), 4);
  EXPECT_EQ(CopyCountingBall::copies(), before); // the ball itself was never copied
  EXPECT_EQ(held(real_array(0.0, 0.0, 0.0)), 1.0);
}

TEST(ChomboAdapter, NegativeIsFluidOnTheChosenSide) {
  EbOptions opt;
  opt.fluid = FluidSide::inside;
  opt.z_slice = 0.5;
  const ebgeom::ChomboImplicitFunction<Ball<double>> f(Ball<double>{}, opt);
  std::unique_ptr<BaseIF> clone(f.newImplicitFunction());
  const double z = dim == 3 ? 0.0 : 0.5;
  const double expected = std::sqrt(0.0625 + z * z) - 1.0; // fluid inside: +S, negative inside
  EXPECT_DOUBLE_EQ(clone->value(real_vect(0.25, 0.0, 0.0)), expected);
  EXPECT_DOUBLE_EQ(f.value(real_vect(0.25, 0.0, 0.0)), expected);
  const ebgeom::ChomboImplicitFunction<Ball<double>> out(Ball<double>{},
                                                         EbOptions{FluidSide::outside, 0.5});
  EXPECT_DOUBLE_EQ(out.value(real_vect(0.25, 0.0, 0.0)), -expected); // fluid outside: -S
  // BaseIF's other `value` overload stays visible through the adapter (`using BaseIF::value`)
  IndexTM<int, GLOBALDIM> no_derivative;
  IndexTM<Real, GLOBALDIM> point;
  point[0] = 0.25;
  EXPECT_DOUBLE_EQ(f.value(no_derivative, point), expected);
}

TEST(ChomboAdapter, ClonesAndGeometryShopsShareTheGeometry) {
  const long before = CopyCountingBall::copies();
  const ebgeom::ChomboImplicitFunction<CopyCountingBall> f{CopyCountingBall{}};
  std::vector<std::unique_ptr<BaseIF>> clones;
  for (int i = 0; i < 100; ++i) clones.emplace_back(f.newImplicitFunction());
  const GeometryShop shop(f, 0, 0.1 * RealVect::Unit); // clones f, as Chombo's does
  using Adapter = ebgeom::ChomboImplicitFunction<CopyCountingBall>;
  EXPECT_EQ(&dynamic_cast<const Adapter&>(*clones[42]).function().sdf(), &f.function().sdf());
  EXPECT_EQ(&dynamic_cast<const Adapter&>(shop.implicitFunction()).function().sdf(),
            &f.function().sdf());
  EXPECT_EQ(f.function().shared_sdf().use_count(), 102);
  EXPECT_EQ(CopyCountingBall::copies(), before);
  EXPECT_EQ(shop.value(real_vect(0.0, 0.0, 0.0)), 1.0);
  clones.clear();
  EXPECT_EQ(f.function().shared_sdf().use_count(), 2);
}

TEST(Adapters, MeshSdfThroughBothCodes) {
  const auto mesh = icosphere_sdf<double>();
  expect_adapters_match(*mesh, EbOptions{});
  expect_adapters_match(*mesh, EbOptions{FluidSide::inside, 0.3});
  expect_adapters_match(*icosphere_sdf<float>(2), EbOptions{FluidSide::outside, -0.2});
}

TEST(Adapters, CsgSceneThroughBothCodes) {
  expect_adapters_match(csg_scene(), EbOptions{});
  expect_adapters_match(csg_scene(), EbOptions{FluidSide::inside, -0.5});
}

// AMReX evaluates its implicit function from OpenMP threads (one object, and copies in shops);
// Chombo's GeometryShop may be used per thread (one clone each). All must equal a serial run.
template <class S> void expect_threads_match_serial(std::shared_ptr<const S> sdf) {
  EbOptions opt;
  opt.z_slice = 0.1;
  const ebgeom::AmrexImplicitFunction<S> a(sdf, opt);
  const ebgeom::ChomboImplicitFunction<S> c(sdf, opt);
  const auto pts = points_in(probe_box, 2000, 29);
  std::vector<double> serial(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i)
    serial[i] = a(real_array(pts[i].x, pts[i].y, pts[i].z));
  const int n = test_threads();
  std::vector<std::vector<double>> amrex_one{std::size_t(n)}, amrex_copy{std::size_t(n)},
      chombo_clone{std::size_t(n)};
  on_threads(n, [&](int t) {
    const auto shop = amrex::EB2::makeShop(a);                    // a per-thread copy
    const std::unique_ptr<BaseIF> clone(c.newImplicitFunction()); // a per-thread clone
    const std::size_t u = std::size_t(t);
    for (auto* v : {&amrex_one[u], &amrex_copy[u], &chombo_clone[u]}) v->resize(pts.size());
    for (std::size_t k = 0; k < pts.size(); ++k) {
      const std::size_t i = (k + u * 97) % pts.size();
      amrex_one[u][i] = amrex_call(a, pts[i].x, pts[i].y, pts[i].z);
      amrex_copy[u][i] = shop.GetImpFunc()(real_array(pts[i].x, pts[i].y, pts[i].z));
      chombo_clone[u][i] = clone->value(real_vect(pts[i].x, pts[i].y, pts[i].z));
    }
  });
  for (int t = 0; t < n; ++t) {
    EXPECT_EQ(amrex_one[std::size_t(t)], serial) << "thread " << t;
    EXPECT_EQ(amrex_copy[std::size_t(t)], serial) << "thread " << t;
    EXPECT_EQ(chombo_clone[std::size_t(t)], serial) << "thread " << t;
  }
  EXPECT_EQ(sdf.use_count(), 3); // sdf, a and c: every thread's copy and clone is gone
}

TEST(Adapters, ConcurrentCallsMatchSerialWithMeshSdf) {
  expect_threads_match_serial(icosphere_sdf<double>());
}

TEST(Adapters, ConcurrentCallsMatchSerialWithCsgScene) {
  using Scene = decltype(csg_scene());
  expect_threads_match_serial(std::make_shared<const Scene>(csg_scene()));
}

// Chombo's GeometryShop asks the function's box hook first; the adapter's answer (one evaluation
// for a box far from the surface, else its nodes) must be the shop's own node-by-node answer, for
// single cells (what fillGraph asks) and larger boxes, on both fluid sides and with NaN signs.
template <class S>
void expect_inside_outside_equals_every_node(std::shared_ptr<const S> sdf, const EbOptions& opt,
                                             bool expect_fast) {
  const ebgeom::ChomboImplicitFunction<S> f(sdf, opt);
  const GeometryShop shop(f, 0);
  const ProblemDomain domain;
  const double origin_xyz[3] = {-1.05, -1.1, -0.95};
  RealVect origin = real_vect(origin_xyz[0], origin_xyz[1], origin_xyz[2]);
  const Real dx = 2.2 / 20;
  EXPECT_EQ(f.fastIntersection(Box(), domain, origin, dx), expect_fast);
  int seen[3] = {0, 0, 0};
  for (int size : {1, 2, 5}) {
    const int kmax = dim == 3 ? 20 - size : 0;
    for (int k = 0; k <= kmax; k += size)
      for (int j = 0; j <= 20 - size; j += size)
        for (int i = 0; i <= 20 - size; i += size) {
#if CH_SPACEDIM == 2
          const Box region(IntVect(i, j), IntVect(i + size - 1, j + size - 1));
#else
          const Box region(IntVect(i, j, k), IntVect(i + size - 1, j + size - 1, k + size - 1));
#endif
          const auto fast = shop.InsideOutside(region, domain, origin, dx);
          const auto slow = shop.InsideOutsideEveryNode(region, origin, dx);
          ASSERT_EQ(fast, slow) << "cells from (" << i << ", " << j << ", " << k << "), size "
                                << size;
          ++seen[int(slow)];
        }
  }
  EXPECT_GT(seen[GeometryService::Regular], 0);
  EXPECT_GT(seen[GeometryService::Covered], 0);
  EXPECT_GT(seen[GeometryService::Irregular], 0);
}

TEST(Adapters, ChomboInsideOutsideEqualsGeometryShopsNodeRule) {
  const auto mesh = icosphere_sdf<double>(); // closed: the pseudonormal sign, an exact SDF
  expect_inside_outside_equals_every_node(mesh, EbOptions{}, true);
  expect_inside_outside_equals_every_node(mesh, EbOptions{FluidSide::inside, 0.2}, true);
  expect_inside_outside_equals_every_node(icosphere_sdf<float>(2), EbOptions{}, true);
  using Scene = decltype(csg_scene());
  expect_inside_outside_equals_every_node(std::make_shared<const Scene>(csg_scene()),
                                          EbOptions{FluidSide::inside, 0.0}, true);
}
