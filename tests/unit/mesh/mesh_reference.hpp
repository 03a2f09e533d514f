// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Independent references for mesh tests: a double-precision closest point on a triangle
// (barycentric projection by Cramer's rule, else clamped segments), the unsigned distance to a
// soup by scanning its fan triangles, the winding number by solid angles (geom/solid_angle.hpp),
// and closed-form SDFs of a box and an octahedron.

#include <algorithm>
#include <cmath>
#include <limits>

#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/solid_angle.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom::test {

inline Vec3<double> ref_segment_point(const Vec3<double>& p, const Vec3<double>& a,
                                      const Vec3<double>& b) {
  const Vec3<double> e = b - a;
  const double ee = dot(e, e);
  if (ee == 0) return a;
  return a + e * clamp(dot(p - a, e) / ee, 0.0, 1.0);
}

inline double ref_triangle_distance(const Vec3<double>& p, const Vec3<double>& a,
                                    const Vec3<double>& b, const Vec3<double>& c) {
  const Vec3<double> e0 = b - a, e1 = c - a, r = p - a;
  const double a00 = dot(e0, e0), a01 = dot(e0, e1), a11 = dot(e1, e1);
  const double b0 = dot(r, e0), b1 = dot(r, e1);
  const double det = a00 * a11 - a01 * a01;
  if (det > 1e-14 * a00 * a11) {
    const double s = (a11 * b0 - a01 * b1) / det, t = (a00 * b1 - a01 * b0) / det;
    if (s >= 0 && t >= 0 && s + t <= 1) return norm(p - (a + e0 * s + e1 * t));
  }
  double d = std::numeric_limits<double>::infinity();
  for (const auto& q :
       {ref_segment_point(p, a, b), ref_segment_point(p, b, c), ref_segment_point(p, c, a)})
    d = std::min(d, norm(p - q));
  return d;
}

/// Unsigned distance to the fan triangles of every face, and the winding number, in double.
template <class T> double ref_unsigned_distance(const PolygonSoup<T>& s, const Vec3<double>& p) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    const auto c = s.face(f);
    for (std::size_t i = 1; i + 1 < c.size(); ++i)
      d = std::min(d, ref_triangle_distance(p, Vec3<double>::from(s.vertices[c[0]]),
                                            Vec3<double>::from(s.vertices[c[i]]),
                                            Vec3<double>::from(s.vertices[c[i + 1]])));
  }
  return d;
}

template <class T> double ref_winding_number(const PolygonSoup<T>& s, const Vec3<double>& p) {
  double w = 0;
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    const auto c = s.face(f);
    for (std::size_t i = 1; i + 1 < c.size(); ++i)
      w +=
          solid_angle(p, Vec3<double>::from(s.vertices[c[0]]), Vec3<double>::from(s.vertices[c[i]]),
                      Vec3<double>::from(s.vertices[c[i + 1]]));
  }
  return w / (4 * 3.14159265358979323846);
}

/// Signed distance oracle: magnitude by scanning, sign by winding number (> 1/2 inside).
template <class T> double ref_signed_distance(const PolygonSoup<T>& s, const Vec3<double>& p) {
  const double d = ref_unsigned_distance(s, p);
  return ref_winding_number(s, p) > 0.5 ? -d : d;
}

/// Exact box SDF (half sizes h, centred at c).
inline double box_sdf(const Vec3<double>& p, const Vec3<double>& c, const Vec3<double>& h) {
  const Vec3<double> q = abs(p - c) - h;
  return norm(max(q, Vec3<double>::zero())) + std::min(max_component(q), 0.0);
}

/// Exact SDF of the octahedron |x|+|y|+|z| = s (Quilez's closed form).
inline double octahedron_sdf(Vec3<double> p, double s) {
  p = abs(p);
  const double m = p.x + p.y + p.z - s;
  Vec3<double> q;
  if (3 * p.x < m)
    q = p;
  else if (3 * p.y < m)
    q = {p.y, p.z, p.x};
  else if (3 * p.z < m)
    q = {p.z, p.x, p.y};
  else
    return m * 0.57735026918962576451;
  const double k = clamp(0.5 * (q.z - q.y + s), 0.0, s);
  return norm(Vec3<double>{q.x, q.y - s + k, q.z - k});
}

/// An L-shaped prism (non-convex: one reflex edge along z at (1, 1)): profile
/// (0,0),(2,0),(2,1),(1,1),(1,2),(0,2) extruded over z in [0, 1]; hexagon caps and quad sides.
template <class T> PolygonSoup<T> l_prism() {
  const double xy[6][2] = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  PolygonSoup<T> s;
  for (int z = 0; z < 2; ++z)
    for (const auto& v : xy) s.add_vertex({T(v[0]), T(v[1]), T(z)});
  s.add_face({0, 5, 4, 3, 2, 1});   // bottom, normal -z (fan from (0,0) stays inside the L)
  s.add_face({6, 7, 8, 9, 10, 11}); // top, normal +z
  for (Index i = 0; i < 6; ++i) {
    const Index j = (i + 1) % 6;
    s.add_face({i, j, Index(j + 6), Index(i + 6)});
  }
  return s;
}

} // namespace ebgeom::test
