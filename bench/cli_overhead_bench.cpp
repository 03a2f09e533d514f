// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// What the command-line tools' evaluation paths cost over the library's own, on the same points
// and grid in one process (interleaved, median of the repetitions, one thread by default):
//
//   query  `ebgeom query MESH` (the scene component's mesh input, evaluated through
//          `SceneSdf::visit` as tools/ebgeom/query.cpp does) vs `evaluate` on the library's
//          `MeshSdf` / `SignedMeshSdf` built directly;
//   grid   `ebgeom sdf MESH` (the same input through `visit` into `sample_grid`, as
//          tools/ebgeom/sdf.cpp does) vs `sample_grid` on the library's mesh SDF, dense and with a
//          narrow band of 3 cells;
//   scene  a CSG scene of analytic shapes compiled from JSON (run-time nodes, batch evaluation)
//          vs the same shapes composed statically in C++ (everything inlined).
//
// Usage: ebgeom_bench_cli_overhead_bench MESH [POINTS=1000000] [RES=128] [REPS=5] [THREADS=1]
// [SIGN=auto]. Prints one line per comparison: the median seconds of each side and their ratio
// (tool / library; 1.00 = no overhead).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/scene/scene.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"
#include "ebgeom/sdf/transforms.hpp"

using namespace ebgeom;
using V = Vec3<double>;

namespace {

double seconds(const std::function<void()>& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// Runs `tool` and `lib` alternately `reps` times and prints the medians and their ratio.
void compare(const char* what, int reps, const std::function<void()>& tool,
             const std::function<void()>& lib) {
  std::vector<double> a, b;
  tool(); // warm caches and pages
  lib();
  for (int r = 0; r < reps; ++r) {
    a.push_back(seconds(tool));
    b.push_back(seconds(lib));
  }
  const double ma = median(a), mb = median(b);
  std::printf("%-34s tool %9.4f s   library %9.4f s   tool/library %.3f\n", what, ma, mb, ma / mb);
  std::fflush(stdout);
}

void check_equal(const char* what, const std::vector<double>& a, const std::vector<double>& b) {
  for (std::size_t i = 0; i < a.size(); ++i)
    if (!(a[i] == b[i]) && !(a[i] != a[i] && b[i] != b[i])) {
      std::fprintf(stderr, "%s: value %zu differs (%.17g vs %.17g)\n", what, i, a[i], b[i]);
      std::exit(1);
    }
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH [POINTS] [RES] [REPS] [THREADS] [SIGN]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const std::size_t npts = argc > 2 ? std::size_t(std::atol(argv[2])) : 1000000;
  const std::size_t res = argc > 3 ? std::size_t(std::atol(argv[3])) : 128;
  const int reps = std::max(3, argc > 4 ? std::atoi(argv[4]) : 5);
  ExecOptions ex;
  ex.threads = argc > 5 ? std::atoi(argv[5]) : 1;
  const std::string sign_name = argc > 6 ? argv[6] : "auto";
  auto sign = parse_sign_mode(sign_name);
  if (!sign) {
    std::fprintf(stderr, "%s\n", sign.error().what().c_str());
    return 2;
  }

  // The tools' input: the scene component's mesh loading and mesh SDF (ebgeom sdf / query).
  const PolygonSoup<double> soup = scene::load_mesh<double>(path);
  const scene::SceneSdf<double> tool = scene::mesh_scene(soup, path, *sign);
  // The library directly.
  SignOptions so;
  so.mode = *sign;
  auto lib = SignedMeshSdf<double>::build(soup, so);
  if (!lib) {
    std::fprintf(stderr, "%s\n", lib.error().what().c_str());
    return 1;
  }
  const bool pseudo = lib->resolved_mode() == SignMode::pseudonormal;
  std::printf("%s: %zu triangles, sign %s, %zu points, grid %zu^3, %d repetitions, %d thread(s)\n",
              path.c_str(), lib->triangle_count(), to_string(lib->resolved_mode()), npts, res, reps,
              resolve_threads(ex));

  // Uniform points in the box + 10%.
  const Aabb<double> box = lib->bounds();
  const V pad = box.extent() * 0.1;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<V> pts(npts);
  for (V& p : pts)
    for (int a = 0; a < 3; ++a) p[a] = box.lo[a] - pad[a] + u(rng) * (box.extent()[a] + 2 * pad[a]);
  std::vector<double> d_tool(npts), d_lib(npts);
  const Span<const V> ps(pts);

  auto lib_eval = [&](Span<double> out) {
    if (pseudo)
      (void)evaluate(lib->mesh_sdf(), ps, out, ex);
    else
      (void)evaluate(*lib, ps, out, ex);
  };
  compare(
      "query: visit vs mesh SDF", reps,
      [&] {
        (void)tool.visit([&](const auto& s) { return evaluate(s, ps, Span<double>(d_tool), ex); });
      },
      [&] { lib_eval(Span<double>(d_lib)); });
  check_equal("query", d_tool, d_lib);
  compare(
      "query: scene tree vs mesh SDF", reps,
      [&] { (void)evaluate(tool, ps, Span<double>(d_tool), ex); },
      [&] { lib_eval(Span<double>(d_lib)); });
  check_equal("query (scene tree)", d_tool, d_lib);

  // Grids: cell-centred res^3 over the box + 10%, dense and with a band of 3 cells.
  GridSpec<double> spec;
  spec.box = Aabb<double>(box.lo - pad, box.hi + pad);
  spec.dims = {{res, res, res}};
  std::vector<double> g_tool(spec.size()), g_lib(spec.size());
  for (double cells : {0.0, 3.0}) {
    GridOptions opt;
    opt.exec = ex;
    opt.band = cells * max_component(spec.spacing());
    auto lib_grid = [&] {
      if (pseudo)
        (void)sample_grid(lib->mesh_sdf(), spec, Span<double>(g_lib), opt);
      else
        (void)sample_grid(*lib, spec, Span<double>(g_lib), opt);
    };
    compare(
        cells > 0 ? "grid band 3: visit vs mesh SDF" : "grid dense: visit vs mesh SDF", reps,
        [&] {
          (void)tool.visit(
              [&](const auto& s) { return sample_grid(s, spec, Span<double>(g_tool), opt); });
        },
        lib_grid);
    check_equal("grid", g_tool, g_lib);
  }

  // A scene of analytic shapes: compiled nodes vs the static composition.
  const scene::SceneSdf<double> csg = scene::compile_scene<double>(
      scene::parse_json_text(R"({"type": "union", "smooth": 0.2, "children": [
        {"type": "difference", "children": [
          {"type": "box", "half_size": [1, 1, 1], "rounding": 0.1},
          {"type": "sphere", "radius": 1.2}]},
        {"type": "capsule", "a": [-1.5, 0, 0], "b": [1.5, 0, 0], "radius": 0.3,
         "rotate": {"axis": [0, 0, 1], "degrees": 30}, "translate": [0, 0.5, 0]}]})",
                             "bench.json"),
      "bench.json");
  const auto stat =
      smooth_unite(subtract(RoundedBox<double>{{1, 1, 1}, 0.1}, Sphere<double>{V::zero(), 1.2}),
                   transform(scale(Capsule<double>{{-1.5, 0, 0}, {1.5, 0, 0}, 0.3}, 1.0),
                             Mat3<double>::axis_degrees({0, 0, 1}, 30), V{0, 0.5, 0}),
                   0.2);
  std::vector<V> cp(npts);
  for (V& p : cp)
    for (int a = 0; a < 3; ++a) p[a] = -2 + 4 * u(rng);
  const Span<const V> cs(cp);
  compare(
      "scene CSG: nodes vs static C++", reps,
      [&] { (void)evaluate(csg, cs, Span<double>(d_tool), ex); },
      [&] { (void)evaluate(stat, cs, Span<double>(d_lib), ex); });
  check_equal("scene CSG", d_tool, d_lib);
  return 0;
}
