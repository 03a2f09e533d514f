#pragma once
/// \file
/// `TriangleMesh<T>`: the "pseudo-triangle" fast path. Triangles that carry their face, edge and
/// vertex pseudonormals, so the per-triangle kernel (geom/closest_point_triangle.hpp) gives the
/// signed distance without any topology at query time, equal to the half-edge mesh's.

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/mesh/polygon_geometry.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/pseudonormals.hpp"
#include "ebgeom/mesh/soup_check.hpp"

namespace ebgeom {

/// Triangles with precomputed pseudonormals (Bærentzen & Aanæs 2005).
///
/// Memory per triangle: 12 B indices + 4 B `source_face` + 3 T face normal + 9 T edge normals,
/// i.e. 64 B (float) / 112 B (double); plus 6 T per vertex (position and pseudonormal), about
/// half a vertex per triangle on closed meshes: ~76 B (float) / ~136 B (double) per triangle.
///
/// Invariants (established by `make_triangle_mesh`): all arrays indexed by triangle have
/// `triangles.size()` entries; `vertices` and `vertex_normals` have the same size; every index
/// is < `vertices.size()`; coordinates are finite. Immutable use is thread-safe.
template <class T> struct TriangleMesh {
  using scalar_type = T;
  std::vector<Vec3<T>> vertices;
  std::vector<std::array<Index, 3>> triangles;      ///< CCW seen from outside
  std::vector<Index> source_face;                   ///< polygon of the soup each triangle came from
  std::vector<Vec3<T>> face_normals;                ///< unit, per triangle (its polygon's normal)
  std::vector<std::array<Vec3<T>, 3>> edge_normals; ///< edges (v0,v1),(v1,v2),(v2,v0)
  std::vector<Vec3<T>> vertex_normals;              ///< angle-weighted pseudonormal per vertex

  std::size_t triangle_count() const noexcept { return triangles.size(); }
  std::size_t vertex_count() const noexcept { return vertices.size(); }
  /// Vertex `k` (0, 1, 2) of triangle `t`.
  const Vec3<T>& corner(std::size_t t, int k) const noexcept { return vertices[triangles[t][k]]; }
  Aabb<T> bounds() const noexcept { return Aabb<T>::of_range(vertices); }
  /// Tight box of triangle `t`.
  Aabb<T> triangle_bounds(std::size_t t) const noexcept {
    return Aabb<T>::of(corner(t, 0), corner(t, 1), corner(t, 2));
  }
  /// Heap bytes held by the arrays (sizes, not capacities).
  std::size_t memory_bytes() const noexcept {
    return vertices.size() * sizeof(Vec3<T>) * 2 + triangles.size() * sizeof(triangles[0]) +
           source_face.size() * sizeof(Index) + face_normals.size() * sizeof(Vec3<T>) +
           edge_normals.size() * sizeof(edge_normals[0]);
  }
};

namespace detail {
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
/// (a face with < 3 corners), `bad_index`, `non_finite` (see `check_soup`). Topological defects
/// (holes, non-manifold edges, flipped faces) are not errors here: run `validate` to learn whether
/// the signed distance is well defined. O(n log n) in the number of corners.
template <class T> Result<TriangleMesh<T>> make_triangle_mesh(const PolygonSoup<T>& soup) {
  Error err = check_soup(soup);
  if (err.code != ErrorCode::ok) return err;

  const std::vector<Vec3<T>> poly_normals = face_unit_normals(soup);
  const EdgeNormalTable<T> edges = edge_pseudonormals(soup, poly_normals);

  TriangleMesh<T> m;
  m.vertices = soup.vertices;
  m.vertex_normals = vertex_pseudonormals(soup, poly_normals);
  const std::size_t nt = soup.triangle_count();
  m.triangles.reserve(nt);
  m.source_face.reserve(nt);
  m.face_normals.reserve(nt);
  m.edge_normals.reserve(nt);
  auto edge_normal = [&](Index a, Index b) -> Vec3<T> {
    const std::size_t e = edges.find(a, b);
    return e < edges.edges.size() ? edges.normals[e] : Vec3<T>::zero();
  };
  std::vector<std::array<std::size_t, 3>> tris; // corner positions within the polygon
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    const std::size_t k = soup.face_size(f);
    const Index* c = soup.indices.data() + soup.offsets[f];
    const Vec3<T>& n = poly_normals[f];
    detail::triangulate_polygon<T>(
        k, [&](std::size_t i) -> const Vec3<T>& { return soup.vertices[c[i]]; }, n, tris);
    for (const auto& t : tris) {
      m.triangles.push_back({c[t[0]], c[t[1]], c[t[2]]});
      m.source_face.push_back(static_cast<Index>(f));
      m.face_normals.push_back(n);
      // A side is a polygon edge when its corners are consecutive; otherwise it is an internal
      // diagonal and gets the polygon normal.
      std::array<Vec3<T>, 3> en;
      for (int e = 0; e < 3; ++e) {
        const std::size_t a = t[e], b = t[(e + 1) % 3];
        en[e] = (b == (a + 1) % k) ? edge_normal(c[a], c[b]) : n;
      }
      m.edge_normals.push_back(en);
    }
  }
  return m;
}

} // namespace ebgeom
