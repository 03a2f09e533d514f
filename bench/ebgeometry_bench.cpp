// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// ebgeom against EBGeometry, the system it re-implements, in one process: the two cases
// EBGeometry's own examples time.
//
// 1. Mesh SDF (EBGeometry's MeshSDF example): for each mesh, ebgeom's MeshSdf against
//    EBGeometry's TriMeshSDF (`Parser::readIntoTriangleBVH`, its fastest mesh SDF, SoA triangle
//    leaves with its ISA-tuned defaults) and MeshSDF (`Parser::readIntoPackedBVH`, K = 4, any
//    polygon), one thread, the same random points (uniform in the mesh's box grown by 10% per
//    side). Every method reads the file with its own reader and builds its own tree.
// 2. Fast union (EBGeometry's PackedSpheres example): M^3 spheres of radius 1 spaced by 3,
//    EBGeometry's BVHUnionIF (K = 4) against ebgeom's BvhUnion, points uniform in the union's box.
//
// Timed passes are interleaved (round r of every method, then round r + 1), medians of the
// rounds; "vs ebgeom" is the method's time per query over ebgeom's (> 1: ebgeom faster). Every
// method's values are compared with ebgeom's on all points (largest difference, sign
// differences). Meshes with vertices that no face uses are skipped with a message: EBGeometry's
// DCEL conversion crashes on them (the Stanford bunny has 1,113). EBGeometry is GPL-3.0-or-later:
// this program is built only when you point EBGEOM_EBGEOMETRY_DIR at its source
// (bench/fetch-ebgeometry.sh unpacks the snapshot in
// ../shared/peers); the binary is a local measuring tool, never shipped.
//
// Usage: ebgeom_bench_ebgeometry_bench [--points N] [--rounds R] [--spheres M]
//                                      [--precision float|double|both] [mesh ...]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <limits>
#include <memory>
#include <random>
#include <string>
#include <vector>

#if __has_include(<EBGeometry.hpp>)
#include <EBGeometry.hpp>
#define EBGEOM_BENCH_HAVE_EBGEOMETRY 1
#endif

#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/bvh_union.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"

namespace {

using Clock = std::chrono::steady_clock;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

struct Options {
  std::size_t points = 200000;
  int rounds = 5;
  int spheres = 40; // M: M^3 spheres (40: 64,000)
  bool run_float = false, run_double = true;
  std::vector<std::string> meshes;
};

// One method: evaluates all points into `out`.
struct Method {
  std::string name;
  double build_ms = 0;
  std::function<void(std::vector<double>&)> run;
  std::vector<double> out, times_ns;
};

// Interleaved rounds, then one line per method with its ratio and agreement with methods[0].
void time_and_report(const char* what, const char* precision, std::vector<Method>& methods,
                     std::size_t n, int rounds) {
  for (int r = 0; r < rounds; ++r)
    for (Method& m : methods) {
      const auto t0 = Clock::now();
      m.run(m.out);
      m.times_ns.push_back(ms_since(t0) * 1e6 / double(n));
    }
  const double ref = median(methods[0].times_ns);
  std::printf("\n== %s, %s, %zu points, %d rounds, 1 thread\n", what, precision, n, rounds);
  std::printf("%-34s %10s %12s %10s %12s %10s\n", "method", "build ms", "ns/query", "vs ebgeom",
              "max |diff|", "sign diff");
  for (const Method& m : methods) {
    double max_diff = 0;
    std::size_t sign_diff = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double a = methods[0].out[i], b = m.out[i];
      max_diff = std::max(max_diff, std::abs(a - b));
      if ((a < 0) != (b < 0)) ++sign_diff;
    }
    const double t = median(m.times_ns);
    std::printf("%-34s %10.1f %12.1f %10.2f %12.3g %10zu\n", m.name.c_str(), m.build_ms, t, t / ref,
                max_diff, sign_diff);
  }
}

#ifdef EBGEOM_BENCH_HAVE_EBGEOMETRY

template <class T> const char* type_name() { return sizeof(T) == 4 ? "float" : "double"; }

template <class T> int bench_mesh(const std::string& path, const Options& o) {
  auto t0 = Clock::now();
  auto soup = ebgeom::io::read_mesh<T>(path);
  if (!soup) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), soup.error().what().c_str());
    return 1;
  }
  // EBGeometry's DCEL conversion dereferences a null edge on a vertex no face uses (it crashes on
  // the Stanford bunny): such meshes are reported and skipped rather than crashing the run.
  std::vector<char> used(soup->vertices.size(), 0);
  for (const ebgeom::Index v : soup->indices) used[v] = 1;
  const auto unused = std::size_t(std::count(used.begin(), used.end(), 0));
  if (unused > 0) {
    std::printf("\n== %s: skipped, %zu vertices belong to no face (EBGeometry's reader crashes on "
                "them)\n",
                path.c_str(), unused);
    return 0;
  }
  auto mesh = ebgeom::make_triangle_mesh(*soup);
  if (!mesh) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), mesh.error().what().c_str());
    return 1;
  }
  const ebgeom::Aabb<T> box = mesh->bounds();
  auto made = ebgeom::MeshSdf<T>::make(std::move(*mesh));
  if (!made) {
    std::fprintf(stderr, "%s: %s\n", path.c_str(), made.error().what().c_str());
    return 1;
  }
  const ebgeom::MeshSdf<T> sdf = std::move(*made);
  const double ebgeom_build = ms_since(t0);

  t0 = Clock::now();
  const auto tri = EBGeometry::Parser::readIntoTriangleBVH<T>(path);
  const double tri_build = ms_since(t0);
  t0 = Clock::now();
  const auto packed =
      EBGeometry::Parser::readIntoPackedBVH<T, EBGeometry::DCEL::DefaultMetaData, 4>(path);
  const double packed_build = ms_since(t0);

  std::mt19937_64 rng(12345);
  std::vector<ebgeom::Vec3<T>> pts(o.points);
  std::vector<EBGeometry::Vec3T<T>> epts(o.points);
  const ebgeom::Vec3<T> lo = box.lo - T(0.1) * box.extent(), ext = T(1.2) * box.extent();
  std::uniform_real_distribution<double> u(0, 1);
  for (std::size_t i = 0; i < o.points; ++i) {
    for (int k = 0; k < 3; ++k) pts[i][k] = lo[k] + T(u(rng)) * ext[k];
    epts[i] = EBGeometry::Vec3T<T>(pts[i][0], pts[i][1], pts[i][2]);
  }
  const std::size_t n = o.points;
  std::vector<Method> m(3);
  m[0].name = "ebgeom MeshSdf";
  m[0].build_ms = ebgeom_build;
  m[0].run = [&](std::vector<double>& out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = double(sdf(pts[i]));
  };
  m[1].name = "EBGeometry TriMeshSDF";
  m[1].build_ms = tri_build;
  m[1].run = [&](std::vector<double>& out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = double(tri->signedDistance(epts[i]));
  };
  m[2].name = "EBGeometry MeshSDF (PackedBVH, K=4)";
  m[2].build_ms = packed_build;
  m[2].run = [&](std::vector<double>& out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = double(packed->signedDistance(epts[i]));
  };
  for (Method& x : m) x.out.assign(n, 0.0);
  const std::string what = "mesh " + path.substr(path.find_last_of('/') + 1) + " (" +
                           std::to_string(sdf.mesh().triangle_count()) + " triangles)";
  time_and_report(what.c_str(), type_name<T>(), m, n, o.rounds);
  return 0;
}

template <class T> int bench_union(const Options& o) {
  const int M = o.spheres;
  const T radius = 1, spacing = 3;
  std::vector<ebgeom::Sphere<T>> balls;
  std::vector<std::shared_ptr<EBGeometry::SphereSDF<T>>> eballs;
  std::vector<EBGeometry::BoundingVolumes::AABBT<T>> boxes;
  for (int i = 0; i < M; ++i)
    for (int j = 0; j < M; ++j)
      for (int k = 0; k < M; ++k) {
        const T x = i * spacing, y = j * spacing, z = k * spacing;
        balls.push_back({{x, y, z}, radius});
        const EBGeometry::Vec3T<T> c(x, y, z);
        eballs.push_back(std::make_shared<EBGeometry::SphereSDF<T>>(c, radius));
        boxes.emplace_back(c - radius * EBGeometry::Vec3T<T>::ones(),
                           c + radius * EBGeometry::Vec3T<T>::ones());
      }
  auto t0 = Clock::now();
  const ebgeom::BvhUnion<ebgeom::Sphere<T>> ours(balls);
  const double ours_build = ms_since(t0);
  t0 = Clock::now();
  const EBGeometry::BVHUnionIF<T, EBGeometry::SphereSDF<T>, EBGeometry::BoundingVolumes::AABBT<T>,
                               4>
      theirs(eballs, boxes);
  const double theirs_build = ms_since(t0);

  std::mt19937_64 rng(6789);
  std::uniform_real_distribution<double> u(0, 1);
  const T lo = -radius, hi = (M - 1) * spacing + radius;
  const std::size_t n = o.points;
  std::vector<ebgeom::Vec3<T>> pts(n);
  std::vector<EBGeometry::Vec3T<T>> epts(n);
  for (std::size_t i = 0; i < n; ++i) {
    for (int k = 0; k < 3; ++k) pts[i][k] = lo + T(u(rng)) * (hi - lo);
    epts[i] = EBGeometry::Vec3T<T>(pts[i][0], pts[i][1], pts[i][2]);
  }
  std::vector<Method> m(2);
  m[0].name = "ebgeom BvhUnion";
  m[0].build_ms = ours_build;
  m[0].run = [&](std::vector<double>& out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = double(ours(pts[i]));
  };
  m[1].name = "EBGeometry BVHUnionIF (K=4)";
  m[1].build_ms = theirs_build;
  m[1].run = [&](std::vector<double>& out) {
    for (std::size_t i = 0; i < n; ++i) out[i] = double(theirs.value(epts[i]));
  };
  for (Method& x : m) x.out.assign(n, 0.0);
  const std::string what = "union of " + std::to_string(balls.size()) + " spheres";
  time_and_report(what.c_str(), type_name<T>(), m, n, o.rounds);
  return 0;
}

#endif

} // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--points" && has_value)
      o.points = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--rounds" && has_value)
      o.rounds = std::atoi(argv[++i]);
    else if (a == "--spheres" && has_value)
      o.spheres = std::atoi(argv[++i]);
    else if (a == "--precision" && has_value) {
      const std::string p = argv[++i];
      o.run_float = p == "float" || p == "both";
      o.run_double = p == "double" || p == "both";
      if (!o.run_float && !o.run_double) {
        std::fprintf(stderr, "--precision takes float, double or both, not '%s'\n", p.c_str());
        return 2;
      }
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr,
                   "usage: %s [--points N] [--rounds R] [--spheres M] "
                   "[--precision float|double|both] [mesh ...]\n",
                   argv[0]);
      return 2;
    } else
      o.meshes.push_back(a);
  }
  if (o.points < 1 || o.rounds < 1 || o.spheres < 1) {
    std::fprintf(stderr, "--points, --rounds and --spheres must be >= 1\n");
    return 2;
  }
#ifndef EBGEOM_BENCH_HAVE_EBGEOMETRY
  std::fprintf(stderr, "built without EBGeometry: configure with "
                       "-DEBGEOM_EBGEOMETRY_DIR=$(sh bench/fetch-ebgeometry.sh)\n");
  return 2;
#else
  int rc = 0;
  for (const std::string& path : o.meshes) {
    if (o.run_double) rc |= bench_mesh<double>(path, o);
    if (o.run_float) rc |= bench_mesh<float>(path, o);
  }
  if (o.run_double) rc |= bench_union<double>(o);
  if (o.run_float) rc |= bench_union<float>(o);
  return rc;
#endif
}
