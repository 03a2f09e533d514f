// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom info MESH [--json]`: counts, bounding box and the validation report of a mesh.
#include "commands.hpp"

#include <cstdio>
#include <filesystem>
#include <string>

#include "common.hpp"
#include "ebgeom/jobs/mesh_report.hpp"
#include "ebgeom/mesh/validate.hpp"
#include "ebgeom/scene/mesh_input.hpp"
#include "ebgeom/scene/scene.hpp"

namespace ebgeom::cli {

namespace {

struct InfoOptions {
  std::string input;
  bool json = false;
};

int run_info(const InfoOptions& o) {
  require_input_file(o.input);
  const PolygonSoup<double> soup = load_mesh<double>(o.input);
  const ValidationReport<double> r = validate(soup);
  const bool watertight = r.boundary_edges.empty() && r.non_manifold_edges.empty();
  const bool oriented = r.inconsistent_edges.empty();
  const Aabb<double>& b = r.bounds;
  const SignChoice auto_sign = choose_sign_mode(r);
  if (o.json) {
    Json j;
    j["input"] = o.input;
    j.update(mesh_report_json(r, soup.triangle_count()));
    std::printf("%s\n", j.dump(2).c_str());
    return exit_ok;
  }
  std::printf("%s\n", o.input.c_str());
  std::printf("  vertices %zu, faces %zu, triangles %zu, edges %zu\n", r.vertex_count, r.face_count,
              soup.triangle_count(), r.edge_count);
  if (!b.is_empty())
    std::printf("  bbox     [%.6g %.6g %.6g] - [%.6g %.6g %.6g]\n", b.lo.x, b.lo.y, b.lo.z, b.hi.x,
                b.hi.y, b.hi.z);
  std::printf("  area     %.6g   volume %.6g\n", r.area, r.signed_volume);
  std::printf("  watertight %s (boundary edges %zu in %zu holes, non-manifold edges %zu, "
              "vertices %zu)\n",
              watertight ? "yes" : "no", r.boundary_edges.count, r.holes,
              r.non_manifold_edges.count, r.non_manifold_vertices.count);
  std::printf("  consistently oriented %s (inconsistent edges %zu), %s\n", oriented ? "yes" : "no",
              r.inconsistent_edges.count, r.signed_volume > 0 ? "outward" : "inward or open");
  std::printf("  degenerate faces %zu, duplicate faces %zu, isolated vertices %zu\n",
              r.degenerate_faces.count, r.duplicate_faces.count, r.isolated_vertices.count);
  std::printf("  %s\n", r.verdict.c_str());
  std::printf("  --sign auto would use %s: %s\n", sign_name(auto_sign.mode),
              auto_sign.reason.c_str());
  return exit_ok;
}

} // namespace

Subcommand add_info(CLI::App& app) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* sub = app.add_subcommand(
      "info", "Mesh counts, bounding box and validation report (is the SDF well defined?)");
  sub->add_option("MESH", o->input, "mesh file (STL, PLY, OBJ, OFF, VTK)")->required();
  sub->add_flag("--json", o->json, "print the report as one JSON object");
  sub->footer("Example:\n  ebgeom info bunny.obj --json");
  return {sub, [o] { return run_info(*o); }};
}

} // namespace ebgeom::cli
