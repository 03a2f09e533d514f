// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "ebgeom/bvh/node_obbs.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/isa.hpp"
#include "ebgeom/geom/closest_point_triangle.hpp"
#include "test_support.hpp"

using namespace ebgeom;
using namespace ebgeom::bvh;

template <class T> class NodeObbsTest : public ::testing::Test {};
TYPED_TEST_SUITE(NodeObbsTest, test::FloatTypes);

namespace {
template <class T> using Tri = std::array<Vec3<T>, 3>;

/// A patch of 16 triangles of a given kind, `size` across, centred near `at`, turned at random.
template <class T>
std::vector<Tri<T>> patch(int kind, std::mt19937_64& rng, const Vec3<double>& at, double size) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3<double> n = Vec3<double>::from(test::random_unit<double>(rng));
  const Vec3<double> h = std::abs(n.x) < 0.9 ? Vec3<double>{1, 0, 0} : Vec3<double>{0, 1, 0};
  const Vec3<double> t0 = normalized(cross(h, n)), t1 = cross(n, t0);
  const double radius = size * (1 + 20 * (u(rng) + 1)); // curvature of the cap
  auto surface = [&](double x, double y) {
    double z = 0;
    if (kind == 1) z = (x * x + y * y) / (2 * radius); // a cap of a sphere
    if (kind == 2) z = size * 0.3 * std::sin(7 * x / size) * std::cos(5 * y / size); // wavy
    return at + t0 * x + t1 * y + n * z;
  };
  auto to_t = [](const Vec3<double>& v) { return Vec3<T>{T(v.x), T(v.y), T(v.z)}; };
  std::vector<Tri<T>> tris;
  for (int i = 0; i < 16; ++i) {
    if (kind == 3) { // a random soup in a box
      tris.push_back({to_t(at + Vec3<double>{u(rng), u(rng), u(rng)} * size),
                      to_t(at + Vec3<double>{u(rng), u(rng), u(rng)} * size),
                      to_t(at + Vec3<double>{u(rng), u(rng), u(rng)} * size)});
      continue;
    }
    if (kind == 4) { // every corner the same point
      tris.push_back({to_t(at), to_t(at), to_t(at)});
      continue;
    }
    const double x0 = size * (i % 4 - 2) / 4, y0 = size * (i / 4 - 2) / 4, d = size / 4;
    tris.push_back({to_t(surface(x0, y0)), to_t(surface(x0 + d, y0)), to_t(surface(x0, y0 + d))});
  }
  return tris;
}

template <class T, int K>
void fit_child(NodeObbs<T, K>& o, int k, const std::vector<Tri<T>>& tris) {
  Vec3<double> normal{0, 0, 0};
  auto corner = [&](std::size_t j) {
    const Vec3<T>& v = tris[j / 3][j % 3];
    return Vec3<double>{double(v.x), double(v.y), double(v.z)};
  };
  for (std::size_t t = 0; t < tris.size(); ++t)
    normal = normal + cross(corner(3 * t + 1) - corner(3 * t), corner(3 * t + 2) - corner(3 * t));
  o.fit(k, normal, tris.size() * 3, corner);
}

/// A random point of triangle t (barycentric weights from rng).
template <class T> Vec3<double> point_on(const Tri<T>& t, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double w0 = (u(rng) + 1) / 2, w1 = (1 - w0) * (u(rng) + 1) / 2;
  return Vec3<double>::from(t[0]) * w0 + Vec3<double>::from(t[1]) * w1 +
         Vec3<double>::from(t[2]) * (1 - w0 - w1);
}

using LD = long double;

/// Squared distance from p to x, in long double.
template <class T> LD dist2_ld(const Vec3<T>& p, const Vec3<LD>& x) {
  const LD dx = LD(p.x) - x.x, dy = LD(p.y) - x.y, dz = LD(p.z) - x.z;
  return dx * dx + dy * dy + dz * dz;
}

/// Points of the triangles (corners, centroids, and each triangle's point nearest to p, in long
/// double): the bound must not exceed the distance to any of them.
template <class T> LD nearest_sampled_dist2(const std::vector<Tri<T>>& tris, const Vec3<T>& p) {
  LD best = std::numeric_limits<LD>::infinity();
  auto ld = [](const Vec3<T>& v) { return Vec3<LD>{LD(v.x), LD(v.y), LD(v.z)}; };
  for (const Tri<T>& t : tris) {
    const Vec3<LD> a = ld(t[0]), b = ld(t[1]), c = ld(t[2]);
    const Vec3<LD> cp = closest_point_triangle(ld(p), a, b, c).point;
    for (const Vec3<LD>& x : {a, b, c, (a + b + c) / LD(3), cp})
      best = std::min(best, dist2_ld(p, x));
  }
  return best;
}

/// The forms of `raise_dist2` this build and CPU can run.
template <class T>
std::vector<
    std::pair<std::string, std::function<void(const NodeObbs<T, 4>&, const Vec3<T>&, T (&)[4])>>>
forms() {
  std::vector<
      std::pair<std::string, std::function<void(const NodeObbs<T, 4>&, const Vec3<T>&, T(&)[4])>>>
      f;
  f.push_back({"generic", [](const NodeObbs<T, 4>& o, const Vec3<T>& p, T(&d2)[4]) {
                 raise_dist2_generic(o, p, d2);
               }});
  f.push_back({"native", [](const NodeObbs<T, 4>& o, const Vec3<T>& p, T(&d2)[4]) {
                 raise_dist2<native_isa>(o, p, d2);
               }});
#if EBGEOM_ISA_DISPATCH
  if (int(detected_isa()) >= int(Isa::avx2))
    f.push_back({"avx2", [](const NodeObbs<T, 4>& o, const Vec3<T>& p, T(&d2)[4]) {
                   raise_dist2<Isa::avx2>(o, p, d2);
                 }});
#endif
  return f;
}
} // namespace

TYPED_TEST(NodeObbsTest, NeverExceedsTheDistanceToAnyPointOfTheLeaf) {
  using T = TypeParam;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto fs = forms<T>();
  int checked = 0, raised = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const int kind = trial % 5;
    const double size = std::pow(10.0, 3 * u(rng));                  // 1e-3 .. 1e3
    const double offset = size * std::pow(10.0, 1.5 * (u(rng) + 1)); // up to 1000 sizes away
    const Vec3<double> at = Vec3<double>::from(test::random_unit<double>(rng)) * offset;
    const auto tris = patch<T>(kind, rng, at, size);
    NodeObbs<T, 4> o;
    o.clear();
    const int k = trial % 4;
    fit_child(o, k, tris);
    std::vector<Vec3<T>> pts;
    for (int i = 0; i < 60; ++i) { // near, far, and on the patch
      const double s = i < 30 ? 2 * size : i < 50 ? 200 * size : 0;
      Vec3<double> q = at + Vec3<double>{u(rng), u(rng), u(rng)} * s;
      if (i >= 50) {
        q = point_on(tris[std::size_t(i) % tris.size()], rng);
      }
      pts.push_back({T(q.x), T(q.y), T(q.z)});
    }
    for (const Vec3<T>& p : pts) {
      const LD ref = nearest_sampled_dist2(tris, p);
      for (const auto& [name, f] : fs) {
        T d2[4] = {T(0), T(0), T(0), T(0)};
        f(o, p, d2);
        for (int j = 0; j < 4; ++j) {
          if (j == k) continue;
          ASSERT_EQ(d2[j], T(0)) << name << ": a cleared child was raised";
        }
        ASSERT_LE(LD(d2[k]), ref) << name << " kind " << kind << " size " << size << " offset "
                                  << offset << " p " << p;
        ++checked;
        raised += d2[k] > T(0);
      }
    }
  }
  EXPECT_GT(checked, 10000);
  EXPECT_GT(raised, checked / 4); // a bound that is always 0 would pass the check above
}

namespace {
EBGEOM_BEGIN_EXACT_FP
/// The formula of `raise_dist2_generic`, never contracted into fused multiply-adds: the reference
/// of every form.
template <class T, int K>
EBGEOM_EXACT_KERNEL void reference_raise(const NodeObbs<T, K>& o, const Vec3<T>& p, T (&d2)[K]) {
  for (int k = 0; k < K; ++k) {
    const T dx = p.x - o.cx[k], dy = p.y - o.cy[k], dz = p.z - o.cz[k];
    const T tu = o.ux[k] * dx + o.uy[k] * dy + o.uz[k] * dz;
    const T tv = o.vx[k] * dx + o.vy[k] * dy + o.vz[k] * dz;
    const T tn = o.nx[k] * dx + o.ny[k] * dy + o.nz[k] * dz;
    const T gu = std::max(std::abs(tu) - o.hu[k], T(0));
    const T gv = std::max(std::abs(tv) - o.hv[k], T(0));
    const T gn = std::max(std::abs(tn) - o.hn[k], T(0));
    const T s = gu * gu + gv * gv + gn * gn;
    d2[k] = std::max(d2[k], s);
  }
}
EBGEOM_END_EXACT_FP

/// GCC fuses a*b + c into one rounding where FMA is enabled (`-mfma`), in the generic loop and in
/// SSE / AVX intrinsics alike; the forms then round differently from the scalar formula (their
/// bound still holds: fewer roundings).
#if defined(__FMA__) && defined(__GNUC__) && !defined(__clang__)
constexpr bool may_contract = true;
#else
constexpr bool may_contract = false;
#endif

/// Every form of `raise_dist2` for K children that this build and CPU can run, on boxes fitted to
/// random patches (and cleared children) and points near, far and on them, from starting
/// distances below and above the boxes': never lowers a distance, never raises one above the
/// distance to the child's triangles, and gives the scalar formula's values bit for bit where the
/// compiler cannot contract.
template <class T, int K> void every_form_bounds_and_equals_the_scalar_formula() {
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  using Form = std::function<void(const NodeObbs<T, K>&, const Vec3<T>&, T(&)[K])>;
  std::vector<std::pair<std::string, Form>> fs;
  fs.push_back({"native", [](const NodeObbs<T, K>& o, const Vec3<T>& p, T(&d2)[K]) {
                  raise_dist2<native_isa>(o, p, d2);
                }});
  fs.push_back({"baseline", [](const NodeObbs<T, K>& o, const Vec3<T>& p, T(&d2)[K]) {
                  raise_dist2<Isa::baseline>(o, p, d2);
                }});
  fs.push_back({"generic", [](const NodeObbs<T, K>& o, const Vec3<T>& p, T(&d2)[K]) {
                  raise_dist2_generic(o, p, d2);
                }});
#if EBGEOM_ISA_DISPATCH
  if (int(detected_isa()) >= int(Isa::avx2))
    fs.push_back({"avx2", [](const NodeObbs<T, K>& o, const Vec3<T>& p, T(&d2)[K]) {
                    raise_dist2<Isa::avx2>(o, p, d2);
                  }});
  if (int(detected_isa()) >= int(Isa::avx512))
    fs.push_back({"avx512", [](const NodeObbs<T, K>& o, const Vec3<T>& p, T(&d2)[K]) {
                    raise_dist2<Isa::avx512>(o, p, d2);
                  }});
#endif
  int compared = 0, raised = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double size = std::pow(10.0, 2 * u(rng));
    NodeObbs<T, K> o;
    o.clear();
    std::vector<std::vector<Tri<T>>> tris(K); // per child; empty for a cleared child
    std::vector<Tri<T>> all;
    for (int k = 0; k < K; ++k) {
      if ((trial + k) % 5 == 4) continue;
      const Vec3<double> at = Vec3<double>{u(rng), u(rng), u(rng)} * (4 * size);
      tris[std::size_t(k)] = patch<T>(k % 4, rng, at, size);
      fit_child(o, k, tris[std::size_t(k)]);
      all.insert(all.end(), tris[std::size_t(k)].begin(), tris[std::size_t(k)].end());
    }
    for (int i = 0; i < 50; ++i) {
      const double s = i < 25 ? 6 * size : 100 * size;
      Vec3<double> q = Vec3<double>{u(rng), u(rng), u(rng)} * s;
      if (i >= 40) q = point_on(all[std::size_t(i) % all.size()], rng);
      const Vec3<T> p{T(q.x), T(q.y), T(q.z)};
      T start[K], want[K];
      for (int k = 0; k < K; ++k) start[k] = want[k] = T((u(rng) + 1) * size * size * (i % 3));
      reference_raise(o, p, want);
      for (const auto& [name, f] : fs) {
        T got[K];
        std::copy(start, start + K, got);
        f(o, p, got);
        for (int k = 0; k < K; ++k) {
          const auto& tk = tris[std::size_t(k)];
          const LD cap =
              tk.empty() ? LD(start[k]) : std::max(LD(start[k]), nearest_sampled_dist2(tk, p));
          ASSERT_GE(got[k], start[k]) << name << " K " << K << " child " << k;
          ASSERT_LE(LD(got[k]), cap) << name << " K " << K << " child " << k << " p " << p;
          if (!may_contract) {
            ASSERT_EQ(std::memcmp(&got[k], &want[k], sizeof(T)), 0)
                << name << " K " << K << " child " << k << ": " << got[k] << " vs " << want[k];
          }
        }
        ++compared;
      }
      for (int k = 0; k < K; ++k) raised += want[k] > start[k];
    }
  }
  EXPECT_EQ(compared, 40 * 50 * int(fs.size()));
  EXPECT_GT(raised, 40 * 50 * K / 10); // the boxes do raise distances
}
} // namespace

TYPED_TEST(NodeObbsTest, EveryFormBoundsAndEqualsTheScalarFormulaForFourToSixteenChildren) {
  every_form_bounds_and_equals_the_scalar_formula<TypeParam, 4>();
  every_form_bounds_and_equals_the_scalar_formula<TypeParam, 8>();
  every_form_bounds_and_equals_the_scalar_formula<TypeParam, 16>(); // AVX-512: one register
}

TYPED_TEST(NodeObbsTest, AnySumsGiveABoxThatHoldsThePatch) {
  // The sums only orient the box (`fit_from_sums`): wrong, extreme or NaN sums still give a box
  // around the corners, so a bound that never exceeds the distance to the patch.
  using T = TypeParam;
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double nan = std::nan("");
  int checked = 0, raised = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const double size = std::pow(10.0, 2 * u(rng));
    const Vec3<double> at = Vec3<double>::from(test::random_unit<double>(rng)) * (10 * size);
    const auto tris = patch<T>(trial % 4, rng, at, size);
    PatchStats st;
    st.ref = Vec3<double>{u(rng), u(rng), u(rng)} * (trial % 3 == 0 ? 1e300 : size);
    st.n = trial % 5 == 0 ? 0 : 1 + 100 * (u(rng) + 1);
    st.sum = Vec3<double>{u(rng), u(rng), u(rng)} * (trial % 7 == 0 ? nan : 1e3);
    st.sxx = trial % 2 ? -1e200 : u(rng), st.syy = u(rng), st.szz = u(rng);
    st.sxy = trial % 11 == 0 ? nan : u(rng), st.sxz = u(rng), st.syz = u(rng);
    st.normal = trial % 6 == 0 ? Vec3<double>{0, 0, 0} : Vec3<double>{u(rng), u(rng), u(rng)};
    NodeObbs<T, 4> o;
    o.clear();
    o.fit_from_sums(1, st, tris.size() * 3, [&](std::size_t j) {
      const Vec3<T>& v = tris[j / 3][j % 3];
      return Vec3<double>{double(v.x), double(v.y), double(v.z)};
    });
    for (int i = 0; i < 60; ++i) { // near, far, and on the patch
      const double s = i < 20 ? 2 * size : 100 * size;
      Vec3<double> q = at + Vec3<double>{u(rng), u(rng), u(rng)} * s;
      if (i >= 40) {
        q = point_on(tris[std::size_t(i) % tris.size()], rng);
      }
      const Vec3<T> p{T(q.x), T(q.y), T(q.z)};
      const LD ref = nearest_sampled_dist2(tris, p);
      for (const auto& [name, f] : forms<T>()) {
        T d2[4] = {T(0), T(0), T(0), T(0)};
        f(o, p, d2);
        ASSERT_FALSE(std::isnan(d2[1])) << name << " trial " << trial;
        ASSERT_LE(LD(d2[1]), ref) << name << " trial " << trial << " p " << p;
        ++checked;
        raised += d2[1] > T(0);
      }
    }
  }
  EXPECT_GT(checked, 3000);
  EXPECT_GT(raised, checked / 4); // boxes that raise nothing would pass the check above
}

TEST(PatchStatsTest, MergedSumsEqualOnePassOverAllCorners) {
  // Two halves merged give the sums of the whole (up to rounding), and `scatter` is n times the
  // covariance of the corners along two directions, computed here about their mean directly.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3<double> ref{100, -50, 20};
  std::vector<Vec3<double>> pts;
  for (int i = 0; i < 30; ++i)
    pts.push_back(Vec3<double>{100 + 3 * u(rng), -50 + u(rng), 20 + 0.1 * u(rng)});
  PatchStats all, a, b;
  all.ref = a.ref = b.ref = ref;
  for (int t = 0; t < 10; ++t) {
    all.add_triangle(pts[3 * t], pts[3 * t + 1], pts[3 * t + 2]);
    (t < 4 ? a : b).add_triangle(pts[3 * t], pts[3 * t + 1], pts[3 * t + 2]);
  }
  a.merge(b);
  Vec3<double> mean{0, 0, 0};
  for (const auto& x : pts) mean = mean + x / 30.0;
  const Vec3<double> dirs[3] = {{1, 0, 0}, normalized(Vec3<double>{1, 2, 3}), {0, 0, 1}};
  for (const Vec3<double>& d0 : dirs)
    for (const Vec3<double>& d1 : dirs) {
      double direct = 0;
      for (const auto& x : pts) direct += dot(d0, x - mean) * dot(d1, x - mean);
      EXPECT_NEAR(all.scatter(d0, d1), direct, 1e-9 * (1 + std::abs(direct)));
      EXPECT_NEAR(a.scatter(d0, d1), direct, 1e-9 * (1 + std::abs(direct)));
    }
  EXPECT_EQ(a.n, 30);
  EXPECT_NEAR(norm(a.normal - all.normal), 0, 1e-12 * norm(all.normal));
}

TYPED_TEST(NodeObbsTest, IsTighterThanTheAxisAlignedBoxOnATiltedPatch) {
  using T = TypeParam;
  // A flat square in the plane x + y + z = 0, and a point 1 above its centre along the normal:
  // its axis-aligned box reaches within 0.4 of the point, its oriented box no nearer than 1.
  const Vec3<double> n = normalized(Vec3<double>{1, 1, 1});
  const Vec3<double> a = normalized(Vec3<double>{1, -1, 0}), b = cross(n, a);
  std::vector<Tri<T>> tris;
  auto pt = [&](double x, double y) {
    const Vec3<double> v = a * x + b * y;
    return Vec3<T>{T(v.x), T(v.y), T(v.z)};
  };
  tris.push_back({pt(-1, -1), pt(1, -1), pt(1, 1)});
  tris.push_back({pt(-1, -1), pt(1, 1), pt(-1, 1)});
  NodeObbs<T, 4> o;
  o.clear();
  fit_child(o, 2, tris);
  const Vec3<T> p{T(n.x), T(n.y), T(n.z)};
  Aabb<T> box;
  for (const auto& t : tris)
    for (const auto& v : t) box.extend(v);
  for (const auto& [name, f] : forms<T>()) {
    T d2[4] = {T(0), T(0), box.distance2(p), T(0)};
    EXPECT_LT(d2[2], T(0.2));
    f(o, p, d2);
    EXPECT_GT(d2[2], T(0.999)) << name;
    EXPECT_LE(d2[2], T(1)) << name;
  }
}

TYPED_TEST(NodeObbsTest, AZeroOrNonFiniteNormalGivesTheCoordinateAxes) {
  using T = TypeParam;
  NodeObbs<T, 4> o;
  o.clear();
  const Vec3<double> pts[2] = {{0, 0, 0}, {1, 2, 3}};
  auto corner = [&](std::size_t j) { return pts[j]; };
  o.fit(0, {0, 0, 0}, 2, corner);
  o.fit(1, {std::nan(""), 0, 0}, 2, corner);
  for (int k = 0; k < 2; ++k) {
    T d2[4] = {T(0), T(0), T(0), T(0)};
    raise_dist2_generic(o, Vec3<T>{T(3), T(2), T(3)}, d2); // 2 beyond x = 1
    EXPECT_LE(d2[k], T(4));
    EXPECT_GT(d2[k], T(3.999));
  }
}

TEST(NodeObbsEdgeTest, APatchAtTheEdgeOfTheFloatRangeNeverGivesNaN) {
  // Corners at the largest float: the oriented box's centre or extents may fall beyond the range
  // of float. The box must then raise nothing rather than give NaN (which would drop the child).
  const float m = std::numeric_limits<float>::max(), d = m * 1e-3f;
  for (int variant = 0; variant < 3; ++variant) {
    std::vector<Tri<float>> tris;
    if (variant == 0) tris.push_back({Vec3<float>{m, m, m}, {m, m - d, m}, {m - d, m, m}});
    if (variant == 1) tris.push_back({Vec3<float>{m, m, m}, {m - d, m - d, m}, {m - d, m, m - d}});
    if (variant == 2) tris.push_back({Vec3<float>{-m, m, 0}, {m, -m, 0}, {m, m, 0}});
    NodeObbs<float, 4> o;
    o.clear();
    fit_child(o, 1, tris);
    for (const auto& [name, f] : forms<float>()) {
      // The corners: from anywhere else near the patch, squared distances overflow float (as the
      // axis-aligned box's do).
      for (const Vec3<float>& p : tris[0]) {
        float d2[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        f(o, p, d2);
        EXPECT_FALSE(std::isnan(d2[1])) << name << " variant " << variant;
        EXPECT_LE(LD(d2[1]), nearest_sampled_dist2(tris, p)) << name << " variant " << variant;
      }
    }
  }
}
