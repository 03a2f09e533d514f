// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `BruteForceDcelSdf<T>`: the exact signed distance to a half-edge (DCEL) mesh of planar polygons
/// by scanning every face with EBGeometry's face/edge/vertex cases. O(faces) per query; the
/// polygon-mesh oracle (non-convex planar polygons included).

#include <cstddef>
#include <limits>
#include <utility>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/config.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/mesh/half_edge_mesh.hpp"
#include "ebgeom/sdf/concepts.hpp"
#include "ebgeom/sdf/dcel_distance.hpp"

namespace ebgeom {

/// Exact signed distance (< 0 inside) to a closed, manifold, consistently outward-oriented
/// half-edge mesh of planar polygons. The closest face is the first (lowest index) with the
/// smallest squared distance. `inside_test` selects the point-in-polygon algorithm. Immutable;
/// concurrent calls are safe.
template <class T> class BruteForceDcelSdf {
 public:
  using scalar_type = T;
  static constexpr SdfKind kind = SdfKind::exact;

  /// Precondition: `is_valid(inside_test)` (checked in every build).
  explicit BruteForceDcelSdf(HalfEdgeMesh<T> mesh,
                             InsideTest inside_test = InsideTest::crossing_number)
      : mesh_(std::move(mesh)), bounds_(mesh_.bounds()), inside_test_(inside_test) {
    EBGEOM_PRECONDITION(is_valid(inside_test), "BruteForceDcelSdf: InsideTest value out of range");
  }

  /// Builds the half-edge mesh from a soup; errors as `make_half_edge_mesh`.
  static Result<BruteForceDcelSdf> build(const PolygonSoup<T>& soup,
                                         InsideTest inside_test = InsideTest::crossing_number) {
    Result<HalfEdgeMesh<T>> m = make_half_edge_mesh(soup);
    if (!m) return m.error();
    return BruteForceDcelSdf(std::move(*m), inside_test);
  }

  T operator()(const Vec3<T>& p) const noexcept { return closest(p).distance; }

  /// Signed distance, closest point and feature. For an empty mesh: distance +inf, face invalid.
  DcelClosestPoint<T> closest(const Vec3<T>& p) const noexcept {
    DcelClosestPoint<T> best{std::numeric_limits<T>::infinity(),
                             std::numeric_limits<T>::infinity(),
                             Vec3<T>::zero(),
                             DcelFeature::face,
                             invalid_index,
                             invalid_index};
    for (std::size_t f = 0; f < mesh_.face_count(); ++f) {
      const DcelClosestPoint<T> c = signed_distance_to_face(mesh_, Index(f), p, inside_test_);
      if (c.distance2 < best.distance2) best = c;
    }
    return best;
  }

  Aabb<T> bounds() const noexcept { return bounds_; }
  const HalfEdgeMesh<T>& mesh() const noexcept { return mesh_; }

 private:
  HalfEdgeMesh<T> mesh_;
  Aabb<T> bounds_;
  InsideTest inside_test_;
};

} // namespace ebgeom
