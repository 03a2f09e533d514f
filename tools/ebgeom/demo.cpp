// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// `ebgeom demo`: the built-in job needing no input file.
#include <cstdio>
#include <filesystem>
#include <string>

#include "commands.hpp"
#include "common.hpp"
#include "demo_scene.hpp"
#include "ebgeom/jobs/number_options.hpp"
#include "ebgeom/scene/scene.hpp"
#include "grid_job.hpp"

namespace ebgeom::cli {

namespace {

struct DemoOptions {
  std::string dir = "out/demo";
  std::size_t res = 96;
  int threads = 0;
  bool quiet = false;
};

int run_demo(const DemoOptions& o) {
  const double t0 = now_s();
  using T = float;
  SceneInfo info;
  const SceneSdf<T> scene = compile_scene<T>(Json::parse(demo_scene_json()), "<demo>", &info);
  const double t1 = now_s();
  const Aabb<T> b = scene.bounds();
  const T pad = T(0.1) * max_component(b.extent());
  GridSpec<T> spec = GridSpec<T>::cells(b.grown(pad), o.res);
  // Cubic cells: the longest axis gets `res` cells.
  const Vec3<T> e = spec.box.extent();
  const T h = max_component(e) / T(o.res);
  for (int a = 0; a < 3; ++a)
    spec.dims[a] = std::max<std::size_t>(1, std::size_t(std::ceil(e[a] / h - T(1e-4))));
  spec.box.hi =
      spec.box.lo + Vec3<T>{T(spec.dims[0]) * h, T(spec.dims[1]) * h, T(spec.dims[2]) * h};
  require_memory(std::uint64_t(spec.size()) * sizeof(T), "the demo grid");

  GridOptions gopt;
  gopt.exec.threads = o.threads;
  const auto values = sample_with_progress(scene, spec, gopt, !o.quiet && stderr_is_terminal());
  const double t2 = now_s();

  std::error_code ec;
  std::filesystem::create_directories(o.dir, ec);
  if (ec) fail(exit_output, o.dir + ": cannot create the output directory (" + ec.message() + ")");
  const std::string vti = o.dir + "/demo.vti", npy = o.dir + "/demo.npy", png = o.dir + "/demo.png";
  const Span<const T> v(values);
  OutputGroup outputs; // every output appears only once all are written
  write_grid_or_fail(vti, spec, v, DType::float32);
  write_grid_or_fail(npy, spec, v, DType::float32);
  const PngInfo img = write_png_slice(png, extract_slice(spec, v, SliceSpec{1, 0.5}));
  if (auto ok = outputs.commit(); !ok) fail(exit_output, ok.error().what());
  const double t3 = now_s();
  const GridStats st = grid_stats(v);

  std::printf("ebgeom demo: %s\n", demo_scene_description());
  std::printf("  scene     %zu nodes, %zu analytic primitives, %zu mesh (%zu triangles)\n",
              info.nodes, info.primitives, info.meshes, scene.triangle_count());
  std::printf("  grid      %zu x %zu x %zu cell-centred samples, spacing %.4g, box [%.3g %.3g "
              "%.3g] - [%.3g %.3g %.3g]\n",
              spec.nx(), spec.ny(), spec.nz(), double(h), double(spec.box.lo.x),
              double(spec.box.lo.y), double(spec.box.lo.z), double(spec.box.hi.x),
              double(spec.box.hi.y), double(spec.box.hi.z));
  std::printf("  values    min %.4f  max %.4f  inside fraction %.4f\n", st.min, st.max,
              st.inside_fraction);
  std::printf("  time      build %.3f s  eval %.3f s  write %.3f s  (%d threads)\n", t1 - t0,
              t2 - t1, t3 - t2, resolve_threads(gopt.exec));
  std::printf("  wrote     %s (ParaView)\n            %s (NumPy, shape (%zu, %zu, %zu), float32)\n"
              "            %s (%d x %d slice y = middle)\n",
              vti.c_str(), npy.c_str(), spec.nz(), spec.ny(), spec.nx(), png.c_str(), img.width,
              img.height);
  return exit_ok;
}

} // namespace

Subcommand add_demo(CLI::App& app) {
  auto o = std::make_shared<DemoOptions>();
  CLI::App* sub = app.add_subcommand(
      "demo", "Run the built-in job: a scene of analytic shapes, CSG and a generated mesh, "
              "sampled on a grid; writes DIR/demo.vti, DIR/demo.npy and DIR/demo.png");
  sub->add_option("-o,--output", o->dir, "output directory (created if missing)")
      ->capture_default_str();
  sub->add_option("--res", o->res, "cells along the longest axis")
      ->check(CLI::Range(std::size_t(4), std::size_t(1024)))
      ->capture_default_str();
  sub->add_option("--threads", o->threads, "threads (0 = all cores)")
      ->check(number_rule(NumberRule::non_negative, /*integer=*/true));
  sub->add_flag("-q,--quiet", o->quiet, "no progress bar");
  sub->footer("Example:\n  ebgeom demo -o out/demo && paraview out/demo/demo.vti");
  return {sub, [o] { return run_demo(*o); }};
}

} // namespace ebgeom::cli
