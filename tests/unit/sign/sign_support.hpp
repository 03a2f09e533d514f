// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Mesh surgery for the sign tests: caps removed or flipped, faces duplicated, shells combined.

#include <cmath>
#include <functional>
#include <vector>

#include "ebgeom/core/vec.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

namespace ebgeom::test {

/// Largest |fast - exact| winding number the tests accept with the default beta = 2: the
/// documented band around w = 1/2 in docs/sign.md (measured: mean 0.004, largest 0.06).
inline constexpr double fast_winding_tolerance = 0.1;

template <class T> BruteForceMeshSdf<T> brute_sdf(const TriangleMesh<T>& m) {
  return BruteForceMeshSdf<T>(m);
}

template <class T> Vec3<T> face_centroid(const PolygonSoup<T>& s, std::size_t f) {
  Vec3<T> c{0, 0, 0};
  for (std::size_t i = s.offsets[f]; i < s.offsets[f + 1]; ++i) c += s.vertices[s.indices[i]];
  return c / T(s.face_size(f));
}

/// Copy of `s` keeping the faces for which `keep(f)` holds, each reversed when `flip(f)` holds,
/// and appended again (reversed when `dup_flip`) when `dup(f)` holds. Vertices are kept as is.
template <class T>
PolygonSoup<T> rebuild(const PolygonSoup<T>& s, const std::function<bool(std::size_t)>& keep,
                       const std::function<bool(std::size_t)>& flip = nullptr,
                       const std::function<bool(std::size_t)>& dup = nullptr,
                       bool dup_flip = false) {
  PolygonSoup<T> out;
  out.vertices = s.vertices;
  auto emit = [&](std::size_t f, bool reversed) {
    std::vector<Index> c(s.indices.begin() + s.offsets[f], s.indices.begin() + s.offsets[f + 1]);
    if (reversed) std::reverse(c.begin(), c.end());
    out.add_face(c);
  };
  for (std::size_t f = 0; f < s.face_count(); ++f) {
    if (!keep(f)) continue;
    emit(f, flip && flip(f));
  }
  if (dup)
    for (std::size_t f = 0; f < s.face_count(); ++f)
      if (keep(f) && dup(f)) emit(f, dup_flip);
  return out;
}

/// `s` without the faces whose centroid has z > zmin.
template <class T> PolygonSoup<T> remove_cap(const PolygonSoup<T>& s, T zmin) {
  return rebuild<T>(s, [&](std::size_t f) { return !(face_centroid(s, f).z > zmin); });
}

/// Appends `b` (translated by `shift`, reversed when `reversed`) to `a`.
template <class T>
PolygonSoup<T> combine(PolygonSoup<T> a, const PolygonSoup<T>& b, const Vec3<T>& shift,
                       bool reversed = false) {
  const Index base = Index(a.vertices.size());
  for (const auto& v : b.vertices) a.vertices.push_back(v + shift);
  for (std::size_t f = 0; f < b.face_count(); ++f) {
    std::vector<Index> c;
    for (std::size_t i = b.offsets[f]; i < b.offsets[f + 1]; ++i) c.push_back(base + b.indices[i]);
    if (reversed) std::reverse(c.begin(), c.end());
    a.add_face(c);
  }
  return a;
}

/// `s` scaled by `k` about the origin.
template <class T> PolygonSoup<T> scaled(PolygonSoup<T> s, T k) {
  for (auto& v : s.vertices) v = v * k;
  return s;
}

} // namespace ebgeom::test
