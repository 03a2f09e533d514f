// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// The per-triangle sign kernel shared by every triangle-mesh SDF (`MeshSdf` and its oracle
/// `BruteForceMeshSdf`): `MeshClosestPoint<T>` (what a closest-point query returns),
/// `feature_pseudonormal` (the angle-weighted pseudonormal of the closest feature, Baerentzen &
/// Aanaes 2005) and `triangle_signed_distance` (distance to one triangle, signed by that
/// pseudonormal). Both SDFs perform exactly these operations, so they agree to the last bit.

#include <cstddef>
#include <limits>

#include "ebgeom/core/config.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/closest_point_triangle.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"

EBGEOM_BEGIN_EXACT_FP

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

} // namespace ebgeom

EBGEOM_END_EXACT_FP
