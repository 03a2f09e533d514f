// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Independent references for the sdf tests: signed distances computed without the library's
// formulas (support functions of convex bodies maximised numerically, sampled curves refined by
// golden-section search), and a finite-difference Eikonal check.

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <vector>

#include "ebgeom/core/vec.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "test_support.hpp"

namespace ebgeom::test {

using V3 = Vec3<double>;

/// Signed distance of a convex body K from its support function h(u) = max_{x in K} u.x:
/// S(p) = max_{|u| = 1} (p.u - h(u)) (outside: distance to K; inside: minus the distance to the
/// boundary). The maximum is found by a Fibonacci sphere scan and a shrinking local grid search
/// in the tangent plane, which also converges onto kinks and ridges of h.
inline double convex_sdf(const std::function<double(const V3&)>& h, const V3& p,
                         const std::vector<V3>& extra = {}) {
  static const std::vector<V3> dirs = [] {
    std::vector<V3> d;
    const int n = 3000;
    const double ga = M_PI * (3 - std::sqrt(5.0));
    for (int i = 0; i < n; ++i) {
      const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z);
      d.push_back({r * std::cos(ga * i), r * std::sin(ga * i), z});
    }
    for (int a = 0; a < 3; ++a) {
      d.push_back(V3::unit(a));
      d.push_back(-V3::unit(a));
    }
    return d;
  }();
  const auto f = [&](const V3& u) { return dot(p, u) - h(u); };
  V3 best = dirs[0];
  double fb = f(best);
  const auto consider = [&](const V3& u) {
    const double v = f(u);
    if (v > fb) fb = v, best = u;
  };
  for (const auto& u : dirs) consider(u);
  for (const auto& u : extra) consider(normalized(u));
  for (double s = 0.05; s > 1e-11; s *= 0.5) {
    for (int it = 0; it < 8; ++it) { // recentre a few times at this scale
      const V3 a = std::abs(best.x) < 0.9 ? V3{1, 0, 0} : V3{0, 1, 0};
      const V3 t1 = normalized(cross(best, a)), t2 = cross(best, t1);
      const V3 centre = best;
      for (int i = -3; i <= 3; ++i)
        for (int j = -3; j <= 3; ++j) consider(normalized(centre + t1 * (s * i) + t2 * (s * j)));
      if (best == centre) break;
    }
  }
  return fb;
}

/// Minimises f over [lo, hi] by golden-section search (f unimodal there).
inline double golden_min(const std::function<double(double)>& f, double lo, double hi) {
  const double g = (std::sqrt(5.0) - 1) / 2;
  double a = lo, b = hi, c = b - g * (b - a), d = a + g * (b - a);
  double fc = f(c), fd = f(d);
  for (int i = 0; i < 100; ++i) {
    if (fc < fd) {
      b = d, d = c, fd = fc, c = b - g * (b - a), fc = f(c);
    } else {
      a = c, c = d, fc = fd, d = a + g * (b - a), fd = f(d);
    }
  }
  return std::min({f(a), f(b), fc, fd});
}

/// min over t in [lo, hi] of f(t): dense scan, then golden-section refinement around the best.
inline double curve_min(const std::function<double(double)>& f, double lo, double hi,
                        int n = 4000) {
  int bi = 0;
  double bv = f(lo);
  for (int i = 1; i <= n; ++i) {
    const double v = f(lo + (hi - lo) * i / n);
    if (v < bv) bv = v, bi = i;
  }
  const double step = (hi - lo) / n;
  const double a = std::max(lo, lo + step * (bi - 1)), b = std::min(hi, lo + step * (bi + 1));
  return std::min(bv, golden_min(f, a, b));
}

/// Signed distance to a convex 2D polygon (vertices counter-clockwise): outside, the distance to
/// the nearest edge segment; inside, minus the distance to the nearest edge line.
inline double convex_polygon_sdf(const Vec2<double>& q, const std::vector<Vec2<double>>& v) {
  double out = 1e300, in = 1e300;
  bool inside = true;
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Vec2<double> a = v[i], b = v[(i + 1) % v.size()], e = b - a;
    const double l = norm(e);
    const double side = cross(e, q - a) / l; // > 0 left of the edge (inside for CCW)
    inside = inside && side >= 0;
    in = std::min(in, side);
    const double t = std::clamp(dot(q - a, e) / (l * l), 0.0, 1.0);
    out = std::min(out, norm(q - (a + e * t)));
  }
  return inside ? -in : out;
}

/// Signed distance to a convex polytope given by its faces (vertex loops, counter-clockwise seen
/// from outside): outside, the distance to the nearest face polygon (plane distance when the
/// projection falls in the face, else the nearest edge); inside, minus the nearest plane.
inline double convex_polytope_sdf(const V3& p, const std::vector<std::vector<V3>>& faces) {
  double out = 1e300, in = -1e300;
  for (const auto& f : faces) {
    const V3 n = normalized(cross(f[1] - f[0], f[2] - f[0]));
    const double d = dot(p - f[0], n);
    in = std::max(in, d);
    const V3 q = p - n * d;
    bool in_face = true;
    double edge = 1e300;
    for (std::size_t i = 0; i < f.size(); ++i) {
      const V3 a = f[i], b = f[(i + 1) % f.size()], e = b - a;
      in_face = in_face && dot(cross(e, q - a), n) >= 0;
      const double t = std::clamp(dot(p - a, e) / dot(e, e), 0.0, 1.0);
      edge = std::min(edge, norm(p - (a + e * t)));
    }
    out = std::min(out, in_face ? std::abs(d) : edge);
  }
  return in <= 0 ? in : out;
}

/// Meridian coordinates of `p` for the axis a -> b, computed with the cross product:
/// (radial distance, axial coordinate from a).
inline Vec2<double> meridian(const V3& p, const V3& a, const V3& b) {
  const V3 w = normalized(b - a);
  return {norm(cross(p - a, w)), dot(p - a, w)};
}

/// Points of the zero set of `s` inside `box`: every edge of an n^3 grid whose end values have
/// opposite signs is bisected (in double) down to 1e-9 of its length. The distance from a point
/// to this cloud is >= the true distance to the surface and at most about one grid step more.
template <class S> std::vector<V3> surface_cloud(const S& s, const Aabb<double>& box, int n) {
  using T = sdf_scalar_t<S>;
  const V3 step = box.extent() / double(n);
  const auto at = [&](int i, int j, int k) {
    return box.lo + V3{step.x * i, step.y * j, step.z * k};
  };
  const auto f = [&](const V3& p) { return double(s(Vec3<T>::from(p))); };
  std::vector<double> val(std::size_t(n + 1) * (n + 1) * (n + 1));
  const auto idx = [&](int i, int j, int k) {
    return (std::size_t(i) * (n + 1) + j) * (n + 1) + k;
  };
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k) val[idx(i, j, k)] = f(at(i, j, k));
  std::vector<V3> cloud;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      for (int k = 0; k <= n; ++k)
        for (int a = 0; a < 3; ++a) {
          const int i2 = i + (a == 0), j2 = j + (a == 1), k2 = k + (a == 2);
          if (i2 > n || j2 > n || k2 > n) continue;
          const double v0 = val[idx(i, j, k)], v1 = val[idx(i2, j2, k2)];
          if ((v0 < 0) == (v1 < 0)) continue;
          V3 lo = at(i, j, k), hi = at(i2, j2, k2);
          for (int it = 0; it < 40; ++it) {
            const V3 mid = (lo + hi) * 0.5;
            ((f(mid) < 0) == (v0 < 0) ? lo : hi) = mid;
          }
          cloud.push_back((lo + hi) * 0.5);
        }
  return cloud;
}

inline double cloud_distance(const std::vector<V3>& cloud, const V3& p) {
  double best = 1e300;
  for (const auto& q : cloud) best = std::min(best, norm2(q - p));
  return std::sqrt(best);
}

/// Checks the `bound` contract of `s` at random points of `box`: |S| <= the distance to a
/// surface cloud of `s`'s own zero set (which is >= the true distance to that surface).
/// With `exact_within` > 0 also checks |S| >= cloud distance - exact_within.
template <class S>
void expect_bound(const S& s, const Aabb<double>& box, double exact_within = 0, int n = 90,
                  std::size_t queries = 250) {
  using T = sdf_scalar_t<S>;
  const auto cloud = surface_cloud(s, box, n);
  ASSERT_GT(cloud.size(), 100u);
  const double step = max_component(box.extent()) / n;
  const double tol = sizeof(T) == 4 ? 2e-5 : 1e-7;
  const Aabb<T> qbox = Aabb<T>::from(box);
  for (const auto& p : random_points(qbox, queries, 4321)) {
    const double d = cloud_distance(cloud, V3::from(p));
    const double v = double(s(p));
    EXPECT_LE(std::abs(v), d + tol) << "overestimate at " << p;
    if (exact_within > 0) {
      EXPECT_GE(std::abs(v), d - exact_within) << "not exact at " << p;
    }
    (void)step;
  }
}

/// Number of non-fatal failures `fn` reports (intercepted, so they do not fail the test): shows
/// that a check can fail.
template <class F> int count_failures(F&& fn) {
  ::testing::TestPartResultArray results;
  {
    ::testing::ScopedFakeTestPartResultReporter rep(
        ::testing::ScopedFakeTestPartResultReporter::INTERCEPT_ONLY_CURRENT_THREAD, &results);
    fn();
  }
  int n = 0;
  for (int i = 0; i < results.size(); ++i) n += results.GetTestPartResult(i).nonfatally_failed();
  return n;
}

/// Tolerance for comparing a T evaluation with a double reference at points of size ~`scale`.
template <class T> double ref_tol(double scale = 4) {
  return sizeof(T) == 4 ? 4e-6 * scale + 1e-5 : 1e-7;
}

/// Finite-difference gradient of `s` in double steps around the T point `p`.
template <class S> V3 fd_gradient(const S& s, const Vec3<sdf_scalar_t<S>>& p, double h) {
  using T = sdf_scalar_t<S>;
  V3 g;
  for (int a = 0; a < 3; ++a) {
    Vec3<T> lo = p, hi = p;
    lo[a] -= T(h);
    hi[a] += T(h);
    g[a] = (double(s(hi)) - double(s(lo))) / double(hi[a] - lo[a]);
  }
  return g;
}

/// Eikonal check: |grad S| = 1 at random points of `box`, skipping points whose second
/// differences show a kink within the stencil (the medial axis). Requires at least `min_frac`
/// of the points to be checked, so the test cannot pass vacuously.
template <class S>
void expect_eikonal(const S& s, const Aabb<sdf_scalar_t<S>>& box, std::size_t n = 400,
                    double min_frac = 0.5, std::uint64_t seed = 17) {
  using T = sdf_scalar_t<S>;
  const double h = sizeof(T) == 4 ? 2e-3 : 1e-5;
  const double tol = sizeof(T) == 4 ? 2e-2 : 1e-4;
  std::size_t checked = 0;
  for (const auto& p : random_points(box, n, seed)) {
    const double s0 = double(s(p));
    bool kink = false;
    for (int a = 0; a < 3 && !kink; ++a) {
      Vec3<T> lo = p, hi = p;
      lo[a] -= T(h);
      hi[a] += T(h);
      const double second = double(s(hi)) + double(s(lo)) - 2 * s0;
      kink = std::abs(second) > 0.02 * h + (sizeof(T) == 4 ? 1e-5 : 0);
    }
    if (kink) continue;
    ++checked;
    EXPECT_NEAR(norm(fd_gradient(s, p, h)), 1.0, tol) << "at " << p << " value " << s0;
  }
  EXPECT_GE(double(checked), min_frac * double(n)) << "too few points away from kinks";
}

} // namespace ebgeom::test
