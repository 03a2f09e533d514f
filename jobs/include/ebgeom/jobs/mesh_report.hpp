// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// The validation report of a mesh as JSON: the fields of `ebgeom info --json`, also returned by
// the Python package's `Mesh.info()`.
#include <nlohmann/json.hpp>

#include <cstddef>

#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/scene/mesh_input.hpp"

namespace ebgeom::jobs {

/// `r` as JSON (no "input": the caller adds it when there is a file); `triangles` is the mesh's
/// triangle count after fan triangulation.
inline nlohmann::json mesh_report_json(const ValidationReport<double>& r, std::size_t triangles) {
  nlohmann::json j;
  j["vertices"] = r.vertex_count;
  j["faces"] = r.face_count;
  j["triangles"] = triangles;
  j["edges"] = r.edge_count;
  j["boundary_edges"] = r.boundary_edges.count;
  j["holes"] = r.holes;
  j["non_manifold_edges"] = r.non_manifold_edges.count;
  j["non_manifold_vertices"] = r.non_manifold_vertices.count;
  j["inconsistent_edges"] = r.inconsistent_edges.count;
  j["degenerate_faces"] = r.degenerate_faces.count;
  j["duplicate_faces"] = r.duplicate_faces.count;
  j["isolated_vertices"] = r.isolated_vertices.count;
  j["bad_index_faces"] = r.bad_index_faces.count;
  j["short_faces"] = r.short_faces.count;
  j["non_finite_vertices"] = r.non_finite_vertices.count;
  j["watertight"] = r.boundary_edges.empty() && r.non_manifold_edges.empty();
  j["consistently_oriented"] = r.inconsistent_edges.empty();
  j["outward"] = r.signed_volume > 0;
  j["area"] = r.area;
  j["volume"] = r.signed_volume;
  const Aabb<double>& b = r.bounds;
  if (b.is_empty())
    j["bbox"] = nullptr;
  else
    j["bbox"] = {{"lo", {b.lo.x, b.lo.y, b.lo.z}}, {"hi", {b.hi.x, b.hi.y, b.hi.z}}};
  j["sdf_well_defined"] = r.sdf_well_defined;
  j["verdict"] = r.verdict;
  const SignChoice auto_sign = choose_sign_mode(r);
  j["auto_sign"] = {{"mode", scene::sign_name(auto_sign.mode)}, {"reason", auto_sign.reason}};
  return j;
}

} // namespace ebgeom::jobs
