// ebgeom command-line tool: entry point and subcommand dispatch.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cstdio>
#include <vector>

#include "ebgeom/ebgeom.hpp"

namespace {

// Interim built-in scene until the analytic-shape module lands: a sphere minus a box, evaluated
// exactly as max(sphere, -box).
struct DemoScene {
  using scalar_type = double;
  static constexpr ebgeom::SdfKind kind = ebgeom::SdfKind::bound;
  double operator()(const ebgeom::Vec3<double>& p) const noexcept {
    const double sphere = ebgeom::norm(p) - 1.0;
    const ebgeom::Vec3<double> q =
        ebgeom::abs(p - ebgeom::Vec3<double>{0.6, 0.6, 0.6}) - ebgeom::Vec3<double>::constant(0.5);
    const double box = ebgeom::norm(ebgeom::max(q, ebgeom::Vec3<double>::zero())) +
                       std::min(ebgeom::max_component(q), 0.0);
    return std::max(sphere, -box);
  }
  ebgeom::Aabb<double> bounds() const noexcept {
    return ebgeom::Aabb<double>::of({-1, -1, -1}, {1, 1, 1});
  }
};

int run_demo(int res) {
  const DemoScene scene;
  const auto box = scene.bounds().grown(0.2);
  const auto h = box.extent() / double(res);
  std::vector<double> values(std::size_t(res) * res * res);
  const auto t0 = std::chrono::steady_clock::now();
  ebgeom::parallel_for(0, std::size_t(res), 1, [&](std::size_t b, std::size_t e) {
    for (std::size_t k = b; k < e; ++k)
      for (int j = 0; j < res; ++j)
        for (int i = 0; i < res; ++i) {
          const ebgeom::Vec3<double> p{box.lo.x + (i + 0.5) * h.x, box.lo.y + (j + 0.5) * h.y,
                                       box.lo.z + (k + 0.5) * h.z};
          values[(k * res + j) * res + i] = scene(p);
        }
  });
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  double lo = values[0], hi = values[0];
  std::size_t inside = 0;
  for (double v : values) {
    lo = std::min(lo, v);
    hi = std::max(hi, v);
    inside += v < 0;
  }
  std::printf("ebgeom demo: sphere minus box on a %d^3 grid\n", res);
  std::printf("  min %.6f  max %.6f  inside fraction %.4f  eval %.3f s\n", lo, hi,
              double(inside) / values.size(), secs);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  CLI::App app{"ebgeom: fast exact signed distance fields"};
  app.require_subcommand(1);
  int res = 64;
  auto* demo =
      app.add_subcommand("demo", "Evaluate the built-in scene on a grid and print a summary");
  demo->add_option("--res", res, "cells per axis")->check(CLI::Range(1, 1024));
  CLI11_PARSE(app, argc, argv);
  if (*demo) return run_demo(res);
  return 0;
}
