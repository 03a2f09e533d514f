// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// The cost of ebgeom inside an embedded-boundary code's geometry generation, without the code:
// the nodes of an n^3 lattice around a mesh (as AMReX's EB2 and Chombo's GeometryShop evaluate
// them, x fastest), evaluated through
//  - plain      MeshSdf::operator(), the plain query (reference),
//  - signed     SignedMeshSdf (the adapters' mesh SDF, automatic sign: pseudonormal here),
//  - adapter    EbFunction::operator()(x, y, z) (what AMReX's per-point call reaches),
//  - virtual    the adapter behind a virtual call with double coordinates (what Chombo's
//               BaseIF::value does),
//  - tiles      EbFunction::node_values over the lattice (8^3 tiles through eval_lattice: what
//               AmrexGeometryShop::fillFab and Chombo's InsideOutside do);
// and the classification of the lattice's 16^3-node boxes (AMReX's getBoxType) node by node
// against EbFunction::node_signs (one evaluation per box far from the surface). Rounds are
// interleaved; the median of the rounds is reported, as ns per node and as a ratio to plain.
// Every path must give the plain values, bit for bit (exit 1 otherwise).
//
// Usage: ebgeom_bench_eb_adapter_bench [mesh file (default: an 81,920-triangle icosphere)]
//        [n = 64] [rounds = 5]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "ebgeom/adapters/eb_function.hpp"
#include "ebgeom/adapters/shared_mesh_sdf.hpp"
#include "ebgeom/io/read_mesh.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"

namespace {
using T = double;
using ebgeom::Vec3;

/// What Chombo's BaseIF is to the adapter: a virtual `value` with the code's coordinates.
struct VirtualIF {
  virtual ~VirtualIF() = default;
  virtual double value(const double* x) const = 0;
};
template <class F> struct AdapterIF final : VirtualIF {
  explicit AdapterIF(F fn) : f(std::move(fn)) {}
  double value(const double* x) const override { return f(x[0], x[1], x[2]); }
  F f;
};

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}
} // namespace

int main(int argc, char** argv) {
  const std::string file = argc > 1 ? argv[1] : "";
  const int n = argc > 2 ? std::atoi(argv[2]) : 64;
  const int rounds = argc > 3 ? std::atoi(argv[3]) : 5;
  if (n < 2 || rounds < 1) {
    std::fprintf(stderr, "eb_adapter_bench: n >= 2 and rounds >= 1 required\n");
    return 2;
  }
  ebgeom::PolygonSoup<T> soup;
  if (file.empty()) {
    soup = ebgeom::make_icosphere<T>(6, T(1)).value();
  } else {
    auto read = ebgeom::io::read_mesh<T>(file);
    if (!read) {
      std::fprintf(stderr, "eb_adapter_bench: %s\n", read.error().what().c_str());
      return 2;
    }
    soup = std::move(*read);
  }
  const auto plain = ebgeom::MeshSdf<T>::build(soup).value();
  const ebgeom::SharedMeshSdf<T> shared = ebgeom::make_shared_mesh_sdf(soup).value();
  const auto f = ebgeom::make_eb_function(shared);
  const std::unique_ptr<VirtualIF> vif = std::make_unique<AdapterIF<decltype(f)>>(f);

  // The lattice: n^3 cells over the mesh's box padded by 10% per side, nodes 0..n.
  const auto b = plain.bounds();
  const Vec3<T> ext = b.hi - b.lo;
  const double pad = 0.1 * std::max({ext.x, ext.y, ext.z});
  const double origin[3] = {b.lo.x - pad, b.lo.y - pad, b.lo.z - pad};
  const double dx[3] = {(ext.x + 2 * pad) / n, (ext.y + 2 * pad) / n, (ext.z + 2 * pad) / n};
  const int lo[3] = {0, 0, 0}, hi[3] = {n, n, n};
  const std::size_t nodes = std::size_t(n + 1) * std::size_t(n + 1) * std::size_t(n + 1);
  std::vector<double> xyz(3 * nodes);
  std::size_t c = 0;
  for (int k = 0; k <= n; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i, ++c) {
        xyz[3 * c] = origin[0] + double(i) * dx[0];
        xyz[3 * c + 1] = origin[1] + double(j) * dx[1];
        xyz[3 * c + 2] = origin[2] + double(k) * dx[2];
      }

  std::vector<double> ref(nodes), out(nodes);
  auto point = [&](std::size_t q) { return Vec3<T>{xyz[3 * q], xyz[3 * q + 1], xyz[3 * q + 2]}; };
  struct Method {
    const char* name;
    std::function<void()> run;
    std::vector<double> ns;
  };
  // plain gives -S; the others give the adapter's value (-S for the default fluid side)
  std::vector<Method> methods = {
      {"plain MeshSdf",
       [&] {
         for (std::size_t q = 0; q < nodes; ++q) out[q] = -plain(point(q));
       },
       {}},
      {"SignedMeshSdf",
       [&] {
         for (std::size_t q = 0; q < nodes; ++q) out[q] = -(*shared)(point(q));
       },
       {}},
      {"adapter (x, y, z)",
       [&] {
         for (std::size_t q = 0; q < nodes; ++q)
           out[q] = f(xyz[3 * q], xyz[3 * q + 1], xyz[3 * q + 2]);
       },
       {}},
      {"adapter, virtual",
       [&] {
         for (std::size_t q = 0; q < nodes; ++q) out[q] = vif->value(&xyz[3 * q]);
       },
       {}},
      {"adapter, 8^3 tiles", [&] { f.node_values(origin, dx, lo, hi, 3, out.data()); }, {}},
  };
  for (std::size_t q = 0; q < nodes; ++q) ref[q] = -plain(point(q));

  // Box classification: boxes of 16^3 cells (17^3 nodes), as AMReX's getBoxType sees them.
  const int bs = 16;
  std::vector<std::array<int, 6>> boxes;
  for (int k = 0; k < n; k += bs)
    for (int j = 0; j < n; j += bs)
      for (int i = 0; i < n; i += bs)
        boxes.push_back({i, j, k, std::min(n, i + bs), std::min(n, j + bs), std::min(n, k + bs)});
  std::vector<int> types_ref(boxes.size()), types(boxes.size());
  auto every_node_type = [&](const std::array<int, 6>& bx) { // AMReX's loop, node by node
    bool body = false, fluid = false;
    for (int k = bx[2]; k <= bx[5]; ++k)
      for (int j = bx[1]; j <= bx[4]; ++j)
        for (int i = bx[0]; i <= bx[3]; ++i) {
          const double v = f(origin[0] + double(i) * dx[0], origin[1] + double(j) * dx[1],
                             origin[2] + double(k) * dx[2]);
          if (v > 0)
            body = true;
          else if (!(v == 0))
            fluid = true;
          if (body && fluid) return 0;
        }
    return body ? 1 : -1;
  };
  std::vector<double> cls_every, cls_signs;
  using clock = std::chrono::steady_clock;
  for (int r = 0; r < rounds; ++r) {
    for (auto& m : methods) {
      std::fill(out.begin(), out.end(), 0.0);
      const auto t0 = clock::now();
      m.run();
      m.ns.push_back(std::chrono::duration<double, std::nano>(clock::now() - t0).count() /
                     double(nodes));
      if (out != ref) {
        std::fprintf(stderr, "eb_adapter_bench: %s differs from the plain query\n", m.name);
        return 1;
      }
    }
    auto t0 = clock::now();
    for (std::size_t q = 0; q < boxes.size(); ++q) types_ref[q] = every_node_type(boxes[q]);
    cls_every.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
    t0 = clock::now();
    for (std::size_t q = 0; q < boxes.size(); ++q) {
      const auto s = f.node_signs(origin, dx, boxes[q].data(), boxes[q].data() + 3, 3);
      types[q] = s.positive && s.negative ? 0 : (s.positive ? 1 : -1);
    }
    cls_signs.push_back(std::chrono::duration<double, std::milli>(clock::now() - t0).count());
    if (types != types_ref) {
      std::fprintf(stderr, "eb_adapter_bench: node_signs differs from node-by-node\n");
      return 1;
    }
  }
  // The level-set fill (AMReX's fillFab) sees only the boxes the surface cuts: their nodes per
  // point through the adapter, against node_values (8^3 tiles).
  std::vector<double> fill_point, fill_tiles;
  std::size_t cut_nodes = 0;
  for (int r = 0; r < rounds; ++r) {
    double tp = 0, tt = 0;
    cut_nodes = 0;
    for (std::size_t q = 0; q < boxes.size(); ++q) {
      if (types_ref[q] != 0) continue;
      const auto& bx = boxes[q];
      const std::size_t m = std::size_t(bx[3] - bx[0] + 1) * std::size_t(bx[4] - bx[1] + 1) *
                            std::size_t(bx[5] - bx[2] + 1);
      std::vector<double> a(m), t(m);
      auto t0 = clock::now();
      std::size_t u = 0;
      for (int k = bx[2]; k <= bx[5]; ++k)
        for (int j = bx[1]; j <= bx[4]; ++j)
          for (int i = bx[0]; i <= bx[3]; ++i)
            a[u++] = f(origin[0] + double(i) * dx[0], origin[1] + double(j) * dx[1],
                       origin[2] + double(k) * dx[2]);
      tp += std::chrono::duration<double, std::nano>(clock::now() - t0).count();
      t0 = clock::now();
      f.node_values(origin, dx, bx.data(), bx.data() + 3, 3, t.data());
      tt += std::chrono::duration<double, std::nano>(clock::now() - t0).count();
      if (a != t) {
        std::fprintf(stderr, "eb_adapter_bench: node_values differs on a cut box\n");
        return 1;
      }
      cut_nodes += m;
    }
    fill_point.push_back(tp / double(std::max<std::size_t>(1, cut_nodes)));
    fill_tiles.push_back(tt / double(std::max<std::size_t>(1, cut_nodes)));
  }
  std::printf("%s: %zu triangles, sign %s; %d^3 cells, %zu nodes; median of %d interleaved "
              "rounds\n",
              file.empty() ? "icosphere" : file.c_str(), plain.triangle_count(),
              ebgeom::to_string(shared->resolved_mode()), n, nodes, rounds);
  const double base = median(methods[0].ns);
  std::printf("%-22s %12s %10s\n", "path", "ns per node", "vs plain");
  for (const auto& m : methods)
    std::printf("%-22s %12.1f %9.2fx\n", m.name, median(m.ns), median(m.ns) / base);
  std::printf("box classification, %zu boxes of %d^3 cells: node by node %.1f ms, node_signs "
              "%.1f ms (%.1fx)\n",
              boxes.size(), bs, median(cls_every), median(cls_signs),
              median(cls_every) / median(cls_signs));
  std::printf("level-set fill of the %zu nodes of the cut boxes: per point %.1f ns per node, 8^3 "
              "tiles %.1f ns per node (%.2fx)\n",
              cut_nodes, median(fill_point), median(fill_tiles),
              median(fill_point) / median(fill_tiles));
  return 0;
}
