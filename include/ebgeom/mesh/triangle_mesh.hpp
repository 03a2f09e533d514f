// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `TriangleMesh<T>`: the "pseudo-triangle" fast path. Triangles that carry their face, edge and
/// vertex pseudonormals, so the per-triangle kernel (geom/closest_point_triangle.hpp) gives the
/// signed distance without any topology at query time, equal to the half-edge mesh's.

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/error.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/polygon_geometry.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/pseudonormals.hpp"
#include "ebgeom/mesh/soup_check.hpp"

namespace ebgeom {

/// Triangles with precomputed pseudonormals (Bærentzen & Aanæs 2005).
///
/// Edge pseudonormals are not stored: each triangle side holds a 4-byte link (`edge_links`) from
/// which `edge_normal` recomputes, bit for bit, the value `edge_pseudonormals` gives its edge.
///
/// Memory per triangle: 12 B indices + 3 T face normal + 12 B edge links (+ 4 B `source_faces`
/// when some polygon is not a triangle), i.e. 36 B (float) / 48 B (double); plus 6 T per vertex
/// (position and pseudonormal), about half a vertex per triangle on closed meshes: ~48 B (float) /
/// ~72 B (double) per triangle, and 3 T per non-manifold edge.
///
/// Invariants (established by `make_triangle_mesh`): `triangles`, `face_normals` and `edge_links`
/// have one entry per triangle, `source_faces` one or none; `vertices` and `vertex_normals` have
/// the same size; every index is < `vertices.size()`; every link is valid (`valid_link`);
/// coordinates are finite. Immutable use is thread-safe.
template <class T> struct TriangleMesh {
  using scalar_type = T;
  /// Link of a side inside a polygon (a fan or ear-clipping diagonal): the face normal.
  static constexpr Index diagonal_link = ~Index(0);
  /// Link of a side on an edge that only one polygon side uses (a boundary edge).
  static constexpr Index boundary_link = ~Index(0) - 1;
  /// Links from here down are overflow slots: `edge_overflow[overflow_link - link]`.
  static constexpr Index overflow_link = ~Index(0) - 2;

  std::vector<Vec3<T>> vertices;
  std::vector<std::array<Index, 3>> triangles; ///< CCW seen from outside
  /// Polygon of the soup each triangle came from; empty when every polygon is a triangle
  /// (triangle t is polygon t). Read it through `source_face`.
  std::vector<Index> source_faces;
  std::vector<Vec3<T>> face_normals; ///< unit, per triangle (its polygon's normal)
  /// Per side (v0,v1), (v1,v2), (v2,v0): a triangle of the other polygon on an edge shared by
  /// exactly two polygon sides (possibly this triangle), or `diagonal_link`, `boundary_link`, or
  /// an overflow slot (edges of three or more polygon sides). See `edge_normal`.
  std::vector<std::array<Index, 3>> edge_links;
  std::vector<Vec3<T>> edge_overflow;  ///< pseudonormals of the overflow edges
  std::vector<Vec3<T>> vertex_normals; ///< angle-weighted pseudonormal per vertex

  std::size_t triangle_count() const noexcept { return triangles.size(); }
  std::size_t vertex_count() const noexcept { return vertices.size(); }
  /// Polygon of the soup triangle `t` came from.
  Index source_face(std::size_t t) const noexcept {
    return source_faces.empty() ? static_cast<Index>(t) : source_faces[t];
  }
  /// Vertex `k` (0, 1, 2) of triangle `t`.
  const Vec3<T>& corner(std::size_t t, int k) const noexcept { return vertices[triangles[t][k]]; }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of_range(vertices); }
  /// Tight box of triangle `t`.
  Aabb<T> triangle_bounds(std::size_t t) const noexcept {
    return Aabb<T>::of(corner(t, 0), corner(t, 1), corner(t, 2));
  }
  /// Pseudonormal of side `e` (0: (v0,v1), 1: (v1,v2), 2: (v2,v0)) of triangle `t`: on a polygon
  /// edge, normalise(sum of the normals of the polygon sides on it, added from zero in polygon
  /// order), exactly as `edge_pseudonormals` computes it; on a diagonal, the face normal.
  /// Precondition: t < triangle_count(), 0 <= e < 3. O(1).
  Vec3<T> edge_normal(std::size_t t, int e) const noexcept {
    const Index link = edge_links[t][e];
    if (link < triangles.size()) {
      // Triangles are in polygon order, so the lower id is the polygon the table adds first.
      const std::size_t o = link;
      return normalized(Vec3<T>::zero() + face_normals[std::min(t, o)] +
                        face_normals[std::max(t, o)]);
    }
    if (link == diagonal_link) return face_normals[t];
    if (link == boundary_link) return normalized(Vec3<T>::zero() + face_normals[t]);
    return edge_overflow[overflow_link - link];
  }
  /// Whether `link` can be followed by `edge_normal` (checks of hand-made meshes).
  bool valid_link(Index link) const noexcept {
    return link < triangles.size() || link == diagonal_link || link == boundary_link ||
           (link <= overflow_link && std::size_t(overflow_link - link) < edge_overflow.size());
  }
  /// Heap bytes held by the arrays (sizes, not capacities).
  std::size_t memory_bytes() const noexcept {
    return (vertices.size() + vertex_normals.size()) * sizeof(Vec3<T>) +
           triangles.size() * sizeof(triangles[0]) + source_faces.size() * sizeof(Index) +
           (face_normals.size() + edge_overflow.size()) * sizeof(Vec3<T>) +
           edge_links.size() * sizeof(edge_links[0]);
  }
};

namespace detail {
/// Whether `triangles` ids and `overflow` slots fit `TriangleMesh` links: every id (< triangles)
/// must stay below the lowest code in use, 2^32 - 2 - overflow (the top two values are taken).
constexpr bool edge_links_fit(std::size_t triangles, std::size_t overflow) noexcept {
  const std::size_t max_total = std::size_t(~Index(0)) - 1;
  return triangles <= max_total && overflow <= max_total - triangles;
}

/// Triangulates a planar polygon of `k` corners with unit normal `n` into `out` (corner positions,
/// counter-clockwise about n). Convex polygons (and any polygon whose fan from corner 0 is valid,
/// i.e. every fan triangle is oriented along n) get the fan (0, i, i+1); others are ear-clipped
/// in the polygon's plane, O(k^2). If no ear is found (degenerate input), the rest is fanned.
template <class T, class CornerFn>
void triangulate_polygon(std::size_t k, const CornerFn& corner, const Vec3<T>& n,
                         std::vector<std::array<std::size_t, 3>>& out) {
  out.clear();
  if (k < 3) return;
  auto area = [&](std::size_t a, std::size_t b, std::size_t c) {
    return dot(n, cross(corner(b) - corner(a), corner(c) - corner(a)));
  };
  bool fan_ok = true;
  for (std::size_t i = 1; i + 1 < k && fan_ok; ++i) fan_ok = area(0, i, i + 1) >= T(0);
  // Fan triangles all oriented along n can still overlap only if the polygon winds around
  // vertex 0 more than once, which a simple polygon cannot.
  if (fan_ok) {
    for (std::size_t i = 1; i + 1 < k; ++i) out.push_back({0, i, i + 1});
    return;
  }
  std::vector<std::size_t> ring(k);
  for (std::size_t i = 0; i < k; ++i) ring[i] = i;
  auto inside = [&](std::size_t p, std::size_t a, std::size_t b, std::size_t c) {
    return area(a, b, p) > T(0) && area(b, c, p) > T(0) && area(c, a, p) > T(0);
  };
  while (ring.size() > 3) {
    const std::size_t m = ring.size();
    bool clipped = false;
    for (std::size_t i = 0; i < m && !clipped; ++i) {
      const std::size_t a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
      if (!(area(a, b, c) > T(0))) continue; // reflex or flat corner
      bool ear = true;
      for (std::size_t j = 0; j < m && ear; ++j) {
        const std::size_t p = ring[j];
        if (p != a && p != b && p != c && inside(p, a, b, c)) ear = false;
      }
      if (!ear) continue;
      out.push_back({a, b, c});
      ring.erase(ring.begin() + std::ptrdiff_t(i));
      clipped = true;
    }
    if (!clipped) break;
  }
  for (std::size_t i = 1; i + 1 < ring.size(); ++i) out.push_back({ring[0], ring[i], ring[i + 1]});
}
} // namespace detail

/// Builds a `TriangleMesh` from a polygon soup: each polygon (c0, ..., c_{k-1}) is fan-triangulated
/// into (c0, c_i, c_{i+1}) when that fan is valid (convex and star-shaped-from-c0 polygons), and
/// ear-clipped in its plane otherwise (simple non-convex planar polygons). Normals:
/// - face normal: the unit Newell normal of the source polygon (the same for all its triangles);
/// - edge pseudonormal: normalise(sum of the normals of the polygons sharing the edge); a boundary
///   edge gets its one polygon's normal; a fan diagonal (inside a polygon) gets the polygon normal,
///   so signed distances equal those of the half-edge mesh;
/// - vertex pseudonormal: angle-weighted over the polygon corners (polygon angles, not fan angles).
///
/// Errors (nothing is dereferenced before it is checked): `empty`, `size_mismatch`, `degenerate`
/// (a face with < 3 corners), `bad_index`, `non_finite` (see `check_soup`); `size_mismatch` also
/// when the triangles and non-manifold edges do not fit the 32-bit edge links (about 4 G).
/// Topological defects (holes, non-manifold edges, flipped faces) are not errors here: run
/// `validate` to learn whether the signed distance is well defined. O(n log n) in the number of
/// corners.
template <class T> Result<TriangleMesh<T>> make_triangle_mesh(const PolygonSoup<T>& soup) {
  Error err = check_soup(soup);
  if (err.code != ErrorCode::ok) return err;

  const std::vector<Vec3<T>> poly_normals = face_unit_normals(soup);
  const EdgeNormalTable<T> edges = edge_pseudonormals(soup, poly_normals);
  const std::size_t nt = soup.triangle_count();
  if (!detail::edge_links_fit(nt, 0))
    return make_error(ErrorCode::size_mismatch, "triangle mesh: ", nt,
                      " triangles exceed the 32-bit edge links");

  TriangleMesh<T> m;
  m.vertices = soup.vertices;
  m.vertex_normals = vertex_pseudonormals(soup, poly_normals);
  m.triangles.reserve(nt);
  m.face_normals.reserve(nt);
  m.edge_links.reserve(nt);
  const bool all_triangles = soup.indices.size() == 3 * soup.face_count();
  if (!all_triangles) m.source_faces.reserve(nt);
  // First pass: each polygon side's triangle side gets its edge's table index (diagonals get
  // `diagonal_link`), and each edge records the triangles holding its first two polygon sides.
  constexpr Index none = ~Index(0);
  std::vector<std::array<Index, 2>> holders(edges.edges.size(), {none, none});
  std::vector<std::array<std::size_t, 3>> tris; // corner positions within the polygon
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    const std::size_t k = soup.face_size(f);
    const Index* c = soup.indices.data() + soup.offsets[f];
    const Vec3<T>& n = poly_normals[f];
    detail::triangulate_polygon<T>(
        k, [&](std::size_t i) -> const Vec3<T>& { return soup.vertices[c[i]]; }, n, tris);
    for (const auto& t : tris) {
      const Index id = static_cast<Index>(m.triangles.size());
      m.triangles.push_back({c[t[0]], c[t[1]], c[t[2]]});
      if (!all_triangles) m.source_faces.push_back(static_cast<Index>(f));
      m.face_normals.push_back(n);
      // A side is a polygon edge when its corners are consecutive; otherwise it is an internal
      // diagonal and gets the polygon normal.
      std::array<Index, 3> link;
      for (int e = 0; e < 3; ++e) {
        const std::size_t a = t[e], b = t[(e + 1) % 3];
        link[e] = TriangleMesh<T>::diagonal_link;
        if (b != (a + 1) % k) continue;
        const std::size_t edge = edges.find(c[a], c[b]);
        EBGEOM_ASSERT(edge < edges.edges.size()); // the table holds every polygon side
        link[e] = static_cast<Index>(edge);
        auto& h = holders[edge];
        (h[0] == none ? h[0] : h[1]) = id; // in triangle (so polygon) order
      }
      m.edge_links.push_back(link);
    }
  }
  // Second pass: edge indices become links. An edge of exactly two polygon sides links to the
  // other side's triangle (its pseudonormal is recomputed from the two face normals); one side is
  // a boundary (recomputed from the face normal); any other edge gets an overflow slot holding
  // the table's normal.
  std::vector<Index> slot(edges.edges.size(), none);
  for (std::size_t t = 0; t < nt; ++t)
    for (Index& link : m.edge_links[t]) {
      if (link == TriangleMesh<T>::diagonal_link) continue;
      const std::size_t edge = link;
      const auto& h = holders[edge];
      if (edges.face_count[edge] == 1) {
        link = TriangleMesh<T>::boundary_link;
      } else if (edges.face_count[edge] == 2 && h[1] != none) { // both sides were seen
        link = h[0] == t ? h[1] : h[0];
      } else {
        if (slot[edge] == none) {
          slot[edge] = static_cast<Index>(m.edge_overflow.size());
          m.edge_overflow.push_back(edges.normals[edge]);
        }
        link = TriangleMesh<T>::overflow_link - slot[edge];
      }
    }
  if (!detail::edge_links_fit(nt, m.edge_overflow.size()))
    return make_error(ErrorCode::size_mismatch, "triangle mesh: ", nt, " triangles and ",
                      m.edge_overflow.size(), " non-manifold edges exceed the 32-bit edge links");
  return m;
}

} // namespace ebgeom
