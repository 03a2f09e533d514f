// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Single-query throughput of MeshSdf<T, K> for several BVH arities K on one mesh, in the build's
// own flags: float with 8 (the default) and 16 children per node, double with 4 (the default)
// and 8. Every arity answers the same uniform points in the mesh box + 10%, one thread, in rounds
// that run each arity once (alternately); the time is the thread's CPU time. Prints each arity's
// median rate and the median over rounds of its time against the default arity's in the same
// round (paired). Every value must equal the default arity's bit for bit, and the brute force on
// the first `--check` points.
//
//   cmake --preset bench && cmake --build --preset bench --target ebgeom_bench_arity_bench
//   build/bench/bench/ebgeom_bench_arity_bench MESH [--points N=300000] [--reps R=5] [--check
//   C=500]
#include <time.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

using namespace ebgeom;

namespace {

double thread_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

template <class T> std::vector<Vec3<T>> uniform_points(const Aabb<T>& box, std::size_t n) {
  const Vec3<T> lo = box.lo - box.extent() * T(0.1), hi = box.hi + box.extent() * T(0.1);
  std::mt19937_64 rng(20240604);
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
  std::vector<Vec3<T>> p(n);
  for (auto& q : p) q = Vec3<T>{T(ux(rng)), T(uy(rng)), T(uz(rng))};
  return p;
}

struct Arity {
  int k = 0;
  std::size_t bytes = 0;
  std::vector<double> seconds;
  std::vector<double> values;
  std::function<double(std::vector<double>&)> pass;
};

template <class T, int K>
Arity make_arity(const PolygonSoup<T>& soup, const std::vector<Vec3<T>>& pts) {
  auto sdf = std::make_shared<MeshSdf<T, K>>(MeshSdf<T, K>::build(soup).value());
  Arity a;
  a.k = K;
  a.bytes = sdf->memory_bytes();
  a.pass = [sdf, &pts](std::vector<double>& out) {
    out.resize(pts.size());
    const double t0 = thread_seconds();
    for (std::size_t i = 0; i < pts.size(); ++i) out[i] = double((*sdf)(pts[i]));
    return thread_seconds() - t0;
  };
  return a;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

template <class T, int K0, int K1>
int run(const std::string& mesh, std::size_t n, int reps, std::size_t check) {
  auto soup = io::read_mesh<T>(mesh);
  if (!soup) {
    std::fprintf(stderr, "%s\n", soup.error().message.c_str());
    return 3;
  }
  const Aabb<T> box = Aabb<T>::of_range(soup->vertices);
  const auto pts = uniform_points(box, n);
  std::vector<Arity> arities;
  arities.push_back(make_arity<T, K0>(*soup, pts));
  arities.push_back(make_arity<T, K1>(*soup, pts));
  std::vector<double> ratio; // time of K1 / time of K0, per round
  for (int r = 0; r < reps; ++r) {
    for (auto& a : arities) a.seconds.push_back(a.pass(a.values));
    ratio.push_back(arities[1].seconds.back() / arities[0].seconds.back());
  }
  std::printf("%s, %s, %zu points, %d rounds, one thread (CPU time)\n", mesh.c_str(),
              sizeof(T) == 4 ? "float" : "double", n, reps);
  int rc = 0;
  for (const auto& a : arities) {
    const bool same = std::memcmp(a.values.data(), arities[0].values.data(),
                                  a.values.size() * sizeof(double)) == 0;
    std::printf("  K = %2d: %8.1f kq/s (median), %7.1f MB%s\n", a.k,
                double(n) / median(a.seconds) * 1e-3, double(a.bytes) * 1e-6,
                same ? "" : "  VALUES DIFFER");
    if (!same) rc = 1;
  }
  std::printf("  K = %d / K = %d, time, paired median: %.3f (speed-up %.3f)\n", K1, K0,
              median(ratio), 1.0 / median(ratio));
  const BruteForceMeshSdf<T> brute = BruteForceMeshSdf<T>::build(*soup).value();
  std::size_t equal = 0;
  for (std::size_t i = 0; i < std::min(check, n); ++i) {
    const double b = double(brute(pts[i]));
    equal += std::memcmp(&b, &arities[1].values[i], sizeof b) == 0;
  }
  std::printf("  brute force equal bit for bit on %zu of %zu points\n", equal, std::min(check, n));
  if (equal != std::min(check, n)) rc = 1;
  return rc;
}

} // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s MESH [--points N=300000] [--reps R=5] [--check C=500]\n",
                 argv[0]);
    return 2;
  }
  std::size_t n = 300000, check = 500;
  int reps = 5;
  for (int i = 2; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--points")) n = std::strtoull(argv[i + 1], nullptr, 10);
    if (!std::strcmp(argv[i], "--reps")) reps = std::atoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--check")) check = std::strtoull(argv[i + 1], nullptr, 10);
  }
  const int a = run<float, 8, 16>(argv[1], n, reps, check);
  const int b = run<double, 4, 8>(argv[1], n, reps, check);
  return a ? a : b;
}
