// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Cost of the sign modes of SignedMeshSdf (sdf/signed_mesh_sdf.hpp) on real meshes: time per
// query (one thread) of
//   pseudonormal   MeshSdf's signed distance (nearest search + pseudonormal sign),
//   fast_winding   exact distance + Barill et al. fast winding number sign (beta = 2),
//   fast w only    the fast winding number alone,
//   winding        exact distance + exact winding number sign (O(n); fewer points),
// with medians over repetitions, methods interleaved within each repetition. Times are the
// thread's CPU time (CLOCK_THREAD_CPUTIME_ID), so that a machine shared with other jobs slows the
// figures less than wall time would; the wall-time medians are printed too.
//
//   cmake --preset bench && cmake --build --preset bench --target ebgeom_bench_sign_bench
//   build/bench/bench/ebgeom_bench_sign_bench [MESH_DIR=../shared/meshes] [POINTS=200000] [REPS=7]
//       [MESHES=stanford-bunny.obj,ogre.obj] [PRECISION=float|double]
//
// Query points are uniform in the mesh's box grown by 10% per side (the CLI's default padding).

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <sstream>
#include <string>
#include <vector>

#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

namespace {

using namespace ebgeom;
using Clock = std::chrono::steady_clock;

struct Time {
  double cpu, wall; // ns per query
};

double thread_cpu_ns() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e9 + double(ts.tv_nsec);
}

template <class F> Time ns_per_query(std::size_t n, F&& f) {
  const double c0 = thread_cpu_ns();
  const auto t0 = Clock::now();
  f();
  const double wall = std::chrono::duration<double, std::nano>(Clock::now() - t0).count();
  return {(thread_cpu_ns() - c0) / double(n), wall / double(n)};
}

double median(std::vector<Time> v, bool cpu = true) {
  std::vector<double> x;
  for (const Time& t : v) x.push_back(cpu ? t.cpu : t.wall);
  std::sort(x.begin(), x.end());
  return x[x.size() / 2];
}

volatile double sink = 0; // keeps the results alive

template <class T> int run(const std::string& path, std::size_t n, int reps) {
  auto soup = io::read_mesh<T>(path);
  if (!soup) {
    std::fprintf(stderr, "%s\n", soup.error().what().c_str());
    return 1;
  }
  SignOptions o;
  o.mode = SignMode::pseudonormal;
  const auto pn = SignedMeshSdf<T>::build(*soup, o).value();
  o.mode = SignMode::fast_winding;
  const auto fw = SignedMeshSdf<T>::build(*soup, o).value();
  o.mode = SignMode::winding;
  const auto ex = SignedMeshSdf<T>::build(*soup, o).value();
  o.mode = SignMode::automatic;
  const auto au = SignedMeshSdf<T>::build(*soup, o).value();
  const MeshSdf<T>& raw = pn.mesh_sdf();

  const Aabb<T> b = raw.bounds();
  const Vec3<T> pad = b.extent() * T(0.1);
  std::vector<Vec3<T>> pts(n);
  std::uint64_t s = 12345;
  auto next = [&] {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return T(double(s >> 11) / 9007199254740992.0);
  };
  for (auto& p : pts)
    for (int a = 0; a < 3; ++a) p[a] = b.lo[a] - pad[a] + next() * (b.extent()[a] + 2 * pad[a]);
  const std::size_t n_exact = std::max<std::size_t>(50, n / 2000);

  std::vector<Time> t_pn, t_fw, t_w, t_ex;
  std::size_t disagree_fw = 0, inside_pn = 0, inside_fw = 0;
  for (int r = 0; r < reps; ++r) {
    t_pn.push_back(ns_per_query(n, [&] {
      double acc = 0;
      for (const auto& p : pts) acc += raw(p);
      sink = sink + acc;
    }));
    t_fw.push_back(ns_per_query(n, [&] {
      double acc = 0;
      for (const auto& p : pts) acc += fw(p);
      sink = sink + acc;
    }));
    t_w.push_back(ns_per_query(n, [&] {
      double acc = 0;
      for (const auto& p : pts) acc += fw.winding_number(p);
      sink = sink + acc;
    }));
    t_ex.push_back(ns_per_query(n_exact, [&] {
      double acc = 0;
      for (std::size_t i = 0; i < n_exact; ++i) acc += ex(pts[i]);
      sink = sink + acc;
    }));
  }
  for (const auto& p : pts) {
    const bool a = raw(p) < 0, c = fw(p) < 0;
    inside_pn += a;
    inside_fw += c;
    disagree_fw += a != c;
  }
  const double mpn = median(t_pn), mfw = median(t_fw), mw = median(t_w), mex = median(t_ex);
  std::printf("%s: %zu triangles, %s, auto -> %s (%s)\n", path.c_str(), raw.triangle_count(),
              sizeof(T) == 4 ? "float" : "double", to_string(au.resolved_mode()),
              au.reason().c_str());
  std::printf("  %zu points, median of %d runs, ns per query (one thread, thread CPU time)\n", n,
              reps);
  std::printf("  pseudonormal          %10.1f\n", mpn);
  std::printf("  fast_winding (sdf)    %10.1f   x%.2f of pseudonormal\n", mfw, mfw / mpn);
  std::printf("  fast winding alone    %10.1f\n", mw);
  std::printf("  winding (exact, sdf)  %10.1f   x%.0f of pseudonormal (%zu points)\n", mex,
              mex / mpn, n_exact);
  std::printf("  wall-time medians: pseudonormal %.1f, fast_winding %.1f (x%.2f)\n",
              median(t_pn, false), median(t_fw, false), median(t_fw, false) / median(t_pn, false));
  std::printf("  inside fraction: pseudonormal %.4f, fast_winding %.4f; signs differ at %.4f%%\n",
              double(inside_pn) / double(n), double(inside_fw) / double(n),
              100.0 * double(disagree_fw) / double(n));
  std::printf("  memory: MeshSdf %.1f MB, + fast winding %.1f MB\n", raw.memory_bytes() / 1e6,
              (fw.memory_bytes() - raw.memory_bytes()) / 1e6);
  return 0;
}

} // namespace

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "../shared/meshes";
  const std::size_t n = argc > 2 ? std::size_t(std::strtoull(argv[2], nullptr, 10)) : 200000;
  const int reps = argc > 3 ? std::atoi(argv[3]) : 7;
  const std::string meshes = argc > 4 ? argv[4] : "stanford-bunny.obj,ogre.obj";
  const bool dbl = argc > 5 && std::strcmp(argv[5], "double") == 0;
  std::stringstream ss(meshes);
  std::string name;
  int rc = 0;
  while (std::getline(ss, name, ','))
    rc |= dbl ? run<double>(dir + "/" + name, n, std::max(1, reps))
              : run<float>(dir + "/" + name, n, std::max(1, reps));
  return rc;
}
