// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Mesh reading throughput (MB/s of input) for every reader, from memory and from a (page-cached)
// file. The input is a generated torus of about EBGEOM_BENCH_TRIANGLES triangles (default 2 M),
// written once with ebgeom's own writers to $TMPDIR (default /tmp)/ebgeom_read_bench/.
//
//   cmake --preset bench && cmake --build --preset bench --target ebgeom_bench_read_bench
//   build/bench/bench/ebgeom_bench_read_bench --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one command line)
//
// Reported: bytes_per_second (input bytes) and triangles per second; use the median rows.

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>

#include "ebgeom/io.hpp"

namespace {

using namespace ebgeom;

std::size_t target_triangles() {
  const char* env = std::getenv("EBGEOM_BENCH_TRIANGLES");
  return env ? std::size_t(std::strtoull(env, nullptr, 10)) : std::size_t(2000000);
}

// A closed torus of n x m quads split in two triangles each (2 n m triangles, n m vertices).
PolygonSoup<float> torus(std::size_t triangles) {
  const std::size_t n = std::size_t(std::sqrt(double(triangles) / 2.0 * 2.0)),
                    m = triangles / (2 * n);
  PolygonSoup<float> s;
  const double pi = 3.14159265358979323846;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < m; ++j) {
      const double u = 2 * pi * double(i) / double(n), v = 2 * pi * double(j) / double(m);
      s.add_vertex({float((1.7 + 0.6 * std::cos(v)) * std::cos(u)),
                    float((1.7 + 0.6 * std::cos(v)) * std::sin(u)), float(0.6 * std::sin(v))});
    }
  auto id = [&](std::size_t i, std::size_t j) { return Index((i % n) * m + (j % m)); };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < m; ++j) {
      s.add_triangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      s.add_triangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return s;
}

struct Input {
  std::string path;
  std::string bytes;
};

// The generated files, keyed by name ("stl_binary", "obj", ...), made on first use.
const Input& input(const std::string& key) {
  static std::map<std::string, Input> cache;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  static const PolygonSoup<float> mesh = torus(target_triangles());
  const char* tmp = std::getenv("TMPDIR");
  const std::filesystem::path dir = std::filesystem::path(tmp ? tmp : "/tmp") / "ebgeom_read_bench";
  std::filesystem::create_directories(dir);
  io::WriteOptions w;
  const std::string fmt = key.substr(0, 3);
  w.format = fmt == "stl"   ? io::MeshFormat::stl
             : fmt == "ply" ? io::MeshFormat::ply
             : fmt == "obj" ? io::MeshFormat::obj
                            : io::MeshFormat::vtk;
  w.encoding = key.find("ascii") != std::string::npos || fmt == "obj" ? io::Encoding::ascii
                                                                      : io::Encoding::binary;
  Input in;
  in.path = (dir / (key + "_" + std::to_string(mesh.face_count()) + "." + fmt)).string();
  in.bytes = io::encode_mesh(mesh, w).value();
  std::ofstream(in.path, std::ios::binary).write(in.bytes.data(), std::streamsize(in.bytes.size()));
  return cache.emplace(key, std::move(in)).first->second;
}

void report(benchmark::State& state, std::size_t bytes, std::size_t triangles) {
  state.SetBytesProcessed(std::int64_t(state.iterations() * bytes));
  state.counters["triangles/s"] =
      benchmark::Counter(double(state.iterations() * triangles), benchmark::Counter::kIsRate);
  state.counters["MB"] = double(bytes) / 1e6;
}

// Parse from memory (the parser alone).
void BM_parse(benchmark::State& state, std::string key, io::StlVertices stl) {
  const Input& in = input(key);
  io::ReadOptions opt;
  opt.stl_vertices = stl;
  std::size_t tris = 0;
  for (auto _ : state) {
    auto r = io::parse_mesh<float>(in.bytes, opt);
    if (!r) {
      state.SkipWithError(r.error().what().c_str());
      return;
    }
    tris = r->triangle_count();
    benchmark::DoNotOptimize(r->vertices.data());
  }
  report(state, in.bytes.size(), tris);
}

// Read the file (page cache) and parse: what `read_mesh` costs a user.
void BM_read_file(benchmark::State& state, std::string key) {
  const Input& in = input(key);
  std::size_t tris = 0;
  for (auto _ : state) {
    auto r = io::read_mesh<float>(in.path);
    if (!r) {
      state.SkipWithError(r.error().what().c_str());
      return;
    }
    tris = r->triangle_count();
    benchmark::DoNotOptimize(r->vertices.data());
  }
  report(state, in.bytes.size(), tris);
}

const io::StlVertices weld = io::StlVertices::weld_exact, keep = io::StlVertices::keep;
BENCHMARK_CAPTURE(BM_parse, stl_binary, "stl_binary", weld)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_parse, stl_binary_noweld, "stl_binary", keep)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_parse, stl_ascii, "stl_ascii", weld)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_parse, ply_binary, "ply_binary", weld)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_parse, ply_ascii, "ply_ascii", weld)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_parse, obj, "obj", weld)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_parse, vtk_binary, "vtk_binary", weld)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_parse, vtk_ascii, "vtk_ascii", weld)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_read_file, stl_binary, "stl_binary")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_read_file, ply_binary, "ply_binary")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_read_file, obj, "obj")->Unit(benchmark::kMillisecond);

} // namespace

BENCHMARK_MAIN();
