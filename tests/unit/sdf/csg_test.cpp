// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/csg.hpp"

#include <gtest/gtest.h>

#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/transforms.hpp"
#include "sdf_reference.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using test::V3;

template <class T> class CsgTest : public ::testing::Test {};
TYPED_TEST_SUITE(CsgTest, test::FloatTypes);

namespace {
template <class T> Vec3<T> v3(double x, double y, double z) { return {T(x), T(y), T(z)}; }
template <class T> Aabb<T> cube(double h) { return Aabb<T>::of(v3<T>(-h, -h, -h), v3<T>(h, h, h)); }
template <class T> struct Implicit {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit;
  T operator()(const Vec3<T>& p) const noexcept { return norm2(p) - T(1); }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(Vec3<T>::zero()).grown(1); }
};
using Sd = Sphere<double>;
using Bd = Box<double>;
} // namespace

// kinds (STYLE.md section 3)
static_assert(decltype(unite(Sd{}, Bd{}))::kind == SdfKind::bound);
static_assert(decltype(unite(Sd{}))::kind == SdfKind::exact);
static_assert(decltype(unite(Sd{}, Sd{}, Bd{}, Capsule<double>{}))::kind == SdfKind::bound);
static_assert(decltype(disjoint_unite(Sd{}, Bd{}))::kind == SdfKind::exact);
static_assert(decltype(disjoint_unite(Sd{}, Ellipsoid<double>{}))::kind == SdfKind::bound);
static_assert(decltype(intersect(Sd{}, Bd{}))::kind == SdfKind::bound);
static_assert(decltype(subtract(Sd{}, Bd{}))::kind == SdfKind::bound);
static_assert(decltype(subtract(Sd{}))::kind == SdfKind::exact);
static_assert(decltype(smooth_unite(Sd{}, Bd{}, 0.1))::kind == SdfKind::bound);
static_assert(decltype(exp_smooth_subtract(Sd{}, Bd{}, 0.1))::kind == SdfKind::bound);
static_assert(decltype(unite(Sd{}, Implicit<double>{}))::kind == SdfKind::implicit);
static_assert(decltype(disjoint_unite(Sd{}, Implicit<double>{}))::kind == SdfKind::implicit);
static_assert(decltype(smooth_intersect(Implicit<double>{}, Sd{}, 0.1))::kind == SdfKind::implicit);
// the style guide's example composes and is a bound
static_assert(decltype(subtract(smooth_unite(Sd{{0, 0, 0}, 1.0},
                                             Capsule<double>{{0, 0, 0}, {2, 0, 0}, 0.3}, 0.1),
                                translate(Bd{{0.5, 0.5, 0.5}}, {0, 0, 1})))::kind ==
              SdfKind::bound);
static_assert(is_sdf_v<decltype(unite(Sphere<float>{}, intersect(Box<float>{}, Torus<float>{})))>);

TYPED_TEST(CsgTest, SharpOperationsMatchMinMaxAndIdentities) {
  using T = TypeParam;
  const Sphere<T> a{v3<T>(0.3, 0, 0), T(0.8)};
  const Box<T> b{v3<T>(0.5, 0.6, 0.4), v3<T>(-0.2, 0.1, 0)};
  const Capsule<T> c{v3<T>(-1, -1, 0), v3<T>(1, 1, 0.2), T(0.2)};
  for (const auto& p : test::random_points(cube<T>(2), 500)) {
    const T va = a(p), vb = b(p), vc = c(p);
    EXPECT_EQ(unite(a, b, c)(p), std::min({va, vb, vc}));
    EXPECT_EQ(intersect(a, b, c)(p), std::max({va, vb, vc}));
    EXPECT_EQ(subtract(a, b, c)(p), std::max({va, -vb, -vc}));
    // A u A = A, A n A = A, A \ A is empty (never negative)
    EXPECT_EQ(unite(a, a)(p), va);
    EXPECT_EQ(intersect(a, a)(p), va);
    EXPECT_GE(subtract(a, a)(p), T(0));
    // A n B is inside A and inside B; A and B are inside A u B
    if (intersect(a, b)(p) < T(0)) {
      EXPECT_LT(va, T(0));
      EXPECT_LT(vb, T(0));
    }
    if (va < T(0)) {
      EXPECT_LT(unite(a, b)(p), T(0));
    }
    // commutativity, associativity, A \ B = A n complement(B)
    EXPECT_EQ(unite(a, b)(p), unite(b, a)(p));
    EXPECT_EQ(unite(unite(a, b), c)(p), unite(a, unite(b, c))(p));
    EXPECT_EQ(subtract(a, b)(p), intersect(a, complement(b))(p));
    EXPECT_EQ(disjoint_unite(a, c)(p), unite(a, c)(p));
  }
  // bounds: union merges, intersection overlaps, difference keeps the first
  EXPECT_EQ(unite(a, b).bounds(), merge(a.bounds(), b.bounds()));
  const auto ib = intersect(a, b).bounds();
  EXPECT_TRUE(a.bounds().contains(ib) && b.bounds().contains(ib));
  EXPECT_EQ(subtract(a, b).bounds(), a.bounds());
  EXPECT_TRUE(intersect(a, Sphere<T>{v3<T>(9, 9, 9), T(1)}).bounds().is_empty());
  for (const auto& p : test::random_points(cube<T>(2), 2000, 5)) {
    if (intersect(a, b)(p) < T(0)) {
      EXPECT_TRUE(ib.contains(p));
    }
  }
}

TYPED_TEST(CsgTest, DisjointUnionIsExactAndIsTheClosestObjectRule) {
  using T = TypeParam;
  const Sphere<T> s1{v3<T>(-1, 0, 0), T(0.5)}, s2{v3<T>(0.8, 0.3, 0), T(0.4)};
  const Torus<T> tor{v3<T>(0, 0, 1.2), T(0.5), T(0.15)};
  const auto u = disjoint_unite(s1, s2, tor);
  for (const auto& p : test::random_points(cube<T>(2), 500)) {
    // EBGeometry: the value of the object with the smallest |S_i|
    const T v[3] = {s1(p), s2(p), tor(p)};
    int k = 0;
    for (int i = 1; i < 3; ++i)
      if (std::abs(v[i]) < std::abs(v[k])) k = i;
    EXPECT_EQ(u(p), v[k]);
  }
  test::expect_eikonal(u, cube<T>(2), 400, 0.8);
  // exact: within a cloud step of the brute-force distance to its surface
  test::expect_bound(u, cube<double>(2), 0.08);
}

TYPED_TEST(CsgTest, OverlappingCombinationsAreBounds) {
  using T = TypeParam;
  const Sphere<T> a{v3<T>(0.3, 0, 0), T(0.8)};
  const Box<T> b{v3<T>(0.5, 0.6, 0.4), v3<T>(-0.2, 0.1, 0)};
  const auto ct = CappedTorus<T>::make(v3<T>(0, 0, 0), T(1), T(0.2), T(2.5));
  const Aabb<double> box = Aabb<double>::of({-1.7, -1.7, -1.2}, {1.7, 1.7, 1.2});
  test::expect_bound(unite(a, b, ct), box);
  test::expect_bound(intersect(a, b), box);
  test::expect_bound(subtract(a, b, ct), box);
  test::expect_bound(smooth_unite(a, ct, T(0.3)), box);
  test::expect_bound(smooth_intersect(a, b, T(0.3)), box);
  test::expect_bound(smooth_subtract(a, b, T(0.3)), box);
  test::expect_bound(exp_smooth_unite(a, ct, T(0.1)), box);
  test::expect_bound(exp_smooth_intersect(a, b, T(0.1)), box);
  test::expect_bound(exp_smooth_subtract(a, b, T(0.1)), box);
}

TYPED_TEST(CsgTest, SmoothVariantsConvergeToSharp) {
  using T = TypeParam;
  const Sphere<T> a{v3<T>(0.3, 0, 0), T(0.8)};
  const Box<T> b{v3<T>(0.5, 0.6, 0.4), v3<T>(-0.2, 0.1, 0)};
  const auto pts = test::random_points(cube<T>(2), 400);
  for (const T k : {T(0.5), T(0.1), T(0.01), T(1e-4)}) {
    double worst_poly = 0, worst_exp = 0;
    for (const auto& p : pts) {
      const double u = unite(a, b)(p), i = intersect(a, b)(p), d = subtract(a, b)(p);
      const double su = smooth_unite(a, b, k)(p), si = smooth_intersect(a, b, k)(p),
                   sd = smooth_subtract(a, b, k)(p);
      const double eu = exp_smooth_unite(a, b, k)(p), ei = exp_smooth_intersect(a, b, k)(p),
                   ed = exp_smooth_subtract(a, b, k)(p);
      const double eps = sizeof(T) == 4 ? 1e-6 : 1e-14;
      // smooth union lies below the union (the shape grows), within the blend's gap
      EXPECT_LE(su, u + eps);
      EXPECT_GE(su, u - double(k) / 4 - eps);
      EXPECT_LE(eu, u + eps);
      EXPECT_GE(eu, u - double(k) * std::log(2.0) - eps);
      // smooth intersection and difference lie above (the shape shrinks)
      EXPECT_GE(si, i - eps);
      EXPECT_LE(si, i + double(k) / 4 + eps);
      EXPECT_GE(sd, d - eps);
      EXPECT_LE(sd, d + double(k) / 4 + eps);
      EXPECT_GE(ei, i - eps);
      EXPECT_GE(ed, d - eps);
      EXPECT_LE(ed, d + double(k) * std::log(2.0) + eps);
      worst_poly = std::max({worst_poly, u - su, si - i, sd - d});
      worst_exp = std::max({worst_exp, u - eu, ei - i, ed - d});
      // far from the blend region (|a - b| >= k) the polynomial blend is exactly sharp
      if (std::abs(double(a(p)) - double(b(p))) >= double(k)) {
        EXPECT_EQ(su, u);
      }
    }
    // and the blend does act: the largest deviation is of the order of k (random points find
    // the blend region |a - b| < k only when k is not tiny)
    if (k >= T(0.01)) {
      EXPECT_GT(worst_poly, double(k) * 0.01);
      EXPECT_GT(worst_exp, double(k) * 0.1);
    }
  }
  // k = 0 is the sharp operation
  for (const auto& p : pts) {
    EXPECT_EQ(smooth_unite(a, b, T(0))(p), unite(a, b)(p));
    EXPECT_EQ(exp_smooth_intersect(a, b, T(0))(p), intersect(a, b)(p));
  }
  // smooth-union bounds contain its inside
  const auto su = smooth_unite(a, b, T(0.4));
  const auto eu = exp_smooth_unite(a, b, T(0.4));
  for (const auto& p : test::random_points(cube<T>(2), 4000, 9)) {
    if (su(p) < T(0)) {
      EXPECT_TRUE(su.bounds().contains(p));
    }
    if (eu(p) < T(0)) {
      EXPECT_TRUE(eu.bounds().contains(p));
    }
  }
}
