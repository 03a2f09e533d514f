// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Helpers for the io tests: canonical triangle lists (to compare meshes whose vertex numbering
// differs), file loading and little binary builders.

#include <algorithm>
#include <array>
#include <fstream>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "ebgeom/io.hpp"

namespace ebgeom::test {

/// A triangle as its three corner positions.
template <class T> using TriangleXyz = std::array<Vec3<T>, 3>;

template <class T> bool lex_less(const Vec3<T>& a, const Vec3<T>& b) {
  return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
}

/// The mesh as a sorted list of triangles given by coordinates: each face is fan-triangulated,
/// each triangle rotated (keeping its orientation) so its lexicographically smallest corner comes
/// first. Two soups describe the same oriented surface, whatever their vertex numbering and face
/// order, iff these lists are equal.
template <class T> std::vector<TriangleXyz<T>> canonical_triangles(const PolygonSoup<T>& s) {
  std::vector<TriangleXyz<T>> out;
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    const auto c = s.face(f);
    for (std::size_t k = 2; k < c.size(); ++k) {
      TriangleXyz<T> t{s.vertices[c[0]], s.vertices[c[k - 1]], s.vertices[c[k]]};
      int m = 0;
      for (int i = 1; i < 3; ++i)
        if (lex_less(t[i], t[m])) m = i;
      std::rotate(t.begin(), t.begin() + m, t.end());
      out.push_back(t);
    }
  }
  std::sort(out.begin(), out.end(), [](const TriangleXyz<T>& a, const TriangleXyz<T>& b) {
    for (int i = 0; i < 3; ++i) {
      if (lex_less(a[i], b[i])) return true;
      if (lex_less(b[i], a[i])) return false;
    }
    return false;
  });
  return out;
}

/// Same welded mesh up to numbering: equal vertex counts, face counts and canonical triangles.
template <class T>
::testing::AssertionResult same_mesh(const PolygonSoup<T>& a, const PolygonSoup<T>& b) {
  if (a.vertex_count() != b.vertex_count())
    return ::testing::AssertionFailure()
           << "vertex counts " << a.vertex_count() << " vs " << b.vertex_count();
  if (a.face_count() != b.face_count())
    return ::testing::AssertionFailure()
           << "face counts " << a.face_count() << " vs " << b.face_count();
  if (canonical_triangles(a) != canonical_triangles(b))
    return ::testing::AssertionFailure() << "the triangles differ";
  return ::testing::AssertionSuccess();
}

inline std::string slurp(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

/// Appends scalars with a byte order to a byte string.
struct Bytes {
  std::string s;
  io::Endian e = io::Endian::little;
  template <class V> Bytes& put(V v) {
    io::detail::store(s, v, e);
    return *this;
  }
  Bytes& text(const std::string& t) {
    s += t;
    return *this;
  }
};

/// The unit tetrahedron (0,0,0), (1,0,0), (0,1,0), (0,0,1), outward-facing.
template <class T> PolygonSoup<T> tetrahedron() {
  PolygonSoup<T> s;
  s.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  s.add_triangle(0, 2, 1);
  s.add_triangle(0, 1, 3);
  s.add_triangle(1, 2, 3);
  s.add_triangle(0, 3, 2);
  return s;
}

} // namespace ebgeom::test
