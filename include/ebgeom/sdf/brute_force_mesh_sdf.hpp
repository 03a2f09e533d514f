// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `BruteForceMeshSdf<T>`: the exact signed distance to a triangle mesh by scanning every triangle.
/// O(n) per query; the oracle that accelerated mesh SDFs (BVH) must match to the last bit. The
/// per-triangle sign kernel both use is in `sdf/mesh_closest_point.hpp`.

#include <cstddef>
#include <limits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/closest_point_triangle.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/mesh_closest_point.hpp"

EBGEOM_BEGIN_EXACT_FP

namespace ebgeom {

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

EBGEOM_END_EXACT_FP
