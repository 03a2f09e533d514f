// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Mesh signed-distance queries: ebgeom's MeshSdf against brute force, Embree 3, CGAL and fcpw.
// A plain driver (not Google Benchmark): every method answers the same points in the same process.
//
//   sh bench/install-peers.sh     (Debian: libembree-dev, libcgal-dev; peers are optional)
//   fcpw=$(sh bench/fetch-fcpw.sh)  (fcpw from ../shared/peers, optional)
//   cmake --preset bench -DEBGEOM_FCPW_DIR=$fcpw
//   cmake --build --preset bench --target ebgeom_bench_mesh_sdf_bench
//   build/bench/bench/ebgeom_bench_mesh_sdf_bench MESH | --generate N
//       [--points N=1000000] [--reps R=5] [--precision float|double|both] [--threads T=2]
//       [--check M=20000] [--cgal-points K=100000] [--grid N] [--bands] [--json]
//       [--json-file PATH]
//
// For the mesh: parse time (io::read_mesh) or generation time, TriangleMesh build time. For each
// method: build time, memory, and query throughput (median of R runs) over N uniform random points
// (fixed seed) in the mesh box grown by 10% of its extent on every side, on 1 and on T threads
// (ebgeom::parallel_for, dynamic chunks); one-thread passes are timed in CPU time of the thread
// (robust to a loaded machine), T-thread passes in wall time. The first M points check every
// method's signed distance against ebgeom's (or brute force's when MeshSdf is not built in). See
// docs/performance.md.
//
// --grid N: the points are the N^3 cell centres of the same box (GridSpec::cells, x fastest)
// instead of random ones, and ebgeom answers them three ways, all timed per point in the same
// rounds as the peers: one query per point (`ebgeom`), the batch path `evaluate` on the points
// (`ebgeom-batch`) and the grid path `sample_grid`, one 8^3 tile at a time (`ebgeom-tile`). All
// points are checked (the tile and batch paths must equal the per-point queries bit for bit).
//
// --bands: after the main rounds, ebgeom and fcpw (one thread) are timed again on the points of
// each band of |S| (ebgeom's answer) in units of the points' box diagonal, the two methods
// alternately in each of R rounds: where on the distance range one is faster than the other.

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <iterator>
#include <limits>
#include <malloc.h>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "ebgeom/core/morton.hpp"
#include "ebgeom/core/parallel.hpp"
#include "ebgeom/eval/evaluate.hpp"
#include "ebgeom/eval/grid.hpp"
#include "ebgeom/geom/solid_angle.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/triangle_mesh.hpp"
#include "ebgeom/sdf/brute_force_mesh_sdf.hpp"

// -DEBGEOM_BENCH_NO_MESH_SDF builds the peers alone (e.g. while mesh_sdf.hpp does not compile).
#if __has_include("ebgeom/sdf/mesh_sdf.hpp") && !defined(EBGEOM_BENCH_NO_MESH_SDF)
#include "ebgeom/sdf/mesh_sdf.hpp"
#define EBGEOM_BENCH_HAVE_MESH_SDF 1
#endif
#ifdef EBGEOM_BENCH_HAVE_EMBREE
#include "peers/embree_peer.hpp"
using ebgeom_bench::embree_memory_monitor;
using ebgeom_bench::EmbreePeer;
#endif
#ifdef EBGEOM_BENCH_HAVE_CGAL
#include "peers/cgal_peer.hpp"
#endif
#ifdef EBGEOM_BENCH_HAVE_FCPW
#include "peers/fcpw_peer.hpp"
#endif
#ifdef EBGEOM_BENCH_HAVE_JSON
#include <nlohmann/json.hpp>
#endif

namespace {

using namespace ebgeom;
using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
}

// CPU seconds of the calling thread: one-thread passes are timed with it, so that time the
// thread spends waiting for a core of a loaded machine does not count (each method's pass runs
// on the calling thread: ebgeom's with one thread too). Wall time where it is unavailable.
double thread_seconds() {
#if defined(CLOCK_THREAD_CPUTIME_ID)
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) == 0)
    return double(ts.tv_sec) + 1e-9 * ts.tv_nsec;
#endif
  return std::chrono::duration<double>(Clock::now().time_since_epoch()).count();
}

// Seconds taken by a pass on `threads` threads: thread CPU time for one, wall time for more.
struct PassTimer {
  int threads;
  double t0 = threads <= 1 ? thread_seconds() : 0;
  Clock::time_point w0 = Clock::now();
  double seconds() const { return threads <= 1 ? thread_seconds() - t0 : ms_since(w0) * 1e-3; }
};

double median(std::vector<double> v) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Heap bytes in use (glibc: main arena + mmapped chunks). Used for CGAL, whose structures have no
// size query; its build runs on the calling thread, so the main arena sees all of it.
std::size_t heap_in_use() {
  const struct mallinfo2 mi = mallinfo2();
  return mi.uordblks + mi.hblkhd;
}

struct Options {
  std::string mesh;
  std::size_t generate = 0; // > 0: generated bumpy torus of about this many triangles
  std::size_t points = 1000000;
  int reps = 5;
  int threads = 2;
  std::size_t check = 20000;
  std::size_t cgal_points = 100000; // CGAL is timed on the first K points (it is slow)
  std::size_t grid = 0; // > 0: the grid^3 cell centres of the box instead of random points
  bool run_float = false, run_double = true;
  bool bands = false; // time ebgeom and fcpw per band of distance (see the file comment)
  bool json = false;
  std::string json_file; // also write the JSON object there (text still goes to stdout)
};

// One method at one precision.
struct Row {
  std::string method;
  std::string precision; // the scalar type of the run (input, points, output)
  std::string compute;   // what the method computes in
  double build_ms = std::numeric_limits<double>::quiet_NaN();
  std::size_t memory = 0;
  std::string memory_note;
  std::size_t queries = 0; // points per run
  std::vector<double> qps1, qpst;
  // agreement with the reference on the first `checked` points
  std::string reference;
  std::size_t checked = 0, distance_bad = 0, sign_diff = 0, bitwise_equal = 0;
  // sign differences arbitrated by the generalized winding number (inside when w > 1/2)
  std::size_t sign_diff_ref_wins = 0, sign_diff_peer_wins = 0;
  double max_rel = 0, max_abs = 0;
  std::string note;
  bool is_reference = false;
};

struct MeshInfo {
  std::string name;
  std::size_t triangles = 0, vertices = 0;
  double parse_ms = 0, triangle_mesh_ms = 0;
  bool generated = false;
  double scale = 0; // max |coordinate| and extent of the box: scale of rounding errors
};

// ---- generated input ------------------------------------------------------------------------

// A closed torus (major radius 1, tube radius 0.35) whose tube radius is modulated by a sum of
// sinusoids (+-32%), split into 2 nu nv triangles with nu ~ sqrt(n). Outward oriented, manifold.
PolygonSoup<double> bumpy_torus(std::size_t n) {
  const std::size_t nu = std::max<std::size_t>(3, std::size_t(std::llround(std::sqrt(double(n))))),
                    nv = std::max<std::size_t>(3, n / (2 * nu));
  const double two_pi = 6.283185307179586476925286766559, R = 1.0, r0 = 0.35;
  PolygonSoup<double> s;
  s.reserve(nu * nv, 2 * nu * nv, 6 * nu * nv);
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t j = 0; j < nv; ++j) {
      const double u = two_pi * double(i) / double(nu), v = two_pi * double(j) / double(nv);
      const double r = r0 * (1 + 0.2 * std::sin(3 * u) * std::cos(2 * v) +
                             0.08 * std::sin(7 * u + 5 * v) + 0.04 * std::cos(13 * u - 9 * v + 1));
      s.add_vertex({(R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                    r * std::sin(v)});
    }
  auto id = [&](std::size_t i, std::size_t j) { return Index((i % nu) * nv + (j % nv)); };
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t j = 0; j < nv; ++j) {
      s.add_triangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      s.add_triangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return s;
}

template <class T> PolygonSoup<T> convert_soup(const PolygonSoup<double>& in) {
  PolygonSoup<T> out;
  out.vertices.reserve(in.vertices.size());
  for (const auto& v : in.vertices) out.vertices.push_back(Vec3<T>::from(v));
  out.indices = in.indices;
  out.offsets = in.offsets;
  return out;
}

// N uniform points in the box grown by 10% of its extent on every side; drawn in double from a
// fixed seed, so the float and double runs query the same points (rounded).
template <class T> std::vector<Vec3<T>> random_points(const Aabb<T>& box, std::size_t n) {
  const Aabb<double> b = Aabb<double>::from(box);
  const Vec3<double> lo = b.lo - b.extent() * 0.1, hi = b.hi + b.extent() * 0.1;
  std::mt19937_64 rng(20240604);
  std::uniform_real_distribution<double> ux(lo.x, hi.x), uy(lo.y, hi.y), uz(lo.z, hi.z);
  std::vector<Vec3<T>> p(n);
  for (auto& q : p) {
    const double x = ux(rng), y = uy(rng), z = uz(rng);
    q = Vec3<T>::from(Vec3<double>{x, y, z});
  }
  return p;
}

// The n^3 cell centres of the box grown by 10% of its extent on every side (n = 0: an empty
// spec, unused).
template <class T> GridSpec<T> grid_of(const Aabb<T>& box, std::size_t n) {
  const Vec3<T> e = box.extent();
  Aabb<T> b = box;
  b.lo = b.lo - e * T(0.1);
  b.hi = b.hi + e * T(0.1);
  return GridSpec<T>::cells(b, std::max<std::size_t>(n, 1));
}

// The samples of `g` in its array order (x fastest), placed as the grid samplers place them.
template <class T> std::vector<Vec3<T>> grid_points(const GridSpec<T>& g) {
  std::vector<Vec3<T>> p;
  p.reserve(g.size());
  for (std::size_t k = 0; k < g.nz(); ++k)
    for (std::size_t j = 0; j < g.ny(); ++j)
      for (std::size_t i = 0; i < g.nx(); ++i) p.push_back(g.point(i, j, k));
  return p;
}

// ---- measurement ----------------------------------------------------------------------------

// One timed pass of a method: answers its first `n` points on `threads` threads (1: a plain loop;
// more: ebgeom::parallel_for with dynamic chunks) into `out`, and returns the seconds taken.
using Pass = std::function<double(int threads)>;

template <class T, class Query>
Pass make_pass(Query query, const std::vector<Vec3<T>>& pts, std::size_t n, std::vector<T>& out) {
  out.assign(n, T(0));
  return [query, &pts, n, &out](int threads) {
    const PassTimer timer{threads};
    if (threads <= 1) {
      for (std::size_t i = 0; i < n; ++i) out[i] = query(pts[i]);
    } else {
      ExecOptions ex;
      ex.threads = threads;
      ex.serial_threshold = 0;
      const std::size_t grain =
          std::clamp<std::size_t>(n / (64 * std::size_t(threads)), std::size_t(16), 1024);
      parallel_for(
          0, n, grain,
          [&](std::size_t b, std::size_t e) {
            for (std::size_t i = b; i < e; ++i) out[i] = query(pts[i]);
          },
          ex);
    }
    return timer.seconds();
  };
}

// Compares `got` with `ref` on the first `m` values: |distance| within rel |ref| + floor, sign.
template <class T>
void check(Row& row, const std::string& ref_name, const std::vector<T>& ref,
           const std::vector<T>& got, std::size_t m, double rel, double floor) {
  m = std::min({m, ref.size(), got.size()});
  row.reference = ref_name;
  row.checked = m;
  for (std::size_t i = 0; i < m; ++i) {
    const double a = double(ref[i]), b = double(got[i]);
    const double err = std::abs(std::abs(a) - std::abs(b));
    if (!(err <= rel * std::abs(a) + floor)) ++row.distance_bad;
    if ((a < 0) != (b < 0)) ++row.sign_diff;
    if (ref[i] == got[i]) ++row.bitwise_equal;
    row.max_abs = std::max(row.max_abs, err);
    if (std::abs(a) > floor) row.max_rel = std::max(row.max_rel, err / std::abs(a));
  }
}

// ---- Embree 3 --------------------------------------------------------------------------------

// ---- one precision --------------------------------------------------------------------------

template <class T> const char* type_name() { return sizeof(T) == 4 ? "float" : "double"; }

template <class T> Result<PolygonSoup<T>> load(const Options& o, MeshInfo& info) {
  const auto t0 = Clock::now();
  if (o.generate > 0) {
    PolygonSoup<T> s = convert_soup<T>(bumpy_torus(o.generate));
    info.parse_ms = ms_since(t0);
    info.generated = true;
    info.name = "generated bumpy torus";
    return s;
  }
  auto r = io::read_mesh<T>(o.mesh);
  info.parse_ms = ms_since(t0);
  info.name = o.mesh.substr(
      o.mesh.find_last_of('/') == std::string::npos ? 0 : o.mesh.find_last_of('/') + 1);
  if (!r) return make_error(r.error().code, r.error().what());
  return std::move(*r);
}

// One band of `--bands`: the points with lo <= |S| / diagonal < hi, and each round's one-thread
// throughput of ebgeom and fcpw on them.
struct Band {
  double lo = 0, hi = 0;
  std::size_t points = 0;
  std::vector<double> ebgeom_qps, fcpw_qps;
};

struct PrecisionRun {
  std::string precision;
  MeshInfo mesh;
  std::vector<Row> rows;
  std::vector<Band> bands; // `--bands`
  std::string error;
};

template <class T> PrecisionRun run_precision(const Options& o) {
  PrecisionRun run;
  run.precision = type_name<T>();
  Result<PolygonSoup<T>> soup = load<T>(o, run.mesh);
  if (!soup) {
    run.error = soup.error().what();
    return run;
  }
  auto t0 = Clock::now();
  Result<TriangleMesh<T>> made = make_triangle_mesh(*soup);
  run.mesh.triangle_mesh_ms = ms_since(t0);
  if (!made) {
    run.error = made.error().what();
    return run;
  }
  const TriangleMesh<T>& mesh = *made;
  run.mesh.triangles = mesh.triangle_count();
  run.mesh.vertices = mesh.vertex_count();
  const Aabb<T> box = mesh.bounds();
  {
    const Aabb<double> b = Aabb<double>::from(box);
    run.mesh.scale =
        std::max({max_component(abs(b.lo)), max_component(abs(b.hi)), max_component(b.extent())});
  }
  const GridSpec<T> grid = grid_of(box, o.grid);
  const std::vector<Vec3<T>> pts = o.grid > 0 ? grid_points(grid) : random_points(box, o.points);
  // On a grid every point is checked (a tile path must equal the per-point queries everywhere).
  const std::size_t m = o.grid > 0 ? o.points : std::min(o.check, o.points);
  // Tolerances: relative 1e-5 (float) / 1e-9 (double) plus 16 rounding units of the coordinates.
  const double rel_t = sizeof(T) == 4 ? 1e-5 : 1e-9;
  const double floor_t = 16 * double(std::numeric_limits<T>::epsilon()) * run.mesh.scale;
  const double floor_f = 16 * double(std::numeric_limits<float>::epsilon()) * run.mesh.scale;
  const std::size_t nt = std::max<std::size_t>(mesh.triangle_count(), 1);

  // Every method is built first; then the timed passes are interleaved (run r of every method,
  // then run r + 1), so that load from other processes hits all methods alike.
  std::vector<Pass> passes;
  std::vector<std::vector<T>> outs(8); // one per method; never resized below (passes hold refs)
  // fcpw-sorted: the points in Morton order, the order, and the values in that order.
  std::vector<Vec3<T>> sorted_points;
  std::vector<std::uint32_t> sorted_order;
  std::vector<T> sorted_out;
  std::vector<T>* out_ref = nullptr; // the reference's output (ebgeom when built in)
  std::string ref_name;

#ifdef EBGEOM_BENCH_HAVE_MESH_SDF
  std::unique_ptr<MeshSdf<T>> sdf;
  {
    Row row;
    row.method = "ebgeom";
    row.precision = row.compute = type_name<T>();
    std::vector<double> builds;
    for (int r = 0; r < o.reps; ++r) {
      sdf.reset();
      TriangleMesh<T> copy = mesh; // MeshSdf owns its mesh; the copy is not the build
      t0 = Clock::now();
      auto made_sdf = MeshSdf<T>::make(std::move(copy));
      builds.push_back(ms_since(t0));
      if (!made_sdf) {
        run.error = std::string("MeshSdf::make: ") + made_sdf.error().what();
        return run;
      }
      sdf = std::make_unique<MeshSdf<T>>(std::move(*made_sdf));
    }
    row.build_ms = median(builds);
    row.memory = sdf->memory_bytes();
    row.memory_note = "MeshSdf::memory_bytes() (BVH + blocks + its TriangleMesh)";
    row.queries = o.points;
    row.is_reference = true;
    const MeshSdf<T>* s = sdf.get();
    passes.push_back(make_pass([s](const Vec3<T>& p) { return (*s)(p); }, pts, o.points, outs[0]));
    run.rows.push_back(std::move(row));
    out_ref = &outs[0];
    ref_name = "ebgeom";
  }
  {
    // The same object through the batch path (`evaluate`: MeshSdf::eval visits the points in
    // Morton order) and, on a grid, the grid path (`sample_grid`, one call per 8^3 tile), on the
    // same points in the same order.
    const MeshSdf<T>* s = sdf.get();
    for (const char* method : {"ebgeom-batch", "ebgeom-tile"}) {
      if (o.grid == 0 && std::strcmp(method, "ebgeom-tile") == 0) continue;
      Row row;
      row.method = method;
      row.precision = row.compute = type_name<T>();
      row.build_ms = run.rows.front().build_ms;
      row.memory = run.rows.front().memory;
      row.memory_note = run.rows.front().memory_note;
      row.queries = o.points;
      const bool tile = row.method == "ebgeom-tile";
      row.note = tile ? "sample_grid (8^3 tiles)"
                      : "evaluate (Morton order inside; sort timed); all points checked";
      std::vector<T>& out = outs[tile ? 6 : 5];
      out.assign(o.points, T(0));
      passes.push_back([s, tile, &pts, &out, grid](int threads) {
        const PassTimer timer{threads};
        if (tile) {
          GridOptions opt;
          opt.exec.threads = threads;
          opt.search = GridSearch::tile;
          if (!sample_grid(*s, grid, Span<T>(out), opt)) std::abort();
        } else {
          ExecOptions ex;
          ex.threads = threads;
          if (!evaluate(*s, Span<const Vec3<T>>(pts), Span<T>(out), ex)) std::abort();
        }
        return timer.seconds();
      });
      run.rows.push_back(std::move(row));
    }
  }
#endif

  // Brute force: the exact oracle (O(n) per query), on a subset sized to the mesh.
  t0 = Clock::now();
  const BruteForceMeshSdf<T> brute(mesh);
  std::vector<T> brute_ref;
  {
    Row row;
    row.method = "brute";
    row.precision = row.compute = type_name<T>();
    row.build_ms = ms_since(t0);
    row.memory = brute.mesh().memory_bytes();
    row.memory_note = "TriangleMesh::memory_bytes() (its copy of the mesh)";
    row.queries = std::min<std::size_t>(
        o.points, std::clamp<std::size_t>(std::size_t(4e8) / nt, std::size_t(50), 2000));
    row.note = "on the first " + std::to_string(row.queries) + " points";
    const BruteForceMeshSdf<T>* b = &brute;
    passes.push_back(
        make_pass([b](const Vec3<T>& p) { return (*b)(p); }, pts, row.queries, outs[1]));
    if (!out_ref) {
      // No MeshSdf: brute force is the reference, on as many check points as affordable.
      const std::size_t mr =
          std::min<std::size_t>(m, std::max<std::size_t>(row.queries, std::size_t(5e9) / nt));
      brute_ref.assign(mr, T(0));
      ExecOptions ex;
      ex.threads = o.threads;
      parallel_for(
          0, mr, 64,
          [&](std::size_t i0, std::size_t i1) {
            for (std::size_t i = i0; i < i1; ++i) brute_ref[i] = brute(pts[i]);
          },
          ex);
      out_ref = &brute_ref;
      ref_name = "brute";
      row.is_reference = true;
    }
    run.rows.push_back(std::move(row));
  }

#ifdef EBGEOM_BENCH_HAVE_EMBREE
  std::atomic<long long> device_bytes{0};
  RTCDevice device = rtcNewDevice(nullptr);
  rtcSetDeviceMemoryMonitorFunction(device, &embree_memory_monitor, &device_bytes);
  std::unique_ptr<EmbreePeer<T>> embree;
  {
    Row row;
    row.method = "embree";
    row.precision = type_name<T>();
    row.compute = sizeof(T) == 4 ? "float" : "float BVH; double distance on the winner";
    std::vector<double> builds;
    long long bvh_bytes = 0;
    for (int r = 0; r < o.reps; ++r) {
      embree.reset();
      const long long before = device_bytes.load();
      t0 = Clock::now();
      embree = std::make_unique<EmbreePeer<T>>(device, mesh);
      builds.push_back(ms_since(t0));
      bvh_bytes = device_bytes.load() - before;
    }
    row.build_ms = median(builds);
    row.memory =
        std::size_t(std::max(0LL, bvh_bytes)) + embree->buffer_bytes() + mesh.memory_bytes();
    row.memory_note = "Embree device allocations " + std::to_string(bvh_bytes) +
                      " + float vertex/index buffers " + std::to_string(embree->buffer_bytes()) +
                      " + TriangleMesh (pseudonormals for the sign) " +
                      std::to_string(mesh.memory_bytes());
    row.queries = o.points;
    if (sizeof(T) != 4) row.note = "Embree computes in float";
    const EmbreePeer<T>* e = embree.get();
    passes.push_back(make_pass([e](const Vec3<T>& p) { return (*e)(p); }, pts, o.points, outs[2]));
    run.rows.push_back(std::move(row));
  }
#endif

#ifdef EBGEOM_BENCH_HAVE_CGAL
  std::unique_ptr<ebgeom_bench::CgalPeer> cgal;
  {
    Row row;
    row.method = "cgal";
    row.precision = type_name<T>();
    row.compute = "double (Epick)";
    std::vector<double> xyz(3 * mesh.vertex_count());
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
      xyz[3 * i] = double(mesh.vertices[i].x);
      xyz[3 * i + 1] = double(mesh.vertices[i].y);
      xyz[3 * i + 2] = double(mesh.vertices[i].z);
    }
    std::vector<double> builds;
    std::size_t bytes = 0;
    for (int r = 0; r < o.reps; ++r) {
      cgal.reset();
      const std::size_t before = heap_in_use();
      t0 = Clock::now();
      cgal = std::make_unique<ebgeom_bench::CgalPeer>(
          xyz.data(), mesh.vertex_count(), mesh.triangles.data()->data(), mesh.triangle_count());
      builds.push_back(ms_since(t0));
      bytes = heap_in_use() - before;
    }
    row.build_ms = median(builds);
    row.memory = bytes;
    row.memory_note = "heap growth over the build (Surface_mesh + AABB tree + KD-tree of hints)";
    if (cgal->failed_faces() > 0)
      row.note = std::to_string(cgal->failed_faces()) + " faces refused by Surface_mesh; ";
    if (!cgal->closed()) row.note += "not closed (Side_of_triangle_mesh precondition); ";
    row.queries = std::min(o.points, o.cgal_points);
    if (row.queries < o.points)
      row.note += "timed on the first " + std::to_string(row.queries) + " points";
    while (!row.note.empty() && (row.note.back() == ' ' || row.note.back() == ';'))
      row.note.pop_back();
    const ebgeom_bench::CgalPeer* c = cgal.get();
    passes.push_back(make_pass(
        [c](const Vec3<T>& p) {
          return T(c->signed_distance(double(p.x), double(p.y), double(p.z)));
        },
        pts, row.queries, outs[3]));
    run.rows.push_back(std::move(row));
  }
#endif

#ifdef EBGEOM_BENCH_HAVE_FCPW
  std::unique_ptr<ebgeom_bench::FcpwPeer> fcpw;
  {
    Row row;
    row.method = "fcpw";
    row.precision = type_name<T>();
    row.compute = "float (SIMD width " + std::to_string(ebgeom_bench::FcpwPeer::simd_width()) + ")";
    std::vector<float> xyz(3 * mesh.vertex_count());
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
      xyz[3 * i] = float(mesh.vertices[i].x);
      xyz[3 * i + 1] = float(mesh.vertices[i].y);
      xyz[3 * i + 2] = float(mesh.vertices[i].z);
    }
    std::vector<double> builds;
    std::size_t bytes = 0;
    for (int r = 0; r < o.reps; ++r) {
      fcpw.reset();
      const std::size_t before = heap_in_use();
      t0 = Clock::now();
      fcpw = std::make_unique<ebgeom_bench::FcpwPeer>(
          xyz.data(), mesh.vertex_count(), mesh.triangles.data()->data(), mesh.triangle_count());
      builds.push_back(ms_since(t0));
      bytes = heap_in_use() - before;
    }
    row.build_ms = median(builds);
    row.memory = bytes;
    row.memory_note = "heap growth over the build (fcpw scene, normals and vectorised BVH)";
    row.queries = o.points;
    if (sizeof(T) != 4) row.note = "fcpw computes in float";
    const ebgeom_bench::FcpwPeer* f = fcpw.get();
    passes.push_back(make_pass(
        [f](const Vec3<T>& p) { return T(f->signed_distance(float(p.x), float(p.y), float(p.z))); },
        pts, o.points, outs[4]));
    Row sorted_row = row;
    run.rows.push_back(std::move(row));
    // fcpw's per-point loop on the same points sorted beforehand in the Morton order that
    // MeshSdf::eval uses (`morton_order` over the whole set: the sort is not timed, unlike
    // ebgeom-batch's), so the gain of the order alone shows for fcpw too. Its values are written
    // in the sorted order and put back in input order after the timed rounds for the check.
    // (fcpw's own batch call `Scene::findClosestPoints` runs the same per-point loop on
    // hardware_concurrency threads, with no one-thread form: not timed.)
    sorted_row.method = "fcpw-sorted";
    sorted_row.note = "per-point loop on the points pre-sorted in Morton order (sort not timed)";
    sorted_points.resize(o.points);
    {
      std::vector<std::uint64_t> scratch;
      morton_order(Span<const Vec3<T>>(pts), sorted_order, scratch);
      for (std::size_t k = 0; k < o.points; ++k) sorted_points[k] = pts[sorted_order[k]];
    }
    passes.push_back(make_pass(
        [f](const Vec3<T>& p) { return T(f->signed_distance(float(p.x), float(p.y), float(p.z))); },
        sorted_points, o.points, sorted_out));
    outs[7].assign(o.points, T(0));
    run.rows.push_back(std::move(sorted_row));
  }
#endif

  // Timed passes, interleaved: in each of R rounds, every method runs once on one thread and then
  // once on T threads, so a method's two passes of a round see about the same load (the paired
  // thread scaling) and the methods of a round too (the paired ratios).
  for (int r = 0; r < o.reps; ++r)
    for (std::size_t k = 0; k < passes.size(); ++k) {
      run.rows[k].qps1.push_back(double(run.rows[k].queries) / passes[k](1));
      if (o.threads > 1)
        run.rows[k].qpst.push_back(double(run.rows[k].queries) / passes[k](o.threads));
    }

  for (std::size_t k = 0; k < sorted_out.size(); ++k) outs[7][sorted_order[k]] = sorted_out[k];

#ifdef EBGEOM_BENCH_HAVE_FCPW
  if (o.bands && sdf && fcpw && !outs[0].empty()) {
    Aabb<double> pbox;
    for (const Vec3<T>& p : pts) pbox.extend(Vec3<double>::from(p));
    const double diag = norm(pbox.extent());
    const double edges[] = {
        0, 0.01, 0.025, 0.05, 0.1, 0.2, std::numeric_limits<double>::infinity()};
    const std::size_t nb = std::size(edges) - 1;
    std::vector<std::vector<Vec3<T>>> band_pts(nb);
    for (std::size_t i = 0; i < outs[0].size(); ++i) {
      const double d = std::abs(double(outs[0][i])) / diag;
      for (std::size_t b = 0; b < nb; ++b)
        if (d >= edges[b] && d < edges[b + 1]) band_pts[b].push_back(pts[i]);
    }
    std::vector<std::vector<T>> band_out(2 * nb);
    std::vector<Pass> band_passes;
    const MeshSdf<T>* s = sdf.get();
    const ebgeom_bench::FcpwPeer* f = fcpw.get();
    for (std::size_t b = 0; b < nb; ++b) {
      Band band;
      band.lo = edges[b], band.hi = edges[b + 1], band.points = band_pts[b].size();
      run.bands.push_back(band);
      band_passes.push_back(make_pass([s](const Vec3<T>& p) { return (*s)(p); }, band_pts[b],
                                      band.points, band_out[2 * b]));
      band_passes.push_back(make_pass(
          [f](const Vec3<T>& p) {
            return T(f->signed_distance(float(p.x), float(p.y), float(p.z)));
          },
          band_pts[b], band.points, band_out[2 * b + 1]));
    }
    for (int r = 0; r < o.reps; ++r)
      for (std::size_t b = 0; b < nb; ++b) {
        if (run.bands[b].points == 0) continue;
        const double n = double(run.bands[b].points);
        run.bands[b].ebgeom_qps.push_back(n / band_passes[2 * b](1));
        run.bands[b].fcpw_qps.push_back(n / band_passes[2 * b + 1](1));
      }
  }
#endif

  // Agreement with the reference on the first points (every point for the batch path).
  for (std::size_t k = 0; k < run.rows.size(); ++k) {
    Row& row = run.rows[k];
    if (row.is_reference) continue;
    const std::vector<T>& out = outs[row.method == "brute"          ? 1
                                     : row.method == "embree"       ? 2
                                     : row.method == "cgal"         ? 3
                                     : row.method == "fcpw"         ? 4
                                     : row.method == "ebgeom-batch" ? 5
                                     : row.method == "ebgeom-tile"  ? 6
                                     : row.method == "fcpw-sorted"  ? 7
                                                                    : 0];
    const bool float_peer =
        row.method == "embree" || row.method == "fcpw" || row.method == "fcpw-sorted";
    check(row, ref_name, *out_ref, out, row.method == "ebgeom-batch" ? o.points : m,
          float_peer ? 1e-5 : rel_t, float_peer ? floor_f : floor_t);
    // Where the signs differ, which one does the generalized winding number (Jacobson et al.
    // 2013, O(n) per point, in double) agree with? On open meshes neither sign is "the" truth,
    // but the winding number is the usual arbiter. At most 1000 points.
    std::size_t arbitrated = 0;
    for (std::size_t i = 0; i < row.checked && arbitrated < 1000; ++i) {
      if (((*out_ref)[i] < 0) == (out[i] < 0)) continue;
      ++arbitrated;
      const Vec3<double> p = Vec3<double>::from(pts[i]);
      double w = 0;
      for (std::size_t t = 0; t < mesh.triangle_count(); ++t)
        w += solid_angle(p, Vec3<double>::from(mesh.corner(t, 0)),
                         Vec3<double>::from(mesh.corner(t, 1)),
                         Vec3<double>::from(mesh.corner(t, 2)));
      const bool inside = w / (4 * 3.14159265358979323846) > 0.5;
      if (((*out_ref)[i] < 0) == inside) ++row.sign_diff_ref_wins;
      if ((out[i] < 0) == inside) ++row.sign_diff_peer_wins;
    }
  }
#ifdef EBGEOM_BENCH_HAVE_EMBREE
  embree.reset();
  rtcReleaseDevice(device);
#endif
  return run;
}

// ---- output ---------------------------------------------------------------------------------

double qps(const std::vector<double>& v) { return median(v); }

// Median over rounds of a / b: the runs are interleaved, so round r of both methods saw about the
// same load; less sensitive to drifting load than the ratio of the medians.
double paired_ratio(const std::vector<double>& a, const std::vector<double>& b) {
  std::vector<double> r;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) r.push_back(a[i] / b[i]);
  return median(r);
}

const Row* find(const PrecisionRun& run, const std::string& method) {
  for (const Row& r : run.rows)
    if (r.method == method) return &r;
  return nullptr;
}

void print_text(const Options& o, const std::vector<PrecisionRun>& runs) {
  for (const PrecisionRun& run : runs) {
    if (!run.error.empty()) {
      std::printf("[%s] error: %s\n", run.precision.c_str(), run.error.c_str());
      continue;
    }
    const MeshInfo& mi = run.mesh;
    std::printf("\n== %s, %s: %zu triangles, %zu vertices; %s %.1f ms; TriangleMesh %.1f ms\n",
                mi.name.c_str(), run.precision.c_str(), mi.triangles, mi.vertices,
                mi.generated ? "generate" : "parse", mi.parse_ms, mi.triangle_mesh_ms);
    if (o.grid > 0)
      std::printf("   %zu^3 = %zu cell centres of the box + 10%%, %d runs (median), %d threads\n",
                  o.grid, o.points, o.reps, o.threads);
    else
      std::printf("   %zu uniform points in the box + 10%%, %d runs (median), %d threads\n",
                  o.points, o.reps, o.threads);
    std::printf("   1-thread rates from the thread's CPU time%s\n",
                o.threads > 1
                    ? (", " + std::to_string(o.threads) + "-thread rates from wall time").c_str()
                    : "");
    std::printf("%-12s %-7s %10s %9s %7s %12s %12s %7s %7s  %s\n", "method", "prec", "build ms",
                "MB", "B/tri", "1-thr kq/s", (std::to_string(o.threads) + "-thr kq/s").c_str(),
                "scaling", "paired", "note");
    for (const Row& r : run.rows) {
      const double q1 = qps(r.qps1), qt = qps(r.qpst);
      std::string note = r.compute == r.precision ? "" : r.compute;
      if (!r.note.empty()) note += (note.empty() ? "" : "; ") + r.note;
      std::printf("%-12s %-7s %10.2f %9.2f %7.1f %12.1f %12.1f %7.2f %7.2f  %s\n", r.method.c_str(),
                  r.precision.c_str(), r.build_ms, double(r.memory) / 1e6,
                  double(r.memory) / double(std::max<std::size_t>(mi.triangles, 1)), q1 / 1e3,
                  qt / 1e3, qt / q1, paired_ratio(r.qpst, r.qps1), note.c_str());
    }
    std::printf("agreement (first points; |d| within rel %g (embree 1e-5) + 16 ulp of the "
                "coordinates):\n",
                run.precision == "float" ? 1e-5 : 1e-9);
    for (const Row& r : run.rows) {
      if (r.is_reference) {
        std::printf("  %-12s reference\n", r.method.c_str());
        continue;
      }
      std::printf("  %-12s vs %-7s %7zu points: %zu |d| out of tolerance, %zu sign differences "
                  "(%.4f%%), max rel err %.2e, max abs err %.2e (%.2e of scale), %zu bitwise "
                  "equal\n",
                  r.method.c_str(), r.reference.c_str(), r.checked, r.distance_bad, r.sign_diff,
                  r.checked ? 100.0 * double(r.sign_diff) / double(r.checked) : 0.0, r.max_rel,
                  r.max_abs, r.max_abs / mi.scale, r.bitwise_equal);
      if (r.sign_diff > 0)
        std::printf("  %-8s    sign differences: the winding number agrees with %s on %zu, with "
                    "%s on %zu\n",
                    "", r.reference.c_str(), r.sign_diff_ref_wins, r.method.c_str(),
                    r.sign_diff_peer_wins);
    }
    if (!run.bands.empty()) {
      std::printf("bands of |S| / diagonal of the points' box (one thread, ebgeom and fcpw "
                  "alternately, medians of %d rounds):\n",
                  o.reps);
      std::printf("  %-13s %9s %7s %12s %12s %14s\n", "band", "points", "share", "ebgeom kq/s",
                  "fcpw kq/s", "ebgeom / fcpw");
      for (const Band& b : run.bands) {
        char name[32];
        std::snprintf(name, sizeof name, std::isfinite(b.hi) ? "%.3f-%.3f" : "%.3f-", b.lo, b.hi);
        std::printf("  %-13s %9zu %6.1f%% %12.1f %12.1f %14.2f\n", name, b.points,
                    100.0 * double(b.points) / double(std::max<std::size_t>(o.points, 1)),
                    qps(b.ebgeom_qps) / 1e3, qps(b.fcpw_qps) / 1e3,
                    paired_ratio(b.ebgeom_qps, b.fcpw_qps));
      }
    }
    for (const char* name : {"ebgeom", "ebgeom-batch", "ebgeom-tile"}) {
      const Row* eb = find(run, name);
      if (!eb) continue;
      std::printf("ratios %s / peer (build and memory: < 1 is smaller; throughput: > 1 is "
                  "faster):\n",
                  name);
      std::printf("  %-12s %9s %9s %12s %12s %14s %14s\n", "peer", "build", "memory", "1-thr q/s",
                  (std::to_string(o.threads) + "-thr q/s").c_str(), "1-thr paired",
                  (std::to_string(o.threads) + "-thr paired").c_str());
      for (const Row& r : run.rows) {
        if (&r == eb) continue;
        std::printf("  %-12s %9.2f %9.2f %12.2f %12.2f %14.2f %14.2f\n", r.method.c_str(),
                    eb->build_ms / r.build_ms, double(eb->memory) / double(r.memory),
                    qps(eb->qps1) / qps(r.qps1), qps(eb->qpst) / qps(r.qpst),
                    paired_ratio(eb->qps1, r.qps1), paired_ratio(eb->qpst, r.qpst));
      }
    }
  }
}

#ifdef EBGEOM_BENCH_HAVE_JSON
nlohmann::json to_json(const Options& o, const std::vector<PrecisionRun>& runs) {
  nlohmann::json j;
  j["mesh"] = o.generate ? "generated bumpy torus" : o.mesh;
  j["points"] = o.points;
  j["reps"] = o.reps;
  j["threads"] = o.threads;
  j["check"] = o.check;
  j["runs"] = nlohmann::json::array();
  for (const PrecisionRun& run : runs) {
    nlohmann::json jr;
    jr["precision"] = run.precision;
    if (!run.error.empty()) {
      jr["error"] = run.error;
      j["runs"].push_back(jr);
      continue;
    }
    const MeshInfo& mi = run.mesh;
    jr["triangles"] = mi.triangles;
    jr["vertices"] = mi.vertices;
    jr[mi.generated ? "generate_ms" : "parse_ms"] = mi.parse_ms;
    jr["triangle_mesh_ms"] = mi.triangle_mesh_ms;
    jr["scale"] = mi.scale;
    jr["methods"] = nlohmann::json::array();
    for (const Row& r : run.rows) {
      nlohmann::json m;
      m["method"] = r.method;
      m["precision"] = r.precision;
      m["compute"] = r.compute;
      m["build_ms"] = r.build_ms;
      m["memory_bytes"] = r.memory;
      m["bytes_per_triangle"] = double(r.memory) / double(std::max<std::size_t>(mi.triangles, 1));
      m["memory_note"] = r.memory_note;
      m["queries"] = r.queries;
      m["qps_1"] = qps(r.qps1);
      m["qps_threads"] = qps(r.qpst);
      m["scaling"] = qps(r.qpst) / qps(r.qps1);
      m["scaling_paired"] = paired_ratio(r.qpst, r.qps1);
      m["qps_1_runs"] = r.qps1;
      m["qps_threads_runs"] = r.qpst;
      if (r.is_reference) {
        m["reference"] = true;
      } else {
        m["check"] = {{"reference", r.reference},
                      {"points", r.checked},
                      {"distance_bad", r.distance_bad},
                      {"sign_diff", r.sign_diff},
                      {"sign_diff_reference_agrees_with_winding", r.sign_diff_ref_wins},
                      {"sign_diff_peer_agrees_with_winding", r.sign_diff_peer_wins},
                      {"bitwise_equal", r.bitwise_equal},
                      {"max_rel_err", r.max_rel},
                      {"max_abs_err", r.max_abs}};
      }
      if (!r.note.empty()) m["note"] = r.note;
      jr["methods"].push_back(m);
    }
    for (const char* name : {"ebgeom", "ebgeom-batch", "ebgeom-tile"}) {
      const Row* eb = find(run, name);
      if (!eb) continue;
      nlohmann::json ratios;
      for (const Row& r : run.rows) {
        if (&r == eb) continue;
        ratios[r.method] = {{"build", eb->build_ms / r.build_ms},
                            {"memory", double(eb->memory) / double(r.memory)},
                            {"qps_1", qps(eb->qps1) / qps(r.qps1)},
                            {"qps_threads", qps(eb->qpst) / qps(r.qpst)},
                            {"qps_1_paired", paired_ratio(eb->qps1, r.qps1)},
                            {"qps_threads_paired", paired_ratio(eb->qpst, r.qpst)}};
      }
      jr[std::string("ratios_") + name + "_over_peer"] = ratios;
    }
    if (!run.bands.empty()) {
      jr["bands"] = nlohmann::json::array();
      for (const Band& b : run.bands)
        jr["bands"].push_back(
            {{"lo", b.lo},
             {"hi", std::isfinite(b.hi) ? nlohmann::json(b.hi) : nullptr},
             {"points", b.points},
             {"ebgeom_qps_1_runs", b.ebgeom_qps},
             {"fcpw_qps_1_runs", b.fcpw_qps},
             {"ebgeom_over_fcpw_paired", paired_ratio(b.ebgeom_qps, b.fcpw_qps)}});
    }
    j["runs"].push_back(jr);
  }
  return j;
}
#endif

int usage(const char* argv0) {
  std::fprintf(stderr,
               "usage: %s MESH | --generate N  [--points N=1000000] [--reps R=5]\n"
               "       [--precision float|double|both] [--threads T=2] [--check M=20000] "
               "[--cgal-points K=100000] [--grid N]\n"
               "       [--bands] [--json] [--json-file PATH]\n",
               argv0);
  return 2;
}

} // namespace

int main(int argc, char** argv) {
  Options o;
  std::string precision = "double";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> const char* { return i + 1 < argc ? argv[++i] : nullptr; };
    const char* v = nullptr;
    if (a == "--json") {
      o.json = true;
    } else if (a == "--bands") {
      o.bands = true;
    } else if (a == "--points" && (v = next())) {
      o.points = std::strtoull(v, nullptr, 10);
    } else if (a == "--reps" && (v = next())) {
      o.reps = std::max(1, std::atoi(v));
    } else if (a == "--threads" && (v = next())) {
      o.threads = std::max(1, std::atoi(v));
    } else if (a == "--check" && (v = next())) {
      o.check = std::strtoull(v, nullptr, 10);
    } else if (a == "--json-file" && (v = next())) {
      o.json_file = v;
    } else if (a == "--cgal-points" && (v = next())) {
      o.cgal_points = std::max<std::size_t>(1, std::strtoull(v, nullptr, 10));
    } else if (a == "--grid" && (v = next())) {
      o.grid = std::strtoull(v, nullptr, 10);
      if (o.grid == 0 || o.grid > 1024) return usage(argv[0]);
    } else if (a == "--generate" && (v = next())) {
      o.generate = std::strtoull(v, nullptr, 10);
    } else if (a == "--precision" && (v = next())) {
      precision = v;
    } else if (!a.empty() && a[0] != '-' && o.mesh.empty()) {
      o.mesh = a;
    } else {
      return usage(argv[0]);
    }
  }
  if (o.grid > 0) o.points = o.grid * o.grid * o.grid;
  if ((o.mesh.empty() == (o.generate == 0)) || o.points == 0) return usage(argv[0]);
  if (precision != "float" && precision != "double" && precision != "both") return usage(argv[0]);
  o.run_float = precision != "double";
  o.run_double = precision != "float";
#ifndef EBGEOM_BENCH_HAVE_FCPW
  if (o.bands) {
    std::fprintf(stderr, "--bands needs fcpw at build time (-DEBGEOM_FCPW_DIR)\n");
    return 2;
  }
#endif
#ifndef EBGEOM_BENCH_HAVE_JSON
  if (o.json || !o.json_file.empty()) {
    std::fprintf(stderr, "--json and --json-file need nlohmann-json at build time\n");
    return 2;
  }
#endif
  std::vector<PrecisionRun> runs;
  if (o.run_float) runs.push_back(run_precision<float>(o));
  if (o.run_double) runs.push_back(run_precision<double>(o));
#ifdef EBGEOM_BENCH_HAVE_JSON
  if (!o.json_file.empty()) {
    std::FILE* f = std::fopen(o.json_file.c_str(), "w");
    if (!f) {
      std::fprintf(stderr, "cannot write %s\n", o.json_file.c_str());
      return 1;
    }
    std::fprintf(f, "%s\n", to_json(o, runs).dump(2).c_str());
    std::fclose(f);
  }
  if (o.json) {
    std::printf("%s\n", to_json(o, runs).dump(2).c_str());
  } else
#endif
  {
#ifndef EBGEOM_BENCH_HAVE_MESH_SDF
    std::printf("note: ebgeom/sdf/mesh_sdf.hpp not found; MeshSdf not measured\n");
#endif
    print_text(o, runs);
  }
  for (const PrecisionRun& r : runs)
    if (!r.error.empty()) return 1;
  return 0;
}
