// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// `HalfEdgeMesh<T>`: an index-based doubly-connected edge list (DCEL) of planar N-sided polygons,
/// as in EBGeometry's "DCEL mesh structure" chapter, with cached face data (normal, centroid, area,
/// 2D projection) and the pseudonormals needed for signed distances.

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

#include "ebgeom/core/aabb.hpp"
#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/polygon_geometry.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/pseudonormals.hpp"
#include "ebgeom/mesh/soup_check.hpp"

namespace ebgeom {

/// "No element" marker for half-edge, vertex and face references.
inline constexpr Index invalid_index = ~Index(0);

/// One directed side of an edge, circulating its face counter-clockwise (seen from outside).
/// `pair` is the opposite half-edge of the neighbouring face, or `invalid_index` on a boundary,
/// a non-manifold edge (more than two faces) or between inconsistently oriented faces. 20 B.
struct HalfEdge {
  Index next = invalid_index;
  Index prev = invalid_index;
  Index pair = invalid_index;
  Index origin = invalid_index; ///< vertex it starts from
  Index face = invalid_index;
};

/// A vertex: position and one outgoing half-edge (a boundary one when the vertex is on a
/// boundary, so circulation can start there). 16 B (float) / 32 B (double) with padding.
template <class T> struct HalfEdgeVertex {
  Vec3<T> position;
  Index edge = invalid_index;
};

/// A planar polygon face: one of its half-edges, and cached geometry: unit Newell normal, area,
/// area-weighted centroid, the number of corners and the 2D projection used by the
/// point-in-polygon test (drop the dominant normal axis, keep counter-clockwise order).
template <class T> struct HalfEdgeFace {
  Index edge = invalid_index;
  Index size = 0;
  Vec3<T> normal;
  Vec3<T> centroid;
  T area = 0;
  PlaneProjection projection;
};

/// Half-edge mesh built from a `PolygonSoup` by `make_half_edge_mesh`. Half-edges of face f are
/// stored contiguously in corner order (face f's k-th half-edge starts at its k-th corner), so
/// half-edge h belongs to soup corner h. Pseudonormals (Bærentzen & Aanæs 2005) are cached per
/// vertex and per half-edge (a half-edge and its pair share the same edge pseudonormal).
/// Immutable after construction; concurrent const use is thread-safe.
template <class T> class HalfEdgeMesh {
 public:
  using scalar_type = T;

  std::size_t vertex_count() const noexcept { return vertices_.size(); }
  std::size_t face_count() const noexcept { return faces_.size(); }
  std::size_t half_edge_count() const noexcept { return edges_.size(); }

  const HalfEdgeVertex<T>& vertex(Index v) const noexcept { return vertices_[v]; }
  const HalfEdge& half_edge(Index h) const noexcept { return edges_[h]; }
  const HalfEdgeFace<T>& face(Index f) const noexcept { return faces_[f]; }
  const Vec3<T>& position(Index v) const noexcept { return vertices_[v].position; }
  /// Vertex a half-edge ends at.
  Index target(Index h) const noexcept { return edges_[edges_[h].next].origin; }

  /// Unit angle-weighted pseudonormal of vertex v.
  const Vec3<T>& vertex_normal(Index v) const noexcept { return vertex_normals_[v]; }
  /// Unit pseudonormal of the edge of half-edge h: normalise(sum of the normals of the faces on
  /// that edge) (one face on a boundary).
  const Vec3<T>& edge_normal(Index h) const noexcept { return edge_normals_[h]; }

  const std::vector<HalfEdgeVertex<T>>& vertices() const noexcept { return vertices_; }
  const std::vector<HalfEdge>& half_edges() const noexcept { return edges_; }
  const std::vector<HalfEdgeFace<T>>& faces() const noexcept { return faces_; }

  /// Half-edges without a pair because exactly one face uses the edge (boundary).
  const std::vector<Index>& boundary_half_edges() const noexcept { return boundary_; }
  /// Half-edges on edges used by more than two face sides (left unpaired).
  const std::vector<Index>& non_manifold_half_edges() const noexcept { return non_manifold_; }
  /// Half-edges on edges whose two faces traverse it in the same direction (left unpaired).
  const std::vector<Index>& inconsistent_half_edges() const noexcept { return inconsistent_; }
  /// True when every edge has exactly two consistently oriented faces.
  bool is_closed_manifold() const noexcept {
    return boundary_.empty() && non_manifold_.empty() && inconsistent_.empty();
  }

  /// Calls `fn(h)` for the half-edges of face f in order. O(size).
  template <class Fn> void for_each_half_edge(Index f, Fn&& fn) const {
    const Index first = faces_[f].edge;
    Index h = first;
    for (Index i = 0; i < faces_[f].size; ++i, h = edges_[h].next) fn(h);
  }
  /// Calls `fn(v)` for the vertices of face f in order.
  template <class Fn> void for_each_vertex(Index f, Fn&& fn) const {
    for_each_half_edge(f, [&](Index h) { fn(edges_[h].origin); });
  }
  /// Calls `fn(h)` for every half-edge leaving vertex v that can be reached by circulating
  /// through paired edges from `vertex(v).edge` (all of them on a manifold vertex; one fan on a
  /// non-manifold one). Each is visited once; terminates on any input.
  template <class Fn> void for_each_outgoing(Index v, Fn&& fn) const {
    const Index start = vertices_[v].edge;
    if (start == invalid_index) return;
    // forward: next(pair(h))
    Index h = start;
    const std::size_t limit = edges_.size();
    std::size_t steps = 0;
    bool closed = false;
    do {
      fn(h);
      const Index p = edges_[h].pair;
      if (p == invalid_index) break;
      h = edges_[p].next;
      if (h == start) closed = true;
    } while (!closed && ++steps < limit);
    if (closed) return;
    // backward from start: pair(prev(h))
    h = edges_[edges_[start].prev].pair;
    steps = 0;
    while (h != invalid_index && h != start && ++steps < limit) {
      fn(h);
      h = edges_[edges_[h].prev].pair;
    }
  }

  Aabb<T> bounds() const noexcept {
    Aabb<T> b;
    for (const auto& v : vertices_) b.extend(v.position);
    return b;
  }

 private:
  template <class U> friend Result<HalfEdgeMesh<U>> make_half_edge_mesh(const PolygonSoup<U>&);
  std::vector<HalfEdgeVertex<T>> vertices_;
  std::vector<HalfEdge> edges_;
  std::vector<HalfEdgeFace<T>> faces_;
  std::vector<Vec3<T>> vertex_normals_;
  std::vector<Vec3<T>> edge_normals_;
  std::vector<Index> boundary_, non_manifold_, inconsistent_;
};

/// Builds the half-edge mesh of `soup`. Edges are matched by sorting the face sides by their
/// undirected vertex pair: O(n log n) in the number of corners. Two opposite sides are paired;
/// a lone side is a boundary; more than two sides (non-manifold) or two sides in the same
/// direction (inconsistent orientation) stay unpaired and are listed, so such input builds
/// without crashing (see `validate` for the diagnosis).
///
/// Errors (from `check_soup`): `empty`, `size_mismatch`, `degenerate` (face with < 3 corners),
/// `bad_index`, `non_finite`.
template <class T> Result<HalfEdgeMesh<T>> make_half_edge_mesh(const PolygonSoup<T>& soup) {
  Error err = check_soup(soup);
  if (err.code != ErrorCode::ok) return err;
  const std::size_t nh = soup.indices.size();
  if (nh >= invalid_index)
    return make_error(ErrorCode::size_mismatch, "too many corners for 32-bit half-edge indices");

  HalfEdgeMesh<T> m;
  m.vertices_.resize(soup.vertex_count());
  for (std::size_t v = 0; v < soup.vertex_count(); ++v) m.vertices_[v].position = soup.vertices[v];
  m.edges_.resize(nh);
  m.faces_.resize(soup.face_count());

  const std::vector<Vec3<T>> normals = face_unit_normals(soup);
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    const Index first = soup.offsets[f];
    const Index k = static_cast<Index>(soup.face_size(f));
    for (Index i = 0; i < k; ++i) {
      HalfEdge& h = m.edges_[first + i];
      h.origin = soup.indices[first + i];
      h.face = static_cast<Index>(f);
      h.next = first + (i + 1 == k ? 0 : i + 1);
      h.prev = first + (i == 0 ? k - 1 : i - 1);
    }
    auto corner = [&](std::size_t i) -> const Vec3<T>& {
      return soup.vertices[soup.indices[first + i]];
    };
    HalfEdgeFace<T>& face = m.faces_[f];
    face.edge = first;
    face.size = k;
    const Vec3<T> nw = newell_normal<T>(k, corner);
    face.normal = normals[f];
    face.area = norm(nw) / T(2);
    face.centroid = polygon_centroid<T>(k, corner);
    face.projection = PlaneProjection::for_normal(nw);
  }

  // Match sides by undirected key; sort by (lo, hi, half-edge) for determinism.
  struct Side {
    Index lo, hi, h;
  };
  std::vector<Side> sides(nh);
  for (Index h = 0; h < nh; ++h) {
    const Index a = m.edges_[h].origin, b = soup.indices[m.edges_[h].next];
    sides[h] = {std::min(a, b), std::max(a, b), h};
  }
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : x.h < y.h);
  });
  m.edge_normals_.assign(nh, Vec3<T>::zero());
  for (std::size_t i = 0; i < nh;) {
    std::size_t j = i;
    Vec3<T> sum = Vec3<T>::zero();
    // faces in increasing order as in edge_pseudonormals (half-edges are stored face by face)
    while (j < nh && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi) {
      sum += normals[m.edges_[sides[j].h].face];
      ++j;
    }
    const Vec3<T> en = normalized(sum);
    for (std::size_t s = i; s < j; ++s) m.edge_normals_[sides[s].h] = en;
    if (j - i == 1) {
      m.boundary_.push_back(sides[i].h);
    } else if (j - i == 2) {
      const Index h0 = sides[i].h, h1 = sides[i + 1].h;
      if (m.edges_[h0].origin != m.edges_[h1].origin) {
        m.edges_[h0].pair = h1;
        m.edges_[h1].pair = h0;
      } else {
        m.inconsistent_.push_back(h0);
        m.inconsistent_.push_back(h1);
      }
    } else {
      for (std::size_t s = i; s < j; ++s) m.non_manifold_.push_back(sides[s].h);
    }
    i = j;
  }
  std::sort(m.boundary_.begin(), m.boundary_.end());
  std::sort(m.non_manifold_.begin(), m.non_manifold_.end());
  std::sort(m.inconsistent_.begin(), m.inconsistent_.end());

  // Outgoing half-edge per vertex: prefer one whose backward rotation is blocked, so the forward
  // circulation from it covers the whole fan of a boundary vertex.
  for (Index h = 0; h < nh; ++h) {
    HalfEdgeVertex<T>& v = m.vertices_[m.edges_[h].origin];
    if (v.edge == invalid_index) v.edge = h;
    if (m.edges_[m.edges_[h].prev].pair == invalid_index &&
        m.edges_[m.edges_[v.edge].prev].pair != invalid_index)
      v.edge = h;
  }
  m.vertex_normals_ = vertex_pseudonormals(soup, normals);
  return m;
}

} // namespace ebgeom
