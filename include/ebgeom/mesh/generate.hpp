// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Procedural closed meshes (outward oriented, welded, manifold) for tests, benchmarks and demos:
/// box, tetrahedron, octahedron, icosahedron, icosphere and torus.

#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>

#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom {

namespace detail {
template <class T> bool positive_finite(T v) noexcept { return std::isfinite(v) && v > T(0); }
} // namespace detail

/// Axis-aligned box [lo, hi] as 6 quads (8 vertices). Error `invalid_argument` unless
/// lo < hi componentwise and both are finite.
template <class T> Result<PolygonSoup<T>> make_box(const Vec3<T>& lo, const Vec3<T>& hi) {
  if (!all_finite(lo) || !all_finite(hi) || !(lo.x < hi.x && lo.y < hi.y && lo.z < hi.z))
    return make_error(ErrorCode::invalid_argument, "make_box needs finite lo < hi, got ", lo, " ",
                      hi);
  PolygonSoup<T> s;
  for (int i = 0; i < 8; ++i)
    s.add_vertex({(i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z});
  // CCW seen from outside (vertex i has bits x=1, y=2, z=4).
  s.add_face({0, 4, 6, 2}); // -x
  s.add_face({1, 3, 7, 5}); // +x
  s.add_face({0, 1, 5, 4}); // -y
  s.add_face({2, 6, 7, 3}); // +y
  s.add_face({0, 2, 3, 1}); // -z
  s.add_face({4, 5, 7, 6}); // +z
  return s;
}

/// Cube [-h, h]^3 as 6 quads. Error `invalid_argument` unless h > 0 and finite.
template <class T> Result<PolygonSoup<T>> make_cube(T half_size = T(1)) {
  if (!detail::positive_finite(half_size))
    return make_error(ErrorCode::invalid_argument, "make_cube needs half_size > 0");
  return make_box(Vec3<T>::constant(-half_size), Vec3<T>::constant(half_size));
}

/// Regular tetrahedron centred at the origin with vertices at distance `radius` along
/// (1,1,1), (1,-1,-1), (-1,1,-1), (-1,-1,1). Inradius = radius / 3.
template <class T> Result<PolygonSoup<T>> make_tetrahedron(T radius = T(1)) {
  if (!detail::positive_finite(radius))
    return make_error(ErrorCode::invalid_argument, "make_tetrahedron needs radius > 0");
  const T s = radius / std::sqrt(T(3));
  PolygonSoup<T> m;
  m.add_vertex({s, s, s});
  m.add_vertex({s, -s, -s});
  m.add_vertex({-s, s, -s});
  m.add_vertex({-s, -s, s});
  m.add_triangle(0, 1, 2);
  m.add_triangle(0, 3, 1);
  m.add_triangle(0, 2, 3);
  m.add_triangle(1, 3, 2);
  return m;
}

/// Regular octahedron |x| + |y| + |z| = radius (vertices at ±radius on each axis), 8 triangles.
template <class T> Result<PolygonSoup<T>> make_octahedron(T radius = T(1)) {
  if (!detail::positive_finite(radius))
    return make_error(ErrorCode::invalid_argument, "make_octahedron needs radius > 0");
  PolygonSoup<T> m;
  const T r = radius;
  m.add_vertex({r, 0, 0});  // 0
  m.add_vertex({-r, 0, 0}); // 1
  m.add_vertex({0, r, 0});  // 2
  m.add_vertex({0, -r, 0}); // 3
  m.add_vertex({0, 0, r});  // 4
  m.add_vertex({0, 0, -r}); // 5
  m.add_triangle(0, 2, 4);
  m.add_triangle(2, 1, 4);
  m.add_triangle(1, 3, 4);
  m.add_triangle(3, 0, 4);
  m.add_triangle(2, 0, 5);
  m.add_triangle(1, 2, 5);
  m.add_triangle(3, 1, 5);
  m.add_triangle(0, 3, 5);
  return m;
}

/// Regular icosahedron with vertices on the sphere of `radius` (12 vertices, 20 triangles).
template <class T> Result<PolygonSoup<T>> make_icosahedron(T radius = T(1)) {
  if (!detail::positive_finite(radius))
    return make_error(ErrorCode::invalid_argument, "make_icosahedron needs radius > 0");
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const double raw[12][3] = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                             {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                             {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  PolygonSoup<T> m;
  for (const auto& v : raw) {
    const Vec3<double> u = normalized(Vec3<double>{v[0], v[1], v[2]}) * double(radius);
    m.add_vertex(Vec3<T>::from(u));
  }
  const Index f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                          {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                          {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                          {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (const auto& t : f) m.add_triangle(t[0], t[1], t[2]);
  return m;
}

/// Icosphere: the icosahedron with every triangle split into 4, `subdivisions` times, and the
/// new vertices pushed onto the sphere of `radius` (20 * 4^s triangles, 10 * 4^s + 2 vertices).
/// Error `invalid_argument` unless 0 <= subdivisions <= 10 and radius > 0. O(output).
template <class T> Result<PolygonSoup<T>> make_icosphere(int subdivisions, T radius = T(1)) {
  if (subdivisions < 0 || subdivisions > 10)
    return make_error(ErrorCode::invalid_argument,
                      "make_icosphere needs 0 <= subdivisions <= 10, "
                      "got ",
                      subdivisions);
  Result<PolygonSoup<T>> base = make_icosahedron(radius);
  if (!base) return base;
  // Subdivide in double, round to T at the end.
  std::vector<Vec3<double>> v;
  for (const auto& p : base->vertices) v.push_back(Vec3<double>::from(p));
  std::vector<Index> tri = base->indices;
  for (int s = 0; s < subdivisions; ++s) {
    std::unordered_map<std::uint64_t, Index> mid;
    auto midpoint = [&](Index a, Index b) {
      const std::uint64_t key = (std::uint64_t(std::min(a, b)) << 32) | std::max(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back(normalized(v[a] + v[b]) * double(radius));
      const Index i = static_cast<Index>(v.size() - 1);
      mid.emplace(key, i);
      return i;
    };
    std::vector<Index> next;
    next.reserve(tri.size() * 4);
    for (std::size_t t = 0; t < tri.size(); t += 3) {
      const Index a = tri[t], b = tri[t + 1], c = tri[t + 2];
      const Index ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
      next.insert(next.end(), {a, ab, ca, b, bc, ab, c, ca, bc, ab, bc, ca});
    }
    tri.swap(next);
  }
  PolygonSoup<T> m;
  m.reserve(v.size(), tri.size() / 3, tri.size());
  for (const auto& p : v) m.add_vertex(Vec3<T>::from(p));
  for (std::size_t t = 0; t < tri.size(); t += 3) m.add_triangle(tri[t], tri[t + 1], tri[t + 2]);
  return m;
}

/// Torus around the z axis: centre circle of radius `major` in the xy-plane, tube radius `minor`,
/// `segments_major` x `segments_minor` planar quads (isosceles trapezoids). Error
/// `invalid_argument` unless 0 < minor < major and both segment counts are in [3, 4096].
template <class T>
Result<PolygonSoup<T>> make_torus(T major, T minor, int segments_major = 48,
                                  int segments_minor = 24) {
  if (!detail::positive_finite(minor) || !detail::positive_finite(major) || !(minor < major))
    return make_error(ErrorCode::invalid_argument, "make_torus needs 0 < minor < major");
  if (segments_major < 3 || segments_minor < 3 || segments_major > 4096 || segments_minor > 4096)
    return make_error(ErrorCode::invalid_argument, "make_torus needs segment counts in [3, 4096]");
  const double two_pi = 6.283185307179586476925286766559;
  PolygonSoup<T> m;
  const auto nu = static_cast<Index>(segments_major), nv = static_cast<Index>(segments_minor);
  m.reserve(std::size_t(nu) * nv, std::size_t(nu) * nv, std::size_t(nu) * nv * 4);
  for (Index i = 0; i < nu; ++i) {
    const double u = two_pi * i / nu;
    for (Index j = 0; j < nv; ++j) {
      const double w = two_pi * j / nv;
      const double rr = double(major) + double(minor) * std::cos(w);
      m.add_vertex(
          Vec3<T>{T(rr * std::cos(u)), T(rr * std::sin(u)), T(double(minor) * std::sin(w))});
    }
  }
  auto id = [&](Index i, Index j) { return (i % nu) * nv + (j % nv); };
  for (Index i = 0; i < nu; ++i)
    for (Index j = 0; j < nv; ++j)
      m.add_face({id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)});
  return m;
}

} // namespace ebgeom
