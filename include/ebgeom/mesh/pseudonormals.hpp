// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Face normals and the pseudonormals of Bærentzen & Aanæs (2005), "Signed distance computation
/// using the angle weighted pseudonormal", IEEE TVCG 11(3): the angle-weighted vertex pseudonormal
/// n_v = normalise(sum_i alpha_i n_{f_i}) and the edge pseudonormal n_e = normalise(n_f + n_f').
/// With them, the sign of n·(x - c), where c is the closest point of a closed, consistently
/// oriented manifold mesh and n the pseudonormal of the feature holding c, is the inside/outside
/// sign (their Theorem 1). Shared by the half-edge mesh and the triangle mesh so both give the same
/// normals.

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

#include "ebgeom/core/vec.hpp"
#include "ebgeom/geom/polygon_geometry.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"

namespace ebgeom {

/// Unit Newell normal of every face of `soup` (zero for zero-area faces).
/// Precondition: `check_soup(soup)` passed. O(corners).
template <class T> std::vector<Vec3<T>> face_unit_normals(const PolygonSoup<T>& soup) {
  std::vector<Vec3<T>> n(soup.face_count());
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    const Index* c = soup.indices.data() + soup.offsets[f];
    n[f] = normalized(newell_normal<T>(
        soup.face_size(f), [&](std::size_t i) -> const Vec3<T>& { return soup.vertices[c[i]]; }));
  }
  return n;
}

/// Angle-weighted vertex pseudonormals: for each vertex, normalise(sum over the polygon corners at
/// it of (interior angle) * (face normal)). Unused vertices get the zero vector. Faces are visited
/// in order, so the result is deterministic. Precondition: `check_soup(soup)` passed and
/// `face_normals.size() == soup.face_count()`. O(corners).
template <class T>
std::vector<Vec3<T>> vertex_pseudonormals(const PolygonSoup<T>& soup,
                                          const std::vector<Vec3<T>>& face_normals) {
  std::vector<Vec3<T>> acc(soup.vertex_count(), Vec3<T>::zero());
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    const std::size_t k = soup.face_size(f);
    const Index* c = soup.indices.data() + soup.offsets[f];
    for (std::size_t i = 0; i < k; ++i) {
      const Index v = c[i];
      const Index vp = c[(i + k - 1) % k], vn = c[(i + 1) % k];
      const T alpha = corner_angle(soup.vertices[vp], soup.vertices[v], soup.vertices[vn]);
      acc[v] += face_normals[f] * alpha;
    }
  }
  for (auto& n : acc) n = normalized(n);
  return acc;
}

/// Undirected edges of a soup with their pseudonormals. `edges` is sorted by (lo, hi) with
/// lo < hi; `normals[i]` is normalise(sum of the unit normals of the faces using edge i) (one
/// face: that face's normal, i.e. boundary edges; more than two: non-manifold, the sum is a
/// best effort and the signed distance is not well defined there). `face_count[i]` counts the
/// face sides on edge i.
template <class T> struct EdgeNormalTable {
  std::vector<std::pair<Index, Index>> edges;
  std::vector<Vec3<T>> normals;
  std::vector<Index> face_count;

  /// Index of undirected edge {a, b} in `edges`, or `edges.size()` if absent. O(log E).
  std::size_t find(Index a, Index b) const noexcept {
    const std::pair<Index, Index> key{std::min(a, b), std::max(a, b)};
    const auto it = std::lower_bound(edges.begin(), edges.end(), key);
    return (it != edges.end() && *it == key) ? std::size_t(it - edges.begin()) : edges.size();
  }
};

/// Builds the edge pseudonormal table of `soup` by sorting its face sides. O(n log n) in the
/// number of corners. Precondition: `check_soup(soup)` passed and `face_normals` per face.
/// `TriangleMesh::edge_normal` recomputes the entries of one and two face sides with the same
/// operations (normalise(zero + n_f [+ n_g]), faces in order) instead of storing them: change
/// both together (tests/unit/mesh/edge_links_test.cpp compares them bit for bit).
template <class T>
EdgeNormalTable<T> edge_pseudonormals(const PolygonSoup<T>& soup,
                                      const std::vector<Vec3<T>>& face_normals) {
  struct Side {
    Index lo, hi, face;
  };
  std::vector<Side> sides;
  sides.reserve(soup.indices.size());
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    const std::size_t k = soup.face_size(f);
    const Index* c = soup.indices.data() + soup.offsets[f];
    for (std::size_t i = 0; i < k; ++i) {
      const Index a = c[i], b = c[(i + 1) % k];
      sides.push_back({std::min(a, b), std::max(a, b), static_cast<Index>(f)});
    }
  }
  // Sorting by face too fixes the summation order: deterministic normals.
  std::sort(sides.begin(), sides.end(), [](const Side& x, const Side& y) {
    return x.lo != y.lo ? x.lo < y.lo : (x.hi != y.hi ? x.hi < y.hi : x.face < y.face);
  });
  EdgeNormalTable<T> t;
  for (std::size_t i = 0; i < sides.size();) {
    std::size_t j = i;
    Vec3<T> sum = Vec3<T>::zero();
    while (j < sides.size() && sides[j].lo == sides[i].lo && sides[j].hi == sides[i].hi) {
      sum += face_normals[sides[j].face];
      ++j;
    }
    t.edges.emplace_back(sides[i].lo, sides[i].hi);
    t.normals.push_back(normalized(sum));
    t.face_count.push_back(static_cast<Index>(j - i));
    i = j;
  }
  return t;
}

} // namespace ebgeom
