// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include <gtest/gtest.h>

#include <atomic>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid.hpp"
#include "test_shapes.hpp"
#include "test_support.hpp"

using namespace ebgeom;

template <class T> class GridTest : public ::testing::Test {};
TYPED_TEST_SUITE(GridTest, test::FloatTypes);

TYPED_TEST(GridTest, CellCentredPointsAndLayout) {
  using T = TypeParam;
  GridSpec<T> g{Aabb<T>({T(-1), T(0), T(2)}, {T(1), T(3), T(3)}), {{4, 6, 2}}, Centering::cell};
  ASSERT_TRUE(g.validate());
  EXPECT_EQ(g.size(), 48u);
  const Vec3<T> h = g.spacing();
  EXPECT_NEAR(h.x, T(0.5), test::tol<T>());
  EXPECT_NEAR(h.y, T(0.5), test::tol<T>());
  EXPECT_NEAR(h.z, T(0.5), test::tol<T>());
  const Vec3<T> p0 = g.point(0, 0, 0), p1 = g.point(3, 5, 1);
  EXPECT_NEAR(p0.x, T(-0.75), test::tol<T>());
  EXPECT_NEAR(p0.y, T(0.25), test::tol<T>());
  EXPECT_NEAR(p0.z, T(2.25), test::tol<T>());
  EXPECT_NEAR(p1.x, T(0.75), test::tol<T>());
  EXPECT_NEAR(p1.y, T(2.75), test::tol<T>());
  EXPECT_NEAR(p1.z, T(2.75), test::tol<T>());
  // x fastest.
  EXPECT_EQ(g.index(1, 0, 0), 1u);
  EXPECT_EQ(g.index(0, 1, 0), 4u);
  EXPECT_EQ(g.index(0, 0, 1), 24u);
}

TYPED_TEST(GridTest, NodeCentredIncludesBothFaces) {
  using T = TypeParam;
  GridSpec<T> g{Aabb<T>({T(0), T(0), T(0)}, {T(1), T(2), T(4)}), {{3, 5, 1}}, Centering::node};
  ASSERT_TRUE(g.validate());
  const Vec3<T> lo = g.point(0, 0, 0), hi = g.point(2, 4, 0);
  EXPECT_EQ(lo, g.box.lo);
  EXPECT_NEAR(hi.x, T(1), test::tol<T>());
  EXPECT_NEAR(hi.y, T(2), test::tol<T>());
  EXPECT_NEAR(g.spacing().z, T(4), test::tol<T>()); // one sample: the extent
}

TYPED_TEST(GridTest, ValidateRejectsBadSpecs) {
  using T = TypeParam;
  GridSpec<T> g;
  g.dims = {{0, 1, 1}};
  EXPECT_EQ(g.validate().error().code, ErrorCode::invalid_argument);
  g = GridSpec<T>{};
  g.box.hi.y = g.box.lo.y;
  auto r = g.validate();
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("axis y"), std::string::npos) << r.error().message;
  g = GridSpec<T>{};
  g.box.lo.x = std::numeric_limits<T>::quiet_NaN();
  EXPECT_FALSE(g.validate());
  g = GridSpec<T>{};
  g.box.lo.z = -std::numeric_limits<T>::max();
  g.box.hi.z = std::numeric_limits<T>::max(); // the extent overflows
  EXPECT_FALSE(g.validate());
}

TYPED_TEST(GridTest, SampleGridEqualsPointwiseForAnyThreadCount) {
  using T = TypeParam;
  const test::Ball<T> ball{{T(0.1), T(-0.2), T(0.05)}, T(0.7)};
  // Odd sizes: partial tiles on every axis.
  GridSpec<T> g{
      Aabb<T>({T(-1), T(-1), T(-1)}, {T(1), T(1.2), T(0.9)}), {{19, 11, 13}}, Centering::cell};
  std::vector<T> ref(g.size());
  for (std::size_t k = 0; k < g.nz(); ++k)
    for (std::size_t j = 0; j < g.ny(); ++j)
      for (std::size_t i = 0; i < g.nx(); ++i) ref[g.index(i, j, k)] = ball(g.point(i, j, k));
  for (int threads : {1, 2, 3}) {
    std::vector<T> out(g.size(), T(-99));
    GridOptions opt;
    opt.exec.threads = threads;
    ASSERT_TRUE(sample_grid(ball, g, Span<T>(out), opt));
    for (std::size_t n = 0; n < out.size(); ++n) ASSERT_EQ(out[n], ref[n]) << n;
  }
  // The batch path gives the same values.
  const test::BatchBall<T> batch{ball};
  std::vector<T> out(g.size());
  ASSERT_TRUE(sample_grid(batch, g, Span<T>(out)));
  EXPECT_EQ(out, ref);
}

TYPED_TEST(GridTest, NarrowBandIsExactInsideAndClampedOutside) {
  using T = TypeParam;
  const test::Ball<T> ball{{T(0), T(0), T(0)}, T(0.5)};
  const auto g = GridSpec<T>::cells(Aabb<T>({T(-1), T(-1), T(-1)}, {T(1), T(1), T(1)}), 40);
  std::vector<T> dense(g.size()), banded(g.size()), batch_banded(g.size());
  ASSERT_TRUE(sample_grid(ball, g, Span<T>(dense)));
  GridOptions opt;
  opt.band = 0.1;
  ASSERT_TRUE(sample_grid(ball, g, Span<T>(banded), opt));
  ASSERT_TRUE(sample_grid(test::BatchBall<T>{ball}, g, Span<T>(batch_banded), opt));
  const T band = T(0.1);
  std::size_t exact = 0;
  for (std::size_t n = 0; n < g.size(); ++n) {
    const T expect = std::abs(dense[n]) <= band ? dense[n] : std::copysign(band, dense[n]);
    ASSERT_EQ(banded[n], expect) << n;
    ASSERT_EQ(batch_banded[n], expect) << n;
    exact += std::abs(dense[n]) <= band;
  }
  EXPECT_GT(exact, 0u);
  // Implicit SDFs are evaluated everywhere and clamped: the sign is still right.
  std::vector<T> imp(g.size());
  ASSERT_TRUE(sample_grid(test::ImplicitBall<T>{T(0.5)}, g, Span<T>(imp), opt));
  for (std::size_t n = 0; n < g.size(); ++n) {
    if (std::abs(dense[n]) <= test::tol<T>()) continue;
    ASSERT_EQ(imp[n] < 0, dense[n] < 0) << n;
  }
}

TYPED_TEST(GridTest, ProgressReportsEveryTile) {
  using T = TypeParam;
  const test::Ball<T> ball{{T(0), T(0), T(0)}, T(0.5)};
  const auto g = GridSpec<T>::cells(Aabb<T>({T(-1), T(-1), T(-1)}, {T(1), T(1), T(1)}), 17);
  std::vector<T> out(g.size());
  std::atomic<std::size_t> calls{0}, last_total{0}, max_done{0};
  GridOptions opt;
  opt.exec.threads = 2;
  opt.progress = [&](std::size_t done, std::size_t total) {
    ++calls;
    last_total = total;
    std::size_t m = max_done.load();
    while (done > m && !max_done.compare_exchange_weak(m, done)) {
    }
  };
  ASSERT_TRUE(sample_grid(ball, g, Span<T>(out), opt));
  EXPECT_EQ(calls.load(), 27u); // ceil(17/8)^3
  EXPECT_EQ(last_total.load(), 27u);
  EXPECT_EQ(max_done.load(), 27u);
}

TYPED_TEST(GridTest, SampleGridErrors) {
  using T = TypeParam;
  const test::Ball<T> ball{{T(0), T(0), T(0)}, T(0.5)};
  const auto g = GridSpec<T>::cells(Aabb<T>({T(-1), T(-1), T(-1)}, {T(1), T(1), T(1)}), 4);
  std::vector<T> small(10);
  EXPECT_EQ(sample_grid(ball, g, Span<T>(small)).error().code, ErrorCode::invalid_argument);
  std::vector<T> out(g.size());
  GridOptions opt;
  opt.band = -1;
  EXPECT_EQ(sample_grid(ball, g, Span<T>(out), opt).error().code, ErrorCode::invalid_argument);
}

TYPED_TEST(GridTest, EvaluateBatchMatchesScalar) {
  using T = TypeParam;
  const test::Ball<T> ball{{T(0.3), T(0), T(0)}, T(0.5)};
  const auto pts = test::random_points(Aabb<T>({T(-1), T(-1), T(-1)}, {T(1), T(1), T(1)}), 3001);
  std::vector<T> out(pts.size()), out2(pts.size());
  ExecOptions ex;
  ex.threads = 2;
  ASSERT_TRUE(evaluate(ball, Span<const Vec3<T>>(pts), Span<T>(out), ex));
  ASSERT_TRUE(evaluate(test::BatchBall<T>{ball}, Span<const Vec3<T>>(pts), Span<T>(out2)));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    ASSERT_EQ(out[i], ball(pts[i]));
    ASSERT_EQ(out2[i], ball(pts[i]));
  }
  std::vector<T> wrong(3);
  EXPECT_EQ(evaluate(ball, Span<const Vec3<T>>(pts), Span<T>(wrong)).error().code,
            ErrorCode::invalid_argument);
  EXPECT_EQ(kind_of(test::BatchBall<T>{ball}), SdfKind::exact);
  EXPECT_EQ(kind_of(ball), SdfKind::exact);
}
