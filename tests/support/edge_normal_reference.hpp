// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// The per-triangle edge pseudonormal table as `make_triangle_mesh` stored it before edge links
// (one Vec3 per triangle side): the soup's edge table (`edge_pseudonormals`) on polygon sides, the
// polygon normal on diagonals. `TriangleMesh::edge_normal` must reproduce it bit for bit, and
// `expect_edge_normals_match` checks that on every side.

#include <gtest/gtest.h>

#include <array>
#include <cstddef>
#include <cstring>
#include <vector>

#include "ebgeom/mesh/pseudonormals.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"

namespace ebgeom::test {

template <class T> struct ReferenceTriangles {
  std::vector<std::array<Index, 3>> triangles;
  std::vector<Index> source_face;
  std::vector<std::array<Vec3<T>, 3>> edge_normals;
};

/// The triangles, source polygons and edge pseudonormal table of `soup`, computed as before edge
/// links. Precondition: `check_soup(soup)` passed.
template <class T> ReferenceTriangles<T> reference_edge_normals(const PolygonSoup<T>& soup) {
  const std::vector<Vec3<T>> poly_normals = face_unit_normals(soup);
  const EdgeNormalTable<T> edges = edge_pseudonormals(soup, poly_normals);
  ReferenceTriangles<T> r;
  std::vector<std::array<std::size_t, 3>> tris;
  for (std::size_t f = 0; f < soup.face_count(); ++f) {
    const std::size_t k = soup.face_size(f);
    const Index* c = soup.indices.data() + soup.offsets[f];
    const Vec3<T>& n = poly_normals[f];
    detail::triangulate_polygon<T>(
        k, [&](std::size_t i) -> const Vec3<T>& { return soup.vertices[c[i]]; }, n, tris);
    for (const auto& t : tris) {
      r.triangles.push_back({c[t[0]], c[t[1]], c[t[2]]});
      r.source_face.push_back(Index(f));
      std::array<Vec3<T>, 3> en;
      for (int e = 0; e < 3; ++e) {
        const std::size_t a = t[e], b = t[(e + 1) % 3];
        if (b == (a + 1) % k) {
          const std::size_t i = edges.find(c[a], c[b]);
          en[e] = i < edges.edges.size() ? edges.normals[i] : Vec3<T>::zero();
        } else {
          en[e] = n;
        }
      }
      r.edge_normals.push_back(en);
    }
  }
  return r;
}

/// Every side's `edge_normal` of the triangle mesh of `soup` equals the reference table's, byte
/// for byte (so signed zeros and NaN payloads too), and triangles and source faces agree. Returns
/// the number of sides compared.
template <class T> std::size_t expect_edge_normals_match(const PolygonSoup<T>& soup) {
  const TriangleMesh<T> m = make_triangle_mesh(soup).value();
  const ReferenceTriangles<T> ref = reference_edge_normals(soup);
  EXPECT_EQ(m.triangles, ref.triangles);
  if (m.triangles != ref.triangles) return 0;
  std::size_t bad = 0;
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    EXPECT_EQ(m.source_face(t), ref.source_face[t]) << "triangle " << t;
    for (int e = 0; e < 3; ++e) {
      const Vec3<T> got = m.edge_normal(t, e), want = ref.edge_normals[t][e];
      if (std::memcmp(&got, &want, sizeof(Vec3<T>)) != 0 && ++bad <= 10)
        ADD_FAILURE() << "triangle " << t << " side " << e << ": edge_normal " << got
                      << " but the table has " << want << " (link " << m.edge_links[t][e] << ")";
    }
  }
  EXPECT_EQ(bad, 0u) << "sides differing from the table";
  return 3 * m.triangle_count();
}

} // namespace ebgeom::test
