// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Query throughput of MeshSdf<T, 4, W> for several block widths W, on one mesh, in the build's
// own flags (configure without EBGEOM_NATIVE to measure the build users get by default). Every
// width answers the same uniform points in the mesh box + 10%; rounds are interleaved (each round
// runs every width once) and the medians and the ratio to the default width are printed. Results
// are checked equal bit for bit across widths.
//
//   cmake -S . -B build/bw -G Ninja -DCMAKE_BUILD_TYPE=Release -DEBGEOM_BUILD_BENCH=ON
//   cmake --build build/bw --target ebgeom_bench_block_width_bench
//   build/bw/bench/ebgeom_bench_block_width_bench MESH [--points N=300000] [--reps R=5]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

using namespace ebgeom;

namespace {

template <class T> std::vector<Vec3<T>> uniform_points(const Aabb<T>& box, std::size_t n) {
  const Vec3<T> lo = box.lo - box.extent() * T(0.1), hi = box.hi + box.extent() * T(0.1);
  std::mt19937_64 rng(20240604);
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
  std::vector<Vec3<T>> p(n);
  for (auto& q : p) q = Vec3<T>{T(ux(rng)), T(uy(rng)), T(uz(rng))};
  return p;
}

struct Method {
  int width;
  std::vector<double> seconds;
  std::vector<double> values;
};

template <class T, int W>
void run_width(const PolygonSoup<T>& soup, const std::vector<Vec3<T>>& pts,
               std::vector<std::function<double(std::vector<double>&)>>& passes,
               std::vector<Method>& methods) {
  auto sdf = std::make_shared<MeshSdf<T, 4, W>>(MeshSdf<T, 4, W>::build(soup).value());
  methods.push_back({W, {}, {}});
  passes.push_back([sdf, &pts](std::vector<double>& out) {
    out.resize(pts.size());
    const auto t0 = std::chrono::steady_clock::now();
    for (std::size_t i = 0; i < pts.size(); ++i) out[i] = double((*sdf)(pts[i]));
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  });
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <class T> int run(const std::string& mesh, std::size_t n, int reps) {
  auto soup = io::read_mesh<T>(mesh);
  if (!soup) {
    std::fprintf(stderr, "%s\n", soup.error().message.c_str());
    return 3;
  }
  const Aabb<T> box = Aabb<T>::of_range(soup->vertices);
  const auto pts = uniform_points(box, n);
  std::vector<std::function<double(std::vector<double>&)>> passes;
  std::vector<Method> methods;
  run_width<T, 4>(*soup, pts, passes, methods);
  run_width<T, 8>(*soup, pts, passes, methods);
  run_width<T, 16>(*soup, pts, passes, methods);
  for (int r = 0; r < reps; ++r)
    for (std::size_t m = 0; m < passes.size(); ++m)
      methods[m].seconds.push_back(passes[m](methods[m].values));
  const int def = MeshSdf<T>::block_width;
  double def_median = 0;
  for (const auto& m : methods)
    if (m.width == def) def_median = median(m.seconds);
  std::printf("%s, %s, %zu points, %d interleaved rounds (default W = %d)\n", mesh.c_str(),
              sizeof(T) == 4 ? "float" : "double", n, reps, def);
  for (const auto& m : methods) {
    const bool same = std::memcmp(m.values.data(), methods[0].values.data(),
                                  m.values.size() * sizeof(double)) == 0;
    std::printf("  W = %2d: %8.1f kq/s (median), %.3fx the default width%s\n", m.width,
                double(n) / median(m.seconds) * 1e-3, def_median / median(m.seconds),
                same ? "" : "  VALUES DIFFER");
    if (!same) return 1;
  }
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH [--points N=300000] [--reps R=5]\n", argv[0]);
    return 2;
  }
  std::size_t n = 300000;
  int reps = 5;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--points")) n = std::strtoull(argv[i + 1], nullptr, 10);
    if (!std::strcmp(argv[i], "--reps")) reps = std::atoi(argv[i + 1]);
  }
  const int a = run<float>(argv[1], n, reps);
  const int b = run<double>(argv[1], n, reps);
  return a ? a : b;
}
