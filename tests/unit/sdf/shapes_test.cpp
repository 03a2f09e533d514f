// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/sdf/shapes.hpp"

#include <gtest/gtest.h>

#include <random>

#include "sdf_reference.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using test::V3;

template <class T> class ShapesTest : public ::testing::Test {};
TYPED_TEST_SUITE(ShapesTest, test::FloatTypes);

static_assert(is_sdf_v<Sphere<float>> && is_sdf_v<Box<double>> && is_sdf_v<RoundedBox<float>> &&
              is_sdf_v<Torus<double>> && is_sdf_v<CappedTorus<float>> &&
              is_sdf_v<CappedCylinder<double>> && is_sdf_v<RoundedCylinder<float>> &&
              is_sdf_v<InfiniteCylinder<double>> && is_sdf_v<Capsule<float>> &&
              is_sdf_v<CappedCone<double>> && is_sdf_v<InfiniteCone<float>> &&
              is_sdf_v<Plane<double>> && is_sdf_v<Ellipsoid<float>> &&
              is_sdf_v<TriangularPrism<double>> && is_sdf_v<HexagonalPrism<float>> &&
              is_sdf_v<PerlinDisplaced<Sphere<double>>>);
static_assert(Ellipsoid<double>::kind == SdfKind::bound);
static_assert(PerlinDisplaced<Sphere<float>>::kind == SdfKind::implicit);
static_assert(CappedCone<float>::kind == SdfKind::exact);

namespace {

// Compares `shape` with `ref` (double, at the same T point) at random points of `box`, checks
// both signs occur and that the bounds contain every inside point.
template <class S, class Ref>
void expect_matches(const S& shape, const Ref& ref, Aabb<sdf_scalar_t<S>> box, std::size_t n = 600,
                    double scale = 4) {
  using T = sdf_scalar_t<S>;
  int inside = 0, outside = 0;
  for (const auto& p : test::random_points(box, n, 1234)) {
    const double r = ref(V3::from(p));
    EXPECT_NEAR(double(shape(p)), r, test::ref_tol<T>(scale)) << "at " << p;
    (r < 0 ? inside : outside)++;
    if (r < 0) {
      EXPECT_TRUE(shape.bounds().contains(p)) << p;
    }
  }
  EXPECT_GT(inside, int(n / 200));
  EXPECT_GT(outside, int(n / 200));
}

template <class T> Vec3<T> v3(double x, double y, double z) { return {T(x), T(y), T(z)}; }

} // namespace

TYPED_TEST(ShapesTest, SphereBoxRoundedBoxMatchSupportFunctionReference) {
  using T = TypeParam;
  const Sphere<T> s{v3<T>(0.3, -0.2, 0.5), T(1.2)};
  const auto hs = [](const V3& u) { return dot(u, V3{0.3, -0.2, 0.5}) + 1.2; };
  expect_matches(
      s, [&](const V3& p) { return test::convex_sdf(hs, p); }, s.bounds().grown(1));

  const Box<T> b{v3<T>(1, 0.5, 0.75), v3<T>(0.1, 0.2, -0.3)};
  const auto hb = [](const V3& u) {
    return dot(u, V3{0.1, 0.2, -0.3}) + std::abs(u.x) + 0.5 * std::abs(u.y) + 0.75 * std::abs(u.z);
  };
  expect_matches(
      b, [&](const V3& p) { return test::convex_sdf(hb, p); }, b.bounds().grown(1));
  const auto bc = Box<T>::from_corners(v3<T>(-1, 0, 2), v3<T>(1, 4, 3));
  EXPECT_EQ(bc.half, v3<T>(1, 2, 0.5));
  EXPECT_EQ(bc.center, v3<T>(0, 2, 2.5));

  const RoundedBox<T> rb{v3<T>(1, 0.5, 0.75), T(0.3), v3<T>(0.1, 0.2, -0.3)};
  const auto hrb = [](const V3& u) {
    return dot(u, V3{0.1, 0.2, -0.3}) + 0.7 * std::abs(u.x) + 0.2 * std::abs(u.y) +
           0.45 * std::abs(u.z) + 0.3;
  };
  expect_matches(
      rb, [&](const V3& p) { return test::convex_sdf(hrb, p); }, rb.bounds().grown(1));
}

TYPED_TEST(ShapesTest, CylindersCapsuleConeMatchMeridianReference) {
  using T = TypeParam;
  // Solids of revolution: the distance equals the 2D distance, in the plane through the axis,
  // to the full (mirror-symmetric) cross-section polygon.
  const V3 a{-0.5, 0.2, 0.1}, b{0.7, 1.1, -0.6};
  const double L = norm(b - a);
  const Vec3<T> at = Vec3<T>::from(a), bt = Vec3<T>::from(b);
  using V2 = Vec2<double>;
  const auto trapezoid = [&](double ra, double rb) {
    return std::vector<V2>{{-ra, 0}, {ra, 0}, {rb, L}, {-rb, L}};
  };

  const CappedCylinder<T> cyl{at, bt, T(0.6)};
  expect_matches(
      cyl,
      [&](const V3& p) {
        return test::convex_polygon_sdf(test::meridian(p, a, b), trapezoid(0.6, 0.6));
      },
      cyl.bounds().grown(0.3));

  // rounded cylinder: the rectangle shrunk by k, offset by k (exact for convex sets)
  const double k = 0.2;
  const RoundedCylinder<T> rc{at, bt, T(0.6), T(k)};
  const std::vector<V2> inner{{-0.6 + k, k}, {0.6 - k, k}, {0.6 - k, L - k}, {-0.6 + k, L - k}};
  expect_matches(
      rc, [&](const V3& p) { return test::convex_polygon_sdf(test::meridian(p, a, b), inner) - k; },
      rc.bounds().grown(0.3));

  for (const auto& radii : {std::pair<double, double>{0.7, 0.25}, {0.0, 0.5}, {0.4, 0.4}}) {
    const CappedCone<T> cone{at, bt, T(radii.first), T(radii.second)};
    const auto poly = radii.first == 0
                          ? std::vector<V2>{{0, 0}, {radii.second, L}, {-radii.second, L}}
                          : trapezoid(radii.first, radii.second);
    expect_matches(
        cone, [&](const V3& p) { return test::convex_polygon_sdf(test::meridian(p, a, b), poly); },
        cone.bounds().grown(0.3));
  }

  // capsule: distance to the segment, minimised over its parameter, minus the radius
  const Capsule<T> cap{at, bt, T(0.4)};
  expect_matches(
      cap,
      [&](const V3& p) {
        return test::curve_min([&](double t) { return norm(p - (a + (b - a) * t)); }, 0, 1) - 0.4;
      },
      cap.bounds().grown(0.3));

  // degenerate segment: no NaN
  const CappedCylinder<T> flat{at, at, T(0.5)};
  EXPECT_TRUE(std::isfinite(flat(v3<T>(1, 2, 3))));
  EXPECT_TRUE(std::isfinite(Capsule<T>{at, at, T(0.5)}(at)));
}

TYPED_TEST(ShapesTest, PrismsAndPlaneMatchReference) {
  using T = TypeParam;
  const V3 c{0.2, -0.1, 0.3};
  const double ap = 0.6, hh = 0.45;
  // z-prism faces over a regular polygon with vertex angles (degrees) and circumradius R
  const auto prism_faces = [&](double R, std::vector<double> angles) {
    std::vector<V3> bot, top;
    for (double a : angles) {
      const V3 v{R * std::cos(a * M_PI / 180), R * std::sin(a * M_PI / 180), 0};
      bot.push_back(c + v - V3{0, 0, hh});
      top.push_back(c + v + V3{0, 0, hh});
    }
    std::vector<std::vector<V3>> f{top, std::vector<V3>(bot.rbegin(), bot.rend())};
    for (std::size_t i = 0; i < bot.size(); ++i) {
      const std::size_t j = (i + 1) % bot.size();
      f.push_back({bot[i], bot[j], top[j], top[i]});
    }
    return f;
  };
  const TriangularPrism<T> tri{Vec3<T>::from(c), T(ap), T(hh)};
  // equilateral triangle: circumradius = 2 * apothem, one vertex on +y
  const auto ft = prism_faces(2 * ap, {90, 210, 330});
  expect_matches(
      tri, [&](const V3& p) { return test::convex_polytope_sdf(p, ft); }, tri.bounds().grown(1));
  const HexagonalPrism<T> hex{Vec3<T>::from(c), T(ap), T(hh)};
  const auto fh = prism_faces(ap * 2 / std::sqrt(3.0), {0, 60, 120, 180, 240, 300});
  expect_matches(
      hex, [&](const V3& p) { return test::convex_polytope_sdf(p, fh); }, hex.bounds().grown(1));
  // the bounds contain every vertex
  for (const auto& f : fh)
    for (const auto& v : f) EXPECT_TRUE(hex.bounds().grown(T(1e-5)).contains(Vec3<T>::from(v)));
  for (const auto& f : ft)
    for (const auto& v : f) EXPECT_TRUE(tri.bounds().grown(T(1e-5)).contains(Vec3<T>::from(v)));
  // the same polytope routine reproduces a box given as six faces (checks the reference)
  const Box<T> box{v3<T>(1, 1, hh), Vec3<T>::from(c)};
  const auto fb = prism_faces(std::sqrt(2.0), {45, 135, 225, 315});
  for (const auto& p : test::random_points(box.bounds().grown(1), 200))
    EXPECT_NEAR(double(box(p)), test::convex_polytope_sdf(V3::from(p), fb), test::ref_tol<T>());

  // plane: signed distance = (p - point on plane) . unit normal
  const Plane<T> pl = Plane<T>::through(v3<T>(1, 2, 3), v3<T>(0, 3, 4));
  const Plane<T> raw{v3<T>(0, 3, 4), T(dot(V3{1, 2, 3}, V3{0, 0.6, 0.8}))};
  for (const auto& p : test::random_points(Aabb<T>::of(v3<T>(-5, -5, -5), v3<T>(5, 5, 5)), 200)) {
    const double r = dot(V3::from(p) - V3{1, 2, 3}, V3{0, 0.6, 0.8});
    EXPECT_NEAR(double(pl(p)), r, test::ref_tol<T>());
    EXPECT_NEAR(double(raw(p)), r, test::ref_tol<T>());
  }
  EXPECT_EQ(pl.bounds(), Aabb<T>::infinite());
  static_assert(std::is_same_v<HalfSpace<T>, Plane<T>>);
}

TYPED_TEST(ShapesTest, TorusAndCappedTorusMatchSampledCurveDistance) {
  using T = TypeParam;
  const V3 c{0.1, 0.2, -0.3};
  const double R = 1.0, r = 0.35;
  const Torus<T> tor{Vec3<T>::from(c), T(R), T(r)};
  const auto circle = [&](const V3& p, double lo, double hi) {
    // distance to the arc {c + R (sin t, cos t, 0), t in [lo, hi]} (t measured from +y)
    return test::curve_min(
        [&](double t) {
          return norm(p - c - V3{R * std::sin(t), R * std::cos(t), 0});
        },
        lo, hi);
  };
  expect_matches(
      tor, [&](const V3& p) { return circle(p, -M_PI, M_PI) - r; }, tor.bounds().grown(0.5));

  for (double aperture : {0.6, 2.0, 3.0}) {
    const auto ct = CappedTorus<T>::make(Vec3<T>::from(c), T(R), T(r), T(aperture));
    expect_matches(
        ct, [&](const V3& p) { return circle(p, -aperture, aperture) - r; },
        ct.bounds().grown(0.5));
    // the bounds contain densely sampled tube points
    for (int i = 0; i <= 200; ++i) {
      const double t = -aperture + 2 * aperture * i / 200;
      for (int j = 0; j < 16; ++j) {
        const double s = 2 * M_PI * j / 16;
        const V3 q = c + V3{(R + r * std::cos(s)) * std::sin(t),
                            (R + r * std::cos(s)) * std::cos(t), r * std::sin(s)};
        EXPECT_TRUE(ct.bounds().grown(T(1e-5)).contains(Vec3<T>::from(q))) << aperture << q;
      }
    }
  }
}

TYPED_TEST(ShapesTest, InfiniteCylinderAndConeMatchReference) {
  using T = TypeParam;
  const V3 o{0.3, -0.4, 0.2}, axis{1, 2, -0.5};
  const V3 w = normalized(axis);
  const InfiniteCylinder<T> ic{Vec3<T>::from(o), Vec3<T>::from(axis * 3.0), T(0.7)};
  const Aabb<T> box = Aabb<T>::of(v3<T>(-2, -2, -2), v3<T>(2, 2, 2));
  // distance to the axis by the cross product
  expect_matches(
      ic, [&](const V3& p) { return norm(cross(p - o, w)) - 0.7; }, box);
  EXPECT_EQ(ic.bounds(), Aabb<T>::infinite());

  const double alpha = 0.5;
  const auto cone = InfiniteCone<T>::make(Vec3<T>::from(o), Vec3<T>::from(axis), T(alpha));
  // reference: distance to the union of generator rays, minimised over the azimuth; inside when
  // the angle to the axis is below alpha
  const V3 e1 = normalized(cross(w, V3{0, 0, 1})), e2 = cross(w, e1);
  const auto ref = [&](const V3& p) {
    const V3 q = p - o;
    const double d = test::curve_min(
        [&](double phi) {
          const V3 g =
              w * std::cos(alpha) + (e1 * std::cos(phi) + e2 * std::sin(phi)) * std::sin(alpha);
          const double t = std::max(dot(q, g), 0.0);
          return norm(q - g * t);
        },
        -M_PI, M_PI, 720);
    const bool inside = dot(q, w) > norm(q) * std::cos(alpha);
    return inside ? -d : d;
  };
  expect_matches(cone, ref, box);
}

TYPED_TEST(ShapesTest, EikonalForEveryExactShape) {
  using T = TypeParam;
  const Vec3<T> a = v3<T>(-0.5, 0.2, 0.1), b = v3<T>(0.7, 1.1, -0.6), c = v3<T>(0.1, 0.2, 0.3);
  test::expect_eikonal(Sphere<T>{c, T(1)}, Sphere<T>{c, T(1)}.bounds().grown(1));
  test::expect_eikonal(Box<T>{v3<T>(1, 0.5, 0.7), c},
                       Box<T>{v3<T>(1, 0.5, 0.7), c}.bounds().grown(1));
  const RoundedBox<T> rb{v3<T>(1, 0.5, 0.7), T(0.2), c};
  test::expect_eikonal(rb, rb.bounds().grown(1));
  const Torus<T> tor{c, T(1), T(0.3)};
  test::expect_eikonal(tor, tor.bounds().grown(1));
  const auto ct = CappedTorus<T>::make(c, T(1), T(0.3), T(2));
  test::expect_eikonal(ct, ct.bounds().grown(1));
  const CappedCylinder<T> cyl{a, b, T(0.5)};
  test::expect_eikonal(cyl, cyl.bounds().grown(0.3));
  const RoundedCylinder<T> rc{a, b, T(0.5), T(0.1)};
  test::expect_eikonal(rc, rc.bounds().grown(0.3));
  const Aabb<T> cube = Aabb<T>::of(v3<T>(-2, -2, -2), v3<T>(2, 2, 2));
  test::expect_eikonal(InfiniteCylinder<T>{a, b - a, T(0.5)}, cube);
  const Capsule<T> cap{a, b, T(0.5)};
  test::expect_eikonal(cap, cap.bounds().grown(0.3));
  const CappedCone<T> cone{a, b, T(0.6), T(0.2)};
  test::expect_eikonal(cone, cone.bounds().grown(0.3));
  test::expect_eikonal(InfiniteCone<T>::make(a, b - a, T(0.4)), cube);
  test::expect_eikonal(Plane<T>{v3<T>(1, -2, 0.5), T(0.3)}, cube);
  const TriangularPrism<T> tri{c, T(0.6), T(0.4)};
  test::expect_eikonal(tri, tri.bounds().grown(1));
  const HexagonalPrism<T> hex{c, T(0.6), T(0.4)};
  test::expect_eikonal(hex, hex.bounds().grown(1));
}

TYPED_TEST(ShapesTest, EllipsoidNeverOverestimatesTrueDistance) {
  using T = TypeParam;
  for (const V3 radii : {V3{1.5, 0.5, 0.8}, V3{3, 0.2, 0.2}, V3{0.7, 0.7, 0.7}}) {
    const V3 c{0.2, -0.3, 0.1};
    const Ellipsoid<T> e{Vec3<T>::from(c), Vec3<T>::from(radii)};
    // exact signed distance of the (convex) ellipsoid from its support function c.u + |radii * u|
    const auto hs = [&](const V3& u) { return dot(c, u) + norm(mul(radii, u)); };
    int checked = 0;
    double worst_ratio = 1;
    for (const auto& p : test::random_points(e.bounds().grown(2), 400, 99)) {
      const double truth = test::convex_sdf(hs, V3::from(p));
      const double v = double(e(p));
      // right sign, never larger in magnitude than the true distance
      if (std::abs(truth) > 1e-4) {
        EXPECT_EQ(v < 0, truth < 0) << p;
      }
      EXPECT_LE(std::abs(v), std::abs(truth) + test::ref_tol<T>()) << p << " truth " << truth;
      if (std::abs(truth) > 0.1) worst_ratio = std::min(worst_ratio, std::abs(v) / std::abs(truth));
      ++checked;
    }
    EXPECT_EQ(checked, 400);
    // useful, not a trivial bound: at least a fifth of the distance everywhere off the surface
    EXPECT_GT(worst_ratio, 0.05);
    // a sphere is exact
    if (radii.x == radii.y && radii.y == radii.z) {
      for (const auto& p : test::random_points(e.bounds().grown(1), 100, 5))
        EXPECT_NEAR(double(e(p)), norm(V3::from(p) - c) - radii.x, test::ref_tol<T>());
    }
    // 1-Lipschitz: |e(p) - e(q)| <= |p - q|
    const auto pts = test::random_points(e.bounds().grown(1), 200, 8);
    for (std::size_t i = 1; i < pts.size(); ++i)
      EXPECT_LE(std::abs(double(e(pts[i])) - double(e(pts[i - 1]))),
                norm(V3::from(pts[i]) - V3::from(pts[i - 1])) + 1e-5);
  }
}

TYPED_TEST(ShapesTest, PerlinNoiseAndDisplacement) {
  using T = TypeParam;
  const PerlinNoise<T> n1(7), n2(7), n3(8);
  bool differs = false;
  double maxabs = 0;
  for (const auto& p : test::random_points(Aabb<T>::of(v3<T>(-9, -9, -9), v3<T>(9, 9, 9)), 2000)) {
    EXPECT_EQ(n1(p), n2(p)); // deterministic for a seed
    differs = differs || n1(p) != n3(p);
    maxabs = std::max(maxabs, double(std::abs(n1(p))));
    EXPECT_LE(std::abs(n1(p)), T(1));
  }
  EXPECT_TRUE(differs);
  EXPECT_GT(maxabs, 0.2);               // not identically zero
  EXPECT_EQ(n1(v3<T>(3, -2, 5)), T(0)); // gradient noise vanishes on the lattice
  // bad input is defined: NaN, infinite and huge coordinates give 0
  EXPECT_EQ(n1(v3<T>(std::nan(""), 0, 0)), T(0));
  EXPECT_EQ(n1(v3<T>(0, std::numeric_limits<double>::infinity(), 0)), T(0));
  EXPECT_EQ(n1(v3<T>(0, 0, 1e30)), T(0));

  PerlinOptions<T> opt;
  opt.amplitude = T(0.2);
  opt.frequency = v3<T>(3, 3, 3);
  opt.octaves = 3;
  const Sphere<T> s{Vec3<T>::zero(), T(1)};
  const auto d = perlin_displace(s, opt);
  EXPECT_NEAR(double(d.max_displacement()), 0.2 * (1 + 0.5 + 0.25), 1e-6);
  bool moved = false;
  for (const auto& p : test::random_points(s.bounds().grown(1), 2000, 3)) {
    const double delta = double(d(p)) - double(s(p));
    EXPECT_LE(std::abs(delta), double(d.max_displacement()) + 1e-6);
    moved = moved || std::abs(delta) > 1e-3;
    if (!d.bounds().contains(p)) {
      EXPECT_GT(d(p), T(0)) << p;
    }
  }
  EXPECT_TRUE(moved);
}
