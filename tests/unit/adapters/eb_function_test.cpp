// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/adapters/eb_function.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <type_traits>
#include <vector>

#include "eb_test_scenes.hpp"
#include "ebgeom/adapters/timed_sdf.hpp"
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

namespace {

// The lattice of nodes origin + i * dx that the EB codes evaluate, as they compute it.
struct Lattice {
  double origin[3] = {-1.23, -1.11, -1.37};
  double dx[3] = {0.071, 0.083, 0.077};
  double node(int d, int i) const { return origin[d] + double(i) * dx[d]; }
};

// Every node's value through the per-point call: the reference for node_values and node_signs.
template <class S>
std::vector<double> every_node(const EbFunction<S>& f, const Lattice& g, const int* lo,
                               const int* hi, int dim) {
  std::vector<double> v;
  const int klo = dim == 3 ? lo[2] : 0, khi = dim == 3 ? hi[2] : 0;
  for (int k = klo; k <= khi; ++k)
    for (int j = lo[1]; j <= hi[1]; ++j)
      for (int i = lo[0]; i <= hi[0]; ++i)
        v.push_back(dim == 3 ? f(g.node(0, i), g.node(1, j), g.node(2, k))
                             : f(g.node(0, i), g.node(1, j)));
  return v;
}

template <class S> void expect_box_paths_equal_points(const EbFunction<S>& f) {
  const Lattice g;
  // Boxes of odd sizes (not multiples of the 8^3 tiles), some far from the surface, some across.
  const int boxes[][6] = {{0, 0, 0, 34, 34, 34}, {3, 5, 7, 12, 9, 30}, {-2, 14, 15, 20, 21, 22},
                          {0, 0, 0, 0, 0, 0},    {30, 0, 0, 34, 6, 4}, {10, 10, 10, 26, 26, 26}};
  int mixed = 0, uniform = 0;
  for (int dim : {3, 2})
    for (const auto& b : boxes) {
      const int* lo = b;
      const int* hi = b + 3;
      const std::vector<double> ref = every_node(f, g, lo, hi, dim);
      std::vector<double> got(ref.size(), -7.0);
      f.node_values(g.origin, g.dx, lo, hi, dim, got.data());
      ASSERT_EQ(got, ref) << "box " << lo[0] << ".." << hi[0] << ", dim " << dim;
      EbSigns want;
      for (const double v : ref) (v > 0 ? want.positive : want.negative) |= !(v == 0);
      const EbSigns s = f.node_signs(g.origin, g.dx, lo, hi, dim);
      EXPECT_EQ(s.positive, want.positive) << "box " << lo[0] << ".." << hi[0] << ", dim " << dim;
      EXPECT_EQ(s.negative, want.negative) << "box " << lo[0] << ".." << hi[0] << ", dim " << dim;
      (want.positive && want.negative ? mixed : uniform)++;
      // A proved box has that sign at every node; a box with both signs is never proved.
      double blo[3], bhi[3];
      for (int d = 0; d < 3; ++d) {
        blo[d] = g.node(d, lo[d]);
        bhi[d] = g.node(d, hi[d]);
      }
      const int sign = f.box_sign(blo, bhi, dim);
      for (const double v : ref) {
        if (sign > 0) {
          EXPECT_GT(v, 0);
        }
        if (sign < 0) {
          EXPECT_LT(v, 0);
        }
      }
    }
  EXPECT_GT(mixed, 0);
  EXPECT_GT(uniform, 0);
}

} // namespace

TEST(EbFunction, BoxPathsEqualThePerPointCalls) {
  // A mesh (through eval_lattice) and closed forms (per point), on both fluid sides and slices.
  const auto mesh = adapter_test::icosphere_sdf<double>();
  expect_box_paths_equal_points(make_eb_function(mesh));
  expect_box_paths_equal_points(make_eb_function(mesh, EbOptions{FluidSide::inside, 0.3}));
  expect_box_paths_equal_points(make_eb_function(adapter_test::icosphere_sdf<float>(2)));
  expect_box_paths_equal_points(EbFunction<Ball<double>>(Ball<double>{{0.1, -0.2, 0.3}}));
  expect_box_paths_equal_points(make_eb_function(adapter_test::csg_scene()));
}

TEST(EbFunction, BoxProofsNeedADistanceBoundAndAValidSide) {
  const auto mesh = adapter_test::icosphere_sdf<double>();
  EXPECT_TRUE(make_eb_function(mesh).proves_boxes());
  // The winding sign (an open mesh, or asked for) is not a distance bound: no proof, every node.
  SignOptions winding;
  winding.mode = SignMode::fast_winding;
  const auto wound = make_shared_mesh_sdf(make_icosphere<double>(3, 0.8).value(), winding).value();
  const auto fw = make_eb_function(wound);
  EXPECT_FALSE(fw.proves_boxes());
  const double lo[3] = {2, 2, 2}, hi[3] = {3, 3, 3};
  EXPECT_EQ(fw.box_sign(lo, hi, 3), 0);
  expect_box_paths_equal_points(fw);
  // A FluidSide outside the enum gives NaN values: never proved, every NaN counted as fluid.
  const auto nan_side = make_eb_function(mesh, EbOptions{static_cast<FluidSide>(7), 0.0});
  EXPECT_FALSE(nan_side.proves_boxes());
  const Lattice g;
  const int ilo[3] = {0, 0, 0}, ihi[3] = {9, 9, 9};
  const EbSigns s = nan_side.node_signs(g.origin, g.dx, ilo, ihi, 3);
  EXPECT_TRUE(s.negative);
  EXPECT_FALSE(s.positive);
  // Far from the object one evaluation proves a big box: fluid outside, covered inside.
  const auto f = make_eb_function(mesh);
  const double far_lo[3] = {1.5, 1.5, 1.5}, far_hi[3] = {3, 3, 3};
  EXPECT_EQ(f.box_sign(far_lo, far_hi, 3), -1);
  const double in_lo[3] = {-0.2, -0.2, -0.2}, in_hi[3] = {0.2, 0.2, 0.2};
  EXPECT_EQ(f.box_sign(in_lo, in_hi, 3), 1);
  const double across_lo[3] = {0.5, -0.1, -0.1}, across_hi[3] = {1.0, 0.1, 0.1};
  EXPECT_EQ(f.box_sign(across_lo, across_hi, 3), 0);
}

TEST(TimedSdf, ForwardsBitForBitAndCountsEveryPoint) {
  const auto mesh = adapter_test::icosphere_sdf<double>();
  auto times = std::make_shared<SdfTimes>();
  const TimedSdf<SignedMeshSdf<double>> timed(mesh, times);
  static_assert(has_lattice_eval_v<TimedSdf<SignedMeshSdf<double>>>);
  static_assert(!has_lattice_eval_v<TimedSdf<Ball<double>>>);
  EXPECT_EQ(kind_of(timed), SdfKind::exact); // the pseudonormal sign of a closed mesh
  const auto plain = make_eb_function(mesh);
  const auto f = make_eb_function(timed);
  EXPECT_TRUE(f.proves_boxes());
  const auto pts = test::random_points(probe_box, 100, 11);
  for (const auto& p : pts) EXPECT_EQ(f(p.x, p.y, p.z), plain(p.x, p.y, p.z));
  EXPECT_EQ(times->calls, pts.size());
  const Lattice g;
  const int lo[3] = {0, 0, 0}, hi[3] = {9, 8, 7}; // 720 nodes: 8 tiles of up to 8^3
  std::vector<double> a(720), b(720);
  f.node_values(g.origin, g.dx, lo, hi, 3, a.data());
  plain.node_values(g.origin, g.dx, lo, hi, 3, b.data());
  EXPECT_EQ(a, b);
  EXPECT_EQ(times->lattice_points, 720u);
  EXPECT_EQ(times->lattice_calls, 4u); // x: 8 + 2, y: 8 + 1, z: 8
  EXPECT_EQ(times->points(), pts.size() + 720);
  EXPECT_GT(times->seconds(), 0.0);
}
