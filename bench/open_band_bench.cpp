// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Narrow bands on an open mesh: the band of a winding sign (`fast-winding`, what `auto` picks on
// an open mesh; far boxes of tiles signed by bounding the winding number, sdf/split_sign.hpp)
// against the same band with the pseudonormal sign, in one process, methods interleaved in every
// repetition, medians of wall and CPU times (CPU time is steadier on a shared machine; with
// --threads 1 it is the one to compare). Sparse output (`sample_grid_sparse`, what `ebgeom sdf -o
// OUT.npz --band` writes), float, the mesh's box grown by 10% of its largest extent per side,
// `--res` cells on the longest axis, a band of `--cells` cells.
//
//   cmake --preset bench && cmake --build --preset bench --target ebgeom_bench_open_band_bench
//   build/bench/bench/ebgeom_bench_open_band_bench [--mesh ../shared/meshes/stanford-bunny.obj]
//       [--res 256,512] [--reps 3] [--cells 3] [--threads 0] [--only fast-winding]
//
// Methods: `pseudonormal` (MeshSdf, the fastest pseudonormal band), `signed-pseudonormal`
// (SignedMeshSdf in pseudonormal mode) and `fast-winding` (SignedMeshSdf). `--only M` runs one
// method once per resolution (for peak-memory measurements with /usr/bin/time -v).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

using namespace ebgeom;
using T = float;

namespace {

struct Options {
  std::string mesh = "../shared/meshes/stanford-bunny.obj";
  std::vector<std::size_t> res{256, 512};
  int reps = 3;
  double cells = 3;
  int threads = 0;
  std::string only;
};

double cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct Run {
  double seconds = 0, cpu = 0;
  std::size_t kept = 0, tiles = 0, bytes = 0;
};

template <class S> Run run_band(const S& sdf, const GridSpec<T>& spec, const GridOptions& opt) {
  const auto t0 = std::chrono::steady_clock::now();
  const double c0 = cpu_seconds();
  auto g = sample_grid_sparse(sdf, spec, opt);
  Run r;
  r.cpu = cpu_seconds() - c0;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!g) {
    std::fprintf(stderr, "sample_grid_sparse: %s\n", g.error().what().c_str());
    std::exit(1);
  }
  r.kept = g->kept_tile_count();
  r.tiles = g->tiles[0] * g->tiles[1] * g->tiles[2];
  r.bytes = g->memory_bytes();
  return r;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

std::vector<std::size_t> parse_list(const char* s) {
  std::vector<std::size_t> out;
  for (const char* p = s; *p;) {
    out.push_back(std::size_t(std::strtoul(p, nullptr, 10)));
    p = std::strchr(p, ',');
    if (!p) break;
    ++p;
  }
  return out;
}

} // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--mesh")
      o.mesh = next();
    else if (a == "--res")
      o.res = parse_list(next());
    else if (a == "--reps")
      o.reps = std::max(1, std::atoi(next()));
    else if (a == "--cells")
      o.cells = std::atof(next());
    else if (a == "--threads")
      o.threads = std::atoi(next());
    else if (a == "--only")
      o.only = next();
    else {
      std::fprintf(stderr, "unknown option %s (see the file comment)\n", a.c_str());
      return 2;
    }
  }
  auto soup = io::read_mesh<T>(o.mesh);
  if (!soup) {
    std::fprintf(stderr, "%s\n", soup.error().what().c_str());
    return 1;
  }
  const auto mesh_sdf = MeshSdf<T>::build(*soup).value();
  SignOptions pn, fw;
  pn.mode = SignMode::pseudonormal;
  fw.mode = SignMode::automatic;
  const auto signed_pn = SignedMeshSdf<T>::build(*soup, pn).value();
  const auto signed_fw = SignedMeshSdf<T>::build(*soup, fw).value();
  std::printf("%s: %zu triangles; auto sign: %s (%s)\n", o.mesh.c_str(), mesh_sdf.triangle_count(),
              to_string(signed_fw.resolved_mode()), signed_fw.reason().c_str());

  const Aabb<T> b = mesh_sdf.bounds();
  const Aabb<T> box = b.grown(T(0.1) * max_component(b.extent()));
  for (std::size_t res : o.res) {
    const GridSpec<T> spec = GridSpec<T>::cells(box, res);
    GridOptions opt;
    opt.band = o.cells * double(max_component(spec.spacing()));
    opt.exec.threads = o.threads;
    std::printf("\ngrid %zux%zux%zu, band %.1f cells, %d thread(s) (0 = all), %d rep(s)\n",
                spec.dims[0], spec.dims[1], spec.dims[2], o.cells, o.threads, o.reps);
    const char* names[] = {"pseudonormal", "signed-pseudonormal", "fast-winding"};
    std::vector<double> t[3], c[3];
    Run last[3];
    for (int r = 0; r < (o.only.empty() ? o.reps : 1); ++r)
      for (int m = 0; m < 3; ++m) {
        if (!o.only.empty() && o.only != names[m]) continue;
        Run run = m == 0   ? run_band(mesh_sdf, spec, opt)
                  : m == 1 ? run_band(signed_pn, spec, opt)
                           : run_band(signed_fw, spec, opt);
        t[m].push_back(run.seconds);
        c[m].push_back(run.cpu);
        last[m] = run;
      }
    for (int m = 0; m < 3; ++m) {
      if (t[m].empty()) continue;
      std::printf("  %-20s median wall %8.3f s  cpu %8.3f s  kept %8zu of %9zu tiles  %8.1f MiB\n",
                  names[m], median(t[m]), median(c[m]), last[m].kept, last[m].tiles,
                  double(last[m].bytes) / (1024.0 * 1024.0));
    }
    if (!t[0].empty() && !t[1].empty() && !t[2].empty())
      std::printf("  fast-winding / pseudonormal (MeshSdf): wall %.2fx, cpu %.2fx;  / "
                  "signed-pseudonormal: wall %.2fx, cpu %.2fx\n",
                  median(t[2]) / median(t[0]), median(c[2]) / median(c[0]),
                  median(t[2]) / median(t[1]), median(c[2]) / median(c[1]));
  }
  return 0;
}
