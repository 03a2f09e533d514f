// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Run-time instruction-set dispatch (core/isa.hpp): mesh SDF queries and 8^3 tiles on each
// instruction set compiled in, in one process, interleaved (median of R rounds), with the check
// that every instruction set gives the same values bit for bit. Build it twice, without and with
// -march=native, to compare a default build with a native one (bench/isa_native_vs_default.sh):
//
//   cmake --preset bench && cmake --build --preset bench --target ebgeom_bench_isa_dispatch_bench
//   cmake --preset bench -B build/bench-default -DEBGEOM_NATIVE=OFF
//   cmake --build build/bench-default --target ebgeom_bench_isa_dispatch_bench
//   build/bench/bench/ebgeom_bench_isa_dispatch_bench MESH... [--points N=200000] [--reps R=5]
//       [--only-auto]
//
// Prints, per mesh and precision, ns per query (uniform points in the box grown by 10%) and ns per
// sample of 8^3 tiles (a 64^3 grid over the same box), for the default choice ("auto") and each
// instruction set.

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/core/isa.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

using namespace ebgeom;

namespace {
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v[v.size() / 2];
}

template <class T> int run(const std::string& path, std::size_t npts, int reps, bool only_auto) {
  auto soup = io::read_mesh<T>(path);
  if (!soup) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), soup.error().what().c_str());
    return 1;
  }
  auto sdf = MeshSdf<T>::build(*soup);
  if (!sdf) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), sdf.error().what().c_str());
    return 1;
  }
  const Aabb<T> box = sdf->bounds().grown(T(0.1) * max_component(sdf->bounds().extent()));
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Vec3<T>> pts(npts);
  for (auto& p : pts)
    for (int a = 0; a < 3; ++a) p[a] = T(double(box.lo[a]) + u(rng) * double(box.extent()[a]));
  // Tiles: a 64^3 lattice over the box, evaluated 8^3 at a time.
  constexpr std::size_t g = 64, t = 8;
  std::vector<Vec3<T>> tile(t * t * t);
  std::vector<T> tile_out(tile.size());

  const Isa chosen = active_isa();
  std::vector<Isa> isas;
  for (Isa i : {Isa::baseline, Isa::avx2, Isa::avx512})
    if ((!only_auto || i == chosen) && set_isa(i)) isas.push_back(i);
  set_isa(chosen);
  std::vector<std::vector<double>> q(isas.size()), l(isas.size());
  std::vector<std::vector<T>> values(isas.size(), std::vector<T>(npts + g * g * g));
  for (int r = 0; r < reps; ++r)
    for (std::size_t k = 0; k < isas.size(); ++k) {
      set_isa(isas[k]);
      auto t0 = std::chrono::steady_clock::now();
      for (std::size_t i = 0; i < npts; ++i) values[k][i] = (*sdf)(pts[i]);
      q[k].push_back(seconds_since(t0) / double(npts) * 1e9);
      t0 = std::chrono::steady_clock::now();
      for (std::size_t tz = 0; tz < g; tz += t)
        for (std::size_t ty = 0; ty < g; ty += t)
          for (std::size_t tx = 0; tx < g; tx += t) {
            for (std::size_t z = 0; z < t; ++z)
              for (std::size_t y = 0; y < t; ++y)
                for (std::size_t x = 0; x < t; ++x) {
                  const std::size_t ijk[3] = {tx + x, ty + y, tz + z};
                  Vec3<T> p;
                  for (int a = 0; a < 3; ++a)
                    p[a] = box.lo[a] + box.extent()[a] * (T(ijk[a]) + T(0.5)) / T(g);
                  tile[x + t * (y + t * z)] = p;
                }
            sdf->eval_lattice(tile, {t, t, t}, tile_out);
            const std::size_t base =
                npts + ((tz / t * (g / t) + ty / t) * (g / t) + tx / t) * tile.size();
            std::copy(tile_out.begin(), tile_out.end(), values[k].begin() + std::ptrdiff_t(base));
          }
      l[k].push_back(seconds_since(t0) / double(g * g * g) * 1e9);
    }
  set_isa(chosen);
  bool same = true;
  for (std::size_t k = 1; k < isas.size(); ++k)
    same =
        same && std::memcmp(values[k].data(), values[0].data(), values[0].size() * sizeof(T)) == 0;
  const char* prec = sizeof(T) == 4 ? "float" : "double";
  for (std::size_t k = 0; k < isas.size(); ++k)
    std::printf("%s %s %s%s query_ns %.1f tile_ns %.1f\n", path.c_str(), prec, to_string(isas[k]),
                isas[k] == chosen ? " (auto)" : "", median(q[k]), median(l[k]));
  std::printf("%s %s native_isa %s, same values on every instruction set: %s\n", path.c_str(), prec,
              to_string(native_isa), same ? "yes" : "NO");
  return same ? 0 : 2;
}
} // namespace

int main(int argc, char** argv) {
  std::size_t npts = 200000;
  int reps = 5;
  bool only_auto = false;
  std::vector<std::string> meshes;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points" && i + 1 < argc)
      npts = std::size_t(std::atol(argv[++i]));
    else if (a == "--reps" && i + 1 < argc)
      reps = std::max(1, std::atoi(argv[++i]));
    else if (a == "--only-auto")
      only_auto = true;
    else
      meshes.push_back(a);
  }
  if (meshes.empty()) {
    std::fprintf(stderr, "usage: %s MESH... [--points N] [--reps R] [--only-auto]\n", argv[0]);
    return 1;
  }
  int rc = 0;
  for (const auto& m : meshes)
    rc =
        std::max({rc, run<float>(m, npts, reps, only_auto), run<double>(m, npts, reps, only_auto)});
  return rc;
}
