// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
/// \file
/// Vertex welding: merge duplicate vertices of a polygon soup (STL files store every triangle's
/// corners separately), exactly or within a tolerance, and drop unused vertices.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

#include "ebgeom/core/result.hpp"
#include "ebgeom/core/vec.hpp"
#include "ebgeom/mesh/polygon_soup.hpp"
#include "ebgeom/mesh/soup_check.hpp"

namespace ebgeom {

/// Options of `weld`.
struct WeldOptions {
  /// Vertices closer than this (Euclidean) are merged, transitively (single linkage). 0 merges
  /// only bitwise-equal positions (-0 and +0 are equal).
  double tolerance = 0;
  /// Remove consecutive repeated corners in each face (created by merging) and drop faces left
  /// with fewer than 3 corners.
  bool drop_collapsed_faces = true;
};

/// Output of `weld`: the welded soup and what happened.
template <class T> struct WeldResult {
  PolygonSoup<T> soup;
  /// New index of every input vertex; `~Index(0)` for unused vertices that were dropped.
  std::vector<Index> vertex_map;
  std::size_t merged_vertices = 0; ///< input vertices that became another vertex
  std::size_t unused_vertices = 0; ///< input vertices no face referenced (dropped)
  std::size_t dropped_faces = 0;   ///< faces collapsed below 3 corners by merging
};

/// Welds the vertices of `soup`: merges duplicates (exact, or within `opt.tolerance`), keeps the
/// position of the lowest-indexed vertex of each group, numbers the kept vertices in order of
/// first appearance in the input, and drops vertices no face uses. Faces keep their order.
///
/// Exact weld: one sort of the vertices, O(n log n). Tolerance weld: vertices are bucketed in a
/// grid of cell size `tolerance`, and each vertex is compared with the 27 neighbouring cells
/// (found by binary search in the sorted cell keys): O(n log n) for meshes without huge clusters.
/// Deterministic (independent of input order ties). Errors: those of `check_soup` except
/// `degenerate` faces are allowed through; `invalid_argument` for a negative or non-finite
/// tolerance.
template <class T>
Result<WeldResult<T>> weld(const PolygonSoup<T>& soup, const WeldOptions& opt = {}) {
  if (!(opt.tolerance >= 0) || !std::isfinite(opt.tolerance))
    return make_error(ErrorCode::invalid_argument, "weld tolerance must be finite and >= 0");
  const Error err = check_soup(soup);
  if (err.code != ErrorCode::ok && err.code != ErrorCode::degenerate) return err;

  const std::size_t n = soup.vertex_count();
  // Representative (lowest index in its group) per vertex, via union-find.
  std::vector<Index> parent(n);
  std::iota(parent.begin(), parent.end(), Index(0));
  auto find = [&](Index v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  auto unite = [&](Index a, Index b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (b < a) std::swap(a, b);
    parent[b] = a;
  };

  if (opt.tolerance == 0) {
    std::vector<Index> order(n);
    std::iota(order.begin(), order.end(), Index(0));
    auto less = [&](Index a, Index b) {
      const Vec3<T>&p = soup.vertices[a], &q = soup.vertices[b];
      return p.x != q.x ? p.x < q.x : (p.y != q.y ? p.y < q.y : (p.z != q.z ? p.z < q.z : a < b));
    };
    std::sort(order.begin(), order.end(), less);
    for (std::size_t i = 1; i < n; ++i)
      if (soup.vertices[order[i]] == soup.vertices[order[i - 1]]) unite(order[i], order[i - 1]);
  } else {
    const double h = opt.tolerance;
    using Key = std::array<std::int64_t, 3>;
    auto key_of = [&](const Vec3<T>& p) {
      return Key{std::int64_t(std::floor(double(p.x) / h)),
                 std::int64_t(std::floor(double(p.y) / h)),
                 std::int64_t(std::floor(double(p.z) / h))};
    };
    struct Entry {
      Key key;
      Index v;
    };
    std::vector<Entry> cells(n);
    for (std::size_t v = 0; v < n; ++v) cells[v] = {key_of(soup.vertices[v]), Index(v)};
    std::sort(cells.begin(), cells.end(), [](const Entry& a, const Entry& b) {
      return a.key != b.key ? a.key < b.key : a.v < b.v;
    });
    const double h2 = h * h;
    for (std::size_t v = 0; v < n; ++v) {
      const Key k = key_of(soup.vertices[v]);
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dz = -1; dz <= 1; ++dz) {
            const Key nk{k[0] + dx, k[1] + dy, k[2] + dz};
            auto it = std::lower_bound(cells.begin(), cells.end(), nk,
                                       [](const Entry& e, const Key& x) { return e.key < x; });
            for (; it != cells.end() && it->key == nk; ++it) {
              if (it->v <= v) continue; // each pair once
              const Vec3<double> d =
                  Vec3<double>::from(soup.vertices[it->v]) - Vec3<double>::from(soup.vertices[v]);
              if (norm2(d) <= h2) unite(Index(v), it->v);
            }
          }
    }
  }

  WeldResult<T> out;
  out.vertex_map.assign(n, ~Index(0));
  // A group (all vertices with the same representative) is kept if any member is used.
  std::vector<bool> group_used(n, false);
  for (Index i : soup.indices) group_used[find(i)] = true;
  std::vector<Index> new_of_rep(n, ~Index(0));
  for (std::size_t v = 0; v < n; ++v) {
    const Index r = find(Index(v));
    if (!group_used[r]) {
      ++out.unused_vertices;
      continue;
    }
    if (r != v) ++out.merged_vertices;
    // r <= v, so r is seen first: kept vertices are numbered in input order.
    if (new_of_rep[r] == ~Index(0)) new_of_rep[r] = out.soup.add_vertex(soup.vertices[r]);
    out.vertex_map[v] = new_of_rep[r];
  }

  std::vector<Index> face;
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    face.clear();
    for (Index i : soup.face(f)) face.push_back(out.vertex_map[i]);
    if (opt.drop_collapsed_faces) {
      face.erase(std::unique(face.begin(), face.end()), face.end());
      while (face.size() > 1 && face.front() == face.back()) face.pop_back();
      if (face.size() < 3) {
        ++out.dropped_faces;
        continue;
      }
    }
    out.soup.add_face(face);
  }
  return out;
}

} // namespace ebgeom
