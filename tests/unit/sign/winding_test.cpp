// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Exact and fast generalized winding numbers (sdf/winding.hpp).
#include "ebgeom/sdf/winding.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "ebgeom/core/isa.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/split_sign.hpp"
#include "sign_support.hpp"
#include "test_support.hpp"

namespace ebgeom {
namespace {

template <class T> class WindingTest : public ::testing::Test {};
TYPED_TEST_SUITE(WindingTest, test::FloatTypes);

TYPED_TEST(WindingTest, ExactIsOneInsideZeroOutsideClosedMeshes) {
  using T = TypeParam;
  for (const auto& soup : {make_icosphere<T>(2).value(), make_torus<T>(1, T(0.3)).value(),
                           make_cube<T>(T(0.5)).value()}) {
    const TriangleMesh<T> m = make_triangle_mesh(soup).value();
    const auto sdf = test::brute_sdf(m);
    for (const auto& p : test::random_points(m.bounds().grown(T(0.3)), 300, 7)) {
      const T s = sdf(p);
      if (std::abs(s) < T(1e-3)) continue;
      const T w = winding_number(m, p);
      EXPECT_NEAR(w, s < 0 ? T(1) : T(0), sizeof(T) == 4 ? 1e-4 : 1e-10) << p;
    }
  }
}

TYPED_TEST(WindingTest, FastEqualsExactOnClosedMeshes) {
  using T = TypeParam;
  for (const auto& soup : {make_icosphere<T>(3).value(), make_torus<T>(1, T(0.3)).value(),
                           make_cube<T>(T(0.5)).value()}) {
    const TriangleMesh<T> m = make_triangle_mesh(soup).value();
    const auto fw = FastWindingNumber<T>::make(m).value();
    double worst = 0;
    for (const auto& p : test::random_points(m.bounds().grown(T(0.5)), 2000, 11)) {
      const T w = fw(p), e = fw.exact(p);
      ASSERT_TRUE(std::isfinite(w));
      worst = std::max(worst, std::abs(double(w) - double(e)));
      EXPECT_NEAR(e, winding_number(m, p), sizeof(T) == 4 ? 1e-5 : 1e-12);
    }
    EXPECT_LT(worst, test::fast_winding_tolerance);
  }
}

TYPED_TEST(WindingTest, FastApproximatesExactOnOpenMeshesAndConvergesWithBeta) {
  using T = TypeParam;
  // An open bowl: the icosphere without its upper cap (z > 0.3), plus a torus with a slot cut out.
  const TriangleMesh<T> bowl =
      make_triangle_mesh(test::remove_cap(make_icosphere<T>(4).value(), T(0.3))).value();
  const auto pts = test::random_points(bowl.bounds().grown(T(0.5)), 3000, 5);
  double prev = 1;
  for (double beta : {1.0, 2.0, 4.0}) {
    WindingOptions o;
    o.beta = beta;
    const auto fw = FastWindingNumber<T>::make(bowl, o).value();
    double worst = 0;
    int side_changes = 0;
    for (const auto& p : pts) {
      const double w = fw(p), e = fw.exact(p);
      worst = std::max(worst, std::abs(w - e));
      if ((w > 0.5) != (e > 0.5) && std::abs(e - 0.5) > test::fast_winding_tolerance)
        ++side_changes;
    }
    EXPECT_LT(worst, prev) << "beta " << beta;
    if (beta >= 2) {
      EXPECT_LT(worst, beta >= 4 ? 0.02 : test::fast_winding_tolerance) << "beta " << beta;
    }
    EXPECT_EQ(side_changes, 0) << "beta " << beta;
    prev = worst;
  }
}

TYPED_TEST(WindingTest, SingleLeafMeshIsExact) {
  using T = TypeParam;
  const TriangleMesh<T> m = make_triangle_mesh(make_tetrahedron<T>().value()).value();
  const auto fw = FastWindingNumber<T>::make(m).value();
  ASSERT_TRUE(fw.tree().root.is_leaf());
  for (const auto& p : test::random_points(m.bounds().grown(T(1)), 200, 3))
    EXPECT_EQ(fw(p), fw.exact(p));
}

TYPED_TEST(WindingTest, FiniteOnVerticesEdgesFacesAndFarAway) {
  using T = TypeParam;
  const TriangleMesh<T> m = make_triangle_mesh(make_icosphere<T>(2).value()).value();
  const auto fw = FastWindingNumber<T>::make(m).value();
  std::vector<Vec3<T>> pts(m.vertices);
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    pts.push_back((m.corner(t, 0) + m.corner(t, 1)) / T(2));
    pts.push_back((m.corner(t, 0) + m.corner(t, 1) + m.corner(t, 2)) / T(3));
  }
  pts.push_back({T(1e30), T(0), T(0)});
  pts.push_back({T(0), T(0), T(0)});
  for (const auto& p : pts) {
    ASSERT_TRUE(std::isfinite(fw(p))) << p;
    ASSERT_TRUE(std::isfinite(fw.exact(p))) << p;
  }
}

TEST(WindingErrors, RefusedInputs) {
  TriangleMesh<double> empty;
  EXPECT_EQ(FastWindingNumber<double>::make(empty).error().code, ErrorCode::empty);
  const TriangleMesh<double> m = make_triangle_mesh(make_cube<double>().value()).value();
  WindingOptions o;
  o.beta = 0;
  EXPECT_EQ(FastWindingNumber<double>::make(m, o).error().code, ErrorCode::invalid_argument);
  o.beta = std::nan("");
  EXPECT_EQ(FastWindingNumber<double>::make(m, o).error().code, ErrorCode::invalid_argument);
  TriangleMesh<double> bad = m;
  bad.vertices[0].x = std::nan("");
  EXPECT_EQ(FastWindingNumber<double>::make(bad).error().code, ErrorCode::non_finite);
  bad = m;
  bad.triangles[0][1] = 1000;
  EXPECT_EQ(FastWindingNumber<double>::make(bad).error().code, ErrorCode::bad_index);
}

TEST(WindingBvh, EveryWidthAgrees) {
  const TriangleMesh<double> m = make_triangle_mesh(make_torus<double>(1, 0.4).value()).value();
  const auto f2 = FastWindingNumber<double, 2>::make(m).value();
  const auto f4 = FastWindingNumber<double, 4>::make(m).value();
  const auto f8 = FastWindingNumber<double, 8>::make(m).value();
  for (const auto& p : test::random_points(m.bounds().grown(0.5), 500, 9)) {
    const double e = winding_number(m, p);
    EXPECT_NEAR(f2(p), e, test::fast_winding_tolerance);
    EXPECT_NEAR(f4(p), e, test::fast_winding_tolerance);
    EXPECT_NEAR(f8(p), e, test::fast_winding_tolerance);
  }
}

template <class T> bool same_bits(T a, T b) { return std::memcmp(&a, &b, sizeof a) == 0; }

/// Runs `fn()` once per instruction set the packet kernels can run here (`set_isa`: baseline
/// always, AVX2 and AVX-512 where the CPU has them and the build dispatches), restoring the
/// active one: the packets must give the per-point values (compiled for the translation unit's
/// own flags) bit for bit on every one.
template <class Fn> void for_each_isa(Fn&& fn) {
  const Isa was = active_isa();
  int ran = 0;
  for (Isa i : {Isa::baseline, Isa::avx2, Isa::avx512}) {
    if (!set_isa(i)) continue;
    SCOPED_TRACE(to_string(i));
    ASSERT_EQ(active_isa(), i);
    ++ran;
    fn();
    if (::testing::Test::HasFatalFailure()) break;
  }
  set_isa(was);
  EXPECT_GE(ran, 1);
}

/// Points to evaluate in packets: random points around the mesh, and the samples of a fine
/// lattice next to the surface, in 4x2x2 groups (two to a packet), some on vertices.
template <class T>
std::vector<Vec3<T>> packet_points(const TriangleMesh<T>& m, std::uint64_t seed) {
  std::vector<Vec3<T>> pts = test::random_points(m.bounds().grown(T(0.4)), 1600, seed);
  const Aabb<T> box = m.bounds().grown(T(0.05));
  const T h = max_component(box.extent()) / T(60);
  std::mt19937_64 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, m.triangle_count() - 1);
  for (int g = 0; g < 200; ++g) { // groups of 4x2x2 lattice samples around a random triangle
    const Vec3<T> c = m.corner(pick(rng), 0);
    const Vec3<T> o{box.lo.x + h * std::floor((c.x - box.lo.x) / h),
                    box.lo.y + h * std::floor((c.y - box.lo.y) / h),
                    box.lo.z + h * std::floor((c.z - box.lo.z) / h)};
    for (int z = 0; z < 2; ++z)
      for (int y = 0; y < 2; ++y)
        for (int x = 0; x < 4; ++x) pts.push_back(o + Vec3<T>{T(x), T(y), T(z)} * h);
  }
  for (std::size_t v = 0; v < m.vertices.size(); v += 7) pts.push_back(m.vertices[v]);
  return pts;
}

template <class T, int K> void expect_packets_equal_points(const TriangleMesh<T>& m, int leaf) {
  WindingOptions o;
  o.max_leaf_size = std::uint32_t(leaf);
  const auto fw = FastWindingNumber<T, K>::make(m, o).value();
  const std::vector<Vec3<T>> pts = packet_points(m, std::uint64_t(K * 100 + leaf));
  std::vector<T> ref(pts.size());
  for (std::size_t i = 0; i < pts.size(); ++i) ref[i] = fw(pts[i]);
  // Packets of every size over consecutive points (near ones in the lattice groups, far apart
  // among the random ones).
  constexpr int P = FastWindingNumber<T, K>::packet_width;
  std::mt19937_64 rng(3);
  std::uniform_int_distribution<int> size(1, P);
  T out[P];
  for (std::size_t i = 0; i < pts.size();) {
    const int n = int(std::min<std::size_t>(std::size_t(size(rng)), pts.size() - i));
    fw.eval_packet(pts.data() + i, n, out);
    for (int j = 0; j < n; ++j)
      ASSERT_TRUE(same_bits(out[j], ref[i + std::size_t(j)]))
          << pts[i + std::size_t(j)] << ": packet " << out[j] << " vs " << ref[i + std::size_t(j)];
    i += std::size_t(n);
  }
  // The batch call, and a packet holding a NaN point: the others are unaffected.
  std::vector<T> all(pts.size());
  fw.eval(Span<const Vec3<T>>(pts), Span<T>(all));
  for (std::size_t i = 0; i < pts.size(); ++i) ASSERT_TRUE(same_bits(all[i], ref[i])) << i;
  Vec3<T> mixed[P];
  for (int j = 0; j < P; ++j) mixed[j] = pts[pts.size() - 1 - std::size_t(j) * 3];
  mixed[5] = {std::numeric_limits<T>::quiet_NaN(), T(0), T(0)};
  fw.eval_packet(mixed, P, out);
  for (int j = 0; j < P; ++j)
    if (j != 5) {
      ASSERT_TRUE(same_bits(out[j], fw(mixed[j]))) << j;
    }
}

/// Three open meshes (holes cut by `remove_cap`) and a closed one, for the packet tests.
template <class T> std::vector<std::pair<const char*, PolygonSoup<T>>> packet_meshes() {
  std::vector<std::pair<const char*, PolygonSoup<T>>> m;
  m.emplace_back("open bowl", test::remove_cap(make_icosphere<T>(4).value(), T(0.3)));
  m.emplace_back("open torus", test::remove_cap(make_torus<T>(1, T(0.3), 48, 16).value(), T(0.1)));
  m.emplace_back("open box", test::remove_cap(
                                 make_box<T>({-1, -0.7f, -0.5f}, {1, 0.7f, 0.5f}).value(), T(0.4)));
  m.emplace_back("closed ball", make_icosphere<T>(3).value());
  return m;
}

TYPED_TEST(WindingTest, PacketsAreThePerPointValuesBitForBit) {
  using T = TypeParam;
  const auto meshes = packet_meshes<T>();
  const TriangleMesh<T> tet = make_triangle_mesh(make_tetrahedron<T>().value()).value();
  for_each_isa([&] {
    for (const auto& [name, soup] : meshes) {
      SCOPED_TRACE(name);
      const TriangleMesh<T> m = make_triangle_mesh(soup).value();
      expect_packets_equal_points<T, 4>(m, 8);
      expect_packets_equal_points<T, 8>(m, 8);
      expect_packets_equal_points<T, 2>(m, 1);
      expect_packets_equal_points<T, 4>(m, 3);
    }
    // A single-leaf tree (the root is a leaf).
    expect_packets_equal_points<T, 4>(tet, 8);
  });
  // An empty packet.
  const auto fw = FastWindingNumber<T>::make(tet).value();
  T untouched = T(7);
  fw.eval_packet(nullptr, 0, &untouched);
  EXPECT_EQ(untouched, T(7));
}

/// The end points of `range_over`'s intervals, alone and from a scope, for boxes of every size
/// (from 1/4096 to 1/2 of the mesh's size) around and across the mesh, in order; each interval
/// is checked to hold the value at its box's centre.
template <class T, int K>
std::vector<double> range_ends(const FastWindingNumber<T, K>& fw, const TriangleMesh<T>& m) {
  std::vector<double> ends;
  std::mt19937_64 rng(5);
  const T size = max_component(m.bounds().extent());
  std::uniform_real_distribution<double> log_half(-12, -1);
  for (const Vec3<T>& c : test::random_points(m.bounds().grown(size), 300, 21)) {
    const T h = T(std::exp2(log_half(rng))) * size;
    const Vec3<T> d{h, h, h};
    const Aabb<T> box{c - d, c + d};
    const WindingRange r = fw.range_over(box);
    EXPECT_TRUE(r.lo <= double(fw(c)) && double(fw(c)) <= r.hi) << c << " half size " << h;
    typename FastWindingNumber<T, K>::RangeScope scope;
    fw.scope(box.grown(h), scope);
    const WindingRange s = fw.range_over(scope, Aabb<T>{c, c + d});
    EXPECT_TRUE(s.lo <= double(fw(c)) && double(fw(c)) <= s.hi) << c << " half size " << h;
    for (const double v : {r.lo, r.hi, s.lo, s.hi}) ends.push_back(v);
  }
  return ends;
}

TYPED_TEST(WindingTest, BoxBoundsAreTheSameOnEveryInstructionSet) {
  // The box bounds' kernels (`range_over`, per instruction set, with 4 children at a time in
  // vector registers for K = 4 with AVX2 and AVX-512) must give the same intervals bit for bit.
  using T = TypeParam;
  for (const auto& [name, soup] : packet_meshes<T>()) {
    SCOPED_TRACE(name);
    const TriangleMesh<T> m = make_triangle_mesh(soup).value();
    const auto f4 = FastWindingNumber<T, 4>::make(m).value();
    const auto f8 = FastWindingNumber<T, 8>::make(m).value();
    std::vector<double> ref4, ref8;
    for_each_isa([&] {
      const std::vector<double> e4 = range_ends(f4, m), e8 = range_ends(f8, m);
      if (ref4.empty()) {
        ref4 = e4, ref8 = e8;
        return;
      }
      ASSERT_EQ(e4.size(), ref4.size());
      for (std::size_t i = 0; i < e4.size(); ++i)
        ASSERT_TRUE(same_bits(e4[i], ref4[i])) << i << ": " << e4[i] << " vs " << ref4[i];
      for (std::size_t i = 0; i < e8.size(); ++i)
        ASSERT_TRUE(same_bits(e8[i], ref8[i])) << i << ": " << e8[i] << " vs " << ref8[i];
    });
    // Not vacuous: boxes of both kinds, decided (one side of 1/2) and not.
    std::size_t decided = 0, finite = 0;
    for (std::size_t i = 0; i < ref4.size(); i += 2) {
      decided += ref4[i] > 0.5 || ref4[i + 1] < 0.5;
      finite += std::isfinite(ref4[i]) && std::isfinite(ref4[i + 1]);
    }
    EXPECT_GT(decided, ref4.size() / 8);
    EXPECT_LT(decided, ref4.size() / 2);
    EXPECT_LT(decided, finite);
  }
}

// ---- The sign-only fast path: bound_packet and above_half_packet -------------------------------

TEST(WindingBoundedAtan2, WithinItsBoundOfStdAtan2) {
  const double bound = detail::atan2_bounded_error;
  double worst = 0;
  const auto check = [&](double y, double x) {
    const double a = detail::atan2_bounded(y, x), e = std::atan2(y, x);
    worst = std::max(worst, std::abs(a - e));
    ASSERT_LE(std::abs(a - e), bound) << "atan2(" << y << ", " << x << ") = " << e << ", got " << a;
  };
  // The polynomial's interval, finely: every octant of the circle, 2^20 ratios.
  constexpr int n = 1 << 20;
  for (int i = 0; i <= n; ++i) {
    const double a = double(i) / n;
    for (const double sx : {1.0, -1.0})
      for (const double sy : {1.0, -1.0}) {
        check(sy * a, sx);
        check(sy, sx * a);
      }
  }
  // Random magnitudes over the whole range, denormals, signed zeros, huge ratios.
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> expo(-1070, 1020), unit(-1, 1);
  for (int i = 0; i < 200000; ++i)
    check(unit(rng) * std::exp2(expo(rng)), unit(rng) * std::exp2(expo(rng)));
  const double specials[] = {0.0,  -0.0,   1e-310, -1e-310, 4.9e-324, -4.9e-324, 1.0,
                             -1.0, 1e-300, 1e300,  -1e300,  1.7e308,  -1.7e308,  0.5};
  for (const double y : specials)
    for (const double x : specials) check(y, x);
  EXPECT_LT(worst, 1e-7); // the bound is not vacuous: the polynomial errs by about 1.4e-8
  // Signed zeros as std::atan2 gives them (exactly), and NaN for non-finite arguments.
  EXPECT_TRUE(std::signbit(detail::atan2_bounded(-0.0, 1.0)));
  EXPECT_EQ(detail::atan2_bounded(-0.0, -1.0), std::atan2(-0.0, -1.0));
  EXPECT_EQ(detail::atan2_bounded(0.0, -0.0), std::atan2(0.0, -0.0));
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  for (const double v : {inf, -inf, nan}) {
    EXPECT_TRUE(std::isnan(detail::atan2_bounded(v, 1.0))) << v;
    EXPECT_TRUE(std::isnan(detail::atan2_bounded(1.0, v))) << v;
  }
}

TEST(WindingBoundedAtan2, FloatWithinItsBoundOfStdAtan2) {
  const double bound = detail::atan2_bounded_f_error;
  double worst = 0;
  const auto check = [&](float y, float x) {
    const double a = double(detail::atan2_bounded_f(y, x)), e = std::atan2(double(y), double(x));
    worst = std::max(worst, std::abs(a - e));
    ASSERT_LE(std::abs(a - e), bound) << "atan2(" << y << ", " << x << ") = " << e << ", got " << a;
  };
  constexpr int n = 1 << 20; // every octant, 2^20 ratios
  for (int i = 0; i <= n; ++i) {
    const float a = float(i) / float(n);
    for (const float sx : {1.0f, -1.0f})
      for (const float sy : {1.0f, -1.0f}) {
        check(sy * a, sx);
        check(sy, sx * a);
      }
  }
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> expo(-148, 126), unit(-1, 1);
  for (int i = 0; i < 200000; ++i)
    check(float(unit(rng) * std::exp2(expo(rng))), float(unit(rng) * std::exp2(expo(rng))));
  const float specials[] = {0.0f,  -0.0f,  1e-40f, -1e-40f, 1.4e-45f, -1.4e-45f, 1.0f,
                            -1.0f, 1e-30f, 1e30f,  -1e30f,  3.4e38f,  -3.4e38f,  0.5f};
  for (const float y : specials)
    for (const float x : specials) check(y, x);
  EXPECT_LT(worst, 1.5e-5); // the bound is not vacuous: the polynomial errs by about 1.15e-5
  EXPECT_GT(worst, 5e-6);
  EXPECT_TRUE(std::signbit(detail::atan2_bounded_f(-0.0f, 1.0f)));
  EXPECT_EQ(double(detail::atan2_bounded_f(-0.0f, -1.0f)), double(float(std::atan2(-0.0, -1.0))));
  const float inf = std::numeric_limits<float>::infinity(), nan = std::nanf("");
  for (const float v : {inf, -inf, nan}) {
    EXPECT_TRUE(std::isnan(detail::atan2_bounded_f(v, 1.0f))) << v;
    EXPECT_TRUE(std::isnan(detail::atan2_bounded_f(1.0f, v))) << v;
  }
}

/// `rsqrt_lanes_f` on the instruction set `I`: within `rsqrt_lanes_f_error_u` u of 1 / √x at
/// positive normal floats over the whole range.
template <Isa I> void expect_rsqrt_lanes_within_bound() {
  constexpr int N = 32;
  const double bound = detail::rsqrt_lanes_f_error_u * 5.9604644775390625e-08;
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> expo(-125, 127), mant(1, 2);
  double worst = 0;
  for (int round = 0; round < 20000; ++round) {
    alignas(64) float x[N], y[N];
    for (int j = 0; j < N; ++j) x[j] = y[j] = float(mant(rng) * std::exp2(std::floor(expo(rng))));
    if (round == 0) y[0] = x[0] = 1.0f, y[1] = x[1] = 4.0f, y[2] = x[2] = 1.17549435e-38f;
    detail::rsqrt_lanes_f<I, N>(y);
    for (int j = 0; j < N; ++j) {
      const double e = 1 / std::sqrt(double(x[j]));
      const double rel = std::abs(double(y[j]) - e) / e;
      worst = std::max(worst, rel);
      ASSERT_LE(rel, bound) << "x = " << x[j] << ": " << y[j] << " against " << e;
    }
  }
  EXPECT_GT(worst, 0.0); // not the exact reciprocal square root everywhere
}

TEST(WindingRsqrtLanes, WithinItsBoundOnEveryInstructionSet) {
  expect_rsqrt_lanes_within_bound<Isa::baseline>();
#if EBGEOM_ISA_DISPATCH
  if (int(detected_isa()) >= int(Isa::avx2)) expect_rsqrt_lanes_within_bound<Isa::avx2>();
  if (int(detected_isa()) >= int(Isa::avx512)) expect_rsqrt_lanes_within_bound<Isa::avx512>();
#endif
}

/// `atan2_bounded_f` with the fused multiply-adds of the AVX2 and AVX-512 kernels (where this CPU
/// has them): within its bound at 2^18 ratios per octant.
template <Isa I> void expect_atan2_f_within_bound() {
  const double bound = detail::atan2_bounded_f_error;
  constexpr int n = 1 << 18;
  for (int i = 0; i <= n; ++i) {
    const float a = float(i) / float(n);
    for (const float sx : {1.0f, -1.0f})
      for (const float sy : {1.0f, -1.0f})
        for (const auto& yx : {std::pair<float, float>{sy * a, sx}, {sy, sx * a}}) {
          const double got = double(detail::atan2_bounded_f<I>(yx.first, yx.second));
          const double e = std::atan2(double(yx.first), double(yx.second));
          ASSERT_LE(std::abs(got - e), bound) << yx.first << ", " << yx.second;
        }
  }
}

TEST(WindingBoundedAtan2, FloatWithFusedStepsWithinItsBound) {
  expect_atan2_f_within_bound<Isa::baseline>();
#if EBGEOM_ISA_DISPATCH
  if (int(detected_isa()) >= int(Isa::avx2)) expect_atan2_f_within_bound<Isa::avx2>();
  if (int(detected_isa()) >= int(Isa::avx512)) expect_atan2_f_within_bound<Isa::avx512>();
#endif
}

/// Points where the fast winding number crosses 1/2 (through holes, across the surface), as close
/// as the precision allows: bisection along segments from points with w > 1/2 to points with
/// w <= 1/2 down to neighbouring representable points; both ends and the bisection's last
/// midpoints are kept.
template <class T, int K>
std::vector<Vec3<T>> near_half_points(const FastWindingNumber<T, K>& fw, const TriangleMesh<T>& m,
                                      std::uint64_t seed) {
  const std::vector<Vec3<T>> cand = test::random_points(m.bounds().grown(T(0.3)), 400, seed);
  std::vector<Vec3<T>> in, out, res;
  for (const auto& p : cand) (fw(p) > T(0.5) ? in : out).push_back(p);
  for (std::size_t i = 0; i < std::min(in.size(), out.size()) && res.size() < 600; ++i) {
    Vec3<T> a = in[i], b = out[i]; // w(a) > 1/2 >= w(b)
    for (int it = 0; it < 200; ++it) {
      const Vec3<T> c = (a + b) * T(0.5);
      if (c == a || c == b) break;
      (fw(c) > T(0.5) ? a : b) = c;
      if (it > 150 || norm(a - b) < T(64) * std::numeric_limits<T>::epsilon()) res.push_back(c);
    }
    res.push_back(a);
    res.push_back(b);
  }
  return res;
}

/// bound_packet's intervals hold `fw(p)` and are narrow; above_half_packet gives `fw(p) > 1/2`
/// exactly, at random points, lattice groups near the surface, vertices, edge midpoints, points
/// next to w = 1/2 and a packet with a NaN point. Adds to `undecided` the number of points whose
/// interval held 1/2 (decided by the exact fallback).
template <class T, int K>
void expect_bounds_hold(const TriangleMesh<T>& m, int leaf, int& undecided) {
  WindingOptions o;
  o.max_leaf_size = std::uint32_t(leaf);
  const auto fw = FastWindingNumber<T, K>::make(m, o).value();
  std::vector<Vec3<T>> pts = packet_points(m, std::uint64_t(K * 10 + leaf));
  for (std::size_t t = 0; t < m.triangle_count(); t += 3)
    pts.push_back((m.corner(t, 0) + m.corner(t, 1)) / T(2));
  const std::vector<Vec3<T>> half = near_half_points(fw, m, std::uint64_t(leaf + 5));
  pts.insert(pts.end(), half.begin(), half.end());
  constexpr int P = FastWindingNumber<T, K>::packet_width;
  std::mt19937_64 rng(9);
  std::uniform_int_distribution<int> size(1, P);
  T lo[P], hi[P];
  bool above[P];
  for (std::size_t i = 0; i < pts.size();) {
    const int n = int(std::min<std::size_t>(std::size_t(size(rng)), pts.size() - i));
    const Vec3<T>* q = pts.data() + i;
    fw.bound_packet(q, n, lo, hi);
    fw.above_half_packet(q, n, above);
    for (int j = 0; j < n; ++j) {
      const T w = fw(q[j]);
      ASSERT_TRUE(lo[j] <= w && w <= hi[j])
          << q[j] << ": " << w << " not in [" << lo[j] << ", " << hi[j] << "]";
      // Narrow: a few hundred angles of error 6e-7 each at most.
      ASSERT_LT(double(hi[j]) - double(lo[j]), 1e-3) << q[j];
      ASSERT_EQ(above[j], w > T(0.5)) << q[j] << ": w = " << w;
      undecided += lo[j] <= T(0.5) && T(0.5) < hi[j];
    }
    i += std::size_t(n);
  }
  // A packet with a NaN point: no claim there (infinite bounds), the others unaffected.
  Vec3<T> mixed[P];
  for (int j = 0; j < P; ++j) mixed[j] = pts[std::size_t(j) * 5 % pts.size()];
  mixed[3] = {std::numeric_limits<T>::quiet_NaN(), T(0), T(0)};
  fw.bound_packet(mixed, P, lo, hi);
  fw.above_half_packet(mixed, P, above);
  EXPECT_TRUE(std::isinf(lo[3]) && std::isinf(hi[3]));
  EXPECT_EQ(above[3], fw(mixed[3]) > T(0.5));
  for (int j = 0; j < P; ++j)
    if (j != 3) {
      const T w = fw(mixed[j]);
      ASSERT_TRUE(lo[j] <= w && w <= hi[j]) << j;
      ASSERT_EQ(above[j], w > T(0.5)) << j;
    }
}

TYPED_TEST(WindingTest, SignBoundsHoldAndDecideAsThePerPointValues) {
  using T = TypeParam;
  const auto meshes = packet_meshes<T>();
  const TriangleMesh<T> tet = make_triangle_mesh(make_tetrahedron<T>().value()).value();
  for_each_isa([&] {
    int undecided = 0;
    for (const auto& [name, soup] : meshes) {
      SCOPED_TRACE(name);
      const TriangleMesh<T> m = make_triangle_mesh(soup).value();
      expect_bounds_hold<T, 4>(m, 8, undecided);
      expect_bounds_hold<T, 8>(m, 8, undecided);
      expect_bounds_hold<T, 2>(m, 1, undecided);
      expect_bounds_hold<T, 4>(m, 3, undecided);
    }
    // The points next to w = 1/2 reach the exact fallback (the test is adversarial).
    EXPECT_GT(undecided, 10);
    // A single-leaf tree (the root is a leaf).
    expect_bounds_hold<T, 4>(tet, 8, undecided);
  });
  // Empty packets.
  const auto fw = FastWindingNumber<T>::make(tet).value();
  T untouched = T(7);
  bool flag = true;
  fw.bound_packet(nullptr, 0, &untouched, &untouched);
  fw.above_half_packet(nullptr, 0, &flag);
  EXPECT_EQ(untouched, T(7));
  EXPECT_TRUE(flag);
}

// ---- Batches: bound_batch's model of the clusters far from a whole box, and above_half ----------

/// Checks `bound_batch` and `above_half` on `pts` (one call, chunks of `batch_size`): every
/// interval holds `fw(p)` and every side is `fw(p) > 1/2`. Adds to `decided` the points whose
/// interval lies on one side of 1/2.
template <class T, int K>
void expect_batch_bounds_hold(const FastWindingNumber<T, K>& fw, const std::vector<Vec3<T>>& pts,
                              std::size_t& decided) {
  std::vector<T> lo(pts.size()), hi(pts.size());
  std::vector<char> above(pts.size());
  fw.bound_batch(pts.data(), pts.size(), lo.data(), hi.data());
  fw.above_half(pts.data(), pts.size(), reinterpret_cast<bool*>(above.data()));
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const T w = fw(pts[i]);
    if (std::isnan(w)) {
      EXPECT_TRUE(std::isinf(lo[i]) && std::isinf(hi[i])) << pts[i];
    } else {
      ASSERT_TRUE(lo[i] <= w && w <= hi[i])
          << pts[i] << ": " << w << " not in [" << lo[i] << ", " << hi[i] << "]";
    }
    ASSERT_EQ(bool(above[i]), w > T(0.5)) << pts[i] << ": w = " << w;
    decided += lo[i] > T(0.5) || hi[i] <= T(0.5);
  }
}

/// Batches as grid tiles give them (8³ lattice blocks next to the surface, in 4x4x2 groups),
/// 4³ blocks around points next to w = 1/2, random clouds over the whole box (one chunk of 512
/// and the rest), a batch with a NaN point and a batch of one point repeated.
template <class T, int K> void expect_batches_hold(const TriangleMesh<T>& m, int leaf) {
  WindingOptions o;
  o.max_leaf_size = std::uint32_t(leaf);
  const auto fw = FastWindingNumber<T, K>::make(m, o).value();
  const Aabb<T> box = m.bounds().grown(T(0.05));
  const T h = max_component(box.extent()) / T(120);
  std::mt19937_64 rng(std::uint64_t(K * 31 + leaf));
  std::uniform_int_distribution<std::size_t> pick(0, m.triangle_count() - 1);
  std::size_t decided = 0, lattice = 0;
  for (int b = 0; b < test::full_or_sanitized(12, 4); ++b) { // 8³ blocks at random triangles
    const Vec3<T> c = m.corner(pick(rng), 0);
    const Vec3<T> o0{box.lo.x + h * std::floor((c.x - box.lo.x) / h) - 4 * h,
                     box.lo.y + h * std::floor((c.y - box.lo.y) / h) - 4 * h,
                     box.lo.z + h * std::floor((c.z - box.lo.z) / h) - 4 * h};
    std::vector<Vec3<T>> pts;
    detail::for_each_in_sign_groups({{8, 8, 8}}, [&](std::size_t x, std::size_t y, std::size_t z) {
      pts.push_back(o0 + Vec3<T>{T(x), T(y), T(z)} * h);
    });
    expect_batch_bounds_hold(fw, pts, decided);
    lattice += pts.size();
    if (::testing::Test::HasFatalFailure()) return;
  }
  // Most lattice samples are decided by the batch bound (it is not vacuous).
  EXPECT_GT(decided, lattice * 3 / 4);
  for (const Vec3<T>& q : near_half_points(fw, m, std::uint64_t(leaf + 11))) {
    std::vector<Vec3<T>> pts{q};
    for (int z = -2; z < 2; ++z)
      for (int y = -2; y < 2; ++y)
        for (int x = -2; x < 2; ++x) pts.push_back(q + Vec3<T>{T(x), T(y), T(z)} * (h / T(4)));
    expect_batch_bounds_hold(fw, pts, decided);
    if (::testing::Test::HasFatalFailure()) return;
  }
  std::vector<Vec3<T>> cloud = test::random_points(box.grown(T(0.3)), 600, std::uint64_t(leaf));
  expect_batch_bounds_hold(fw, cloud, decided);
  cloud.resize(100);
  cloud[17] = {std::numeric_limits<T>::quiet_NaN(), T(0), T(0)};
  expect_batch_bounds_hold(fw, cloud, decided);
  const std::vector<Vec3<T>> same(70, m.corner(pick(rng), 1) + Vec3<T>{h, h / 3, -h / 2});
  expect_batch_bounds_hold(fw, same, decided);
}

TYPED_TEST(WindingTest, BatchBoundsHoldAndDecideAsThePerPointValues) {
  using T = TypeParam;
  const auto meshes = packet_meshes<T>();
  for_each_isa([&] {
    for (const auto& [name, soup] : meshes) {
      SCOPED_TRACE(name);
      const TriangleMesh<T> m = make_triangle_mesh(soup).value();
      expect_batches_hold<T, 4>(m, 8);
      expect_batches_hold<T, 8>(m, 8);
      expect_batches_hold<T, 2>(m, 1);
      if (::testing::Test::HasFatalFailure()) return;
    }
  });
  // An empty batch.
  const auto fw = FastWindingNumber<T>::make(make_triangle_mesh(meshes[0].second).value()).value();
  T untouched = T(7);
  bool flag = true;
  fw.bound_batch(nullptr, 0, &untouched, &untouched);
  fw.above_half(nullptr, 0, &flag);
  EXPECT_EQ(untouched, T(7));
  EXPECT_TRUE(flag);
}

/// The parts of bound_batch's margin, each where it is nearly tight, so that a smaller margin
/// fails: a dipole's far field along its axis, where the model's second-order remainder is within
/// a factor 1.3 of its bound; and a batch of one point repeated (a box of size 0, no
/// remainder), where only the far sums' rounding separates the model from the per-point values.
TYPED_TEST(WindingTest, BatchMarginsAreNeeded) {
  using T = TypeParam;
  // Two unit triangles facing +x, one at the origin and one far behind it, one per leaf.
  PolygonSoup<T> soup;
  soup.vertices = {{0, -0.5f, -0.5f},     {0, 0.5f, -0.5f},     {0, 0, 0.5f},
                   {-1000, -0.5f, -0.5f}, {-1000, 0.5f, -0.5f}, {-1000, 0, 0.5f}};
  soup.indices = {0, 1, 2, 3, 4, 5};
  soup.offsets = {0, 3, 6};
  const TriangleMesh<T> m = make_triangle_mesh(soup).value();
  WindingOptions o;
  o.max_leaf_size = 1;
  const auto fw = FastWindingNumber<T>::make(m, o).value();
  ASSERT_TRUE(fw.tree().root.is_inner());
  for_each_isa([&] {
    std::size_t decided = 0;
    // Points on the axis, 20 to 24 away (a box of radius 2, the triangle 10 radii away).
    std::vector<Vec3<T>> axis;
    for (int i = 0; i <= 64; ++i) axis.push_back({T(20) + T(i) / T(16), T(0), T(0)});
    expect_batch_bounds_hold(fw, axis, decided);
    std::vector<T> lo(axis.size()), hi(axis.size());
    fw.bound_batch(axis.data(), axis.size(), lo.data(), hi.data());
    // Not vacuous: the remainder's bound at x = 20 is about 3e-6 (the value about 1e-4).
    for (std::size_t i = 0; i < axis.size(); ++i)
      EXPECT_LT(double(hi[i]) - double(lo[i]), 2e-5) << axis[i];
    // One point repeated: no remainder, only rounding.
    for (const Vec3<T>& p : test::random_points(Aabb<T>{{2, -3, -3}, {8, 3, 3}}, 40, 7)) {
      const std::vector<Vec3<T>> same(40, p);
      expect_batch_bounds_hold(fw, same, decided);
    }
  });
}

} // namespace
} // namespace ebgeom
