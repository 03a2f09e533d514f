// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Grid sampling benchmark (issue 5): dense exact grids (tile evaluation, the default, against
// independent per-point searches, and Embree 3's per-point closest query
// on the same samples when built with EBGEOM_BENCH_HAVE_EMBREE), the
// octree narrow band (dense and sparse output) against ebgeom's dense grid and OpenVDB's
// meshToVolume (when built with EBGEOM_BENCH_HAVE_OPENVDB), thread scaling, and the memory of a
// sparse narrow band. Every figure is the median of --reps runs (wall clock, steady_clock).
//
// Usage: ebgeom_bench_grid_bench [--mesh PATH] [--reps N] [--dense N] [--band N] [--sparse N]
//                                [--cells C] [--threads T] [--only dense|band|sparse]
//                                [--no-embree] [--check N]
// Defaults: ../shared/meshes/ogre.obj, 5 reps, dense 256^3, band 512^3, sparse 1024^3, 3 cells,
// 2 threads. Box: the mesh's bounding box grown by 10% of its extent per side. float throughout.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

#if defined(EBGEOM_BENCH_HAVE_EMBREE)
#include "peers/embree_peer.hpp"
#endif
#if defined(EBGEOM_BENCH_HAVE_OPENVDB)
#include <openvdb/openvdb.h>
#include <openvdb/tools/MeshToVolume.h>
#include <tbb/global_control.h>
#endif

using namespace ebgeom;
using T = float;

namespace {

struct Options {
  std::string mesh = "../shared/meshes/ogre.obj";
  int reps = 5;
  std::size_t dense = 256, band = 512, sparse = 1024;
  double cells = 3;
  int threads = 2;
  std::string only;
  bool embree = true;
  std::size_t check = 200000; ///< samples (evenly strided) checked against Embree
};

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Median wall time of `reps` runs of `fn`.
double median_time(int reps, const std::function<void()>& fn) {
  std::vector<double> t;
  for (int r = 0; r < reps; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    fn();
    t.push_back(seconds_since(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// Thread scaling measured in interleaved pairs (1 thread, then T threads, `reps` times): the
// median of the per-pair ratios, which drifts of a shared or turbo-clocked machine affect less
// than a ratio of two medians taken minutes apart.
double paired_scaling(int reps, const std::function<void(int)>& fn, int threads) {
  std::vector<double> r;
  for (int i = 0; i < reps; ++i) {
    auto t0 = std::chrono::steady_clock::now();
    fn(1);
    const double one = seconds_since(t0);
    t0 = std::chrono::steady_clock::now();
    fn(threads);
    r.push_back(one / seconds_since(t0));
  }
  std::sort(r.begin(), r.end());
  std::printf("  %d threads vs 1, paired (interleaved) runs: median %.2fx (runs:", threads,
              r[r.size() / 2]);
  for (double x : r) std::printf(" %.2f", x);
  std::printf(")\n");
  return r[r.size() / 2];
}

GridSpec<T> grid_over(const Aabb<T>& bounds, std::size_t n) {
  const Vec3<T> e = bounds.extent();
  Aabb<T> box = bounds;
  box.lo = box.lo - e * T(0.1);
  box.hi = box.hi + e * T(0.1);
  // Cubic cells: n cells on the longest axis, the others rounded up to whole cells.
  const T h = std::max({box.extent().x, box.extent().y, box.extent().z}) / T(n);
  GridSpec<T> g;
  for (int a = 0; a < 3; ++a) {
    g.dims[a] = std::size_t(std::ceil(box.extent()[a] / h));
    box.hi[a] = box.lo[a] + h * T(g.dims[a]);
  }
  g.box = box;
  return g;
}

void print_row(const char* what, std::size_t n, int threads, double s, const char* note = "") {
  std::printf("%-44s %5zu^3 %2d thr  %10.3f s  %s\n", what, n, threads, s, note);
  std::fflush(stdout);
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
    else if (a == "--reps")
      o.reps = std::atoi(next());
    else if (a == "--dense")
      o.dense = std::size_t(std::atol(next()));
    else if (a == "--band")
      o.band = std::size_t(std::atol(next()));
    else if (a == "--sparse")
      o.sparse = std::size_t(std::atol(next()));
    else if (a == "--cells")
      o.cells = std::atof(next());
    else if (a == "--threads")
      o.threads = std::atoi(next());
    else if (a == "--only")
      o.only = next();
    else if (a == "--no-embree")
      o.embree = false;
    else if (a == "--check")
      o.check = std::size_t(std::atol(next()));
    else {
      std::fprintf(stderr, "unknown option %s (see the file comment)\n", a.c_str());
      return 2;
    }
  }
  auto soup = io::read_mesh<T>(o.mesh);
  if (!soup) {
    std::fprintf(stderr, "cannot read %s: %s\n", o.mesh.c_str(), soup.error().message.c_str());
    return 1;
  }
  auto sdf_r = MeshSdf<T>::build(*soup);
  if (!sdf_r) {
    std::fprintf(stderr, "cannot build the SDF: %s\n", sdf_r.error().message.c_str());
    return 1;
  }
  const MeshSdf<T>& sdf = *sdf_r;
  std::printf("mesh %s: %zu triangles; medians of %d runs\n", o.mesh.c_str(), sdf.triangle_count(),
              o.reps);
  auto want = [&](const char* part) { return o.only.empty() || o.only == part; };

  if (want("dense")) {
    const GridSpec<T> g = grid_over(sdf.bounds(), o.dense);
    std::vector<T> a(g.size()), b(g.size());
    std::printf("dense grid %zux%zux%zu = %zu samples\n", g.nx(), g.ny(), g.nz(), g.size());
    GridOptions opt;
    opt.exec.threads = 1;
    opt.search = GridSearch::tile; // the default
    const double tile = median_time(o.reps, [&] { (void)sample_grid(sdf, g, Span<T>(a), opt); });
    print_row("dense exact, tile evaluation (default)", o.dense, 1, tile);
    opt.search = GridSearch::independent;
    const double ind = median_time(o.reps, [&] { (void)sample_grid(sdf, g, Span<T>(b), opt); });
    print_row("dense exact, independent per-point", o.dense, 1, ind);
    const auto per = [&](double s) { return 1e9 * s / double(g.size()); };
    std::printf("  tile vs independent %.2fx; %.1f ns/sample tile, %.1f independent; %s\n",
                ind / tile, per(tile), per(ind), a == b ? "identical values" : "VALUES DIFFER");
    double best = std::min(tile, ind);
#if defined(EBGEOM_BENCH_HAVE_EMBREE)
    if (o.embree) {
      // Embree 3 per grid point: the same samples (GridSpec::point), one thread, x fastest.
      RTCDevice device = rtcNewDevice(nullptr);
      {
        const ebgeom_bench::EmbreePeer<T> peer(device, sdf.mesh());
        std::vector<T> e(g.size());
        const double emb = median_time(o.reps, [&] {
          for (std::size_t k = 0; k < g.nz(); ++k)
            for (std::size_t j = 0; j < g.ny(); ++j)
              for (std::size_t i = 0; i < g.nx(); ++i) e[g.index(i, j, k)] = peer(g.point(i, j, k));
        });
        print_row("Embree 3 rtcPointQuery per grid point", o.dense, 1, emb);
        // Agreement on evenly strided samples: |d| within 1e-5 relative + 16 ulps of the box.
        const std::size_t stride =
            std::max<std::size_t>(1, g.size() / std::max<std::size_t>(1, o.check));
        const T scale =
            std::max({std::abs(g.box.lo.x), std::abs(g.box.lo.y), std::abs(g.box.lo.z),
                      std::abs(g.box.hi.x), std::abs(g.box.hi.y), std::abs(g.box.hi.z)});
        std::size_t n = 0, off = 0, sign = 0;
        for (std::size_t s = 0; s < g.size(); s += stride, ++n) {
          const T tol =
              T(1e-5) * std::abs(a[s]) + T(16) * std::numeric_limits<T>::epsilon() * scale;
          off += !(std::abs(std::abs(e[s]) - std::abs(a[s])) <= tol);
          sign += std::signbit(e[s]) != std::signbit(a[s]);
        }
        std::printf("  Embree agreement on %zu samples: %zu distances out of tolerance, %zu sign "
                    "differences\n",
                    n, off, sign);
        std::printf("  ebgeom dense (tile) vs Embree per point: %.2fx; %.1f ns/sample Embree\n",
                    emb / tile, per(emb));
        std::printf("  ebgeom dense (independent) vs Embree per point: %.2fx\n", emb / ind);
      }
      rtcReleaseDevice(device);
    }
#else
    std::printf("  Embree peer not built (sh bench/install-peers.sh, re-run CMake)\n");
#endif
    opt.exec.threads = o.threads;
    opt.search = GridSearch::tile; // the default
    const double tile2 = median_time(o.reps, [&] { (void)sample_grid(sdf, g, Span<T>(b), opt); });
    print_row("dense exact, tile evaluation (default)", o.dense, o.threads, tile2);
    std::printf("  %d threads vs 1: %.2fx; %s\n", o.threads, tile / tile2,
                a == b ? "identical values" : "VALUES DIFFER");
    paired_scaling(
        o.reps,
        [&](int t) {
          opt.exec.threads = t;
          (void)sample_grid(sdf, g, Span<T>(b), opt);
        },
        o.threads);
    const double n3 = double(o.band) / double(o.dense);
    std::printf("  extrapolated dense %zu^3 (x%.0f): %.1f s (1 thread)\n", o.band, n3 * n3 * n3,
                best * n3 * n3 * n3);
  }

  if (want("band")) {
    const GridSpec<T> g = grid_over(sdf.bounds(), o.band);
    const double h = double(g.spacing().x);
    GridOptions opt;
    opt.band = o.cells * h;
    std::printf("band grid %zux%zux%zu, band %.2f cells = %.5g\n", g.nx(), g.ny(), g.nz(), o.cells,
                opt.band);
    std::size_t kept = 0;
    for (int threads : {1, o.threads}) {
      opt.exec.threads = threads;
      const double sp = median_time(o.reps, [&] {
        auto r = sample_grid_sparse(sdf, g, opt);
        kept = r ? r->kept_tile_count() : 0;
      });
      print_row("narrow band, sparse output (kept 8^3 tiles)", o.band, threads, sp);
      std::vector<T> out(g.size());
      const double dn = median_time(o.reps, [&] { (void)sample_grid(sdf, g, Span<T>(out), opt); });
      print_row("narrow band, dense output", o.band, threads, dn);
    }
    paired_scaling(
        o.reps,
        [&](int t) {
          opt.exec.threads = t;
          (void)sample_grid_sparse(sdf, g, opt);
        },
        o.threads);
    std::printf("  kept tiles: %zu of %zu\n", kept,
                ((g.nx() + 7) / 8) * ((g.ny() + 7) / 8) * ((g.nz() + 7) / 8));
#if defined(EBGEOM_BENCH_HAVE_OPENVDB)
    openvdb::initialize();
    std::vector<openvdb::Vec3s> pts;
    std::vector<openvdb::Vec3I> tris;
    const auto& m = sdf.mesh();
    for (const auto& v : m.vertices) pts.emplace_back(v.x, v.y, v.z);
    for (const auto& t : m.triangles) tris.emplace_back(t[0], t[1], t[2]);
    const auto xform = openvdb::math::Transform::createLinearTransform(h);
    for (int threads : {1, o.threads}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, std::size_t(threads));
      std::size_t voxels = 0;
      const double vdb = median_time(o.reps, [&] {
        auto grid = openvdb::tools::meshToSignedDistanceField<openvdb::FloatGrid>(
            *xform, pts, tris, std::vector<openvdb::Vec4I>(), float(o.cells), float(o.cells));
        voxels = grid->activeVoxelCount();
      });
      print_row("OpenVDB meshToSignedDistanceField", o.band, threads, vdb);
      std::printf("  OpenVDB active voxels: %zu\n", voxels);
    }
#else
    std::printf("  OpenVDB peer not built (sh bench/install-openvdb.sh, re-run CMake)\n");
#endif
  }

  if (want("sparse")) {
    const GridSpec<T> g = grid_over(sdf.bounds(), o.sparse);
    GridOptions opt;
    opt.band = o.cells * double(g.spacing().x);
    opt.exec.threads = o.threads;
    std::size_t bytes = 0, kept = 0;
    const double t = median_time(std::max(1, o.reps / 2), [&] {
      auto r = sample_grid_sparse(sdf, g, opt);
      bytes = r ? r->memory_bytes() : 0;
      kept = r ? r->kept_tile_count() : 0;
    });
    print_row("narrow band, sparse output", o.sparse, o.threads, t);
    std::printf("  grid %zux%zux%zu: %zu kept tiles, %.1f MiB (a dense float array: %.1f MiB)\n",
                g.nx(), g.ny(), g.nz(), kept, double(bytes) / 1048576.0,
                double(g.size()) * sizeof(T) / 1048576.0);
  }
  return 0;
}
