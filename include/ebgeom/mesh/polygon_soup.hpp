// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `PolygonSoup<T>`: vertices plus faces of any size, the common output of every mesh reader and
/// the input of every mesh structure. No topology, no validation (see mesh/validate.hpp).

#include <cstdint>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/span.hpp"
#include "ebgeom/core/vec.hpp"

namespace ebgeom {

/// Index type for vertices and faces (meshes up to 4 G vertices).
using Index = std::uint32_t;

/// Vertices and polygon faces in compressed-row form: face `f` uses
/// `indices[offsets[f] .. offsets[f+1])`, counter-clockwise seen from outside (outward normal by
/// the right-hand rule). `offsets` always starts with 0 and has `face_count() + 1` entries.
/// Memory: 12/24 B per vertex (float/double) + 4 B per face corner + 4 B per face.
template <class T> struct PolygonSoup {
  using scalar_type = T;
  std::vector<Vec3<T>> vertices;
  std::vector<Index> indices;
  std::vector<Index> offsets{0};

  std::size_t vertex_count() const noexcept { return vertices.size(); }
  std::size_t face_count() const noexcept { return offsets.size() - 1; }
  /// Number of corners of face `f`.
  std::size_t face_size(std::size_t f) const noexcept { return offsets[f + 1] - offsets[f]; }
  /// The vertex indices of face `f`.
  Span<const Index> face(std::size_t f) const noexcept {
    return {indices.data() + offsets[f], face_size(f)};
  }
  /// Triangles after fan-triangulating every face (sum over faces of size - 2).
  std::size_t triangle_count() const noexcept {
    std::size_t n = 0;
    for (std::size_t f = 0; f < face_count(); ++f) n += face_size(f) >= 3 ? face_size(f) - 2 : 0;
    return n;
  }

  Index add_vertex(const Vec3<T>& p) {
    vertices.push_back(p);
    return static_cast<Index>(vertices.size() - 1);
  }
  void add_triangle(Index a, Index b, Index c) {
    indices.insert(indices.end(), {a, b, c});
    offsets.push_back(static_cast<Index>(indices.size()));
  }
  /// Appends a face with the given corners (any count; validation rejects fewer than 3 later).
  template <class Range> void add_face(const Range& corners) {
    for (Index i : corners) indices.push_back(i);
    offsets.push_back(static_cast<Index>(indices.size()));
  }
  void add_face(std::initializer_list<Index> corners) {
    indices.insert(indices.end(), corners);
    offsets.push_back(static_cast<Index>(indices.size()));
  }
  void reserve(std::size_t vertex_count, std::size_t face_count, std::size_t corner_count) {
    vertices.reserve(vertex_count);
    offsets.reserve(face_count + 1);
    indices.reserve(corner_count);
  }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of_range(vertices); }

  friend bool operator==(const PolygonSoup& a, const PolygonSoup& b) noexcept {
    return a.vertices == b.vertices && a.indices == b.indices && a.offsets == b.offsets;
  }
};

} // namespace ebgeom
