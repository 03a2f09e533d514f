// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// CGAL peer for bench/mesh_sdf_bench.cpp, compiled in its own translation unit: CGAL::CGAL adds
// -frounding-math (and CGAL's headers are heavy), which must not reach the code of the other
// methods. One out-of-line call per query is negligible next to a CGAL query.

#include <cstddef>
#include <cstdint>
#include <memory>

namespace ebgeom_bench {

/// Signed distance with CGAL 5: an `AABB_tree` of `AABB_face_graph_triangle_primitive` over a
/// `Surface_mesh<Epick::Point_3>` (double), `accelerate_distance_queries()` (the KD-tree of
/// hints), `closest_point_and_primitive` for the distance and `Side_of_triangle_mesh` (ray
/// parity, sharing the same tree) for the sign. Queries are const and thread-safe.
class CgalPeer {
 public:
  /// `xyz`: 3 `nv` coordinates; `tri`: 3 `nt` vertex indices (CCW from outside).
  CgalPeer(const double* xyz, std::size_t nv, const std::uint32_t* tri, std::size_t nt);
  ~CgalPeer();
  CgalPeer(const CgalPeer&) = delete;
  CgalPeer& operator=(const CgalPeer&) = delete;

  /// Distance to the closest point, negative when `Side_of_triangle_mesh` says bounded side.
  double signed_distance(double x, double y, double z) const;
  /// Faces `Surface_mesh::add_face` refused (non-manifold or inconsistently oriented input).
  std::size_t failed_faces() const noexcept;
  /// Whether `CGAL::is_closed` holds (Side_of_triangle_mesh's precondition).
  bool closed() const noexcept;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

} // namespace ebgeom_bench
