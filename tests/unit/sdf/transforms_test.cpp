// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/transforms.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "ebgeom/sdf/shapes.hpp"
#include "sdf_reference.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using test::V3;

template <class T> class TransformsTest : public ::testing::Test {};
TYPED_TEST_SUITE(TransformsTest, test::FloatTypes);

namespace {
template <class T> Vec3<T> v3(double x, double y, double z) { return {T(x), T(y), T(z)}; }

// `a` and `b` agree at random points of `box`.
template <class A, class B>
void expect_same(const A& a, const B& b, const Aabb<sdf_scalar_t<A>>& box, double tol,
                 std::size_t n = 500) {
  for (const auto& p : test::random_points(box, n, 77))
    EXPECT_NEAR(double(a(p)), double(b(p)), tol) << "at " << p;
}
template <class T> double tol() { return sizeof(T) == 4 ? 2e-5 : 1e-11; }
template <class T> Aabb<T> cube(double h) { return Aabb<T>::of(v3<T>(-h, -h, -h), v3<T>(h, h, h)); }

// Not an SDF in the distance sense: twice a sphere (used to show the checks can fail).
template <class T> struct TwiceSphere {
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::implicit;
  T operator()(const Vec3<T>& p) const noexcept { return T(2) * (norm(p) - T(1)); }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of(Vec3<T>::zero()).grown(1); }
};
} // namespace

// kinds derived from the operand
static_assert(decltype(translate(Sphere<double>{}, {}))::kind == SdfKind::exact);
static_assert(decltype(rotate(Box<double>{}, Axis::z, 30.0))::kind == SdfKind::exact);
static_assert(decltype(scale(Torus<float>{}, 2.0f))::kind == SdfKind::exact);
static_assert(decltype(transform(Box<float>{}, Mat3<float>{}, Vec3<float>{}))::kind ==
              SdfKind::exact);
static_assert(decltype(reflect(Box<float>{}, {1, 0, 0}))::kind == SdfKind::exact);
static_assert(decltype(complement(Box<float>{}))::kind == SdfKind::exact);
static_assert(decltype(offset(Box<float>{}, 1.0f))::kind == SdfKind::bound);
static_assert(decltype(shell(Sphere<float>{}, 1.0f))::kind == SdfKind::bound);
static_assert(decltype(elongate(Sphere<float>{}, {}))::kind == SdfKind::bound);
static_assert(decltype(mirror(Sphere<float>{}, Axis::x))::kind == SdfKind::bound);
static_assert(decltype(mollify(Sphere<float>{}, 0.1f))::kind == SdfKind::bound);
static_assert(decltype(repeat(Sphere<float>{}, {1, 1, 1}))::kind == SdfKind::bound);
static_assert(decltype(translate(Ellipsoid<double>{}, {}))::kind == SdfKind::bound);
static_assert(decltype(offset(TwiceSphere<double>{}, 1.0))::kind == SdfKind::implicit);
static_assert(decltype(rotate(TwiceSphere<double>{}, Axis::x, 1.0))::kind == SdfKind::implicit);
static_assert(is_sdf_v<decltype(repeat(translate(Sphere<float>{}, {}), {1, 0, 0}, {{2, 0, 0}}))>);

TYPED_TEST(TransformsTest, ChecksCanFail) {
  using T = TypeParam;
  // the Eikonal and bound checks reject a field with gradient 2
  EXPECT_GT(test::count_failures([] { test::expect_eikonal(TwiceSphere<T>{}, cube<T>(2)); }), 100);
  EXPECT_GT(test::count_failures([] { test::expect_bound(TwiceSphere<T>{}, cube<double>(2)); }),
            100);
  // and the exactness variant rejects a bound that is far from exact
  EXPECT_GT(test::count_failures([] {
              test::expect_bound(scale(Ellipsoid<T>{Vec3<T>::zero(), v3<T>(1.5, 0.2, 0.2)}, T(1)),
                                 cube<double>(2), 0.05);
            }),
            10);
}

TYPED_TEST(TransformsTest, TranslateRotateScaleEquivariance) {
  using T = TypeParam;
  std::mt19937_64 rng(3);
  const Vec3<T> a = v3<T>(-0.5, 0.2, 0.1), b = v3<T>(0.7, 1.1, -0.6), t = v3<T>(0.3, -1, 2);
  const Capsule<T> cap{a, b, T(0.4)};
  // translate: the capsule built at the moved end points
  expect_same(translate(cap, t), Capsule<T>{a + t, b + t, T(0.4)}, cube<T>(3), tol<T>() * 10);
  EXPECT_TRUE(translate(cap, t).bounds().contains(Aabb<T>::of(a + t, b + t)));
  for (int i = 0; i < 10; ++i) {
    const Vec3<T> axis = test::random_unit<T>(rng);
    const T deg = T(-180 + 36 * i + 7);
    const Mat3<T> r = Mat3<T>::axis_degrees(axis, deg);
    const Capsule<T> moved{r * a, r * b, T(0.4)};
    // rotate by axis + degrees, by the matrix, by the quaternion: all equal the moved capsule
    expect_same(rotate(cap, axis, deg), moved, cube<T>(3), tol<T>() * 10, 100);
    expect_same(rotate(cap, r), moved, cube<T>(3), tol<T>() * 10, 100);
    expect_same(rotate(cap, Quaternion<T>::axis_degrees(axis, deg)), moved, cube<T>(3),
                tol<T>() * 10, 100);
    // rigid transform = rotate then translate
    expect_same(transform(cap, r, t), Capsule<T>{r * a + t, r * b + t, T(0.4)}, cube<T>(3),
                tol<T>() * 10, 100);
    expect_same(transform(cap, Quaternion<T>::axis_degrees(axis, deg), t),
                translate(rotate(cap, r), t), cube<T>(3), tol<T>() * 10, 100);
    // rotated bounds contain the rotated shape
    const auto rb = rotate(cap, r).bounds();
    for (int k = 0; k <= 10; ++k) {
      const Vec3<T> q = lerp(r * a, r * b, T(k / 10.0));
      EXPECT_TRUE(rb.grown(T(1e-4)).contains(q + Vec3<T>::unit(k % 3) * T(0.4)));
    }
  }
  // coordinate-axis rotation, EBGeometry's convention: 90 degrees about z maps x to y, so a box
  // long in x becomes long in y
  const Box<T> box{v3<T>(2, 0.5, 0.3)};
  expect_same(rotate(box, Axis::z, T(90)), Box<T>{v3<T>(0.5, 2, 0.3)}, cube<T>(3), tol<T>());
  expect_same(rotate(Capsule<T>{Vec3<T>::zero(), v3<T>(1, 0, 0), T(0.2)}, Axis::z, T(90)),
              Capsule<T>{Vec3<T>::zero(), v3<T>(0, 1, 0), T(0.2)}, cube<T>(3), tol<T>());
  // uniform scale: the capsule with scaled end points and radius
  expect_same(scale(cap, T(2.5)), Capsule<T>{a * T(2.5), b * T(2.5), T(1.0)}, cube<T>(5),
              tol<T>() * 10);
  expect_same(scale(Sphere<T>{v3<T>(1, 0, 0), T(1)}, T(0.5)), Sphere<T>{v3<T>(0.5, 0, 0), T(0.5)},
              cube<T>(2), tol<T>());
  EXPECT_TRUE(scale(cap, T(2.5)).bounds().contains(Aabb<T>::of(a * T(2.5), b * T(2.5))));
  // reflection across x = 0.25 and the complement
  expect_same(reflect(Sphere<T>{v3<T>(1, 0, 0), T(0.3)}, v3<T>(2, 0, 0), T(0.25)),
              Sphere<T>{v3<T>(-0.5, 0, 0), T(0.3)}, cube<T>(2), tol<T>());
  expect_same(complement(cap), translate(scale(cap, T(1)), Vec3<T>::zero()), Aabb<T>{}, 0, 0);
  for (const auto& p : test::random_points(cube<T>(2), 100)) EXPECT_EQ(complement(cap)(p), -cap(p));
  EXPECT_EQ(complement(cap).bounds(), Aabb<T>::infinite());
}

TYPED_TEST(TransformsTest, EikonalForExactnessPreservingTransforms) {
  using T = TypeParam;
  const Torus<T> tor{v3<T>(0.2, 0, 0), T(1), T(0.3)};
  const Box<T> box{v3<T>(0.5, 0.7, 0.3), v3<T>(0.1, 0.1, 0)};
  test::expect_eikonal(translate(tor, v3<T>(1, 2, 3)),
                       translate(tor, v3<T>(1, 2, 3)).bounds().grown(1));
  test::expect_eikonal(rotate(tor, v3<T>(1, 1, 0), T(33)),
                       rotate(tor, v3<T>(1, 1, 0), T(33)).bounds().grown(1));
  test::expect_eikonal(rotate(box, Axis::x, T(45)), rotate(box, Axis::x, T(45)).bounds().grown(1));
  test::expect_eikonal(transform(box, Mat3<T>::coordinate_axis(Axis::y, 20), v3<T>(0, 1, 0)),
                       cube<T>(2));
  test::expect_eikonal(scale(tor, T(1.7)), scale(tor, T(1.7)).bounds().grown(1));
  test::expect_eikonal(reflect(box, v3<T>(1, 2, 3), T(0.5)), cube<T>(2));
  test::expect_eikonal(complement(tor), tor.bounds().grown(1));
}

TYPED_TEST(TransformsTest, OffsetShellElongateMirrorHaveKnownClosedForms) {
  using T = TypeParam;
  // offset of a convex box is the rounded box (exact), of a torus the fatter torus
  const Box<T> box{v3<T>(0.5, 0.7, 0.3), v3<T>(0.1, 0.1, 0)};
  expect_same(offset(box, T(0.2)), RoundedBox<T>{v3<T>(0.7, 0.9, 0.5), T(0.2), box.center},
              cube<T>(2), tol<T>() * 10);
  EXPECT_TRUE(offset(box, T(0.2))
                  .bounds()
                  .grown(T(1e-5))
                  .contains(Aabb<T>::of(v3<T>(-0.6, -0.8, -0.5), v3<T>(0.8, 1, 0.5))));
  expect_same(offset(Torus<T>{Vec3<T>::zero(), T(1), T(0.2)}, T(0.1)),
              Torus<T>{Vec3<T>::zero(), T(1), T(0.3)}, cube<T>(2), tol<T>() * 10);
  // shell of a sphere: the hollow ball between radii R - t and R + t
  const Sphere<T> s{v3<T>(0.1, 0.2, 0.3), T(1)};
  for (const auto& p : test::random_points(cube<T>(2), 300)) {
    const double r = norm(V3::from(p) - V3{0.1, 0.2, 0.3});
    EXPECT_NEAR(double(shell(s, T(0.1))(p)), std::abs(r - 1) - 0.1, tol<T>() * 10);
  }
  // elongating a ball along x gives a capsule; a cube gives the longer box
  expect_same(elongate(Sphere<T>{Vec3<T>::zero(), T(0.5)}, v3<T>(0.8, 0, 0)),
              Capsule<T>{v3<T>(-0.8, 0, 0), v3<T>(0.8, 0, 0), T(0.5)}, cube<T>(2), tol<T>() * 10);
  expect_same(elongate(Box<T>{v3<T>(0.4, 0.4, 0.4)}, v3<T>(0.3, 0.6, 0)),
              Box<T>{v3<T>(0.7, 1.0, 0.4)}, cube<T>(2), tol<T>() * 10);
  EXPECT_TRUE(elongate(Box<T>{v3<T>(0.4, 0.4, 0.4)}, v3<T>(0.3, 0.6, 0))
                  .bounds()
                  .grown(T(1e-5))
                  .contains(Aabb<T>::of(v3<T>(-0.7, -1, -0.4), v3<T>(0.7, 1, 0.4))));
  // mirror of a ball on the positive side: the union of the ball and its image (exact)
  const Sphere<T> c{v3<T>(0.9, 0.2, 0), T(0.5)};
  const auto m = mirror(c, Axis::x);
  for (const auto& p : test::random_points(cube<T>(2), 300)) {
    const V3 q = V3::from(p);
    const double ref = std::min(norm(q - V3{0.9, 0.2, 0}), norm(q - V3{-0.9, 0.2, 0})) - 0.5;
    EXPECT_NEAR(double(m(p)), ref, tol<T>() * 10);
  }
  EXPECT_TRUE(m.bounds().contains(Sphere<T>{v3<T>(-0.9, 0.2, 0), T(0.5)}.bounds()));
}

TYPED_TEST(TransformsTest, BoundKindsNeverOverestimate) {
  using T = TypeParam;
  // non-convex operand (a C-shaped capped torus): offsets both ways, shell, elongation of an
  // off-centre operand, mirror of an operand crossing the plane, mollification
  const auto ct = CappedTorus<T>::make(v3<T>(0, -0.2, 0), T(0.9), T(0.25), T(2.4));
  const Aabb<double> box = Aabb<double>::of({-1.6, -1.6, -0.9}, {1.6, 1.6, 0.9});
  test::expect_bound(offset(ct, T(0.15)), box);
  test::expect_bound(offset(ct, T(-0.1)), box);
  test::expect_bound(shell(ct, T(0.05)), box);
  test::expect_bound(elongate(ct, v3<T>(0.2, 0.1, 0.15)), box.grown(0.3));
  test::expect_bound(mirror(ct, Axis::y), box);
  test::expect_bound(mollify(ct, T(0.1)), box.grown(0.2));
  test::expect_bound(mollify(Box<T>{v3<T>(0.5, 0.6, 0.7)}, T(0.2)), box);
  // offset outside of an exact shape is exact outside: the check with exactness for a convex one
  test::expect_bound(offset(Box<T>{v3<T>(0.5, 0.6, 0.7)}, T(0.2)), box.grown(0.3), 0.06);
}

TYPED_TEST(TransformsTest, MollifyIsSmoothingNotMoving) {
  using T = TypeParam;
  // a plane is linear: averaging leaves it unchanged
  const Plane<T> pl{v3<T>(1, 2, -1), T(0.3)};
  expect_same(mollify(pl, T(0.2)), pl, cube<T>(2), tol<T>() * 100);
  // a ball moves by O(radius^2 / R) only, and bounds contain the result
  const Sphere<T> s{Vec3<T>::zero(), T(1)};
  const auto m = mollify(s, T(0.05));
  for (const auto& p : test::random_points(cube<T>(2), 300)) {
    EXPECT_NEAR(double(m(p)), double(s(p)), 0.05 * 0.05 * 3 / std::max(0.2, double(norm(p))));
    if (m(p) < T(0)) {
      EXPECT_TRUE(m.bounds().contains(p));
    }
  }
}

TYPED_TEST(TransformsTest, RepetitionEqualsExplicitUnionOfCopies) {
  using T = TypeParam;
  const Vec3<T> period = v3<T>(1.0, 1.5, 0);
  // an asymmetric operand inside its cell, so neighbouring copies matter
  const Capsule<T> cap{v3<T>(0.3, -0.2, 0), v3<T>(0.1, 0.5, 0.3), T(0.15)};
  const auto inf = repeat(cap, period);
  const auto fin = repeat(cap, period, {{2, 1, 5}});
  for (const auto& p : test::random_points(Aabb<T>::of(v3<T>(-5, -5, -2), v3<T>(5, 5, 2)), 400)) {
    double all = 1e300, limited = 1e300;
    for (int i = -8; i <= 8; ++i)
      for (int j = -6; j <= 6; ++j) {
        const Vec3<T> off = v3<T>(i * 1.0, j * 1.5, 0);
        const double v = double(cap(p - off));
        all = std::min(all, v);
        if (std::abs(i) <= 2 && std::abs(j) <= 1) limited = std::min(limited, v);
      }
    EXPECT_NEAR(double(inf(p)), all, tol<T>() * 10) << p;
    EXPECT_NEAR(double(fin(p)), limited, tol<T>() * 10) << p;
  }
  const auto fb = fin.bounds();
  EXPECT_TRUE(fb.contains(cap.bounds().grown(T(0))));
  EXPECT_NEAR(double(fb.hi.x), double(cap.bounds().hi.x) + 2, 1e-5);
  EXPECT_NEAR(double(fb.lo.y), double(cap.bounds().lo.y) - 1.5, 1e-5);
  EXPECT_EQ(fb.hi.z, cap.bounds().hi.z); // z not repeated
  EXPECT_TRUE(std::isinf(inf.bounds().hi.x));
  // disjoint copies of exact spheres: Eikonal away from the cell boundaries
  test::expect_eikonal(repeat(Sphere<T>{Vec3<T>::zero(), T(0.3)}, v3<T>(1, 1, 1)), cube<T>(2));
}

TYPED_TEST(TransformsTest, BoundsContainTheInside) {
  using T = TypeParam;
  const Capsule<T> cap{v3<T>(0.3, -0.2, 0), v3<T>(0.6, 0.5, 0.3), T(0.2)};
  const auto check = [](const auto& s) {
    const auto b = s.bounds();
    int inside = 0;
    // dense near the box (where a too-small box shows), sparse farther out
    auto pts = test::random_points(b.grown(T(0.5)), 20000, 13);
    const auto far = test::random_points(cube<T>(4), 5000, 14);
    pts.insert(pts.end(), far.begin(), far.end());
    for (const auto& p : pts) {
      if (s(p) < T(0)) {
        ++inside;
        EXPECT_TRUE(b.contains(p)) << p;
      }
    }
    EXPECT_GT(inside, 200);
  };
  check(translate(cap, v3<T>(1, -1, 0.5)));
  check(rotate(cap, v3<T>(1, 2, 3), T(70)));
  check(transform(cap, Quaternion<T>::axis_degrees(v3<T>(0, 1, 1), T(-40)), v3<T>(0, 0, 1)));
  check(scale(cap, T(2)));
  check(offset(cap, T(0.3)));
  check(shell(cap, T(0.1)));
  check(elongate(cap, v3<T>(0.5, 0.2, 0)));
  check(reflect(cap, v3<T>(1, 1, 0), T(0.2)));
  check(mirror(cap, Axis::y));
  check(mollify(cap, T(0.1)));
  check(repeat(cap, v3<T>(2, 0, 0), {{1, 0, 0}}));
}

// A coordinate axis is an `Axis`, never a number: EBGeometry's argument order `rotate(s, 90, 0)`
// (angle, axis) resolves to a trap whose body does not compile (tests/compile_fail checks the
// error), so it can never yield a silently unrotated SDF.
static_assert(!is_sdf_v<decltype(rotate(Box<double>{}, 90, 0))>);
static_assert(!is_sdf_v<decltype(rotate(Box<double>{}, 2, 90.0))>);
static_assert(!is_sdf_v<decltype(mirror(Box<double>{}, 0))>);
static_assert(is_sdf_v<decltype(rotate(Box<double>{}, Axis::x, 90))>);

TYPED_TEST(TransformsTest, EBGeometryRotateIsShapeAxisAngleAndNeverIdentity) {
  using T = TypeParam;
  // EBGeometry's `sdf.rotate(90, 0)` (90 degrees about x) maps +y to +z: a box long in y becomes
  // long in z, which the identity would not give
  const Box<T> box{v3<T>(0.3, 2, 0.5)};
  const auto turned = rotate(box, Axis::x, 90);
  expect_same(turned, Box<T>{v3<T>(0.3, 0.5, 2)}, cube<T>(3), tol<T>());
  EXPECT_GT(std::abs(double(turned(v3<T>(0, 1.5, 0)) - box(v3<T>(0, 1.5, 0)))), 0.5);
  // y and z as well, and the same through mirror's Axis
  expect_same(rotate(box, Axis::y, 90), Box<T>{v3<T>(0.5, 2, 0.3)}, cube<T>(3), tol<T>());
  expect_same(rotate(box, Axis::z, 90), Box<T>{v3<T>(2, 0.3, 0.5)}, cube<T>(3), tol<T>());
}

TYPED_TEST(TransformsTest, ArgumentsThatDescribeNoTransformGiveNaNNotIdentity) {
  using T = TypeParam;
  const Sphere<T> s{v3<T>(0.5, 0.2, 0.1), T(0.4)};
  const Vec3<T> p = v3<T>(0.3, -0.2, 0.6);
  const Vec3<T> zero = Vec3<T>::zero();
  const T inf = std::numeric_limits<T>::infinity();
  for (const int bad : {-1, 3, 90}) {
    EXPECT_TRUE(std::isnan(rotate(s, static_cast<Axis>(bad), T(90))(p))) << bad;
    EXPECT_TRUE(std::isnan(mirror(s, static_cast<Axis>(bad))(p))) << bad;
    EXPECT_TRUE(std::isnan(mirror(s, static_cast<Axis>(bad)).bounds().lo.x)) << bad;
  }
  EXPECT_TRUE(std::isnan(rotate(s, zero, T(30))(p)));
  EXPECT_TRUE(std::isnan(rotate(s, v3<T>(0, double(inf), 0), T(30))(p)));
  EXPECT_TRUE(std::isnan(rotate(s, Quaternion<T>{0, 0, 0, 0})(p)));
  EXPECT_TRUE(std::isnan(transform(s, Quaternion<T>{0, 0, 0, 0}, v3<T>(1, 0, 0))(p)));
  EXPECT_TRUE(std::isnan(reflect(s, zero, T(0))(p)));
  EXPECT_TRUE(std::isnan(reflect(s, zero, T(0)).bounds().hi.y));
  for (const T f : {T(0), T(-1), T(-2), inf, std::numeric_limits<T>::quiet_NaN()})
    EXPECT_TRUE(std::isnan(scale(s, f)(p))) << f;
  // the valid neighbours of each are finite
  EXPECT_FALSE(std::isnan(rotate(s, Axis::y, T(30))(p)));
  EXPECT_FALSE(std::isnan(mirror(s, Axis::z)(p)));
  EXPECT_FALSE(std::isnan(rotate(s, v3<T>(0, 0, 1e-20), T(30))(p)));
  EXPECT_FALSE(std::isnan(reflect(s, v3<T>(0, 2, 0), T(0))(p)));
  EXPECT_NEAR(double(scale(s, T(2))(p)), double(T(2) * s(p / T(2))), tol<T>());
}

TYPED_TEST(TransformsTest, NegativeRadiiAndZeroDirectionsGiveNaN) {
  using T = TypeParam;
  const Vec3<T> p = v3<T>(0.3, -0.2, 0.6), a = v3<T>(0, 0, 0), b = v3<T>(1, 0, 0);
  EXPECT_TRUE(std::isnan(Sphere<T>{a, T(-0.5)}(p)));
  EXPECT_TRUE(std::isnan((Capsule<T>{a, b, T(-0.1)}(p))));
  EXPECT_TRUE(std::isnan((CappedCylinder<T>{a, b, T(-0.1)}(p))));
  EXPECT_TRUE(std::isnan((InfiniteCylinder<T>{a, b, T(-0.1)}(p))));
  EXPECT_TRUE(std::isnan((InfiniteCylinder<T>{a, Vec3<T>::zero(), T(0.1)}(p))));
  EXPECT_TRUE(std::isnan((Torus<T>{a, T(1), T(-0.1)}(p))));
  EXPECT_TRUE(std::isnan((Plane<T>{Vec3<T>::zero(), T(0)}(p))));
  EXPECT_TRUE(std::isnan((Plane<T>::through(a, Vec3<T>::zero())(p))));
  // zero radii are valid (a point, a segment): finite, the distance to it
  EXPECT_NEAR(double(Sphere<T>{a, T(0)}(p)), double(norm(p)), tol<T>());
  EXPECT_NEAR(double(Capsule<T>{a, b, T(0)}(p)), std::sqrt(0.04 + 0.36), tol<T>());
  EXPECT_FALSE(std::isnan((Torus<T>{a, T(1), T(0)}(p))));
}
