// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Signed distance from a point to a face, an edge and a vertex of a `HalfEdgeMesh`, exactly as
/// EBGeometry's three cases (EBGeometry "DCEL mesh structure", §Signed distance), with the sign
/// from the face normal or the edge/vertex pseudonormal (Bærentzen & Aanæs 2005) and the
/// magnitude always the Euclidean distance to the closest point.

#include <cmath>
#include <cstdint>
#include <limits>

#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/point_in_polygon.hpp"
#include "ebgeom/mesh/half_edge_mesh.hpp"

namespace ebgeom {

/// Kind of DCEL feature a closest point lies on.
enum class DcelFeature : std::uint8_t { face, edge, vertex };

inline const char* to_string(DcelFeature f) noexcept {
  return f == DcelFeature::face ? "face" : (f == DcelFeature::edge ? "edge" : "vertex");
}

/// Result of a DCEL distance query: signed distance (< 0 inside), closest point, squared
/// distance, the feature kind and its index (face index, half-edge index or vertex index), and
/// the face that produced it.
template <class T> struct DcelClosestPoint {
  T distance;
  T distance2;
  Vec3<T> point;
  DcelFeature feature;
  Index index;
  Index face;
};

/// Vertex case: magnitude |x - x_v|, sign of n_v·(x - x_v) with n_v the angle-weighted vertex
/// pseudonormal. O(1).
template <class T>
DcelClosestPoint<T> signed_distance_to_vertex(const HalfEdgeMesh<T>& m, Index v,
                                              const Vec3<T>& x) noexcept {
  const Vec3<T>& xv = m.position(v);
  const Vec3<T> d = x - xv;
  const T d2 = norm2(d);
  const T s = std::sqrt(d2);
  return {
      dot(m.vertex_normal(v), d) < T(0) ? -s : s, d2, xv, DcelFeature::vertex, v, invalid_index};
}

/// Edge case for half-edge h = (x0, x1): project x on e(t) = x0 + (x1 - x0) t; for t in (0, 1)
/// the magnitude is the distance to e(t) and the sign that of n_e·(x - x0) (edge pseudonormal);
/// otherwise the vertex case of the nearer end. A zero-length edge is its origin vertex. O(1).
template <class T>
DcelClosestPoint<T> signed_distance_to_edge(const HalfEdgeMesh<T>& m, Index h,
                                            const Vec3<T>& x) noexcept {
  const HalfEdge& he = m.half_edge(h);
  const Index v0 = he.origin, v1 = m.target(h);
  const Vec3<T>& x0 = m.position(v0);
  const Vec3<T> e = m.position(v1) - x0;
  const T ee = dot(e, e), t = dot(x - x0, e);
  if (t <= T(0) || !(ee > T(0))) return signed_distance_to_vertex(m, v0, x);
  if (t >= ee) return signed_distance_to_vertex(m, v1, x);
  const Vec3<T> q = x0 + e * (t / ee);
  const T d2 = norm2(x - q);
  const T s = std::sqrt(d2);
  return {
      dot(m.edge_normal(h), x - x0) < T(0) ? -s : s, d2, q, DcelFeature::edge, h, invalid_index};
}

/// Face case: project x to the face plane and test the projection with `method` in the face's
/// 2D projection. Inside: d = n_f·(x - x_f) (x_f the centroid), closest point the projection.
/// Outside: the nearest of the face's edges (edge or vertex case). O(face size).
template <class T>
DcelClosestPoint<T> signed_distance_to_face(const HalfEdgeMesh<T>& m, Index f, const Vec3<T>& x,
                                            InsideTest method = InsideTest::crossing_number) {
  const HalfEdgeFace<T>& face = m.face(f);
  const Vec3<T>& n = face.normal;
  const T h = dot(n, x - face.centroid);
  if (norm2(n) > T(0)) {
    const Vec3<T> xp = x - n * h;
    const PlaneProjection& pr = face.projection;
    const Index first = face.edge;
    // half-edges of a face are contiguous from face.edge (see HalfEdgeMesh)
    auto corner = [&](std::size_t i) {
      return pr(m.position(m.half_edge(first + Index(i)).origin));
    };
    if (point_in_polygon(pr(xp), face.size, corner, method))
      return {h, h * h, xp, DcelFeature::face, f, f};
  }
  DcelClosestPoint<T> best{};
  best.distance2 = std::numeric_limits<T>::infinity();
  m.for_each_half_edge(f, [&](Index e) {
    const DcelClosestPoint<T> c = signed_distance_to_edge(m, e, x);
    if (c.distance2 < best.distance2) best = c;
  });
  best.face = f;
  return best;
}

} // namespace ebgeom
