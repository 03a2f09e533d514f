// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// BVH internals (issue #4): build throughput of each builder, memory per triangle, and the
// traversal variants EBGeometry lists (ordered + farthest-box shrink, ordered, unordered,
// recursive), all on the same mesh and points in one process. A plain driver.
//
//   cmake --preset bench && cmake --build --preset bench --target ebgeom_bench_bvh_bench
//   build/bench/bench/ebgeom_bench_bvh_bench [MESH | --generate N] [--points N=200000] [--reps R=5]
//       [--builds-only] [--callgrind build|query]
//
// Without a mesh, a closed torus of about 2,000,000 triangles is generated. Float throughout.
// Times are medians of R runs; ratios are taken per run, then the median. Every builder row also
// gives the SAH cost of its K = 4 tree (see `sah_cost`), a measure of query quality.
// `--builds-only` prints the builder table alone. `--callgrind build|query` runs one `MeshSdf`
// default build (builder tree and flatten), or `--points` unsigned-distance queries on a fixed
// point set, with callgrind collecting only that part:
//   valgrind --tool=callgrind --collect-atstart=no ebgeom_bench_bvh_bench MESH --callgrind query
// (build with -march=x86-64-v3 or lower: valgrind cannot run AVX-512).

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/bvh/build.hpp"
#include "ebgeom/bvh/experimental/nearest_variants.hpp"
#include "ebgeom/bvh/traverse.hpp"
#include "ebgeom/bvh/wide_bvh.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

#if __has_include(<valgrind/callgrind.h>)
#include <valgrind/callgrind.h>
#else
#define CALLGRIND_TOGGLE_COLLECT
#endif

using namespace ebgeom;
using T = float;

namespace {
template <class F> double seconds(F&& f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}
double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
const char* name(bvh::BuildMethod m) {
  return m == bvh::BuildMethod::sah_binned ? "sah"
                                           : (m == bvh::BuildMethod::median ? "median" : "morton");
}
/// SAH cost of a K-wide tree, relative to its root box: the sum over nodes of their box's area
/// (one visit tests K child boxes) plus, over leaves, the leaf box's area times the number of
/// blocks of `block` primitives it holds (one block kernel each). Lower is better; it predicts
/// the cost of a query that lands uniformly in the root box.
template <int K> double sah_cost(const bvh::WideBvh<T, K>& w, std::uint32_t block) {
  const double root = w.box.half_area();
  if (!(root > 0) || w.nodes.empty()) return 0;
  double c = 1; // the root node
  for (const auto& n : w.nodes)
    for (int k = 0; k < K; ++k) {
      const double a = n.child_box(k).half_area() / root;
      if (n.child[k].is_inner())
        c += a;
      else if (n.child[k].is_leaf())
        c += a * double((n.child[k].count + block - 1) / block);
    }
  return c;
}
} // namespace

int main(int argc, char** argv) {
  std::string mesh_path;
  long generate = 2000000, npoints = 200000;
  int reps = 5;
  bool builds_only = false;
  std::string callgrind;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--generate" && i + 1 < argc)
      generate = std::atol(argv[++i]), mesh_path.clear();
    else if (a == "--points" && i + 1 < argc)
      npoints = std::atol(argv[++i]);
    else if (a == "--reps" && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (a == "--builds-only")
      builds_only = true;
    else if (a == "--callgrind" && i + 1 < argc)
      callgrind = argv[++i];
    else if (!a.empty() && a[0] != '-')
      mesh_path = a;
    else {
      std::fprintf(stderr,
                   "usage: %s [MESH | --generate N] [--points N] [--reps R] [--builds-only] "
                   "[--callgrind build|query]\n",
                   argv[0]);
      return 2;
    }
  }
  PolygonSoup<T> soup;
  if (!mesh_path.empty()) {
    auto r = io::read_mesh<T>(mesh_path);
    if (!r) {
      std::fprintf(stderr, "%s\n", r.error().what().c_str());
      return 1;
    }
    soup = std::move(*r);
  } else {
    const int seg = std::max(3, int(std::sqrt(double(generate) / 2)));
    soup = make_torus<T>(T(1), T(0.3), seg, seg).value();
  }
  const TriangleMesh<T> mesh = make_triangle_mesh(soup).value();
  const std::size_t n = mesh.triangle_count();
  std::printf("input: %s, %zu triangles; medians of %d runs\n",
              mesh_path.empty() ? "generated torus" : mesh_path.c_str(), n, reps);

  std::vector<Aabb<T>> boxes(n);
  std::vector<Vec3<T>> cent(n);
  for (std::size_t t = 0; t < n; ++t)
    boxes[t] = mesh.triangle_bounds(t), cent[t] = boxes[t].center();
  const Span<const Aabb<T>> B(boxes);
  const Span<const Vec3<T>> C(cent);

  // Fixed query points: uniform in the mesh box grown by 10% of its largest extent.
  Aabb<T> box = mesh.bounds();
  box = box.grown(T(0.1) * max_component(box.extent()));
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<T> u(0, 1);
  std::vector<Vec3<T>> pts(static_cast<std::size_t>(npoints));
  for (auto& p : pts)
    p = {box.lo.x + u(rng) * (box.hi.x - box.lo.x), box.lo.y + u(rng) * (box.hi.y - box.lo.y),
         box.lo.z + u(rng) * (box.hi.z - box.lo.z)};

  if (callgrind == "build") {
    const auto o = MeshSdf<T>::default_build_options();
    CALLGRIND_TOGGLE_COLLECT;
    const bvh::BuildTree<T> tree = bvh::build(B, C, o);
    const bvh::WideBvh<T, 4> w = bvh::flatten<4>(tree);
    CALLGRIND_TOGGLE_COLLECT;
    std::printf("default MeshSdf build: %zu builder nodes, %zu wide nodes, SAH cost %.4f\n",
                tree.nodes.size(), w.nodes.size(), sah_cost(w, o.block));
    return 0;
  }
  if (callgrind == "query") {
    const auto sdf = MeshSdf<T>::make(mesh).value();
    double sum = 0;
    CALLGRIND_TOGGLE_COLLECT;
    for (const auto& p : pts) sum += double(sdf.unsigned_distance(p));
    CALLGRIND_TOGGLE_COLLECT;
    std::printf("%zu queries, sum of distances %.9g, SAH cost %.4f\n", pts.size(), sum,
                sah_cost(sdf.tree(), std::uint32_t(MeshSdf<T>::block_width)));
    return 0;
  }

  std::printf("\n%-8s %-6s %10s %10s %12s %10s %10s\n", "builder", "leaf", "tree ms", "Mtri/s",
              "flatten ms", "depth", "SAH cost");
  for (auto m :
       {bvh::BuildMethod::sah_binned, bvh::BuildMethod::median, bvh::BuildMethod::morton}) {
    for (std::uint32_t leaf : {4u, 8u}) {
      bvh::BuildOptions o;
      o.method = m;
      o.max_leaf_size = leaf;
      o.block = m == bvh::BuildMethod::sah_binned ? leaf : 1;
      std::vector<double> tb, tf;
      int depth = 0;
      double cost = 0;
      for (int r = 0; r < reps; ++r) {
        bvh::BuildTree<T> tree;
        tb.push_back(seconds([&] { tree = bvh::build(B, C, o); }));
        bvh::WideBvh<T, 4> w;
        tf.push_back(seconds([&] { w = bvh::flatten<4>(tree); }));
        depth = w.depth;
        cost = sah_cost(w, leaf);
      }
      std::printf("%-8s %-6u %10.1f %10.2f %12.1f %10d %10.3f\n", name(m), leaf, median(tb) * 1e3,
                  double(n) / median(tb) / 1e6, median(tf) * 1e3, depth, cost);
    }
  }
  if (builds_only) return 0;

  // Memory and full MeshSdf build per configuration.
  std::printf("\n%-22s %12s %10s %12s\n", "MeshSdf<float, K, W>", "build ms", "B/tri",
              "of which mesh");
  auto report = [&](const char* label, auto tag) {
    using S = typename decltype(tag)::type;
    std::vector<double> t;
    std::size_t mem = 0;
    for (int r = 0; r < reps; ++r)
      t.push_back(seconds([&] { mem = S::make(mesh).value().memory_bytes(); }));
    std::printf("%-22s %12.1f %10.1f %12.1f\n", label, median(t) * 1e3, double(mem) / double(n),
                double(mesh.memory_bytes()) / double(n));
  };
  struct K4W8 {
    using type = MeshSdf<T, 4, 8>;
  };
  struct K8W8 {
    using type = MeshSdf<T, 8, 8>;
  };
  struct K4W4 {
    using type = MeshSdf<T, 4, 4>;
  };
  report("K=4, W=8 (default)", K4W8{});
  report("K=8, W=8", K8W8{});
  report("K=4, W=4", K4W4{});

  // Traversal variants on a point-to-triangle nearest search over the same tree (scalar kernel).
  const auto w = bvh::flatten<4>(bvh::build(B, C));
  auto leaf_fn = [&](const Vec3<T>& p) {
    return [&mesh, &w, p](std::uint32_t first, std::uint32_t count, T& b2) {
      for (std::uint32_t s = first; s < first + count; ++s) {
        const std::uint32_t t = w.prim[s];
        b2 = std::min(
            b2, closest_point_triangle(p, mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2))
                    .distance2);
      }
    };
  };
  std::vector<T> ref(pts.size()), got(pts.size());
  auto run = [&](const char* label, auto search, bool check = true) {
    std::vector<double> t;
    for (int r = 0; r < reps; ++r)
      t.push_back(seconds([&] {
        for (std::size_t i = 0; i < pts.size(); ++i) {
          T b2 = std::numeric_limits<T>::infinity();
          search(pts[i], b2);
          got[i] = b2;
        }
      }));
    const bool same = !check || std::memcmp(got.data(), ref.data(), got.size() * sizeof(T)) == 0;
    std::printf("%-34s %10.0f kq/s %s\n", label, double(pts.size()) / median(t) / 1e3,
                same ? "" : "  RESULTS DIFFER");
    return median(t);
  };
  for (std::size_t i = 0; i < pts.size(); ++i) {
    T b2 = std::numeric_limits<T>::infinity();
    bvh::nearest(w, pts[i], b2, leaf_fn(pts[i]));
    ref[i] = b2;
  }
  std::printf("\ntraversal (K = 4, SAH, leaves of 4, scalar triangle kernel), %ld points:\n",
              npoints);
  run("ordered + farthest-box shrink",
      [&](const Vec3<T>& p, T& b2) { bvh::nearest<true>(w, p, b2, leaf_fn(p)); });
  run("ordered (nearest child first)",
      [&](const Vec3<T>& p, T& b2) { bvh::nearest(w, p, b2, leaf_fn(p)); });
  run("unordered",
      [&](const Vec3<T>& p, T& b2) { bvh::experimental::nearest_unordered(w, p, b2, leaf_fn(p)); });
  run("recursive (ordered)",
      [&](const Vec3<T>& p, T& b2) { bvh::experimental::nearest_recursive(w, p, b2, leaf_fn(p)); });
  const auto sdf = MeshSdf<T>::make(mesh).value();
  run(
      "MeshSdf (SoA blocks of 8, vector kernel)",
      [&](const Vec3<T>& p, T& b2) { b2 = sdf.unsigned_distance(p); }, false);
  return 0;
}
