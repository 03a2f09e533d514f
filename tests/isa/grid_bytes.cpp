// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
// Writes the bytes of a few grids to the file named by its argument: an analytic scene (shapes,
// smooth CSG) sampled densely over its padded bounds, and narrow bands of a closed and an open
// mesh (pseudonormal and fast winding signs). Built twice (tests/CMakeLists.txt): with the
// build's flags, and with AVX2/FMA (or AVX-512) plus -ffp-contract=off, as EBGEOM_NATIVE builds
// are; the test compares the two files byte for byte. Each program is a whole program of its own,
// so no inline function is shared between the two builds (as it would be between two translation
// units of one program).
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "ebgeom/eval/grid.hpp"
#include "ebgeom/eval/sparse_grid.hpp"
#include "ebgeom/mesh/generate.hpp"
#include "ebgeom/sdf/csg.hpp"
#include "ebgeom/sdf/mesh_sdf.hpp"
#include "ebgeom/sdf/shapes.hpp"
#include "ebgeom/sdf/signed_mesh_sdf.hpp"

using namespace ebgeom;

namespace {

template <class V> void put(std::FILE* f, const std::vector<V>& v) {
  if (!v.empty()) std::fwrite(v.data(), sizeof(V), v.size(), f);
}

// A box as the command line samples by default: the bounds grown by 10% of the largest extent.
template <class T> GridSpec<T> padded(const Aabb<T>& b, std::size_t n) {
  return GridSpec<T>::cells(b.grown(T(0.1) * max_component(b.extent())), n);
}

template <class T> void scene(std::FILE* f) {
  const auto s = smooth_unite(Torus<T>{{T(0.1), T(-0.2), T(0.05)}, T(0.8), T(0.27)},
                              Sphere<T>{{T(0.45), T(0.3), T(0.2)}, T(0.55)}, T(0.13));
  const GridSpec<T> spec = padded(s.bounds(), 40);
  std::vector<T> v(spec.size());
  if (!sample_grid(s, spec, Span<T>(v))) std::abort();
  put(f, v);
}

// `t` with some faces left out (the holes of an open mesh).
template <class T> PolygonSoup<T> with_holes(const PolygonSoup<T>& t) {
  PolygonSoup<T> o;
  o.vertices = t.vertices;
  for (std::size_t i = 0; i < t.face_count(); ++i)
    if (i % 37 != 5) o.add_face(t.face(i));
  return o;
}

template <class S> void band(std::FILE* f, const S& sdf) {
  using T = sdf_scalar_t<S>;
  const GridSpec<T> spec = padded(sdf.bounds(), 64);
  GridOptions opt;
  opt.band = double(norm(spec.spacing())) * 2;
  const SparseGrid<T> g = sample_grid_sparse(sdf, spec, opt).value();
  put(f, g.kept_tiles);
  put(f, g.values);
}

template <class T> void meshes(std::FILE* f) {
  const PolygonSoup<T> closed = make_torus<T>(T(1), T(0.35), 40, 20).value();
  const auto ms = MeshSdf<T>::build(closed).value();
  band(f, ms);
  SignOptions so;
  so.mode = SignMode::fast_winding;
  const auto fw = SignedMeshSdf<T>::build(with_holes(closed), so).value();
  band(f, fw);
}

} // namespace

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  std::FILE* f = std::fopen(argv[1], "wb");
  if (f == nullptr) return 3;
  scene<float>(f);
  scene<double>(f);
  meshes<float>(f);
  meshes<double>(f);
  return std::fclose(f) == 0 ? 0 : 4;
}
