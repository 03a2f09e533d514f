// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#include "cgal_peer.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

#include <cmath>
#include <vector>

namespace ebgeom_bench {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Side = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;
using Tree = Side::AABB_tree; // AABB_tree<AABB_traits<Epick, AABB_face_graph_triangle_primitive>>
} // namespace

struct CgalPeer::Impl {
  Mesh mesh;
  std::unique_ptr<Tree> tree;
  std::unique_ptr<Side> side;
  std::size_t failed = 0;
  bool closed = false;
};

CgalPeer::CgalPeer(const double* xyz, std::size_t nv, const std::uint32_t* tri, std::size_t nt)
    : impl_(std::make_unique<Impl>()) {
  Mesh& m = impl_->mesh;
  m.reserve(Mesh::size_type(nv), Mesh::size_type(3 * nt / 2), Mesh::size_type(nt));
  std::vector<Mesh::Vertex_index> v(nv);
  for (std::size_t i = 0; i < nv; ++i)
    v[i] = m.add_vertex(Point(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]));
  for (std::size_t t = 0; t < nt; ++t)
    if (m.add_face(v[tri[3 * t]], v[tri[3 * t + 1]], v[tri[3 * t + 2]]) == Mesh::null_face())
      ++impl_->failed;
  impl_->closed = CGAL::is_closed(m);
  impl_->tree = std::make_unique<Tree>(faces(m).first, faces(m).second, m);
  impl_->tree->build();
  impl_->tree->accelerate_distance_queries();
  impl_->side = std::make_unique<Side>(*impl_->tree);
}

CgalPeer::~CgalPeer() = default;

double CgalPeer::signed_distance(double x, double y, double z) const {
  const Point p(x, y, z);
  const auto cp = impl_->tree->closest_point_and_primitive(p);
  const double d = std::sqrt(CGAL::squared_distance(p, cp.first));
  return (*impl_->side)(p) == CGAL::ON_BOUNDED_SIDE ? -d : d;
}

std::size_t CgalPeer::failed_faces() const noexcept { return impl_->failed; }
bool CgalPeer::closed() const noexcept { return impl_->closed; }

} // namespace ebgeom_bench
