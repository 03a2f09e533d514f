// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom query INPUT --points P.npy -o D.npy`: signed distances (and optionally closest points
// and normals) at arbitrary points.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "commands.hpp"
#include "common.hpp"
#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/write_grid.hpp"
#include "ebgeom/jobs/number_options.hpp"
#include "ebgeom/scene/scene.hpp"
#include "grid_job.hpp"
#include "npy.hpp"
#include "progress.hpp"

namespace ebgeom::cli {

namespace {

struct QueryOptions {
  std::string input, points, output, closest, normals;
  std::string sign = "auto";
  int threads = 0;
  bool json = false, quiet = false;
};

void write_or_fail(const std::string& path, const std::vector<double>& v,
                   const std::vector<std::size_t>& shape) {
  auto ok = write_npy(path, Span<const double>(v), shape, DType::float64);
  if (!ok) fail(exit_output, ok.error().what());
}

int run_query(const QueryOptions& o) {
  const SignMode sign = parse_sign_mode(o.sign, exit_usage, "--sign");
  for (const std::string* out : {&o.output, &o.closest, &o.normals})
    if (!out->empty() && std::filesystem::path(*out).extension() != ".npy")
      fail(exit_usage, *out + ": query outputs are .npy files");
  require_input_file(o.input);
  require_input_file(o.points);
  for (const std::string* out : {&o.output, &o.closest, &o.normals})
    if (!out->empty()) require_output_target(*out);

  const double t0 = now_s();
  const bool scene = is_scene_path(o.input);
  SceneSdf<double> prog;
  SceneInfo info;
  double t1;
  if (scene) {
    const Json doc = read_json_file(o.input);
    t1 = now_s();
    prog = compile_scene<double>(doc, o.input, &info);
  } else {
    PolygonSoup<double> soup = load_mesh<double>(o.input);
    t1 = now_s();
    prog = mesh_scene(soup, o.input, sign);
  }
  const SignedMeshSdf<double>* mesh = prog.mesh(); // null for scenes
  const std::vector<Vec3<double>> pts = read_npy_points(o.points);
  const double t2 = now_s();
  const std::size_t n = pts.size();
  require_memory(
      std::uint64_t(n) * 8 *
          (1 + (o.closest.empty() ? 0 : 3) + (o.normals.empty() ? 0 : 3) + (scene ? 6 : 0)),
      std::to_string(n) + " query points");

  ExecOptions ex;
  ex.threads = o.threads;
  std::vector<double> d(n);
  {
    // In chunks, to show progress (each point's value does not depend on the chunking).
    Progress bar("querying", !o.quiet && !o.json && stderr_is_terminal());
    const std::size_t chunk = bar.enabled() ? std::max<std::size_t>(n / 100, 1 << 14) : n;
    for (std::size_t b = 0; b < n; b += chunk) {
      const std::size_t e = std::min(n, b + chunk);
      // A mesh file is evaluated through the mesh SDF itself (its batch queries).
      if (auto ok = prog.visit([&](const auto& sdf) {
            return evaluate(sdf, Span<const Vec3<double>>(pts.data() + b, e - b),
                            Span<double>(d.data() + b, e - b), ex);
          });
          !ok)
        fail(exit_failure, ok.error().what());
      bar.update(e, n);
    }
  }
  std::vector<double> cp, nm;
  const bool want_geo = !o.closest.empty() || !o.normals.empty();
  if (want_geo) {
    cp.resize(3 * n);
    nm.resize(3 * n);
    if (mesh) {
      parallel_for(
          0, n, 256,
          [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) {
              const auto c = mesh->closest(pts[i]);
              Vec3<double> dir = pts[i] - c.point;
              const double len = norm(dir);
              // The gradient of S: away from the surface when outside, into it when inside; on
              // the surface, the triangle's outward normal.
              dir = len > 1e-12 * (1 + norm(pts[i])) ? dir / len * (c.distance < 0 ? -1.0 : 1.0)
                                                     : mesh->mesh().face_normals[c.triangle];
              for (int a = 0; a < 3; ++a) {
                cp[3 * i + a] = c.point[a];
                nm[3 * i + a] = dir[a];
              }
            }
          },
          ex);
    } else {
      // Central differences of the scene's S; closest point p - S(p) grad S / |grad S|^2 ... for
      // exact SDFs |grad S| = 1, so p - S(p) n.
      const double hh = 1e-6 * std::max(1.0, [&] {
                          const Aabb<double> b = prog.bounds();
                          double m = 0;
                          for (int a = 0; a < 3; ++a)
                            if (std::isfinite(b.lo[a]) && std::isfinite(b.hi[a]))
                              m = std::max(m, b.hi[a] - b.lo[a]);
                          return m;
                        }());
      std::vector<Vec3<double>> probe(6 * n);
      for (std::size_t i = 0; i < n; ++i)
        for (int a = 0; a < 3; ++a) {
          probe[6 * i + 2 * a] = pts[i] + Vec3<double>::unit(a) * hh;
          probe[6 * i + 2 * a + 1] = pts[i] - Vec3<double>::unit(a) * hh;
        }
      std::vector<double> pv(6 * n);
      if (auto ok = evaluate(prog, Span<const Vec3<double>>(probe), Span<double>(pv), ex); !ok)
        fail(exit_failure, ok.error().what());
      for (std::size_t i = 0; i < n; ++i) {
        Vec3<double> g;
        for (int a = 0; a < 3; ++a) g[a] = (pv[6 * i + 2 * a] - pv[6 * i + 2 * a + 1]) / (2 * hh);
        const Vec3<double> nn = normalized(g);
        const Vec3<double> c = pts[i] - nn * d[i];
        for (int a = 0; a < 3; ++a) {
          cp[3 * i + a] = c[a];
          nm[3 * i + a] = nn[a];
        }
      }
    }
  }
  const double t3 = now_s();
  {
    OutputGroup outputs; // every output appears only once all are written
    write_or_fail(o.output, d, {n});
    if (!o.closest.empty()) write_or_fail(o.closest, cp, {n, 3});
    if (!o.normals.empty()) write_or_fail(o.normals, nm, {n, 3});
    if (auto ok = outputs.commit(); !ok) fail(exit_output, ok.error().what());
  }
  const double t4 = now_s();
  const GridStats st = grid_stats(Span<const double>(d));
  if (o.json) {
    Json j;
    j["input"] = o.input;
    j["input_kind"] = scene ? "scene" : "mesh";
    j["triangles"] = prog.triangle_count();
    j["points"] = n;
    j["output"] = o.output;
    j["timings"] = {
        {"parse_s", t1 - t0}, {"build_s", t2 - t1}, {"eval_s", t3 - t2}, {"write_s", t4 - t3}};
    j["min"] = n ? st.min : 0.0;
    j["max"] = n ? st.max : 0.0;
    j["inside_fraction"] = st.inside_fraction;
    j["sign"] = sign_name(sign);
    if (mesh)
      j["sign_used"] = {{"mode", sign_name(mesh->resolved_mode())}, {"reason", mesh->reason()}};
    if (scene) j["meshes"] = mesh_signs_json(info);
    j["threads"] = resolve_threads(ex);
    std::printf("%s\n", j.dump(2).c_str());
  } else if (!o.quiet) {
    std::printf("ebgeom query: %s at %zu points -> %s\n", o.input.c_str(), n, o.output.c_str());
    if (n)
      std::printf("  values    min %.6g  max %.6g  inside fraction %.4f\n", st.min, st.max,
                  st.inside_fraction);
    std::printf("  time      parse %.3f s  build %.3f s  eval %.3f s  write %.3f s\n", t1 - t0,
                t2 - t1, t3 - t2, t4 - t3);
  }
  return exit_ok;
}

} // namespace

Subcommand add_query(CLI::App& app) {
  auto o = std::make_shared<QueryOptions>();
  CLI::App* sub = app.add_subcommand(
      "query", "Signed distances (and closest points, normals) at points from an .npy file");
  sub->add_option("INPUT", o->input, "mesh file or scene file (.json)")->required();
  sub->add_option("--points", o->points, "(N, 3) float32 or float64 .npy of query points")
      ->required();
  sub->add_option("-o,--output", o->output, "signed distances: float64 .npy of shape (N,)")
      ->required();
  sub->add_option("--closest", o->closest, "closest surface points: float64 .npy (N, 3)");
  sub->add_option("--normals", o->normals,
                  "unit gradient of S (outward normal direction): float64 .npy (N, 3)");
  sub->add_option("--sign", o->sign,
                  "sign mode for meshes: pseudonormal, winding, fast-winding, unsigned or auto "
                  "(pseudonormal on closed manifold oriented meshes, fast-winding otherwise)")
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "threads (0 = all cores)")
      ->check(number_rule(NumberRule::non_negative, /*integer=*/true));
  sub->add_flag("--json", o->json, "print a JSON summary on stdout");
  sub->add_flag("-q,--quiet", o->quiet, "no progress bar and no summary");
  sub->footer(
      "Example:\n  python -c \"import numpy as np; np.save('p.npy', np.random.rand(1000, 3))\"\n"
      "  ebgeom query bunny.obj --points p.npy -o d.npy --closest c.npy --normals n.npy");
  return {sub, [o] { return run_query(*o); }};
}

} // namespace ebgeom::cli
