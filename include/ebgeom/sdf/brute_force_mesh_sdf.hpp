// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `BruteForceMeshSdf<T>`: the exact signed distance to a triangle mesh by scanning every triangle.
/// O(n) per query; the oracle that accelerated mesh SDFs (BVH) must match to the last bit.

#include <cstddef>
#include <limits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/closest_point_triangle.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/concepts.hpp"

namespace ebgeom {

/// Closest point of a mesh to a query: signed distance (< 0 inside), the point, the triangle
/// holding it and its feature on that triangle. `triangle == invalid_triangle` for an empty mesh
/// (then `distance` is +inf).
template <class T> struct MeshClosestPoint {
  static constexpr Index invalid_triangle = ~Index(0);
  T distance = std::numeric_limits<T>::infinity();
  Vec3<T> point{0, 0, 0};
  Index triangle = invalid_triangle;
  TriangleFeature feature = TriangleFeature::face;
};

/// Pseudonormal of `feature` of triangle `t`: the face normal, an edge pseudonormal (recomputed,
/// `TriangleMesh::edge_normal`) or a vertex pseudonormal. Precondition: t <
/// mesh.triangle_count(). O(1).
template <class T>
EBGEOM_FORCE_INLINE Vec3<T> feature_pseudonormal(const TriangleMesh<T>& mesh, std::size_t t,
                                                 TriangleFeature feature) noexcept {
  if (is_vertex(feature)) return mesh.vertex_normals[mesh.triangles[t][vertex_index(feature)]];
  if (is_edge(feature)) return mesh.edge_normal(t, edge_index(feature));
  return mesh.face_normals[t];
}

/// Signed distance from `p` to triangle `t` of `mesh`, with the pseudonormal of the closest
/// feature deciding the sign (the same operations as `BruteForceMeshSdf` and `MeshSdf`, so the
/// same bits). Precondition: t < mesh.triangle_count(). O(1), deterministic.
template <class T>
EBGEOM_FORCE_INLINE TriangleSignedDistance<T>
triangle_signed_distance(const TriangleMesh<T>& mesh, std::size_t t, const Vec3<T>& p) noexcept {
  const auto& tri = mesh.triangles[t];
  const TriangleClosestPoint<T> cp = closest_point_triangle(
      p, mesh.vertices[tri[0]], mesh.vertices[tri[1]], mesh.vertices[tri[2]]);
  return {
      signed_distance_from(p, cp.point, cp.distance2, feature_pseudonormal(mesh, t, cp.feature)),
      cp.point, cp.feature};
}

/// Exact signed distance to a closed, consistently oriented, manifold triangle mesh (check with
/// `validate`; on other meshes the magnitude is still the unsigned distance but the sign may be
/// wrong near defects). Every query scans all triangles: O(n). The nearest triangle is the first
/// one (lowest index) with the smallest squared distance. Immutable; concurrent calls are safe.
template <class T> class BruteForceMeshSdf {
 public:
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;

  explicit BruteForceMeshSdf(TriangleMesh<T> mesh)
      : mesh_(std::move(mesh)), bounds_(mesh_.bounds()) {}

  /// Builds the triangle mesh from a soup; errors as `make_triangle_mesh`.
  static Result<BruteForceMeshSdf> build(const PolygonSoup<T>& soup) {
    Result<TriangleMesh<T>> m = make_triangle_mesh(soup);
    if (!m) return m.error();
    return BruteForceMeshSdf(std::move(*m));
  }

  /// Signed distance at `p` (< 0 inside); +inf for an empty mesh.
  T operator()(const Vec3<T>& p) const noexcept { return closest(p).distance; }

  /// Closest point, triangle and feature, with the signed distance.
  MeshClosestPoint<T> closest(const Vec3<T>& p) const noexcept {
    MeshClosestPoint<T> best;
    T best2 = std::numeric_limits<T>::infinity();
    for (std::size_t t = 0; t < mesh_.triangle_count(); ++t) {
      const auto& tri = mesh_.triangles[t];
      const TriangleClosestPoint<T> cp = closest_point_triangle(
          p, mesh_.vertices[tri[0]], mesh_.vertices[tri[1]], mesh_.vertices[tri[2]]);
      if (cp.distance2 < best2) {
        best2 = cp.distance2;
        best.point = cp.point;
        best.triangle = static_cast<Index>(t);
        best.feature = cp.feature;
      }
    }
    if (best.triangle == MeshClosestPoint<T>::invalid_triangle) return best;
    best.distance = signed_distance_from(p, best.point, best2,
                                         feature_pseudonormal(mesh_, best.triangle, best.feature));
    return best;
  }

  /// Box of the mesh vertices (contains the surface and the inside).
  Aabb<T> bounds() const noexcept { return bounds_; }
  const TriangleMesh<T>& mesh() const noexcept { return mesh_; }

 private:
  TriangleMesh<T> mesh_;
  Aabb<T> bounds_;
};

} // namespace ebgeom
