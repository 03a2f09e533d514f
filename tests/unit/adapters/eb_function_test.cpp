#include "ebgeom/adapters/eb_function.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <thread>
#include <vector>

#include "test_support.hpp"

using namespace ebgeom;

namespace {

// A closed-form test geometry (sphere of radius 1 at c), independent of the shapes module.
template <class T> struct Ball {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;
  Vec3<T> c{0, 0, 0};
  T operator()(const Vec3<T>& p) const noexcept { return norm(p - c) - T(1); }
  Aabb<T> bounds() const noexcept { return Aabb<T>(c, c).grown(T(1)); }
};

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

TEST(EbFunction, TwoDimensionalCallsEvaluateTheConfiguredSlice) {
  EbOptions opt;
  opt.z_slice = 0.6;
  const EbFunction<Ball<double>> f(Ball<double>{}, opt);
  for (const auto& p : test::random_points(Aabb<double>::of({-2, -2, -2}, {2, 2, 2}), 200)) {
    EXPECT_DOUBLE_EQ(f(p.x, p.y), -(norm(Vec3<double>{p.x, p.y, 0.6}) - 1.0));
    const double xy[2] = {p.x, p.y};
    const double xyz[3] = {p.x, p.y, p.z};
    EXPECT_EQ(f.value(xy, 2), f(p.x, p.y));
    EXPECT_EQ(f.value(xyz, 3), f(p.x, p.y, p.z));
  }
}

TEST(EbFunction, FloatGeometryWithDoubleCoordinates) {
  const EbFunction<Ball<float>> f(Ball<float>{{0.5f, 0, 0}});
  EXPECT_NEAR(f(2.5, 0.0, 0.0), -1.0, 1e-6);
  EXPECT_NEAR(f(2.5f, 0.0f, 0.0f), -1.0f, 1e-6f);
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
}

TEST(EbFunction, ConcurrentCallsMatchSerialOnes) {
  const EbFunction<Ball<double>> f(Ball<double>{{0.1, 0.2, 0.3}});
  const auto pts = test::random_points(Aabb<double>::of({-2, -2, -2}, {2, 2, 2}), 20000, 9);
  std::vector<double> serial(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) serial[i] = f(pts[i].x, pts[i].y, pts[i].z);
  std::vector<double> par(pts.size());
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      const EbFunction<Ball<double>> mine = f; // each thread holds its own copy, as AMReX does
      for (std::size_t i = t; i < pts.size(); i += 4) par[i] = mine(pts[i].x, pts[i].y, pts[i].z);
    });
  for (auto& th : threads) th.join();
  EXPECT_EQ(par, serial);
}
